// Stage 5 of a substep: the positions (the second half of semi-implicit Euler) in paper mode; the
// soft step moved the bodies in stage 4. Then each moved body's world inertia, and a body whose
// state stopped being finite stops the world.

#include "core/stopwatch.h"
#include "sphys/world.h"
#include "world/awake_runs.h"

namespace sphys {

void World::integrate_positions(float dt, bool plausible, StepStats& stats) {
  const StepClock::time_point start = StepClock::now();
  BodyStore& store = *store_;
  const std::span<Transform> poses = store.poses();
  const std::span<Vec3> linear = store.linear_velocities();
  const std::span<Vec3> angular = store.angular_velocities();
  // Each body its own, on the threads; the first non-finite body in the awake order stops the
  // world.
  const std::uint32_t failed =
      first_failed_awake_body(store.awake(), *parallel_, non_finite_in_run_, [&](std::uint32_t i) {
        if (!plausible) {
          integrate_position(poses[i], linear[i], angular[i], store.inertias_body()[i],
                             store.inverse_inertias_body()[i], dt);
        }
        store.update_world_inertia(i);
        return store.finite(i);
      });
  stats.integration_ms += elapsed_ms(start);
  if (failed != kNoFailedBody) {
    stats.non_finite_body = failed;
    stopped_ = true;
  }
}

}  // namespace sphys
