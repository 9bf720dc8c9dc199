#pragma once

// What a run of a scene reports: times and counts gathered frame by frame, the plausibility
// figures, and the bodies' state at the end. `sphys simulate` and the Python module's Simulation
// report the same figures under the same names (the README's `sphys simulate`, docs/python.md).

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "sphys/step_stats.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/experiment.h"
#include "sphys/tools/scene.h"

namespace sphys::tools {

// Totals over the frames that ran, one add() per frame.
struct RunTotals {
  double wall_s = 0.0;          // unit: s
  std::vector<double> step_ms;  // per frame. unit: ms
  // Each phase's time and serial time summed over the frames, by the figure it is (step_figures():
  // the frames CSV's times but the step's), and the steps'. unit: ms
  std::vector<std::pair<const StepFigure*, double>> phases;
  double step = 0;                         // the steps' time summed over the frames. unit: ms
  double contacts = 0;                     // summed over the frames
  std::uint32_t max_contacts = 0;          // in one frame
  double collision_passes = 0;             // summed over the frames
  std::uint32_t max_collision_passes = 0;  // in one frame
  PlausibilityMeter plausibility;          // fed every frame's StepStats
  // The lowest centre of mass of the scene's bodies over the frames. unit: m
  float lowest_center_y = std::numeric_limits<float>::infinity();

  // One frame: its StepStats and the bodies' poses after it.
  void add(const StepStats& stats, const SimulationSetup& setup);
  // A phase's share of the step time. unit: %
  [[nodiscard]] double share(double part) const { return step > 0 ? 100.0 * part / step : 0.0; }
};

// The summary as pretty JSON text (2-space indent), keys in the order `sphys simulate --json`
// prints them; figures a run cannot give (a share without frames) are null.
[[nodiscard]] std::string run_summary_json(const Scene& scene, const SimulationSetup& setup,
                                           const RunTotals& totals);

// "the simulation went non-finite: body 3 (/bodies/3) at frame 120: position (...), velocity
// (...), angular velocity (...)": the diagnostic of a run that stopped, for the world's body at
// `world_index` (StepStats::non_finite_body).
[[nodiscard]] std::string non_finite_message(const SimulationSetup& setup,
                                             std::uint32_t world_index, int frame);

}  // namespace sphys::tools
