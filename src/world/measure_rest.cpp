// The plausibility figures of the bodies at the end of a step (WorldSettings::
// plausibility_figures): kinetic energy, bodies at rest, and how fast the resting ones still move.

#include "collision/collision_detector.h"
#include "sphys/world.h"

namespace sphys {
namespace {

// A body slower than this many times the sleep speed should be resting: its speed is jitter.
constexpr float kSettlingFactor = 10.0f;

}  // namespace

void World::measure_rest(StepStats& stats) {
  touching_.assign(store_->slots(), 0);
  for (const Contact& contact : detector_->contacts()) {
    if (contact.body_a != kGroundPlaneBody) touching_[contact.body_a] = 1;
    touching_[contact.body_b] = 1;
  }
  double jitter_sum = 0.0;
  std::uint32_t resting = 0;
  const std::span<const std::uint8_t> dynamic = store_->dynamic();
  for (std::uint32_t i = 0; i < store_->slots(); ++i) {
    if (dynamic[i] == 0) continue;
    stats.kinetic_energy += store_->kinetic_energy(i);
    if (store_->asleep(i)) {
      ++stats.bodies_at_rest;
      ++resting;
      continue;
    }
    const float speed = store_->fastest_point_speed(i);
    if (speed < settings_.sleep.speed) ++stats.bodies_at_rest;
    if (touching_[i] != 0 && speed < kSettlingFactor * settings_.sleep.speed) {
      jitter_sum += speed;
      ++resting;
    }
  }
  stats.jitter = resting > 0 ? jitter_sum / resting : 0.0;
}

}  // namespace sphys
