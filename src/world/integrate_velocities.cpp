// Stage 1 of a substep. Paper mode: the velocities under gravity (the first half of semi-implicit
// Euler). Plausible mode: each moving body's reach in the substep for speculative contacts, with
// gravity's speed at its end; the soft step integrates in its own substeps (stage 4).

#include <cmath>

#include "core/buffers.h"
#include "core/stopwatch.h"
#include "sphys/world.h"

namespace sphys {
namespace {

// Awake bodies per item of the threaded loop. unit: bodies
constexpr std::size_t kBodiesPerRun = 256;
// No body: a run whose bodies' motions were all finite.
constexpr std::uint32_t kNoBody = ~std::uint32_t{0};

}  // namespace

void World::integrate_velocities(float dt, bool plausible, StepStats& stats) {
  const StepClock::time_point start = StepClock::now();
  // In runs of bodies on the threads, each body its own; a run that meets a body whose motion is
  // not finite notes the first such, and the step stops at the first of all in the awake order.
  const std::span<const std::uint32_t> awake = store_->awake();
  const std::size_t runs = (awake.size() + kBodiesPerRun - 1) / kBodiesPerRun;
  fill_buffer(non_finite_in_run_, runs, kNoBody);
  parallel_->for_each_run(awake.size(), kBodiesPerRun, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      if (integrate_velocity(awake[k], dt, plausible)) continue;
      non_finite_in_run_[begin / kBodiesPerRun] = awake[k];
      return;
    }
  });
  for (const std::uint32_t body : non_finite_in_run_) {
    if (body == kNoBody) continue;
    stats.non_finite_body = body;
    stopped_ = true;
    return;
  }
  stats.integration_ms += elapsed_ms(start);
}

bool World::integrate_velocity(std::uint32_t body, float dt, bool plausible) {
  Vec3& linear = store_->linear_velocities()[body];
  if (!plausible) {
    linear += settings_.gravity * dt;  // the first half of semi-implicit Euler
    return true;
  }
  const Vec3 displacement = (linear + settings_.gravity * dt) * dt;
  const float turn_reach = store_->angular_velocities()[body].norm() * dt * store_->extents()[body];
  // Speeds whose squares overflow single precision leave no bound on the motion to detect
  // with: the simulation has gone non-finite in all but name.
  if (!std::isfinite(displacement.norm()) || !std::isfinite(turn_reach)) return false;
  detector_->set_motion(body, displacement, turn_reach);
  return true;
}

}  // namespace sphys
