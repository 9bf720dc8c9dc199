// Forward kinematics: each link's pose from the root through the joints.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include <Eigen/Geometry>

#include "sphys/error.h"
#include "sphys/tools/robot.h"

namespace sphys::tools {
namespace {

// The joint's own motion at `value`: a turn about its axis or a slide along it.
Pose3d joint_motion(const RobotJoint& joint, double value) {
  Pose3d motion = Pose3d::Identity();
  if (joint.type == "revolute" || joint.type == "continuous") {
    motion.linear() = Eigen::AngleAxisd(value, joint.axis).toRotationMatrix();
  } else if (joint.type == "prismatic") {
    motion.translation() = value * joint.axis;
  }
  return motion;
}

bool movable(const RobotJoint& joint) {
  return joint.type == "revolute" || joint.type == "continuous" || joint.type == "prismatic";
}

}  // namespace

std::map<std::string, Pose3d> link_poses(const Robot& robot,
                                         const std::map<std::string, double>& joint_values) {
  for (const auto& [name, value] : joint_values) {
    const auto joint = std::find_if(robot.joints.begin(), robot.joints.end(),
                                    [&](const RobotJoint& j) { return j.name == name; });
    if (joint == robot.joints.end()) {
      throw Error::in_file(robot.file, "has no joint \"" + name + "\"");
    }
    if (!movable(*joint)) {
      throw Error::in_file(robot.file, "joint \"" + name + "\" is " + joint->type +
                                           ": only revolute, continuous and prismatic joints "
                                           "take a value");
    }
    if (!std::isfinite(value)) {
      throw Error("joint \"" + name + "\": the value must be finite");
    }
  }
  std::map<std::string, Pose3d> poses{{robot.root_link, Pose3d::Identity()}};
  // urdfdom guarantees a tree, so each pass places at least one more link until all are placed.
  for (bool placed = true; placed;) {
    placed = false;
    for (const RobotJoint& joint : robot.joints) {
      const auto parent = poses.find(joint.parent);
      if (parent == poses.end() || poses.contains(joint.child)) continue;
      const auto value = joint_values.find(joint.name);
      poses[joint.child] = parent->second * joint.origin *
                           joint_motion(joint, value == joint_values.end() ? 0.0 : value->second);
      placed = true;
    }
  }
  return poses;
}

}  // namespace sphys::tools
