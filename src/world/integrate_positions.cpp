// Stage 5 of a substep: the positions (the second half of semi-implicit Euler) in paper mode; the
// soft step moved the bodies in stage 4. Then each moved body's world inertia, and a body whose
// state stopped being finite stops the world.

#include "core/stopwatch.h"
#include "sphys/world.h"

namespace sphys {

void World::integrate_positions(float dt, bool plausible, StepStats& stats) {
  const StepClock::time_point start = StepClock::now();
  BodyStore& store = *store_;
  const std::span<Transform> poses = store.poses();
  const std::span<Vec3> linear = store.linear_velocities();
  const std::span<Vec3> angular = store.angular_velocities();
  for (const std::uint32_t i : store.awake()) {
    if (!plausible) {
      integrate_position(poses[i], linear[i], angular[i], store.inertias_body()[i],
                         store.inverse_inertias_body()[i], dt);
    }
    store.update_world_inertia(i);
  }
  stats.integration_ms += elapsed_ms(start);
  for (const std::uint32_t i : store.awake()) {
    if (!store.finite(i)) {
      stats.non_finite_body = i;
      stopped_ = true;
      return;
    }
  }
}

}  // namespace sphys
