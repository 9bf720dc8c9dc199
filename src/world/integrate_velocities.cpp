// Stage 1 of a substep: the velocities under gravity (the first half of semi-implicit Euler), and
// each moving body's reach in the substep for speculative contacts. The soft step integrates in
// its own substeps (stage 4): here it only bounds the reach, with gravity's speed at the end.

#include <cmath>

#include "core/stopwatch.h"
#include "sphys/world.h"

namespace sphys {

void World::integrate_velocities(float dt, bool plausible, StepStats& stats) {
  const StepClock::time_point start = StepClock::now();
  const bool soft = soft_step();
  const Vec3 gravity_speed = soft ? Vec3(settings_.gravity * dt) : Vec3::Zero();
  const std::span<Vec3> linear = store_->linear_velocities();
  const std::span<const Vec3> angular = store_->angular_velocities();
  const std::span<const float> extents = store_->extents();
  for (const std::uint32_t i : store_->awake()) {
    // The first half of semi-implicit Euler.
    if (!soft) linear[i] += settings_.gravity * dt;
    if (plausible) {
      const Vec3 displacement = (linear[i] + gravity_speed) * dt;
      const float turn_reach = angular[i].norm() * dt * extents[i];
      // Speeds whose squares overflow single precision leave no bound on the motion to detect
      // with: the simulation has gone non-finite in all but name.
      if (!std::isfinite(displacement.norm()) || !std::isfinite(turn_reach)) {
        stats.non_finite_body = i;
        stopped_ = true;
        return;
      }
      detector_.set_motion(i, displacement, turn_reach);
    }
  }
  stats.integration_ms += elapsed_ms(start);
}

}  // namespace sphys
