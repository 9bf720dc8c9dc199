#pragma once

// A quintic between two joint values, at rest at both ends: the smooth motion the robot tests, the
// push_bunny example and the arm benchmark drive joints along.

#include <algorithm>
#include <utility>

namespace sphys::test {

// A quintic from `from` to `to` over `duration` (unit: s): the position and speed at time t.
[[nodiscard]] inline std::pair<double, double> quintic(double from, double to, double duration,
                                                       double t) {
  const double s = std::clamp(t / duration, 0.0, 1.0);
  const double shape = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
  const double rate = 30.0 * s * s * (1.0 - s) * (1.0 - s) / duration;
  return {from + (to - from) * shape, (to - from) * rate};
}

// A quintic's top speed over its mean speed.
inline constexpr double kQuinticPeakOverMean = 1.875;

}  // namespace sphys::test
