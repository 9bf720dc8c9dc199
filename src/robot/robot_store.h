#pragma once

// The world's robots (sphys/robot_world.h): a slot per robot with its generation
// (core/slot_store.h), each holding its model, the bodies and joints it was made of, where each
// link lies on its body, and its joints' controls.

#include <cstdint>
#include <utility>
#include <vector>

#include "core/slot_store.h"
#include "sphys/body_id.h"
#include "sphys/joint.h"
#include "sphys/robot_model.h"
#include "sphys/robot_world.h"
#include "world/robots_in_world.h"

namespace sphys {

struct SimulatedRobot {
  RobotModel model;  // as added, its base where the root link's body was put
  RobotBase base = RobotBase::kFixed;
  // The robot's bodies: [0] carries the root link, [j + 1] the link model joint j moves; each
  // with the links fixed to it.
  std::vector<BodyId> bodies;
  std::vector<JointId> joints;  // one per model joint
  // Per link: the body (index into `bodies`) it rides on, and its frame in that body's frame
  // (whose origin is the body's centre of mass, its axes those of the body's own link). unit: m
  std::vector<std::uint32_t> link_body;
  std::vector<Eigen::Isometry3d> link_in_body;
  std::vector<RobotJointControl> controls;  // one per model joint
  // Per joint: kTorque's torque as applied in the last step. unit: N·m or N
  std::vector<double> applied;
  // Per joint: the last position read, which a continuous joint's angle is unwrapped near.
  // unit: rad or m
  std::vector<double> positions;
  bool alive = false;
};

class RobotStore final : public RobotsInWorld, public SlotStore<RobotId, SimulatedRobot> {
 public:
  // The world's robots through its face (world/robots_in_world.h): control_robots, the live
  // robots' allowed_link_pairs as body pairs, and whether a live robot is made of the body.
  void before_step(WorldState& world, float dt) override;
  void append_unpaired(std::vector<std::pair<std::uint32_t, std::uint32_t>>& out) const override;
  [[nodiscard]] bool holds(BodyId body) const override;
};

}  // namespace sphys
