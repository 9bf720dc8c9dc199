#pragma once

// What a RobotChecker poses configurations with, one per run of them (robot_check.cpp,
// robot_motion.cpp): the kernel's blocks of joint values and link poses, and the posed spheres.

#include <vector>

#include "query/configuration_layout.h"
#include "query/robot_kinematics.h"
#include "sphys/robot_check.h"

namespace sphys {

struct RobotChecker::PoseScratch {
  explicit PoseScratch(const RobotModel& model)
      : values(model.joints.size()),
        links(model.links.size() * 12),
        posed(kPoseLanes * model.spheres.size() * kFloatsPerSphere) {}
  std::vector<PoseLane> values;  // per joint
  std::vector<PoseLane> links;   // per link, 12 lane vectors
  std::vector<float> posed;      // kPoseLanes configurations' spheres
};

}  // namespace sphys
