#pragma once

// The checks of a joint's parameters at the world's boundary: each throws sphys::Error naming the
// joint (`who`: "add_joint (hinge)", "joint 3.1 (slider)") and the field that is wrong.

#include <string>
#include <string_view>

#include "sphys/joint.h"

namespace sphys {

// "hinge", "slider", "ball", "weld" or "distance".
[[nodiscard]] std::string_view joint_type_name(JointType type);
// Every field but the bodies (the world checks those): finite numbers, axes not zero, limits in
// order, no negative effort, frequency or damping, a cone within 0..π, a distance's positive
// length and limits.
void check_joint_desc(const std::string& who, const JointDesc& desc);
void check_joint_limit(const std::string& who, JointType type, const JointLimit& limit);
void check_joint_motor(const std::string& who, const JointMotor& motor);
void check_joint_spring(const std::string& who, const JointSpring& spring);

}  // namespace sphys
