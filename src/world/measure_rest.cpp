// The plausibility figures of the bodies at the end of a step (WorldSettings::
// plausibility_figures): kinetic energy, bodies at rest, and how fast the resting ones still move.

#include <atomic>

#include "core/buffers.h"
#include "world/stages.h"
#include "world/world_state.h"

namespace sphys {
namespace {

// A body slower than this many times the sleep speed should be resting: its speed is jitter.
constexpr float kSettlingFactor = 10.0f;

// Contacts or body slots per item of the threaded loops. unit: items
constexpr std::size_t kItemsPerRun = 256;

}  // namespace

void measure_rest(WorldState& world, StepStats& stats) {
  const BodyStore& store = world.store;
  const Parallel& parallel = world.parallel;
  fill_buffer(world.touching, store.slots(), std::uint8_t{0});
  const std::span<const Contact> contacts = world.detector.contacts();
  parallel.for_each_run(contacts.size(), kItemsPerRun, [&](std::size_t begin, std::size_t end) {
    const auto touch = [&](std::uint32_t body) {
      std::atomic_ref<std::uint8_t>(world.touching[body]).store(1, std::memory_order_relaxed);
    };
    for (std::size_t k = begin; k < end; ++k) {
      if (contacts[k].body_a != kGroundPlaneBody) touch(contacts[k].body_a);
      touch(contacts[k].body_b);
    }
  });
  // Each run's sums, added up in the runs' order: the same figures whatever the thread count.
  const std::span<const std::uint8_t> dynamic = store.dynamic();
  const float sleep_speed = world.settings.sleep.speed;
  resize_buffer(world.rest_sums, (store.slots() + kItemsPerRun - 1) / kItemsPerRun);
  parallel.for_each_run(store.slots(), kItemsPerRun, [&](std::size_t begin, std::size_t end) {
    RestSums sums;
    for (std::size_t k = begin; k < end; ++k) {
      const auto i = static_cast<std::uint32_t>(k);
      if (dynamic[i] == 0) continue;
      sums.kinetic_energy += store.kinetic_energy(i);
      if (store.asleep(i)) {
        ++sums.at_rest;
        ++sums.resting;
        continue;
      }
      const float speed = store.fastest_point_speeds()[i];
      if (speed < sleep_speed) ++sums.at_rest;
      if (world.touching[i] != 0 && speed < kSettlingFactor * sleep_speed) {
        sums.jitter += speed;
        ++sums.resting;
      }
    }
    world.rest_sums[begin / kItemsPerRun] = sums;
  });
  RestSums all;
  for (const RestSums& sums : world.rest_sums) {
    all.kinetic_energy += sums.kinetic_energy;
    all.jitter += sums.jitter;
    all.at_rest += sums.at_rest;
    all.resting += sums.resting;
  }
  stats.kinetic_energy += all.kinetic_energy;
  stats.bodies_at_rest += all.at_rest;
  stats.jitter = all.resting > 0 ? all.jitter / all.resting : 0.0;
}

}  // namespace sphys
