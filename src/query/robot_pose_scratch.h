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
      : pose(checker.model_), checks(checker.checker_) {}
  PoseScratch pose;
  ConfigurationChecker::Run checks;
  // A motion's: every block's link poses as the kernel wrote them, and each link's box over
  // every state (Run::bound's rows). unit: m
  std::vector<float> link_poses;
  std::vector<float> boxes;
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
