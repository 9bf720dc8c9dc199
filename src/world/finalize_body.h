#pragma once

// A body finished after it moved, once a collision pass: its world inertia at its new pose, its
// bound there for the next detection (CollisionDetector::bound_at_pose), and its fastest point's
// speed, the one measure of it that the collision passes' count, sleep and the rest figures read
// (BodyStore::fastest_point_speeds).

#include <cstdint>

#include "world/world_state.h"

namespace sphys {

// False when the body's state is no longer finite (the world stops); else its speed is measured.
[[nodiscard]] inline bool finalize_body(WorldState& world, std::uint32_t body) {
  BodyStore& store = world.store;
  store.update_world_inertia(body);
  if (!store.finite(body)) return false;
  world.detector.bound_at_pose(body);
  store.measure_fastest_point_speed(body);
  return true;
}

}  // namespace sphys
