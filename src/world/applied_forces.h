#pragma once

// What acts on a body through a collision pass beside its contacts: gravity, and the force and
// torque applied for the step (World::apply_force, apply_torque).

#include <cstdint>

#include "sphys/math.h"
#include "world/world_state.h"

namespace sphys {

struct AppliedForces {
  Vec3 acceleration;  // unit: m/s²
  Vec3 spin_gained;   // over the pass. unit: rad/s
};

// Where no body has a force (most steps) the body's inverse inertia is not touched.
inline AppliedForces applied_forces(const WorldState& world, std::uint32_t body, float pass_dt) {
  AppliedForces applied{world.settings.gravity, Vec3::Zero()};
  const BodyStore& store = world.store;
  if (!store.forced().empty()) {
    applied.acceleration += store.inverse_masses()[body] * store.forces()[body];
    applied.spin_gained = store.inverse_inertias_world()[body] * store.torques()[body] * pass_dt;
  }
  return applied;
}

}  // namespace sphys
