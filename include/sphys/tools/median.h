#pragma once

// The median of a sample, as the benchmark tables and run summaries report it, and its other
// quantiles.

#include <algorithm>
#include <cstddef>
#include <vector>

namespace sphys::tools {

// The middle value, or the mean of the two middle values of an even count; 0 for no values.
inline double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  if (values.size() % 2 == 1) return *middle;
  return 0.5 * (*middle + *std::max_element(values.begin(), middle));
}

// The value that `share` (0 to 1) of the values are at or below: the lowest value for 0, the
// highest for 1, the nearest rank between; 0 for no values.
inline double quantile(std::vector<double> values, double share) {
  if (values.empty()) return 0.0;
  const auto rank = static_cast<std::ptrdiff_t>(
      std::clamp(share, 0.0, 1.0) * static_cast<double>(values.size() - 1) + 0.5);
  std::nth_element(values.begin(), values.begin() + rank, values.end());
  return values[static_cast<std::size_t>(rank)];
}

}  // namespace sphys::tools
