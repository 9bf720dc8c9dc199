#pragma once

// A URDF's tree of links and joints as a RobotModel's links and moving joints (no spheres yet):
// what the robot checks' model (robot_model_file.cpp) and the URDF's link poses (link_poses.cpp)
// are both made of, so that both pose links by the one forward kinematics (sphys/robot_model.h).

#include <functional>
#include <optional>

#include "sphys/robot_model.h"
#include "sphys/tools/robot.h"

namespace sphys::tools {

// How a revolute, continuous or prismatic joint moves its link; nothing for a fixed, floating or
// planar one.
[[nodiscard]] std::optional<RobotJointType> urdf_joint_motion(const RobotJoint& joint);

// How the chain moves the link a joint carries: its type, or nothing where the link stays fixed to
// its parent. It may throw for a joint the caller refuses.
using ChainJoint = std::function<std::optional<RobotJointType>(const RobotJoint& joint)>;

// Every link of the URDF, parents first, breadth first from the root, siblings by name, each at its
// joint's origin; the joints that move them (as `chain_joint` says) in the same order.
[[nodiscard]] RobotModel robot_chain(const Robot& robot, const ChainJoint& chain_joint);

}  // namespace sphys::tools
