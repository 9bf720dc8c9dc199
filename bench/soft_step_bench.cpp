// The soft step's solver on a settled pile: its contacts solved for one whole step (4 substeps of
// a solve and a relax pass each, with the warm start, the integration and the restitution
// between), from the same state every iteration. Reported: ns per contact point per pass, passes
// being the solve and relax passes (8 a step), the way StepStats::response_passes counts them;
// everything else the solver does in the step is inside the time. Arguments: the lanes
// (SolverLanes: 1 plain floats, 2 SSE2, 3 AVX2; every one gives the same bits) and the threads.

#include <cstdint>
#include <vector>

#include <benchmark/benchmark.h>

#include "dynamics/contact_lanes.h"
#include "dynamics/soft_step_solver.h"
#include "sphys/error.h"
#include "sphys/material.h"
#include "sphys/parallel.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/scenarios.h"
#include "sphys/world.h"

namespace {

using namespace sphys;

constexpr std::uint32_t kSubsteps = 4;
constexpr std::uint32_t kPassesPerStep = 2 * kSubsteps;  // a solve and a relax per substep

// 1,000 bunnies (stacks:100x10, depth 2, on the plane) stepped until they lie still, kept awake
// (sleep off) so that every contact is solved; the bodies, contacts and materials of the last
// step, and the warm start the solver converged to on them.
struct SettledPile {
  WorldSettings settings;
  BodyStore bodies;
  std::vector<Contact> contacts;
  std::vector<PairMaterial> materials;
  std::vector<ContactMemory> memory;
};

const SettledPile& settled_pile() {
  static const SettledPile pile = [] {
    tools::Scene scene = tools::bunny_stacks_scene(100, 10, 2);
    scene.ground.kind = tools::GroundSpec::Kind::kPlane;
    scene.sleep.enabled = false;
    const tools::SimulationSetup setup = tools::build_world(scene, {});
    World& world = *setup.world;
    for (int frame = 0; frame < 600; ++frame) world.step(static_cast<float>(scene.time_step));
    SettledPile p{world.settings(),
                  world.bodies(),
                  {world.contacts().begin(), world.contacts().end()},
                  {},
                  {}};
    const std::span<const float> friction = p.bodies.frictions();
    const std::span<const float> restitution = p.bodies.restitutions();
    for (const Contact& c : p.contacts) {
      const bool ground = c.body_a == kGroundPlaneBody;
      const float fa = ground ? p.settings.ground_friction : friction[c.body_a];
      const float ra = ground ? p.settings.ground_restitution : restitution[c.body_a];
      p.materials.push_back(
          {mix_friction(fa, friction[c.body_b]), mix_restitution(ra, restitution[c.body_b])});
    }
    // The warm start: steps solved from the same state until the kept impulses settle.
    p.memory.assign(p.contacts.size(), ContactMemory{});
    SoftStepSolver solver;
    const Parallel one;
    for (int i = 0; i < 30; ++i) {
      BodyStore bodies = p.bodies;
      solver.solve(bodies, p.contacts, p.memory, p.materials,
                   SoftStepContext(p.settings.solver, p.settings.gravity,
                                   static_cast<float>(scene.time_step), kSubsteps, one));
    }
    return p;
  }();
  return pile;
}

void soft_step_solver(benchmark::State& state) {
  const SettledPile& pile = settled_pile();
  SoftStepSolver solver;
  const auto lanes = static_cast<SolverLanes>(state.range(0));
  try {
    solver.use_lanes(resolve_solver_lanes(lanes));
  } catch (const Error& error) {
    state.SkipWithError(error.what());
    return;
  }
  const Parallel parallel(static_cast<std::uint32_t>(state.range(1)));
  BodyStore bodies = pile.bodies;
  std::vector<ContactMemory> memory = pile.memory;
  SoftStepStats stats;
  for (auto _ : state) {
    state.PauseTiming();
    bodies = pile.bodies;
    memory = pile.memory;
    state.ResumeTiming();
    stats = solver.solve(bodies, pile.contacts, memory, pile.materials,
                         SoftStepContext(pile.settings.solver, pile.settings.gravity, 1.0f / 60.0f,
                                         kSubsteps, parallel));
    benchmark::ClobberMemory();
  }
  state.counters["contact_points"] = stats.contacts_solved;
  // Seconds per contact point per pass (shown with an SI prefix, "n" for ns).
  state.counters["time_per_point_pass"] = benchmark::Counter(
      static_cast<double>(stats.contacts_solved) * kPassesPerStep,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(soft_step_solver)
    ->ArgNames({"lanes", "threads"})
    ->Args({static_cast<int>(SolverLanes::kAvx2), 1})
    ->Args({static_cast<int>(SolverLanes::kSse2), 1})
    ->Args({static_cast<int>(SolverLanes::kPortable), 1})
    ->Args({static_cast<int>(SolverLanes::kAvx2), 2})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

}  // namespace
