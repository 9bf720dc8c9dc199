// sphys-compare: the benchmark scene run in sphys and in the engines a user would pick instead,
// alternating runs, single-threaded; prints per engine the median step time, steps/s, contacts,
// penetration and the state at the end, and each engine's median time over sphys's. A run may
// stop at a time limit on its steps (--time-limit); its row says so.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <exception>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "engine_rows.h"
#include "jointed_scenes.h"
#include "results_csv.h"
#include "robot_scene.h"
#include "run_engine.h"
#include "sphys/error.h"
#include "sphys/solver_settings.h"
#include "sphys/tools/machine.h"
#include "sphys/tools/text_file.h"

namespace sphys::compare {
namespace {

struct Options {
  std::vector<std::string> layouts = {"4x25", "4x50", "8x10", "8x20"};
  std::vector<int> depths = {2, 3};
  std::vector<std::string> jointed;  // jointed_scenes.h, after the layouts
  std::vector<std::string> engines = {"sphys", "bullet-spheres", "bullet-hull", "ode", "mujoco"};
  int frames = 880;
  int runs = 1;
  double time_limit = 0.0;  // of summed step times per run, 0: none. unit: s
  std::string out;
  std::string command;  // as typed, for the report
};

// Today's date in UTC, YYYY-MM-DD.
std::string utc_date() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[16];
  std::strftime(text, sizeof text, "%Y-%m-%d", &utc);
  return text;
}

std::string memory_text(std::optional<double> mib) {
  if (!mib) return "?";
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", *mib);
  return text;
}

std::pair<int, int> parse_layout(const std::string& layout) {
  int stacks = 0;
  int per_stack = 0;
  char x = 0;
  std::istringstream in(layout);
  if (!(in >> stacks >> x >> per_stack) || x != 'x' || !in.eof() || stacks < 1 || per_stack < 1) {
    throw Error("--layouts: '" + layout + "' is not SxN (e.g. 4x25)");
  }
  return {stacks, per_stack};
}

// The bunny scenes of the layouts and depths ("none": no layout), then the jointed ones.
std::vector<std::function<BenchScene()>> scene_makers(const Options& options) {
  std::vector<std::function<BenchScene()>> makers;
  const bool no_layout = options.layouts == std::vector<std::string>{"none"};
  for (const std::string& layout : no_layout ? std::vector<std::string>{} : options.layouts) {
    const auto [stacks, per_stack] = parse_layout(layout);
    for (const int depth : options.depths) {
      makers.emplace_back([=] { return make_bench_scene(stacks, per_stack, depth); });
    }
  }
  for (const std::string& name : options.jointed) {
    if (is_robot_scene(name)) {
      makers.emplace_back([=] { return make_robot_scene(name); });
    } else if (is_jointed_scene(name)) {
      makers.emplace_back([=] { return make_jointed_scene(name); });
    } else {
      throw Error("--jointed: '" + name + "' is not ragdolls:R, chains:CxL, arm:B or arm-drag:M");
    }
  }
  return makers;
}

constexpr int kColumns = 17;  // and two more for a scene with joints, three for a robot

constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;

std::string ratio_text(const std::optional<double>& ratio, const EngineRow& row, int frames) {
  if (!ratio) return {};
  const bool all = row.ratio_frames == static_cast<std::size_t>(frames);
  return formatted("%.2f", *ratio) + (all ? "" : formatted(" (1–%zu)", row.ratio_frames));
}

std::string table(const SceneRows& scene, double time_limit) {
  std::ostringstream out;
  const int frames = scene.frames;
  out << formatted("\n### %s, depth %d, %d frames\n\n", scene.layout.c_str(), scene.depth, frames);
  const int columns = kColumns + (scene.jointed ? 2 : 0) + (scene.robot ? 3 : 0);
  if (!scene.reference.empty() && scene.reference != "sphys") {
    out << "× sphys: over `" << scene.reference << "` (single-threaded sphys did not run).\n\n";
  }
  out << "| engine | frames run | median ms/step | steps/s | × sphys median | mean ms/step | "
         "× sphys mean | mean µs/body/step | contacts/step | deepest (m) | "
         "deepest, last second (m) | overlap at end (m) | KE at end (J) | moving at end | "
         "asleep at end | below plane | peak memory (MiB) |"
      << (scene.jointed ? " largest joint gap (m) | joint gap at end (m) |" : "")
      << (scene.robot ? " largest tracking error (°) | mean tracking error (°) | "
                        "largest finger error (mm) |"
                      : "")
      << "\n| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | "
         "---: | ---: | ---: | ---: | ---: |"
      << (scene.jointed ? " ---: | ---: |" : "") << (scene.robot ? " ---: | ---: | ---: |" : "")
      << "\n";
  bool partial_ratios = false;
  for (const EngineRow& row : scene.rows) {
    const RunResult& worst = row.worst;
    if (!row.ran) {
      out << "| " << row.engine << " | " << worst.warnings << " |";
      for (int column = 2; column < columns; ++column) out << " |";
      out << "\n";
      continue;
    }
    std::string frames_run = std::to_string(row.fewest_frames);
    if (row.most_frames != row.fewest_frames) frames_run += "–" + std::to_string(row.most_frames);
    if (row.stopped) frames_run += formatted(" of %d (time limit)", frames);
    // A ratio over fewer than all the frames says which.
    partial_ratios = partial_ratios ||
                     (row.ratio_frames > 0 && row.ratio_frames != static_cast<std::size_t>(frames));
    const double ms = row.median_ms;
    out << "| " << row.engine << " | " << frames_run << " | "
        << formatted("%.3f | %.0f | ", ms, ms > 0.0 ? 1000.0 / ms : 0.0)
        << ratio_text(row.median_ratio, row, frames) << " | " << formatted("%.3f | ", row.mean_ms)
        << ratio_text(row.mean_ratio, row, frames) << " | "
        << formatted("%.2f | %.1f | %.4f | %.4f | %.4f | %.3g | %u of %u | ", row.us_per_body,
                     row.contacts_per_step, static_cast<double>(worst.deepest),
                     static_cast<double>(worst.deepest_last_second),
                     static_cast<double>(worst.end_overlap), worst.kinetic_energy, worst.moving,
                     worst.bodies)
        << (worst.asleep ? std::to_string(*worst.asleep) : "–") << " | " << worst.below << " | "
        << memory_text(worst.peak_memory_mib) << " |"
        << (scene.jointed ? formatted(" %.4f | %.4f |", static_cast<double>(worst.largest_gap),
                                      static_cast<double>(worst.largest_gap_at_end))
                          : std::string())
        << (scene.robot
                ? formatted(" %.3f | %.3f | %.2f |", worst.largest_turn_error * kDegreesPerRadian,
                            worst.mean_turn_error * kDegreesPerRadian,
                            worst.largest_slide_error * 1000.0)
                : std::string())
        << (worst.warnings.empty() ? "" : " " + worst.warnings) << "\n";
  }
  if (!scene.stops.empty()) {
    out << formatted("\nStopped at the time limit (%g s of steps): ", time_limit);
    for (std::size_t i = 0; i < scene.stops.size(); ++i) {
      out << (i > 0 ? ", " : "") << scene.stops[i];
    }
    out << formatted(
        ". A stopped run's times, µs/body/step and contacts/step are over the frames it ran, and "
        "its columns at end and for the last second describe the frame it stopped at, not frame "
        "%d.\n",
        frames);
  }
  if (partial_ratios) {
    out << "A × sphys figure marked (1–F) divides the two engines' step times over their first F "
           "frames only, the frames both ran.\n";
  }
  return out.str();
}

int run(const Options& options) {
  std::string report = "# sphys-compare\n\ncommand: `" + options.command +
                       "`\n\nmachine: " + tools::machine_description() +
                       "; one thread per engine (sphys:T: T threads); runs per engine: " +
                       std::to_string(options.runs) + "\n\ntime limit: " +
                       (options.time_limit > 0.0
                            ? formatted("%g s of steps per run of an engine (a run over it stops "
                                        "after the step that crossed it)",
                                        options.time_limit)
                            : std::string("none")) +
                       "\n";
  std::vector<SceneRows> scenes;
  for (const std::function<BenchScene()>& make : scene_makers(options)) {
    const BenchScene scene = make();
    const int frames = scene.frames > 0 ? scene.frames : options.frames;
    std::map<std::string, Pooled> results;
    // Alternating: run r of every engine before run r + 1 of any, so that a slow spell of the
    // machine falls on all of them.
    for (int r = 0; r < options.runs; ++r) {
      for (const std::string& engine : options.engines) {
        RunResult result;
        try {
          result = run_engine(engine, scene, frames, options.time_limit);
        } catch (const std::exception& error) {
          // One engine failing (e.g. out of memory for its contacts) leaves the others' rows.
          result.warnings = std::string("failed: ") + error.what();
        }
        const std::string stopped =
            result.stopped ? formatted(": stopped at frame %zu (time limit)", result.step_ms.size())
                           : std::string();
        Pooled& pooled = results[engine];
        pooled.step_ms.insert(pooled.step_ms.end(), result.step_ms.begin(), result.step_ms.end());
        pooled.runs.push_back(std::move(result));
        std::fprintf(stderr, "%s d%d %s run %d done%s\n", scene.name.c_str(), scene.depth,
                     engine.c_str(), r + 1, stopped.c_str());
      }
    }
    scenes.push_back(scene_rows(scene.name, scene.depth, frames, options.engines, results));
    scenes.back().jointed = !scene.joints.empty();
    scenes.back().robot = scene.robot.has_value();
    const std::string part = table(scenes.back(), options.time_limit);
    std::fputs(part.c_str(), stdout);
    std::fflush(stdout);
    report += part;
  }
  if (!options.out.empty()) {
    tools::write_text_file(options.out, report);
    // sphys's worlds run the lanes auto resolves to.
    const std::string build =
        std::string(SPHYS_BUILD_OPTIONS) + ", " +
        std::string(solver_lanes_name(resolve_solver_lanes(SolverLanes::kAuto))) + " lanes";
    const RunDescription description{utc_date(), options.command, build, options.runs,
                                     options.time_limit};
    write_results_csv(std::filesystem::path(options.out).replace_extension(".csv"), description,
                      scenes);
  }
  return 0;
}

}  // namespace
}  // namespace sphys::compare

int main(int argc, char** argv) {
  sphys::compare::Options options;
  CLI::App app("sphys-compare: the bunny scene in sphys, Bullet, ODE and MuJoCo, side by side");
  app.add_option("--layouts", options.layouts, "Layouts SxN of bunny stacks ('none': none)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--depths", options.depths, "Sphere-tree depths")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option(
         "--jointed", options.jointed,
         "Jointed scenes after the layouts: ragdolls:R (R ragdolls of 11 limbs), "
         "chains:CxL (C chains of L links swinging into bunnies), arm:B (the test robot "
         "sweeping through a pile of B bunnies for 10 s at 1 kHz, whatever --frames; arm:B:L "
         "with the shoulder lifted by L rad; arm-drag:M: through one bunny of M kg)")
      ->delimiter(',');
  app.add_option("--engines", options.engines, "Engines, in the order they run")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--frames", options.frames, "Steps per run")->capture_default_str();
  app.add_option("--runs", options.runs, "Runs per engine and scene")->capture_default_str();
  app.add_option("--time-limit", options.time_limit,
                 "Seconds of steps after which a run of an engine stops (0: no limit)")
      ->capture_default_str();
  app.add_option("--out", options.out,
                 "Also write the tables (Markdown) to this file, and the rows as CSV beside it "
                 "(the same name, .csv)");
  bool print_folder = false;
  app.add_flag("--machine-folder", print_folder,
               "Print this machine's folder name under bench/results/ and exit");
  CLI11_PARSE(app, argc, argv);
  if (print_folder) {
    std::printf("%s\n", sphys::tools::machine_folder().c_str());
    return 0;
  }
  options.command = "sphys-compare";
  for (int i = 1; i < argc; ++i) options.command += std::string(" ") + argv[i];
  try {
    if (options.frames < 1 || options.runs < 1)
      throw sphys::Error("--frames and --runs must be at least 1");
    if (!std::isfinite(options.time_limit) || options.time_limit < 0.0) {
      throw sphys::Error(
          "--time-limit must be a finite number of seconds, 0 or more (0: no limit)");
    }
    return sphys::compare::run(options);
  } catch (const sphys::Error& error) {
    std::fprintf(stderr, "sphys-compare: error: %s\n", error.what());
    return 2;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "sphys-compare: %s\n", error.what());
    return 1;
  }
}
