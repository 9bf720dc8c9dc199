#pragma once

// A body finished after it moved, once a collision pass: its world inertia at its new pose and its
// fastest point's speed, the one measure of it that the collision passes' count, sleep and the
// rest figures read (BodyStore::fastest_point_speeds).

#include <cstdint>

#include "sphys/body_store.h"

namespace sphys {

// False when the body's state is no longer finite (the world stops); else its speed is measured.
[[nodiscard]] inline bool finalize_body(BodyStore& store, std::uint32_t body) {
  store.update_world_inertia(body);
  if (!store.finite(body)) return false;
  store.measure_fastest_point_speed(body);
  return true;
}

}  // namespace sphys
