#pragma once

// The world's robots (sphys/robot_world.h): a slot per robot with its generation (as the joint
// store's), each holding its model, the bodies and joints it was made of, where each link lies
// on its body, and its joints' controls.

#include <cstdint>
#include <utility>
#include <vector>

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

class RobotStore final : public RobotsInWorld {
 public:
  // Takes a free slot for `robot`, alive from now on.
  RobotId add(SimulatedRobot robot);
  void remove(std::uint32_t slot);
  // True for a robot in the world; false for a stale or unknown id, or the null one.
  [[nodiscard]] bool alive(RobotId id) const {
    return id.index < robots_.size() && generation_[id.index] == id.generation &&
           robots_[id.index].alive;
  }
  [[nodiscard]] SimulatedRobot& at(std::uint32_t slot) { return robots_[slot]; }
  [[nodiscard]] const SimulatedRobot& at(std::uint32_t slot) const { return robots_[slot]; }
  // Every slot's robot, dead ones included (SimulatedRobot::alive).
  [[nodiscard]] std::vector<SimulatedRobot>& all() { return robots_; }
  // The world's robots through its face (world/robots_in_world.h): control_robots, the live
  // robots' allowed_link_pairs as body pairs, and whether a live robot is made of the body.
  void before_step(WorldState& world, float dt) override;
  void append_unpaired(std::vector<std::pair<std::uint32_t, std::uint32_t>>& out) const override;
  [[nodiscard]] bool holds(BodyId body) const override;

 private:
  std::vector<SimulatedRobot> robots_;
  std::vector<std::uint32_t> generation_;
  std::vector<std::uint32_t> free_;
};

}  // namespace sphys
