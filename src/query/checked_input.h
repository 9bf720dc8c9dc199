#pragma once

// The checks of a query's input at its boundary: each throws sphys::Error naming the argument.

#include <string_view>

#include "sphys/math.h"

namespace sphys::query_detail {

void check_finite(const Vec3& value, std::string_view argument);
// Finite and >= 0.
void check_size(float value, std::string_view argument);
void check_size(const Vec3& value, std::string_view argument);
// A unit quaternion (within kUnitQuaternionTolerance) and a finite translation.
void check_pose(const Transform& pose, std::string_view argument);

}  // namespace sphys::query_detail
