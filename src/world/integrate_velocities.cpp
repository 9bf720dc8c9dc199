// Stage 1 of a substep. Paper mode: the velocities under gravity and the forces applied for the
// step (the first half of semi-implicit Euler). Plausible mode: each moving body's reach in the
// substep for speculative contacts, with gravity's speed at its end; the soft step integrates in
// its own substeps (stage 4).

#include <cmath>

#include "core/stopwatch.h"
#include "sphys/world.h"
#include "world/awake_runs.h"

namespace sphys {

void World::integrate_velocities(float dt, bool plausible, StepStats& stats) {
  const StepClock::time_point start = StepClock::now();
  // A body whose motion is not finite stops the step at the first such in the awake order.
  const std::uint32_t failed = first_failed_awake_body(
      store_->awake(), *parallel_, non_finite_in_run_,
      [&](std::uint32_t body) { return integrate_velocity(body, dt, plausible); });
  if (failed != kNoFailedBody) {
    stats.non_finite_body = failed;
    stopped_ = true;
    return;
  }
  stats.integration_ms += elapsed_ms(start);
}

bool World::integrate_velocity(std::uint32_t body, float dt, bool plausible) {
  Vec3& linear = store_->linear_velocities()[body];
  Vec3& angular = store_->angular_velocities()[body];
  // Gravity, and the force and torque applied for this step where some body has one (most steps
  // have none, and skip the body's inverse inertia).
  Vec3 acceleration = settings_.gravity;
  Vec3 spin_gained = Vec3::Zero();  // unit: rad/s
  if (!store_->forced().empty()) {
    acceleration += store_->inverse_masses()[body] * store_->forces()[body];
    spin_gained = store_->inverse_inertias_world()[body] * store_->torques()[body] * dt;
  }
  if (!plausible) {
    linear += acceleration * dt;  // the first half of semi-implicit Euler
    angular += spin_gained;
    return true;
  }
  const Vec3 displacement = (linear + acceleration * dt) * dt;
  const float turn_reach = (angular + spin_gained).norm() * dt * store_->extents()[body];
  // Speeds whose squares overflow single precision leave no bound on the motion to detect
  // with: the simulation has gone non-finite in all but name.
  if (!std::isfinite(displacement.norm()) || !std::isfinite(turn_reach)) return false;
  detector_->set_motion(body, displacement, turn_reach);
  return true;
}

}  // namespace sphys
