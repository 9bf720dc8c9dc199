#pragma once

// Runs rows of the paper's evaluation (§5) headless: the stacks:SxN scene at the row's depth, one
// World::step per frame, every frame's figures kept.

#include <filesystem>
#include <functional>
#include <optional>

#include "sphys/tools/build_world.h"
#include "sphys/tools/experiment.h"
#include "sphys/tools/scene.h"

namespace sphys::tools {

// A frame of a row as the frame callback sees it: the row's scene and world after `frame` steps
// (0: before the first).
struct ExperimentFrame {
  const Scene& scene;            // the row's scene
  const SimulationSetup& setup;  // its world and shapes
  int frame = 0;                 // steps taken
  bool last = false;             // no step follows
};

// How run_experiment_row runs a row.
struct ExperimentOptions {
  int frames = 880;  // the paper's run length
  // The paper's 5-level octree of a thin box (kOctreeBox), or the exact plane (kPlane) to see
  // what the ground's sphere bumps and finite extent do to the results.
  GroundSpec::Kind ground = GroundSpec::Kind::kOctreeBox;
  // The paper's response by default, so that the rows run as published.
  ExperimentMode mode;
  std::optional<std::filesystem::path> cache_dir;  // of built trees (BuildWorldOptions's)
  // Called with the fraction of the row simulated (0..1).
  std::function<void(double)> progress;
  // Called before the first step and after every step: `sphys experiment` draws frames with it
  // (Figure 2, --render). It returns whether it drew the frame; if so, the time it took after a
  // step is that frame's render_ms.
  std::function<bool(const ExperimentFrame&)> on_frame;
};

// Throws sphys::Error for a frame count below 1.
[[nodiscard]] RowResult run_experiment_row(const ExperimentRow& row,
                                           const ExperimentOptions& options);

// Parses --only: comma-separated ids such as "d2-4x25,d3-8x10"; throws sphys::Error naming an
// unknown id and listing the valid ones. Rows come back in the paper's order.
[[nodiscard]] std::vector<ExperimentRow> parse_rows(std::string_view ids);

}  // namespace sphys::tools
