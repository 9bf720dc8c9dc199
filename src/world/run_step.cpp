// A step: its collision passes, each its pipeline's stages in order, then the step's own
// figures.

#include "core/stopwatch.h"
#include "world/pipeline.h"
#include "world/stages.h"
#include "world/world_state.h"

namespace sphys {

StepStats run_step(WorldState& world, float dt) {
  const PhaseClock step_clock(&world.parallel);
  StepStats stats;
  const Pipeline& pipeline = *world.pipeline;
  const std::uint32_t passes = pipeline.collision_passes(world, dt);
  stats.collision_passes = passes;
  PassContext pass{world, stats, dt / static_cast<float>(passes)};
  if (pipeline.start_step != nullptr) pipeline.start_step(world, stats);
  for (std::uint32_t i = 0; i < passes && !world.stopped; ++i) {
    for (const Stage& stage : pipeline.pass) {
      stage.run(pass);
      if (world.stopped) break;
    }
  }
  world.store.clear_forces();
  stats.movable_bodies = world.store.dynamic_bodies();
  stats.bodies_asleep =
      stats.movable_bodies - static_cast<std::uint32_t>(world.store.awake().size());
  if (world.settings.plausibility_figures) measure_rest(world, stats);
  const PhaseTime spent = step_clock.elapsed();
  stats.step_ms = spent.ms;
  stats.serial_ms = spent.serial_ms;
  return stats;
}

}  // namespace sphys
