// sphys's step: the motion bounded for speculative contacts, detection, waking, the soft step,
// each body finished, sleep. More collision passes in a step where bodies move fast.

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include "core/stopwatch.h"
#include "world/awake_runs.h"
#include "world/pipeline.h"
#include "world/stages.h"
#include "world/world_state.h"

namespace sphys {
namespace {

constexpr auto kPlausiblePass = std::to_array<Stage>({
    {"bound the motion", bound_motion},
    {"detect", detect_contacts},
    {"wake the touched", wake_touched},
    {"solve", solve_contacts},
    {"finalize bodies", finalize_bodies},
    {"sleep", update_sleep},
});

// Enough passes that no moving body's fastest point travels more than collision_pass_travel of
// its extent in one (WorldSettings::max_collision_passes).
std::uint32_t adaptive_collision_passes(const WorldState& world, float dt) {
  const WorldSettings& settings = world.settings;
  const std::uint32_t fewest = settings.collision_passes;
  const std::uint32_t most = std::max(fewest, settings.max_collision_passes);
  if (most == fewest) return fewest;
  // The speed at the end of the step under gravity alone, an upper bound for a falling body.
  const float gravity_speed = settings.gravity.norm() * dt;
  const std::span<const float> extents = world.store.extents();
  const std::span<const float> speeds = world.store.fastest_point_speeds();
  const std::span<const std::uint32_t> awake = world.store.awake();
  // Collision passes, fractional: the largest of the runs' largest, the same whichever thread
  // finds which.
  std::atomic<float> needed{0.0f};
  world.parallel.for_each_run(
      awake.size(), kAwakeBodiesPerRun, [&](std::size_t begin, std::size_t end) {
        float run_needed = 0.0f;
        for (std::size_t k = begin; k < end; ++k) {
          const std::uint32_t i = awake[k];
          // A crowded body's pairs are overlaps served at its root (CollisionSettings::
          // crowd_pairs_per_body): there is nothing for it to pass through unseen, and a crowd
          // parting would otherwise run every pass of the step for all its bodies.
          if (!(extents[i] > 0.0f) || world.detector.crowded(i)) continue;
          const float travel = (speeds[i] + gravity_speed) * dt;
          run_needed = std::max(run_needed, travel / (settings.collision_pass_travel * extents[i]));
        }
        float seen = needed.load(std::memory_order_relaxed);
        while (seen < run_needed && !needed.compare_exchange_weak(seen, run_needed)) {
        }
      });
  // A non-finite speed is left to the step to find and report.
  const float passes = needed.load();
  if (!(passes <= static_cast<float>(most))) return passes > 0.0f ? most : fewest;
  return std::clamp(static_cast<std::uint32_t>(std::ceil(passes)), fewest, most);
}

// Islands whose bodies parted in the last step are built afresh, once a step.
void split_islands(WorldState& world, StepStats& stats) {
  const PhaseClock clock(&world.parallel);
  world.sleep.split_islands(world.detector.contacts());
  clock.add_to(stats.sleep_ms, stats.sleep_serial_ms);
}

constexpr Pipeline kPlausible{
    .collision_passes = adaptive_collision_passes,
    .start_step = split_islands,
    .pass = kPlausiblePass,
};

}  // namespace

const Pipeline& plausible_pipeline() { return kPlausible; }

}  // namespace sphys
