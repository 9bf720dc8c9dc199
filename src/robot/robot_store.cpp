#include "robot/robot_store.h"

#include <algorithm>

#include "robot/robot_control.h"

namespace sphys {

RobotId RobotStore::add(SimulatedRobot robot) {
  std::uint32_t slot = 0;
  if (free_.empty()) {
    slot = static_cast<std::uint32_t>(robots_.size());
    robots_.emplace_back();
    generation_.push_back(0);
  } else {
    slot = free_.back();
    free_.pop_back();
  }
  robots_[slot] = std::move(robot);
  robots_[slot].alive = true;
  ++generation_[slot];  // from 1: the null id's generation 0 names no robot
  return {slot, generation_[slot]};
}

void RobotStore::remove(std::uint32_t slot) {
  robots_[slot] = SimulatedRobot{};
  free_.push_back(slot);
}

bool RobotStore::holds(BodyId body) const {
  return std::ranges::any_of(robots_, [&](const SimulatedRobot& robot) {
    return robot.alive && std::ranges::find(robot.bodies, body) != robot.bodies.end();
  });
}

void RobotStore::before_step(WorldState& world, float dt) { control_robots(world, *this, dt); }

void RobotStore::append_unpaired(
    std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) const {
  for (const SimulatedRobot& robot : robots_) {
    if (!robot.alive) continue;
    for (const auto& [a, b] : robot.model.allowed_link_pairs) {
      const std::uint32_t body_a = robot.link_body[static_cast<std::size_t>(a)];
      const std::uint32_t body_b = robot.link_body[static_cast<std::size_t>(b)];
      if (body_a != body_b) {
        pairs.emplace_back(robot.bodies[body_a].index, robot.bodies[body_b].index);
      }
    }
  }
}

}  // namespace sphys
