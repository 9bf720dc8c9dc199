// sphys-compare: the benchmark scene run in sphys and in the engines a user would pick instead,
// alternating runs, single-threaded; prints per engine the median step time, steps/s, contacts,
// penetration and the state at the end, and each engine's median time over sphys's. A run may
// stop at a time limit on its steps (--time-limit); its row says so.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "run_engine.h"
#include "sphys/error.h"
#include "sphys/tools/machine.h"
#include "sphys/tools/text_file.h"

namespace sphys::compare {
namespace {

struct Options {
  std::vector<std::string> layouts = {"4x25", "4x50", "8x10", "8x20"};
  std::vector<int> depths = {2, 3};
  std::vector<std::string> engines = {"sphys", "bullet-spheres", "bullet-hull", "ode", "mujoco"};
  int frames = 880;
  int runs = 1;
  double time_limit = 0.0;  // of summed step times per run, 0: none. unit: s
  std::string out;
  std::string command;  // as typed, for the report
};

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  if (values.size() % 2 == 1) return *middle;
  return 0.5 * (*middle + *std::max_element(values.begin(), middle));
}

double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double value : values) sum += value;
  return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
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

// All runs of one engine on one scene, pooled.
struct Pooled {
  std::vector<double> step_ms;
  std::vector<RunResult> runs;
};

// printf's formatting into a string.
std::string formatted(const char* pattern, auto... values) {
  const int size = std::snprintf(nullptr, 0, pattern, values...);
  if (size <= 0) return {};
  std::string text(static_cast<std::size_t>(size), '\0');
  std::snprintf(text.data(), text.size() + 1, pattern, values...);
  return text;
}

// The engine the × sphys columns divide by: single-threaded sphys, else the first sphys:T listed
// (e.g. a scale series on two threads); empty if neither runs.
std::string reference_engine(const std::vector<std::string>& engines) {
  if (std::find(engines.begin(), engines.end(), "sphys") != engines.end()) return "sphys";
  for (const std::string& engine : engines) {
    if (engine.starts_with("sphys:")) return engine;
  }
  return {};
}

// The frames every run of these engines ran (a run that failed counts none): all of them, unless
// one stopped at the time limit.
std::size_t common_frames(const Pooled& a, const Pooled& b) {
  std::size_t frames = std::numeric_limits<std::size_t>::max();
  for (const Pooled* pooled : {&a, &b}) {
    for (const RunResult& run : pooled->runs) frames = std::min(frames, run.step_ms.size());
  }
  return frames;
}

// Each run's first `frames` step times, pooled.
std::vector<double> first_frames(const Pooled& pooled, std::size_t frames) {
  std::vector<double> step_ms;
  for (const RunResult& run : pooled.runs) {
    step_ms.insert(step_ms.end(), run.step_ms.begin(),
                   run.step_ms.begin() + static_cast<std::ptrdiff_t>(frames));
  }
  return step_ms;
}

// A run's step times summed. unit: s
double seconds_of_steps(const RunResult& run) {
  return std::accumulate(run.step_ms.begin(), run.step_ms.end(), 0.0) / 1000.0;
}

constexpr int kColumns = 17;

std::string table(const std::string& layout, int depth, const std::vector<std::string>& engines,
                  const std::map<std::string, Pooled>& results, int frames, double time_limit) {
  std::ostringstream out;
  out << formatted("\n### %s, depth %d, %d frames\n\n", layout.c_str(), depth, frames);
  const std::string reference = reference_engine(engines);
  if (!reference.empty() && reference != "sphys") {
    out << "× sphys: over `" << reference << "` (single-threaded sphys did not run).\n\n";
  }
  out << "| engine | frames run | median ms/step | steps/s | × sphys median | mean ms/step | "
         "× sphys mean | mean µs/body/step | contacts/step | deepest (m) | "
         "deepest, last second (m) | overlap at end (m) | KE at end (J) | moving at end | "
         "asleep at end | below plane | peak memory (MiB) |\n"
      << "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | "
         "---: | ---: | ---: | ---: | ---: |\n";
  const Pooled* reference_runs =
      reference.empty() ? nullptr : &results.at(reference);  // every engine listed has an entry
  std::vector<std::string> stops;                            // the runs stopped at the time limit
  bool partial_ratios = false;
  for (const std::string& engine : engines) {
    const Pooled& pooled = results.at(engine);
    if (pooled.step_ms.empty()) {
      out << "| " << engine << " | " << pooled.runs.front().warnings << " |";
      for (int column = 2; column < kColumns; ++column) out << " |";
      out << "\n";
      continue;
    }
    const double ms = median(pooled.step_ms);
    const double mean_ms = mean(pooled.step_ms);
    // The plausibility figures are the worst over the runs.
    RunResult worst = pooled.runs.front();
    double contacts = 0.0;
    std::size_t fewest_frames = pooled.runs.front().step_ms.size();
    std::size_t most_frames = fewest_frames;
    bool stopped = false;
    for (std::size_t r = 0; r < pooled.runs.size(); ++r) {
      const RunResult& run = pooled.runs[r];
      worst.deepest = std::max(worst.deepest, run.deepest);
      worst.deepest_last_second = std::max(worst.deepest_last_second, run.deepest_last_second);
      worst.end_overlap = std::max(worst.end_overlap, run.end_overlap);
      worst.kinetic_energy = std::max(worst.kinetic_energy, run.kinetic_energy);
      worst.moving = std::max(worst.moving, run.moving);
      worst.below = std::max(worst.below, run.below);
      if (worst.asleep && run.asleep) {
        worst.asleep = std::min(*worst.asleep, *run.asleep);
      } else {
        worst.asleep = std::nullopt;
      }
      if (run.peak_memory_mib) {
        worst.peak_memory_mib = std::max(worst.peak_memory_mib.value_or(0.0), *run.peak_memory_mib);
      }
      contacts += run.contacts_per_step;
      if (!run.warnings.empty()) worst.warnings = run.warnings;
      fewest_frames = std::min(fewest_frames, run.step_ms.size());
      most_frames = std::max(most_frames, run.step_ms.size());
      if (run.stopped) {
        stops.push_back(formatted("%s at frame %zu of %d (%.4g s of steps)", engine.c_str(),
                                  run.step_ms.size(), frames, seconds_of_steps(run)));
        if (pooled.runs.size() > 1) stops.back() += formatted(" in run %zu", r + 1);
        stopped = true;
      }
    }
    contacts /= static_cast<double>(pooled.runs.size());

    std::string frames_run = std::to_string(fewest_frames);
    if (most_frames != fewest_frames) frames_run += "–" + std::to_string(most_frames);
    if (stopped) frames_run += formatted(" of %d (time limit)", frames);

    // Over the reference's times, over the frames both ran: a ratio over fewer than all the
    // frames says which (a run that stopped at the time limit ran only the first ones, and the
    // first frames of a fall cost differently from the pile at rest).
    std::string median_ratio;
    std::string mean_ratio;
    const std::size_t common =
        reference_runs == nullptr ? 0 : common_frames(pooled, *reference_runs);
    if (common > 0) {
      const bool all = common == static_cast<std::size_t>(frames);
      const std::vector<double> ours = all ? pooled.step_ms : first_frames(pooled, common);
      const std::vector<double> theirs =
          all ? reference_runs->step_ms : first_frames(*reference_runs, common);
      const std::string span = all ? "" : formatted(" (1–%zu)", common);
      partial_ratios = partial_ratios || !all;
      if (median(theirs) > 0.0)
        median_ratio = formatted("%.2f", median(ours) / median(theirs)) + span;
      if (mean(theirs) > 0.0) mean_ratio = formatted("%.2f", mean(ours) / mean(theirs)) + span;
    }
    const double us_per_body =
        worst.bodies > 0 ? 1000.0 * mean_ms / static_cast<double>(worst.bodies) : 0.0;

    out << "| " << engine << " | " << frames_run << " | "
        << formatted("%.3f | %.0f | ", ms, ms > 0.0 ? 1000.0 / ms : 0.0) << median_ratio << " | "
        << formatted("%.3f | ", mean_ms) << mean_ratio << " | "
        << formatted("%.2f | %.1f | %.4f | %.4f | %.4f | %.3g | %u of %u | ", us_per_body, contacts,
                     static_cast<double>(worst.deepest),
                     static_cast<double>(worst.deepest_last_second),
                     static_cast<double>(worst.end_overlap), worst.kinetic_energy, worst.moving,
                     worst.bodies)
        << (worst.asleep ? std::to_string(*worst.asleep) : "–") << " | " << worst.below << " | "
        << memory_text(worst.peak_memory_mib) << " |"
        << (worst.warnings.empty() ? "" : " " + worst.warnings) << "\n";
  }
  if (!stops.empty()) {
    out << formatted("\nStopped at the time limit (%g s of steps): ", time_limit);
    for (std::size_t i = 0; i < stops.size(); ++i) out << (i > 0 ? ", " : "") << stops[i];
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
  for (const std::string& layout : options.layouts) {
    const auto [stacks, per_stack] = parse_layout(layout);
    for (const int depth : options.depths) {
      const BenchScene scene = make_bench_scene(stacks, per_stack, depth);
      std::map<std::string, Pooled> results;
      // Alternating: run r of every engine before run r + 1 of any, so that a slow spell of the
      // machine falls on all of them.
      for (int r = 0; r < options.runs; ++r) {
        for (const std::string& engine : options.engines) {
          RunResult result;
          try {
            result = run_engine(engine, scene, options.frames, options.time_limit);
          } catch (const std::exception& error) {
            // One engine failing (e.g. out of memory for its contacts) leaves the others' rows.
            result.warnings = std::string("failed: ") + error.what();
          }
          const std::string stopped =
              result.stopped
                  ? formatted(": stopped at frame %zu (time limit)", result.step_ms.size())
                  : std::string();
          Pooled& pooled = results[engine];
          pooled.step_ms.insert(pooled.step_ms.end(), result.step_ms.begin(), result.step_ms.end());
          pooled.runs.push_back(std::move(result));
          std::fprintf(stderr, "%s d%d %s run %d done%s\n", layout.c_str(), depth, engine.c_str(),
                       r + 1, stopped.c_str());
        }
      }
      const std::string part =
          table(layout, depth, options.engines, results, options.frames, options.time_limit);
      std::fputs(part.c_str(), stdout);
      std::fflush(stdout);
      report += part;
    }
  }
  if (!options.out.empty()) tools::write_text_file(options.out, report);
  return 0;
}

}  // namespace
}  // namespace sphys::compare

int main(int argc, char** argv) {
  sphys::compare::Options options;
  CLI::App app("sphys-compare: the bunny scene in sphys, Bullet, ODE and MuJoCo, side by side");
  app.add_option("--layouts", options.layouts, "Layouts SxN")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--depths", options.depths, "Sphere-tree depths")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--engines", options.engines, "Engines, in the order they run")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--frames", options.frames, "Steps per run")->capture_default_str();
  app.add_option("--runs", options.runs, "Runs per engine and scene")->capture_default_str();
  app.add_option("--time-limit", options.time_limit,
                 "Seconds of steps after which a run of an engine stops (0: no limit)")
      ->capture_default_str();
  app.add_option("--out", options.out, "Also write the tables (Markdown) to this file");
  CLI11_PARSE(app, argc, argv);
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
