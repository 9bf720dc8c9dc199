// Stage 5 of a substep: the positions (the second half of semi-implicit Euler) and, in plausible
// mode, the split-impulse penetration recovery (the soft step moved the bodies in stage 4); then
// the detector gets the new poses, and a body whose state stopped being finite stops the world.

#include <cmath>

#include "core/stopwatch.h"
#include "dynamics/contact_solver.h"
#include "sphys/world.h"

namespace sphys {

void World::integrate_positions(float dt, bool plausible, StepStats& stats) {
  const StepClock::time_point start = StepClock::now();
  const bool integrate = !soft_step();
  for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
    if (moving_[i] == 0) continue;
    RigidBody& body = bodies_[i];
    if (integrate) integrate_position(body, dt);
    if (integrate && plausible) {
      correct_position(body, solver_->position_linear()[i], solver_->position_angular()[i], dt);
    }
    detector_.set_pose({i}, body.pose);
  }
  stats.integration_ms += elapsed_ms(start);
  for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
    if (moving_[i] == 0) continue;
    const RigidBody& body = bodies_[i];
    // A quaternion with huge coefficients normalises to zero (its norm overflows), finite but no
    // rotation: that is the same failure.
    if (!body.finite() ||
        !(std::abs(body.pose.rotation.squaredNorm() - 1.0f) < kUnitQuaternionTolerance)) {
      stats.non_finite_body = i;
      stopped_ = true;
      return;
    }
  }
}

}  // namespace sphys
