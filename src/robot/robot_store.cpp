#include "robot/robot_store.h"

#include <algorithm>

#include "robot/robot_control.h"

namespace sphys {

bool RobotStore::holds(BodyId body) const {
  return std::ranges::any_of(all(), [&](const SimulatedRobot& robot) {
    return robot.alive && std::ranges::find(robot.bodies, body) != robot.bodies.end();
  });
}

void RobotStore::before_step(WorldState& world, float dt) { control_robots(world, *this, dt); }

void RobotStore::append_unpaired(
    std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) const {
  for (const SimulatedRobot& robot : all()) {
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
