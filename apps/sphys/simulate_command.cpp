#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "progress.h"
#include "sphys/error.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/csv_file.h"
#include "sphys/tools/experiment.h"
#include "sphys/tools/interrupt.h"
#include "sphys/tools/recording.h"
#include "sphys/tools/run_summary.h"
#include "sphys/tools/scenarios.h"
#include "sphys/tools/scene_file.h"
#include "sphys/tools/scene_robots.h"
#include "sphys/tools/setting_text.h"
#include "sphys/tools/tree_cache.h"
#include "standard_output.h"

namespace sphys::cli {
namespace {

namespace fs = std::filesystem;

struct SimulateOptions {
  std::string scene;
  std::optional<int> depth;
  std::optional<int> frames;
  std::optional<std::string> mode;
  std::optional<std::string> ground;
  std::optional<std::string> contacts;
  std::optional<int> collision_passes;
  std::optional<std::string> substeps;  // the old name of --collision-passes, refused
  std::optional<int> passes;
  std::vector<std::string> settings;  // --set FIELD=VALUE, in order
  std::optional<std::string> out;
  std::uint32_t threads = WorldSettings{}.threads;
  bool json = false;
  bool no_cache = false;
};

// frames.csv's columns: the frame, its time, and StepStats' figures that are in it.
std::vector<std::string> frame_columns() {
  std::vector<std::string> columns = {"frame", "time_s"};
  for (const StepFigure& figure : step_figures()) {
    if (figure.in_frames_csv) columns.push_back(frames_csv_column(figure));
  }
  return columns;
}

std::vector<double> frame_row(int frame, double time, const StepStats& stats) {
  std::vector<double> row = {static_cast<double>(frame), time};
  for (const StepFigure& figure : step_figures()) {
    if (figure.in_frames_csv) row.push_back(figure.read(stats));
  }
  return row;
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

// The bodies a recording keeps: the scene's, then its robots'.
std::vector<BodyId> recorded_bodies(const tools::SimulationSetup& setup,
                                    const tools::SceneRobots& robots) {
  std::vector<BodyId> bodies = setup.bodies;
  bodies.insert(bodies.end(), robots.bodies.begin(), robots.bodies.end());
  return bodies;
}

// The command line's settings over the scene's.
void apply_options(const SimulateOptions& options, tools::Scene& scene) {
  if (options.frames) {
    if (*options.frames < 1) throw Error("--frames must be at least 1");
    scene.frames = *options.frames;
  }
  if (options.passes) {
    scene.paper_passes = checked_count("--passes", *options.passes, setting_of("paper_passes"));
  }
  if (options.ground) scene.ground.kind = tools::parse_ground_option(*options.ground);
  if (options.mode) {
    scene.response = parse_option("--mode", *options.mode, tools::parse_response_mode);
  }
  if (options.contacts) {
    scene.solver.contacts = parse_option("--contacts", *options.contacts, tools::parse_contact_set);
  }
  if (options.substeps) {
    throw Error(
        "--substeps was renamed --collision-passes (whole collision passes a frame; the "
        "solver's own substeps are --set solver.soft_substeps=N)");
  }
  if (options.collision_passes) {
    scene.collision_passes = checked_count("--collision-passes", *options.collision_passes,
                                           setting_of("collision_passes"));
  }
  if (!options.settings.empty()) {
    WorldSettings settings = tools::world_settings(scene);
    for (const std::string& assignment : options.settings) {
      const std::size_t equals = assignment.find('=');
      if (equals == std::string::npos) {
        throw Error("--set takes FIELD=VALUE, got '" + assignment + "'");
      }
      set_setting_from_text(settings, std::string_view(assignment).substr(0, equals),
                            std::string_view(assignment).substr(equals + 1), "--set");
    }
    tools::set_world_settings(scene, settings);
  }
  if (options.depth) {
    for (tools::BodySpec& body : scene.bodies) {
      if (!body.tree.sph_file) body.tree.depth = *options.depth;
    }
  }
}

// "0.42%", or "n/a" for a null figure.
std::string percent_text(const nlohmann::ordered_json& value) {
  if (value.is_null()) return "n/a";
  char text[32];
  std::snprintf(text, sizeof text, "%.3g%%", value.get<double>());
  return text;
}

// "-0.25 m", or "n/a" for a figure the run could not give (no bodies).
std::string metres_text(const nlohmann::ordered_json& value) {
  if (value.is_null()) return "n/a";
  char text[32];
  std::snprintf(text, sizeof text, "%.4g m", value.get<double>());
  return text;
}

// "plausible, reduced contacts, avx2 lanes, 1 collision pass per frame"
std::string response_text(const nlohmann::ordered_json& s) {
  std::string text = s["response"].get<std::string>();
  if (text == tools::response_mode_name(ResponseMode::kPlausible)) {
    text += ", ";
    text += s["contact_set"].get<std::string>();
    text += " contacts, ";
    text += s["solver_lanes"].get<std::string>();
    text += " lanes";
  }
  const int fewest = s["collision_passes"].get<int>();
  const int most = std::max(fewest, s["max_collision_passes"].get<int>());
  const bool adaptive =
      s["response"] == tools::response_mode_name(ResponseMode::kPlausible) && most > fewest;
  char counts[96];
  if (adaptive) {
    std::snprintf(counts, sizeof counts,
                  ", %d to %d collision passes per frame (%.2f on average, %u at most)", fewest,
                  most, s["collision_passes_per_frame"]["mean"].get<double>(),
                  s["collision_passes_per_frame"]["max"].get<unsigned>());
  } else {
    std::snprintf(counts, sizeof counts, ", %d collision pass%s per frame", fewest,
                  fewest == 1 ? "" : "es");
  }
  return text + counts;
}

// "all from frame 95 (1.58 s) on" or "never all at rest".
std::string settled_text(const nlohmann::ordered_json& s) {
  if (s["all_at_rest_from_frame"].is_null()) return "never all at rest";
  char text[64];
  std::snprintf(text, sizeof text, "all from frame %d (%.2f s) on",
                s["all_at_rest_from_frame"].get<int>(), s["all_at_rest_from_s"].get<double>());
  return text;
}

void print_summary(const nlohmann::ordered_json& s) {
  const double frames = s["frames"].get<double>();
  std::printf("scene               %s (%zu bodies)\n", s["scene"].get<std::string>().c_str(),
              s["bodies"].get<std::size_t>());
  if (s["bodies"].get<std::size_t>() > 0) {
    std::printf("sphere-trees        %s\n", s["sphere_trees"].get<std::string>().c_str());
  }
  std::printf("response            %s\n", response_text(s).c_str());
  std::printf("frames              %.0f (%.2f s simulated, step %.6g s)\n", frames,
              frames * s["time_step_s"].get<double>(), s["time_step_s"].get<double>());
  std::printf("speed               %.1f steps/s (step mean %.3f ms, median %.3f ms; %.2f s wall)\n",
              s["steps_per_s"].get<double>(), s["step_ms"]["mean"].get<double>(),
              s["step_ms"]["median"].get<double>(), s["wall_s"].get<double>());
  std::printf("contacts            %.1f per frame on average, %u at most\n",
              s["contacts_per_frame"]["mean"].get<double>(),
              s["contacts_per_frame"]["max"].get<unsigned>());
  const auto& share = s["time_share_percent"];
  std::printf(
      "time share          broad %.1f%%, narrow %.1f%%, contacts %.1f%%, response %.1f%%, "
      "integration %.1f%%\n",
      share["broad_phase"].get<double>(), share["narrow_phase"].get<double>(),
      share["contacts"].get<double>(), share["response"].get<double>(),
      share["integration"].get<double>());
  std::printf("deepest penetration %.4g m (%s of the largest body's %.4g m; frame %d)\n",
              s["deepest_penetration_m"].get<double>(),
              percent_text(s["deepest_penetration_percent_of_size"]).c_str(),
              s["largest_body_size_m"].get<double>(), s["deepest_penetration_frame"].get<int>());
  std::printf("mean penetration    %.4g m (%s; over the %d frames with overlaps)\n",
              s["mean_penetration_m"].get<double>(),
              percent_text(s["mean_penetration_percent_of_size"]).c_str(),
              s["penetrating_frames"].get<int>());
  std::printf("overlap at the end  %.4g m (%s; every pair of bodies, sleeping ones included)\n",
              s["end_overlap_m"].get<double>(),
              percent_text(s["end_overlap_percent_of_size"]).c_str());
  std::printf("kinetic energy      %.6g J at the end\n", s["final_kinetic_energy_J"].get<double>());
  std::printf(
      "at rest             %u of %u movable bodies at the end (%u asleep, %u still "
      "moving); %s\n",
      s["bodies_at_rest"].get<unsigned>(), s["movable_bodies"].get<unsigned>(),
      s["bodies_asleep"].get<unsigned>(), s["bodies_still_moving"].get<unsigned>(),
      settled_text(s).c_str());
  std::printf("jitter              %.4g m/s (mean over the last %zu frames or fewer)\n",
              s["jitter_m_per_s"].get<double>(), tools::kJitterFrames);
  std::printf(
      "below the ground    %u bodies at the end (lowest centre of mass y: %s at the end, "
      "%s over the run)\n",
      s["bodies_below_ground"].get<unsigned>(), metres_text(s["lowest_center_y_end_m"]).c_str(),
      metres_text(s["lowest_center_y_run_m"]).c_str());
  std::printf("wrote               %s, %s\n", s["csv"].get<std::string>().c_str(),
              s["recording"].get<std::string>().c_str());
}

void run(const SimulateOptions& options) {
  tools::catch_interruptions();
  tools::Scene scene = tools::load_scene(options.scene);
  apply_options(options, scene);

  tools::BuildWorldOptions build;
  build.tree_depth = options.depth;
  build.threads = options.threads;
  build.plausibility_figures = true;
  if (!options.no_cache) build.cache_dir = tools::default_cache_dir();
  tools::SimulationSetup setup = [&] {
    ProgressBar bar("preparing bodies");
    build.progress = [&bar](double fraction) { bar.update(fraction); };
    return tools::build_world(scene, build);
  }();
  const tools::SceneRobots robots = tools::add_scene_robots(scene, *setup.world);
  const std::vector<BodyId> recorded = recorded_bodies(setup, robots);

  const fs::path out =
      options.out ? fs::path(*options.out) : fs::path("out") / folder_name(scene.name);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw Error::in_file(out, "cannot create the output folder: " + ec.message());
  const fs::path csv_path = out / "frames.csv";
  const fs::path recording_path = out / "recording.sphysrec";

  tools::RecordingWriter recording(recording_path, static_cast<std::uint32_t>(recorded.size()),
                                   scene.time_step, tools::recorded_scene_json(scene),
                                   tools::recorded_joints(scene, robots));
  recording.add_frame(tools::recorded_poses(*setup.world, recorded));
  std::vector<std::vector<double>> rows;
  rows.reserve(static_cast<std::size_t>(scene.frames));
  tools::RunTotals totals;
  std::optional<std::string> failure;
  const auto dt = static_cast<float>(scene.time_step);
  const auto start = std::chrono::steady_clock::now();
  {
    ProgressBar bar("simulating " + scene.name);
    bool crowd_noted = false;  // a crowd is reported once, at its first frame
    for (int frame = 1; frame <= scene.frames; ++frame) {
      // Unwinding from here removes the recording's temporary file; earlier outputs stay whole.
      tools::throw_if_interrupted();
      const StepStats& stats = setup.world->step(dt);
      if (stats.non_finite_body) {
        failure = tools::non_finite_message(setup, *stats.non_finite_body, frame);
        break;
      }
      totals.add(stats, setup);
      if (stats.pairs_deferred > 0 && !crowd_noted) {
        crowd_noted = true;
        bar.note("sphys: frame " + std::to_string(frame) + ": " +
                 std::to_string(stats.crowded_bodies) +
                 " bodies overlap en masse; until they part, each is paired with its nearest "
                 "only (collision.crowd_pairs_per_body; StepStats.pairs_deferred counts the "
                 "pairs left out)");
      }
      rows.push_back(frame_row(frame, frame * scene.time_step, stats));
      recording.add_frame(tools::recorded_poses(*setup.world, recorded));
      bar.update(static_cast<double>(frame) / scene.frames);
    }
  }
  totals.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  tools::write_csv(csv_path, frame_columns(), rows);
  recording.finish();
  if (failure) throw Error(*failure + " (the frames before it are in " + out.string() + ")");

  nlohmann::ordered_json summary =
      nlohmann::ordered_json::parse(tools::run_summary_json(scene, setup, totals));
  summary["csv"] = csv_path.string();
  summary["recording"] = recording_path.string();
  if (options.json) {
    print_output(summary.dump(2) + "\n");
    return;
  }
  print_summary(summary);
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand("simulate", "Run a scene headless and record it");
  cmd->add_option("scene", options->scene,
                  "A scene file (.json, see docs/scenes.md) or a preset:\n" + tools::preset_help())
      ->check(kFileName)
      ->required();
  cmd->add_option("--depth", options->depth, "Sphere-tree depth of every body (levels, 1..6)");
  cmd->add_option("--frames", options->frames, "Frames to run (one step each)");
  cmd->add_option("--ground", options->ground,
                  "Instead of the scene's ground: octree (the paper's 5-level octree of a 16 m "
                  "thin box) or plane (the exact plane, as the benchmark scene specifies)");
  // Each replaces the scene's value; without it the scene's stands.
  const auto instead = [](std::string_view field) {
    return setting_help(field) + " Replaces the scene's value.";
  };
  cmd->add_option("--mode", options->mode, instead("response"));
  cmd->add_option("--contacts", options->contacts, instead("solver.contacts"));
  cmd->add_option("--collision-passes", options->collision_passes, instead("collision_passes"));
  cmd->add_option("--passes", options->passes, instead("paper_passes"));
  cmd->add_option("--substeps", options->substeps)->group("");  // refused, naming the new name
  cmd->add_option("--set", options->settings,
                  "A setting of the world by its field, FIELD=VALUE: solver.soft_substeps=8, "
                  "sleep.time=0.5, ground_friction=0.8 (docs/scenes.md's keys, with their object "
                  "and a dot for solver and sleep). Applied after the scene and the options "
                  "above; repeatable");
  cmd->add_option("--out", options->out,
                  "Folder for frames.csv and recording.sphysrec (default out/<scene>)")
      ->check(kFileName);
  const SettingRange& threads = setting_of("threads").range;
  cmd->add_option("--threads", options->threads, setting_help("threads"))
      ->check(CLI::Range(static_cast<std::uint32_t>(threads.min),
                         static_cast<std::uint32_t>(threads.max)))
      ->capture_default_str();
  cmd->add_flag("--json", options->json, "Print the summary as JSON");
  cmd->add_flag("--no-cache", options->no_cache, "Build sphere-trees even if they are cached");
  cmd->callback([options] { run(*options); });
}

}  // namespace sphys::cli
