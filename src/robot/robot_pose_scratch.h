#pragma once

// What a RobotChecker poses configurations with (robot_check.cpp, robot_motion.cpp): the
// kinematics compiled once; per run of configurations, the kernel's blocks of joint values and
// link poses, and the posed spheres; and the workspace a call keeps them in with the rest it
// needs.

#include <array>
#include <cstdint>
#include <thread>
#include <vector>

#include "robot/configuration_layout.h"
#include "robot/robot_kinematics.h"
#include "robot/robot_sweep.h"
#include "sphys/robot_check.h"

namespace sphys {

struct RobotChecker::Compiled {
  explicit Compiled(const RobotModel& model) : sweep(model) {}
  std::vector<std::int32_t> parent;
  std::vector<std::int32_t> joint;
  std::vector<LinkMotion> motion;
  std::vector<float> a, b, c, t, d;
  std::vector<std::int32_t> sphere_link;
  std::vector<float> sphere;
  // Per link, the box around its spheres in its own frame: centre and half extents (3 floats
  // each a link; a link without spheres has none), and its spheres (link_spheres from
  // link_first[l] to link_first[l + 1]).
  std::vector<float> link_centre, link_centre_size, link_half;
  // Each joint's limits (infinite for a continuous joint's). unit: rad or m
  std::vector<double> lower, upper;
  std::vector<std::uint32_t> link_first, link_spheres;
  KinematicsTables tables;
  KinematicsKernel kernel;
  const char* lanes = "portable";
  // How far each link's spheres move with the joints, and what a bound from it is widened by
  // against the float kinematics' rounding of the posed states it starts from: a
  // ten-thousandth of the largest coordinate a sphere can have, thousands of roundings. unit: m
  LinkSweep sweep;
  float sweep_margin = 0.0f;
};

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
  std::thread::id thread;  // the thread that used it last
  // A motion's: every block's link poses as the kernel wrote them, and each link's box over
  // every state (Run::bound's rows). unit: m
  std::vector<float> link_poses;
  std::vector<float> boxes;
  // A motion's states in the order they are posed (kPoseLanes to a kernel call), and each
  // state's place in that order.
  std::vector<std::uint32_t> posed_states;
  std::vector<std::uint32_t> state_slots;
  // Each link's box over the states posed so far, lane by lane (PoseScratch::boxes' rows), and
  // over the spread states widened by how far the spheres can move between them. unit: m
  std::vector<PoseLane> united;
  std::vector<float> widened;
  std::vector<double> changes;  // per joint: its change over half the widest gap. unit: rad, m
  std::vector<std::uint32_t> near_spheres;  // the spheres of links near a body
  // A motion's (robot_motion.cpp): a block of states' joint values, the states posed, the order
  // they are checked in and its spans, and the states before a collision.
  std::vector<double> values;
  std::vector<float> posed;
  std::vector<std::uint32_t> order;  // for order_states states
  std::uint32_t order_states = 0;
  std::vector<std::array<std::uint32_t, 2>> spans;
  std::vector<std::array<std::uint32_t, 2>> finer;
  std::vector<std::uint8_t> checked;
  std::vector<std::uint32_t> before;
};

}  // namespace sphys
