// The plausibility figures of the bodies at the end of a step (WorldSettings::
// plausibility_figures): kinetic energy, bodies at rest, and how fast the resting ones still move.

#include "world/stages.h"
#include "world/world_state.h"

namespace sphys {
namespace {

// A body slower than this many times the sleep speed should be resting: its speed is jitter.
constexpr float kSettlingFactor = 10.0f;

}  // namespace

void measure_rest(WorldState& world, StepStats& stats) {
  const BodyStore& store = world.store;
  world.touching.assign(store.slots(), 0);
  for (const Contact& contact : world.detector.contacts()) {
    if (contact.body_a != kGroundPlaneBody) world.touching[contact.body_a] = 1;
    world.touching[contact.body_b] = 1;
  }
  double jitter_sum = 0.0;
  std::uint32_t resting = 0;
  const std::span<const std::uint8_t> dynamic = store.dynamic();
  const float sleep_speed = world.settings.sleep.speed;
  for (std::uint32_t i = 0; i < store.slots(); ++i) {
    if (dynamic[i] == 0) continue;
    stats.kinetic_energy += store.kinetic_energy(i);
    if (store.asleep(i)) {
      ++stats.bodies_at_rest;
      ++resting;
      continue;
    }
    const float speed = store.fastest_point_speeds()[i];
    if (speed < sleep_speed) ++stats.bodies_at_rest;
    if (world.touching[i] != 0 && speed < kSettlingFactor * sleep_speed) {
      jitter_sum += speed;
      ++resting;
    }
  }
  stats.jitter = resting > 0 ? jitter_sum / resting : 0.0;
}

}  // namespace sphys
