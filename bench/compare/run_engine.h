#pragma once

// One run of one engine on the benchmark scene: the step times and what the scene looks like
// during and after it.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine.h"

namespace sphys::compare {

struct RunResult {
  std::vector<double> step_ms;  // wall time of each step call, one per frame run. unit: ms
  bool stopped = false;  // at the time limit, before the frames asked for: step_ms.size() ran
  double contacts_per_step = 0.0;    // mean over the frames run, as the engine counts them
  float deepest = 0.0f;              // engine-reported, over the run. unit: m
  float deepest_last_second = 0.0f;  // over the last second's frames run. unit: m
  // At the end, counted afresh from the poses for every engine alike: the deepest overlap of two
  // bodies' leaf spheres, or of a leaf sphere with the plane. Exact for the engines colliding
  // those spheres; for a convex hull, an over-estimate (the spheres stick out of the mesh).
  // unit: m
  float end_overlap = 0.0f;
  // The largest joint gap: the distance between a joint's two anchor points (each body's, at
  // the poses the engine reports), the worst over the joints and the frames run, and at the
  // end; both 0 without joints. unit: m
  float largest_gap = 0.0f;
  float largest_gap_at_end = 0.0f;
  // A robot's tracking: how far its joints are from their targets after each step (the targets
  // the step was given), the worst over the turning joints and the frames, the mean over them,
  // and the worst of the sliding joints; all 0 without a robot. unit: rad, rad, m
  double largest_turn_error = 0.0;
  double mean_turn_error = 0.0;
  double largest_slide_error = 0.0;
  double kinetic_energy = 0.0;  // at the end, from sphys's mass properties. unit: J
  std::uint32_t moving = 0;     // at the end: |v| + |ω| r_max > 1 cm/s
  std::uint32_t below = 0;      // at the end: centre of mass below y = -0.5 m
  // At the end: the bodies the engine itself reports asleep; nullopt for one without sleeping.
  std::optional<std::uint32_t> asleep;
  std::uint32_t bodies = 0;
  std::uint32_t joints = 0;  // as the engine counts them
  // Resident memory the engine added at its peak (building it and the steps), where the kernel
  // tells. unit: MiB
  std::optional<double> peak_memory_mib;
  std::string warnings;
};

// Builds the engine (not timed), steps it `frames` times timing each step call. With a
// `time_limit` above 0 (unit: s), the run stops after the step that took the summed step times
// over it; "the end" is then that frame.
[[nodiscard]] RunResult run_engine(const std::string& engine, const BenchScene& scene, int frames,
                                   double time_limit = 0.0);

}  // namespace sphys::compare
