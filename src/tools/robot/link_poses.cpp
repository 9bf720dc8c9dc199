// Forward kinematics of a URDF: each link's pose in the root's frame, by the robot model's one
// forward kinematics (sphys/robot_model.h) over the URDF's chain.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "robot_chain.h"
#include "sphys/error.h"
#include "sphys/robot_model.h"
#include "sphys/tools/robot.h"

namespace sphys::tools {

std::map<std::string, Pose3d> link_poses(const Robot& robot,
                                         const std::map<std::string, double>& joint_values) {
  for (const auto& [name, value] : joint_values) {
    const auto joint = std::find_if(robot.joints.begin(), robot.joints.end(),
                                    [&](const RobotJoint& j) { return j.name == name; });
    if (joint == robot.joints.end()) {
      throw Error::in_file(robot.file, "has no joint \"" + name + "\"");
    }
    if (!urdf_joint_motion(*joint)) {
      throw Error::in_file(robot.file, "joint \"" + name + "\" is " + joint->type +
                                           ": only revolute, continuous and prismatic joints "
                                           "take a value");
    }
    if (!std::isfinite(value)) {
      throw Error("joint \"" + name + "\": the value must be finite");
    }
  }
  // Every joint that takes a value moves its link, a mimic joint on its own; floating and planar
  // joints stand at their origins. The root stands at the origin (the model's base).
  const RobotModel chain = robot_chain(robot, urdf_joint_motion);
  std::vector<double> values(chain.joints.size(), 0.0);  // a joint not named stands at 0
  for (std::size_t j = 0; j < chain.joints.size(); ++j) {
    if (const auto value = joint_values.find(chain.joints[j].name); value != joint_values.end()) {
      values[j] = value->second;
    }
  }
  const std::vector<Pose3d> poses = forward_kinematics(chain, values);
  std::map<std::string, Pose3d> named;
  for (std::size_t l = 0; l < chain.links.size(); ++l) named[chain.links[l].name] = poses[l];
  return named;
}

}  // namespace sphys::tools
