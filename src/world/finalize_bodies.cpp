// Plausible mode, after the soft step moved the bodies: each awake body finished once (world
// inertia, finiteness, fastest point speed) and its still time counted for sleep; a body whose
// state stopped being finite stops the world.

#include "core/stopwatch.h"
#include "world/awake_runs.h"
#include "world/finalize_body.h"
#include "world/stages.h"
#include "world/world_state.h"

namespace sphys {

void finalize_bodies(PassContext& pass) {
  const PhaseClock clock(&pass.world.parallel);
  WorldState& world = pass.world;
  BodyStore& store = world.store;
  const SleepSettings& sleep = world.settings.sleep;
  const std::uint32_t failed = first_failed_awake_body(
      store.awake(), world.parallel, world.non_finite_in_run, [&](std::uint32_t i) {
        if (!finalize_body(world, i)) return false;
        world.sleep.count_still_time(i, pass.pass_dt, sleep);
        return true;
      });
  clock.add_to(pass.stats.integration_ms, pass.stats.integration_serial_ms);
  if (failed != kNoFailedBody) {
    pass.stats.non_finite_body = failed;
    world.stopped = true;
  }
}

}  // namespace sphys
