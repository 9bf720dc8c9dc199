#include "sphys/tools/run_experiment.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <string>

#include "sphys/error.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/scenarios.h"

namespace sphys::tools {

RowResult run_experiment_row(const ExperimentRow& row, const ExperimentOptions& options) {
  if (options.frames < 1) {
    throw Error("the experiment needs at least 1 frame, got " + std::to_string(options.frames));
  }
  Scene scene = bunny_stacks_scene(row.stacks, row.per_stack, row.depth);
  scene.ground.kind = options.ground;
  scene.response = options.mode.response;
  scene.solver.contacts = options.mode.contacts;
  BuildWorldOptions build;
  build.tree_depth = row.depth;
  build.cache_dir = options.cache_dir;
  build.plausibility_figures = true;
  SimulationSetup setup = build_world(scene, build);
  World& world = *setup.world;

  RowResult result;
  result.row = row;
  result.tree_builder = setup.shapes.front().tree_source;
  result.ground = scene.ground.kind == GroundSpec::Kind::kPlane
                      ? "exact plane"
                      : "octree of a " + std::to_string(static_cast<int>(scene.ground.size)) +
                            " m box, " + std::to_string(scene.ground.depth) + " levels";
  result.bodies = static_cast<std::uint32_t>(setup.bodies.size());
  result.frames.reserve(static_cast<std::size_t>(options.frames));
  const auto dt = static_cast<float>(scene.time_step);
  // The frame callback, timed when it drew. unit: ms
  const auto show = [&](int frame, bool last) {
    if (!options.on_frame) return 0.0;
    const auto start = std::chrono::steady_clock::now();
    if (!options.on_frame({scene, setup, frame, last})) return 0.0;
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
  };
  show(0, false);
  PlausibilityMeter plausibility;
  for (int frame = 0; frame < options.frames; ++frame) {
    const StepStats& stats = world.step(dt);
    if (stats.non_finite_body) {
      result.stopped_non_finite = true;
      show(frame, true);
      break;
    }
    const double render_ms = show(frame + 1, frame + 1 == options.frames);
    result.frames.push_back(
        {stats.step_ms, stats.detection_ms(), stats.response_ms, stats.contacts, render_ms});
    plausibility.add(stats);
    if (options.progress) options.progress(static_cast<double>(frame + 1) / options.frames);
  }
  result.plausibility = plausibility.result();

  result.lowest_center_y = std::numeric_limits<float>::infinity();
  for (const BodyId body : setup.bodies) {
    const float y = world.body(body).pose.translation.y();
    result.lowest_center_y = std::min(result.lowest_center_y, y);
    if (!(y >= static_cast<float>(scene.ground.height))) ++result.bodies_below_plane;
  }
  return result;
}

std::vector<ExperimentRow> parse_rows(std::string_view ids) {
  std::vector<ExperimentRow> rows;
  std::size_t start = 0;
  while (start <= ids.size()) {
    const std::size_t comma = std::min(ids.find(',', start), ids.size());
    const std::string_view id = ids.substr(start, comma - start);
    const auto table = paper_table();
    const auto found = std::find_if(table.begin(), table.end(),
                                    [&](const PaperRow& paper) { return paper.row.id() == id; });
    if (found == table.end()) {
      std::string valid;
      for (const PaperRow& paper : table) valid += (valid.empty() ? "" : ", ") + paper.row.id();
      throw Error("unknown experiment row '" + std::string(id) + "'; rows: " + valid);
    }
    if (std::find(rows.begin(), rows.end(), found->row) == rows.end()) rows.push_back(found->row);
    start = comma + 1;
  }
  // The paper's order, whatever order they were asked in.
  std::vector<ExperimentRow> ordered;
  for (const PaperRow& paper : paper_table()) {
    if (std::find(rows.begin(), rows.end(), paper.row) != rows.end()) ordered.push_back(paper.row);
  }
  return ordered;
}

}  // namespace sphys::tools
