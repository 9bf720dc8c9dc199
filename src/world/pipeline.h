#pragma once

// A step as its mode's pipeline runs it: a number of collision passes, each the same list of
// named stages in order (docs/architecture.md gives each its line). The mode is chosen once per
// world (WorldState::pipeline); no stage asks which it is in.

#include <cstdint>
#include <span>
#include <string_view>

#include "sphys/step_stats.h"
#include "sphys/world.h"

namespace sphys {

struct WorldState;

// What every stage of a collision pass works with. A stage adds its figures to the step's:
// times and counts summed over the passes, extremes kept.
struct PassContext {
  WorldState& world;
  StepStats& stats;
  float pass_dt;  // the collision pass's share of the step. unit: s
};

struct Stage {
  std::string_view name;
  // Sets WorldState::stopped where a body's state stops being finite; the pass ends there.
  void (*run)(PassContext& pass);
};

struct Pipeline {
  // How many collision passes a step of `dt` (unit: s) runs.
  std::uint32_t (*collision_passes)(const WorldState& world, float dt);
  // Once a step, before its collision passes; null for none.
  void (*start_step)(WorldState& world, StepStats& stats);
  // Each collision pass's stages, in order.
  std::span<const Stage> pass;
};

// The paper's: per contact, eq. 4 in order; semi-implicit Euler (world/paper_pipeline.cpp).
[[nodiscard]] const Pipeline& paper_pipeline();
// Speculative contacts, the soft step, sleep (world/plausible_pipeline.cpp).
[[nodiscard]] const Pipeline& plausible_pipeline();

// Advances the world by dt (unit: s, checked by the caller) through its pipeline and returns the
// step's figures (world/run_step.cpp).
[[nodiscard]] StepStats run_step(WorldState& world, float dt);

}  // namespace sphys
