#pragma once

// The median of a sample, as the benchmark tables and run summaries report it.

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

}  // namespace sphys::tools
