// Plausible mode's first stage: how far each awake body may move in the collision pass, for
// speculative contacts, with the speed gravity and the applied forces give it by the pass's end.
// The soft step integrates the velocities in its own substeps (world/solve_contacts.cpp).

#include <cmath>

#include "core/stopwatch.h"
#include "world/applied_forces.h"
#include "world/awake_runs.h"
#include "world/stages.h"

namespace sphys {

bool bound_body_motion(WorldState& world, std::uint32_t body, float pass_dt) {
  const AppliedForces applied = applied_forces(world, body, pass_dt);
  const Vec3 displacement =
      (world.store.linear_velocities()[body] + applied.acceleration * pass_dt) * pass_dt;
  const float turn_reach = (world.store.angular_velocities()[body] + applied.spin_gained).norm() *
                           pass_dt * world.store.extents()[body];
  // Speeds whose squares overflow single precision leave no bound on the motion to detect
  // with: the simulation has gone non-finite in all but name.
  if (!std::isfinite(displacement.norm()) || !std::isfinite(turn_reach)) return false;
  world.detector.set_motion(body, displacement, turn_reach);
  return true;
}

void bound_motion(PassContext& pass) {
  const PhaseClock clock(&pass.world.parallel);
  WorldState& world = pass.world;
  // A body whose motion is not finite stops the step at the first such in the awake order.
  const std::uint32_t failed = first_failed_awake_body(
      world.store.awake(), world.parallel, world.non_finite_in_run,
      [&](std::uint32_t body) { return bound_body_motion(world, body, pass.pass_dt); });
  if (failed != kNoFailedBody) {
    pass.stats.non_finite_body = failed;
    world.stopped = true;
    return;
  }
  clock.add_to(pass.stats.integration_ms, pass.stats.integration_serial_ms);
}

}  // namespace sphys
