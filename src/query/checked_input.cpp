#include "query/checked_input.h"

#include <cmath>
#include <string>

#include "sphys/error.h"
#include "sphys/rigid_body.h"

namespace sphys::query_detail {

void check_finite(const Vec3& value, std::string_view argument) {
  if (!value.allFinite()) throw Error(std::string(argument) + ": not finite");
}

void check_size(float value, std::string_view argument) {
  if (!std::isfinite(value) || value < 0.0f) {
    throw Error(std::string(argument) + ": must be finite and >= 0 (m), not " +
                std::to_string(value));
  }
}

void check_size(const Vec3& value, std::string_view argument) {
  for (int i = 0; i < 3; ++i) check_size(value[i], argument);
}

void check_pose(const Transform& pose, std::string_view argument) {
  check_finite(pose.translation, std::string(argument) + ".translation");
  const float norm = pose.rotation.coeffs().norm();
  if (!std::isfinite(norm) || std::abs(norm - 1.0f) > kUnitQuaternionTolerance) {
    throw Error(std::string(argument) + ".rotation: not a unit quaternion");
  }
}

}  // namespace sphys::query_detail
