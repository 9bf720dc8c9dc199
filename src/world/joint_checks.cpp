#include "world/joint_checks.h"

#include <cmath>
#include <numbers>

#include "sphys/error.h"

namespace sphys {
namespace {

// An axis shorter than this has no direction. unit: dimensionless (as given, before normalising)
constexpr float kShortestAxis = 1e-6f;

void fail(const std::string& who, std::string_view field, std::string_view problem) {
  throw Error(who + ": " + std::string(field) + " " + std::string(problem));
}

void check_finite(const std::string& who, std::string_view field, float value) {
  if (!std::isfinite(value)) fail(who, field, "must be finite, got " + std::to_string(value));
}

void check_not_negative(const std::string& who, std::string_view field, float value) {
  check_finite(who, field, value);
  if (value < 0.0f) fail(who, field, "must not be negative, got " + std::to_string(value));
}

void check_vector(const std::string& who, std::string_view field, const Vec3& value) {
  if (!value.allFinite()) fail(who, field, "must be finite");
}

void check_axis(const std::string& who, std::string_view field, const Vec3& axis) {
  check_vector(who, field, axis);
  if (!(axis.norm() >= kShortestAxis)) fail(who, field, "must not be zero");
}

}  // namespace

std::string_view joint_type_name(JointType type) {
  switch (type) {
    case JointType::kHinge:
      return "hinge";
    case JointType::kSlider:
      return "slider";
    case JointType::kBall:
      return "ball";
    case JointType::kWeld:
      return "weld";
    case JointType::kDistance:
      return "distance";
  }
  return "unknown";
}

void check_joint_limit(const std::string& who, JointType type, const JointLimit& limit) {
  check_finite(who, "limit.lower", limit.lower);
  check_finite(who, "limit.upper", limit.upper);
  if (!limit.enabled) return;
  if (limit.lower > limit.upper) {
    fail(who, "limit.lower",
         "must not be above limit.upper, got " + std::to_string(limit.lower) + " > " +
             std::to_string(limit.upper));
  }
  if (type == JointType::kDistance) check_not_negative(who, "limit.lower", limit.lower);
}

void check_joint_motor(const std::string& who, const JointMotor& motor) {
  check_finite(who, "motor.speed", motor.speed);
  check_not_negative(who, "motor.max_effort", motor.max_effort);
}

void check_joint_spring(const std::string& who, const JointSpring& spring) {
  check_not_negative(who, "spring.hertz", spring.hertz);
  check_not_negative(who, "spring.damping_ratio", spring.damping_ratio);
  check_finite(who, "spring.target", spring.target);
}

void check_joint_desc(const std::string& who, const JointDesc& desc) {
  check_vector(who, "anchor_a", desc.anchor_a);
  check_vector(who, "anchor_b", desc.anchor_b);
  check_axis(who, "axis_a", desc.axis_a);
  check_axis(who, "axis_b", desc.axis_b);
  check_joint_limit(who, desc.type, desc.limit);
  check_joint_motor(who, desc.motor);
  check_joint_spring(who, desc.spring);
  check_not_negative(who, "friction", desc.friction);
  check_not_negative(who, "cone.angle", desc.cone.angle);
  if (desc.cone.angle > std::numbers::pi_v<float>) {
    fail(who, "cone.angle", "must be at most π, got " + std::to_string(desc.cone.angle));
  }
  check_finite(who, "length", desc.length);
  if (desc.type == JointType::kDistance && !(desc.length > 0.0f)) {
    fail(who, "length", "must be positive, got " + std::to_string(desc.length));
  }
}

}  // namespace sphys
