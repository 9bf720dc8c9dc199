// Stage 1 of a substep: the velocities under gravity (the first half of semi-implicit Euler), and
// each moving body's reach in the substep for speculative contacts. The soft step integrates in
// its own substeps (stage 4): here it only bounds the reach, with gravity's speed at the end.

#include <cmath>

#include "core/stopwatch.h"
#include "sphys/world.h"

namespace sphys {

void World::integrate_velocities(float dt, bool plausible, StepStats& stats) {
  const StepClock::time_point start = StepClock::now();
  for (const std::uint32_t i : store_->awake()) {
    if (!integrate_velocity(i, dt, plausible)) {
      stats.non_finite_body = i;
      stopped_ = true;
      return;
    }
  }
  stats.integration_ms += elapsed_ms(start);
}

bool World::integrate_velocity(std::uint32_t body, float dt, bool plausible) {
  const bool soft = soft_step();
  Vec3& linear = store_->linear_velocities()[body];
  // The first half of semi-implicit Euler.
  if (!soft) linear += settings_.gravity * dt;
  if (!plausible) return true;
  const Vec3 gravity_speed = soft ? Vec3(settings_.gravity * dt) : Vec3::Zero();
  const Vec3 displacement = (linear + gravity_speed) * dt;
  const float turn_reach = store_->angular_velocities()[body].norm() * dt * store_->extents()[body];
  // Speeds whose squares overflow single precision leave no bound on the motion to detect
  // with: the simulation has gone non-finite in all but name.
  if (!std::isfinite(displacement.norm()) || !std::isfinite(turn_reach)) return false;
  detector_.set_motion(body, displacement, turn_reach);
  return true;
}

}  // namespace sphys
