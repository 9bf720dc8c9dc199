#include "robot_chain.h"

#include <algorithm>
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace sphys::tools {

std::optional<RobotJointType> urdf_joint_motion(const RobotJoint& joint) {
  if (joint.type == "revolute") return RobotJointType::kRevolute;
  if (joint.type == "continuous") return RobotJointType::kContinuous;
  if (joint.type == "prismatic") return RobotJointType::kPrismatic;
  return std::nullopt;
}

RobotModel robot_chain(const Robot& robot, const ChainJoint& chain_joint) {
  RobotModel model;
  model.name = robot.name;
  // Each link's joint from its parent, by the link's name.
  std::map<std::string, const RobotJoint*> joint_to;
  std::map<std::string, std::vector<const RobotJoint*>> children;
  for (const RobotJoint& joint : robot.joints) {
    joint_to[joint.child] = &joint;
    children[joint.parent].push_back(&joint);
  }
  for (auto& [parent, list] : children) {
    std::ranges::sort(list,
                      [](const RobotJoint* a, const RobotJoint* b) { return a->child < b->child; });
  }
  std::deque<std::pair<std::string, std::int32_t>> open = {{robot.root_link, -1}};
  while (!open.empty()) {
    const auto [name, parent] = open.front();
    open.pop_front();
    RobotModel::Link link;
    link.name = name;
    link.parent = parent;
    if (const auto joint = joint_to.find(name); joint != joint_to.end()) {
      const RobotJoint& j = *joint->second;
      link.origin = j.origin;
      if (const std::optional<RobotJointType> type = chain_joint(j)) {
        link.joint = static_cast<std::int32_t>(model.joints.size());
        model.joints.push_back({j.name, *type, j.axis, j.lower, j.upper, j.effort, j.velocity});
      }
    }
    const auto index = static_cast<std::int32_t>(model.links.size());
    model.links.push_back(std::move(link));
    for (const RobotJoint* child : children[name]) open.emplace_back(child->child, index);
  }
  return model;
}

}  // namespace sphys::tools
