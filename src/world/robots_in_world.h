#pragma once

// What a world asks of the robots simulated in it (World::add_robot). The robots themselves, their
// models and control, are the robot layer's (src/robot/robot_store.h), above the world's: the
// world holds them through this face, made when the first robot is added.

#include <cstdint>
#include <utility>
#include <vector>

#include "sphys/body_id.h"

namespace sphys {

struct WorldState;

class RobotsInWorld {
 public:
  RobotsInWorld() = default;
  RobotsInWorld(const RobotsInWorld&) = delete;
  RobotsInWorld& operator=(const RobotsInWorld&) = delete;
  virtual ~RobotsInWorld() = default;
  // Before a step of dt (unit: s): every robot joint's motor set from its control, and the
  // torques of torque control applied to its links.
  virtual void before_step(WorldState& world, float dt) = 0;
  // Appends the body pairs (store slots) the robots' allowed link pairs keep apart.
  virtual void append_unpaired(std::vector<std::pair<std::uint32_t, std::uint32_t>>& out) const = 0;
  // Whether a robot is made of the body.
  [[nodiscard]] virtual bool holds(BodyId body) const = 0;
};

}  // namespace sphys
