// Paper mode's last stage: the positions (the second half of semi-implicit Euler), each body then
// finished; a body whose state stopped being finite stops the world.

#include "core/stopwatch.h"
#include "world/awake_runs.h"
#include "world/finalize_body.h"
#include "world/stages.h"
#include "world/world_state.h"

namespace sphys {

void integrate_positions(PassContext& pass) {
  const PhaseClock clock(&pass.world.parallel);
  WorldState& world = pass.world;
  BodyStore& store = world.store;
  const std::span<Transform> poses = store.poses();
  const std::span<Vec3> linear = store.linear_velocities();
  const std::span<Vec3> angular = store.angular_velocities();
  // Each body its own, on the threads; the first non-finite body in the awake order stops the
  // world.
  const std::uint32_t failed = first_failed_awake_body(
      store.awake(), world.parallel, world.non_finite_in_run, [&](std::uint32_t i) {
        integrate_position(poses[i], linear[i], angular[i], store.inertias_body()[i],
                           store.inverse_inertias_body()[i], pass.pass_dt);
        return finalize_body(world, i);
      });
  clock.add_to(pass.stats.integration_ms, pass.stats.integration_serial_ms);
  if (failed != kNoFailedBody) {
    pass.stats.non_finite_body = failed;
    world.stopped = true;
  }
}

}  // namespace sphys
