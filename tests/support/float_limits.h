#pragma once

#include <limits>

namespace sphys::test {

// The gap between 1 and the next float: the unit of the tolerances of single-precision physics.
inline constexpr float kFloatEpsilon = std::numeric_limits<float>::epsilon();

}  // namespace sphys::test
