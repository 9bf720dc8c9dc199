// A robot's one forward kinematics in double: each link's pose from the root out through the
// joints. The checker's float kinematics are checked against it, and the tools pose a URDF's links
// by it (tools::link_poses).

#include <string>

#include "sphys/error.h"
#include "sphys/robot_model.h"

namespace sphys {

std::vector<Eigen::Isometry3d> forward_kinematics(const RobotModel& model,
                                                  std::span<const double> values) {
  if (values.size() != model.joints.size()) {
    throw Error("robot '" + model.name + "': " + std::to_string(values.size()) +
                " joint values for " + std::to_string(model.joints.size()) + " joints");
  }
  std::vector<Eigen::Isometry3d> poses(model.links.size());
  for (std::size_t l = 0; l < model.links.size(); ++l) {
    const RobotModel::Link& link = model.links[l];
    Eigen::Isometry3d local = link.origin;
    if (link.joint >= 0) {
      const auto j = static_cast<std::size_t>(link.joint);
      const RobotModel::Joint& joint = model.joints[j];
      const double value = values[j];
      if (joint.type == RobotJointType::kPrismatic) {
        local.translate(value * joint.axis);
      } else {
        local.rotate(Eigen::AngleAxisd(value, joint.axis));
      }
    }
    poses[l] =
        link.parent < 0 ? model.base * local : poses[static_cast<std::size_t>(link.parent)] * local;
  }
  return poses;
}

std::vector<Eigen::Isometry3d> robot_link_poses(const RobotModel& model,
                                                std::span<const double> values) {
  // The count first: check_joint_values would read a multiple of it as several configurations.
  if (values.size() == model.joints.size()) check_joint_values(model, values, "values");
  return forward_kinematics(model, values);
}

}  // namespace sphys
