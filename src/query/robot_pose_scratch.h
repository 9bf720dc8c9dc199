#pragma once

// What a RobotChecker poses configurations with, one per run of them (robot_check.cpp,
// robot_motion.cpp): the kernel's blocks of joint values and link poses, and the posed spheres;
// and the workspace a call keeps them in with the rest it needs.

#include <array>
#include <cstdint>
#include <vector>

#include "query/configuration_layout.h"
#include "query/robot_kinematics.h"
#include "sphys/robot_check.h"

namespace sphys {

struct RobotChecker::PoseScratch {
  explicit PoseScratch(const RobotModel& model)
      : values(model.joints.size()),
        links(model.links.size() * 12),
        boxes(model.links.size() * 6),
        posed(kPoseLanes * model.spheres.size() * kFloatsPerSphere) {}
  std::vector<PoseLane> values;  // per joint
  std::vector<PoseLane> links;   // per link, 12 lane vectors
  std::vector<PoseLane> boxes;   // per link, 6 lane vectors: its box's low x y z, high x y z
  std::vector<float> posed;      // kPoseLanes configurations' spheres
};

struct RobotChecker::Workspace {
  explicit Workspace(const RobotChecker& checker)
      : pose(checker.model_),
        checks(checker.checker_),
        low(checker.model_.links.size()),
        high(checker.model_.links.size()) {}
  PoseScratch pose;
  ConfigurationChecker::Run checks;
  std::vector<Vec3> low;  // each link's box in the world, one configuration's. unit: m
  std::vector<Vec3> high;
  std::vector<Vec3> state_low;   // a motion's: one state's link boxes, and every block's link
  std::vector<Vec3> state_high;  // poses as the kernel wrote them
  std::vector<float> link_poses;
  // A motion's (robot_motion.cpp): a block of states' joint values, the states posed, the order
  // they are checked in and its spans, and the states before a collision.
  std::vector<double> values;
  std::vector<float> posed;
  std::vector<std::uint32_t> order;
  std::vector<std::array<std::uint32_t, 2>> spans;
  std::vector<std::array<std::uint32_t, 2>> finer;
  std::vector<std::uint8_t> checked;
  std::vector<std::uint32_t> before;
};

}  // namespace sphys
