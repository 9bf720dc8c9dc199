#pragma once

// A simulated robot's joints read from its bodies, driven before each step, and put where a
// configuration says (World's robot calls, world_robots.cpp).

#include <cstddef>
#include <span>
#include <vector>

#include "robot/robot_store.h"

namespace sphys {

struct WorldState;

// A pose in double.
[[nodiscard]] Eigen::Isometry3d to_isometry(const Transform& pose);

// The link model joint `joint` moves.
[[nodiscard]] std::size_t moved_link(const SimulatedRobot& robot, std::size_t joint);

// Every link's pose in the world, from its body's. unit: m
[[nodiscard]] std::vector<Eigen::Isometry3d> simulated_link_poses(const WorldState& world,
                                                                  const SimulatedRobot& robot);

// A joint as its two links stand and move now.
struct JointReading {
  double position = 0.0;                            // unit: rad or m
  double speed = 0.0;                               // unit: rad/s or m/s
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // the joint's axis in the world
};

// Joint `joint` of the robot read from its links' bodies; a continuous joint's angle is the
// turn nearest its last position (SimulatedRobot::positions).
[[nodiscard]] JointReading read_robot_joint(const WorldState& world, const SimulatedRobot& robot,
                                            std::size_t joint);

// Before a step of dt (unit: s): every robot joint's motor set from its control, and kTorque's
// torques applied to its links.
void control_robots(WorldState& world, RobotStore& robots, float dt);

// The robot's bodies where the joint values place them, the root's where it stands, all at
// rest and awake. `values`: one per joint, checked by the caller.
void place_robot(WorldState& world, SimulatedRobot& robot, std::span<const double> values);

}  // namespace sphys
