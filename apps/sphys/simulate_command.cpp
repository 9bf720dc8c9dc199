#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "progress.h"
#include "sphys/error.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/csv_file.h"
#include "sphys/tools/model.h"
#include "sphys/tools/recording.h"
#include "sphys/tools/scenarios.h"
#include "sphys/tools/scene_file.h"
#include "sphys/tools/tree_cache.h"

namespace sphys::cli {
namespace {

namespace fs = std::filesystem;

struct SimulateOptions {
  std::string scene;
  std::optional<int> depth;
  std::optional<int> frames;
  std::optional<std::string> mode;
  std::optional<int> passes;
  std::optional<std::string> out;
  bool json = false;
  bool no_cache = false;
};

// Per-frame figures, one CSV column each.
const std::vector<std::string> kFrameColumns = {
    "frame",       "time_s",      "step_ms",        "broad_phase_ms",   "narrow_phase_ms",
    "contacts_ms", "response_ms", "integration_ms", "candidate_pairs",  "sphere_tests",
    "leaf_pairs",  "contacts",    "impulses",       "kinetic_energy_J", "deepest_penetration_m"};

std::vector<double> frame_row(int frame, double time, const StepStats& s) {
  return {static_cast<double>(frame),
          time,
          s.step_ms,
          s.broad_phase_ms,
          s.narrow_phase_ms,
          s.contacts_ms,
          s.response_ms,
          s.integration_ms,
          static_cast<double>(s.candidate_pairs),
          static_cast<double>(s.sphere_tests),
          static_cast<double>(s.leaf_pairs),
          static_cast<double>(s.contacts),
          static_cast<double>(s.impulses),
          s.kinetic_energy,
          static_cast<double>(s.deepest_penetration)};
}

// A folder name from a scene name: "stacks:4x50" -> "stacks-4x50", "drop.json" -> "drop".
std::string folder_name(const std::string& scene_name) {
  std::string name = fs::path(scene_name).stem().string();
  if (tools::is_preset(scene_name)) name = scene_name;
  std::replace_if(
      name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); },
      '-');
  return name.empty() ? "scene" : name;
}

std::vector<tools::BodyPose> poses(const tools::SimulationSetup& setup) {
  std::vector<tools::BodyPose> result;
  result.reserve(setup.bodies.size());
  for (const BodyId body : setup.bodies) {
    const Transform& pose = setup.world->body(body).pose;
    result.push_back({pose.translation, pose.rotation});
  }
  return result;
}

// Totals over the frames that ran.
struct RunTotals {
  double wall_s = 0.0;
  std::vector<double> step_ms;
  double broad = 0, narrow = 0, contacts_time = 0, response = 0, integration = 0, step = 0;
  double contacts = 0;
  std::uint32_t max_contacts = 0;
  float deepest = 0.0f;
  int deepest_frame = 0;

  void add(int frame, const StepStats& s) {
    step_ms.push_back(s.step_ms);
    broad += s.broad_phase_ms;
    narrow += s.narrow_phase_ms;
    contacts_time += s.contacts_ms;
    response += s.response_ms;
    integration += s.integration_ms;
    step += s.step_ms;
    contacts += s.contacts;
    max_contacts = std::max(max_contacts, s.contacts);
    if (s.deepest_penetration > deepest) {
      deepest = s.deepest_penetration;
      deepest_frame = frame;
    }
  }
  [[nodiscard]] double share(double part) const { return step > 0 ? 100.0 * part / step : 0.0; }
};

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

std::string non_finite_message(const tools::SimulationSetup& setup, std::uint32_t world_index,
                               int frame) {
  const auto found = std::find(setup.bodies.begin(), setup.bodies.end(), BodyId{world_index});
  const auto body = static_cast<std::size_t>(found - setup.bodies.begin());
  const RigidBody& state = setup.world->body({world_index});
  char detail[256];
  std::snprintf(detail, sizeof detail,
                "position (%g, %g, %g), velocity (%g, %g, %g), angular velocity (%g, %g, %g)",
                state.pose.translation.x(), state.pose.translation.y(), state.pose.translation.z(),
                state.linear_velocity.x(), state.linear_velocity.y(), state.linear_velocity.z(),
                state.angular_velocity.x(), state.angular_velocity.y(), state.angular_velocity.z());
  return "the simulation went non-finite: body " + std::to_string(body) + " (/bodies/" +
         std::to_string(body) + ") at frame " + std::to_string(frame) + ": " + detail;
}

// The scene as a recording keeps it: file paths made absolute, so that a viewer replaying the
// recording from anywhere finds the meshes and trees.
std::string recorded_scene(tools::Scene scene) {
  const auto absolute = [&](const fs::path& path) {
    return fs::absolute(path.is_absolute() ? path : scene.base_directory / path);
  };
  for (tools::BodySpec& body : scene.bodies) {
    if (body.mesh != tools::kBunnyName) body.mesh = absolute(body.mesh).string();
    if (body.tree.sph_file) body.tree.sph_file = absolute(*body.tree.sph_file);
  }
  return tools::scene_to_json(scene);
}

void run(const SimulateOptions& options) {
  tools::Scene scene = tools::load_scene(options.scene);
  if (options.frames) {
    if (*options.frames < 1) throw Error("--frames must be at least 1");
    scene.frames = *options.frames;
  }
  if (options.passes) scene.paper_passes = *options.passes;
  if (options.mode) scene.response = tools::parse_response_mode(*options.mode);
  if (options.depth) {
    for (tools::BodySpec& body : scene.bodies) {
      if (!body.tree.sph_file) body.tree.depth = *options.depth;
    }
  }

  tools::BuildWorldOptions build;
  build.tree_depth = options.depth;
  if (!options.no_cache) build.cache_dir = tools::default_cache_dir();
  tools::SimulationSetup setup = [&] {
    ProgressBar bar("preparing bodies");
    build.progress = [&bar](double fraction) { bar.update(fraction); };
    return tools::build_world(scene, build);
  }();

  const fs::path out =
      options.out ? fs::path(*options.out) : fs::path("out") / folder_name(scene.name);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw Error::in_file(out, "cannot create the output folder: " + ec.message());
  const fs::path csv_path = out / "frames.csv";
  const fs::path recording_path = out / "recording.sphysrec";

  tools::RecordingWriter recording(recording_path, static_cast<std::uint32_t>(setup.bodies.size()),
                                   scene.time_step, recorded_scene(scene));
  recording.add_frame(poses(setup));
  std::vector<std::vector<double>> rows;
  rows.reserve(static_cast<std::size_t>(scene.frames));
  RunTotals totals;
  std::optional<std::string> failure;
  const auto dt = static_cast<float>(scene.time_step);
  const auto start = std::chrono::steady_clock::now();
  {
    ProgressBar bar("simulating " + scene.name);
    for (int frame = 1; frame <= scene.frames; ++frame) {
      const StepStats& stats = setup.world->step(dt);
      if (stats.non_finite_body) {
        failure = non_finite_message(setup, *stats.non_finite_body, frame);
        break;
      }
      totals.add(frame, stats);
      rows.push_back(frame_row(frame, frame * scene.time_step, stats));
      recording.add_frame(poses(setup));
      bar.update(static_cast<double>(frame) / scene.frames);
    }
  }
  totals.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  tools::write_csv(csv_path, kFrameColumns, rows);
  recording.finish();
  if (failure) throw Error(*failure + " (the frames before it are in " + out.string() + ")");

  const double frames = static_cast<double>(totals.step_ms.size());
  const double mean_ms = totals.step / frames;
  double below = 0;
  float lowest = std::numeric_limits<float>::infinity();
  for (const BodyId body : setup.bodies) {
    const float y = setup.world->body(body).pose.translation.y();
    lowest = std::min(lowest, y);
    if (scene.ground.kind != tools::GroundSpec::Kind::kNone &&
        !(y >= static_cast<float>(scene.ground.height))) {
      ++below;
    }
  }
  const StepStats& last = setup.world->stats();

  nlohmann::ordered_json summary;
  summary["scene"] = scene.name;
  summary["bodies"] = setup.bodies.size();
  summary["sphere_trees"] = setup.shapes.empty() ? "" : setup.shapes.front().tree_source;
  summary["response"] = tools::response_mode_name(scene.response);
  summary["frames"] = totals.step_ms.size();
  summary["time_step_s"] = scene.time_step;
  summary["wall_s"] = totals.wall_s;
  summary["steps_per_s"] = 1000.0 / mean_ms;
  summary["step_ms"] = {{"mean", mean_ms}, {"median", median(totals.step_ms)}};
  summary["contacts_per_frame"] = {{"mean", totals.contacts / frames},
                                   {"max", totals.max_contacts}};
  summary["time_share_percent"] = {{"broad_phase", totals.share(totals.broad)},
                                   {"narrow_phase", totals.share(totals.narrow)},
                                   {"contacts", totals.share(totals.contacts_time)},
                                   {"response", totals.share(totals.response)},
                                   {"integration", totals.share(totals.integration)}};
  summary["deepest_penetration_m"] = totals.deepest;
  summary["deepest_penetration_frame"] = totals.deepest_frame;
  summary["final_kinetic_energy_J"] = last.kinetic_energy;
  summary["bodies_below_ground"] = below;
  summary["lowest_center_y_m"] = lowest;
  summary["csv"] = csv_path.string();
  summary["recording"] = recording_path.string();
  if (options.json) {
    std::cout << summary.dump(2) << '\n';
    return;
  }
  std::printf("scene               %s (%zu bodies)\n", scene.name.c_str(), setup.bodies.size());
  if (!setup.shapes.empty()) {
    std::printf("sphere-trees        %s\n", setup.shapes.front().tree_source.c_str());
  }
  std::printf("response            %s\n",
              std::string(tools::response_mode_name(scene.response)).c_str());
  std::printf("frames              %.0f (%.2f s simulated, step %.6g s)\n", frames,
              frames * scene.time_step, scene.time_step);
  std::printf("speed               %.1f steps/s (step mean %.3f ms, median %.3f ms; %.2f s wall)\n",
              1000.0 / mean_ms, mean_ms, median(totals.step_ms), totals.wall_s);
  std::printf("contacts            %.1f per frame on average, %u at most\n",
              totals.contacts / frames, totals.max_contacts);
  std::printf(
      "time share          broad %.1f%%, narrow %.1f%%, contacts %.1f%%, response %.1f%%, "
      "integration %.1f%%\n",
      totals.share(totals.broad), totals.share(totals.narrow), totals.share(totals.contacts_time),
      totals.share(totals.response), totals.share(totals.integration));
  std::printf("deepest penetration %.4g m (frame %d)\n", totals.deepest, totals.deepest_frame);
  std::printf("kinetic energy      %.6g J at the end\n", last.kinetic_energy);
  std::printf("below the ground    %.0f bodies (lowest centre of mass y = %.4g m)\n", below,
              lowest);
  std::printf("wrote               %s, %s\n", csv_path.string().c_str(),
              recording_path.string().c_str());
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand("simulate", "Run a scene headless and record it");
  cmd->add_option("scene", options->scene,
                  "A scene file (.json, see docs/scenes.md) or a preset:\n" + tools::preset_help())
      ->required();
  cmd->add_option("--depth", options->depth, "Sphere-tree depth of every body (levels, 1..6)");
  cmd->add_option("--frames", options->frames, "Frames to run (one step each)");
  cmd->add_option("--mode", options->mode, "Collision response: paper");
  cmd->add_option("--passes", options->passes,
                  "Paper mode: passes over the contacts per step at most (see docs/experiment.md)");
  cmd->add_option("--out", options->out,
                  "Folder for frames.csv and recording.sphysrec (default out/<scene>)");
  cmd->add_flag("--json", options->json, "Print the summary as JSON");
  cmd->add_flag("--no-cache", options->no_cache, "Build sphere-trees even if they are cached");
  cmd->callback([options] { run(*options); });
}

}  // namespace sphys::cli
