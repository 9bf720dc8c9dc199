#pragma once

// Robots simulated in a world (World::add_robot, docs/robots.md): a RobotModel's links as bodies,
// its joints as the world's joints, each joint driven by position, velocity or torque control.

#include <cstdint>
#include <limits>
#include <vector>

#include "sphys/slot_id.h"

namespace sphys {

// RobotId's kind (SlotId's tag): declared only, never defined.
struct RobotTag;

// A robot of a world: its slot in the world's robots and the slot's generation (SlotId).
// RobotId{} names no robot.
using RobotId = SlotId<RobotTag>;

// How a robot's root link stands in the world.
enum class RobotBase : std::uint8_t {
  kFixed,  // a static body where it was added: an arm bolted down
  kFree,   // a body like the others: a robot that falls, is pushed and topples
};

// What drives a joint of a simulated robot.
enum class RobotControlMode : std::uint8_t {
  // PyBullet's POSITION_CONTROL law (btMultiBodyJointMotor): a motor whose speed each step is
  // position_gain · (target_position − q) / dt + q̇ + velocity_gain · (target_velocity − q̇),
  // at most the joint's velocity bound, with at most its effort: an implicit PD servo that
  // holds against gravity with no steady error and never exceeds the URDF's effort.
  kPosition,
  kVelocity,  // a motor driving the joint to target_velocity, with at most the effort
  kTorque,    // `torque` applied between the two links (at most the effort), no motor
};

// One joint's control, in the model's joint order (World::set_robot_controls). The default is
// torque control with no torque: a limp joint.
struct RobotJointControl {
  RobotControlMode mode = RobotControlMode::kTorque;  // which of the fields below count
  double target_position = 0.0;                       // kPosition. unit: rad or m
  // kPosition's desired speed (a trajectory's feed-forward), kVelocity's target. unit: rad/s
  // or m/s
  double target_velocity = 0.0;
  // kPosition: the share of the position error closed in one step, 0..1 (PyBullet's
  // positionGain). unit: dimensionless
  double position_gain = 0.2;
  // kPosition: the share of the speed error closed in one step, 0..1 (PyBullet's
  // velocityGain). unit: dimensionless
  double velocity_gain = 1.0;
  double torque = 0.0;  // kTorque, clamped to the effort. unit: N·m or N
  // The most the joint applies; infinite: the model's Joint::effort (the URDF's). > 0. unit:
  // N·m or N
  double max_effort = std::numeric_limits<double>::infinity();
};

// A simulated robot's joints as of the last step (or the last set_robot_configuration), each
// array in the model's joint order.
struct RobotJointStates {
  std::vector<double> positions;  // from the links' poses. unit: rad or m
  std::vector<double> speeds;     // from the links' velocities. unit: rad/s or m/s
  // The torque or force the joint applied along its axis in the last step (motor, limits, and
  // kTorque's torque), on the moved link. unit: N·m or N
  std::vector<double> efforts;
};

}  // namespace sphys
