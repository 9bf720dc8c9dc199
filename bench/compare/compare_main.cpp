// sphys-compare: the benchmark scene run in sphys and in the engines a user would pick instead,
// alternating runs, single-threaded; prints per engine the median step time, steps/s, contacts,
// penetration and the state at the end, and each engine's median time over sphys's.

#include <algorithm>
#include <cstdio>
#include <exception>
#include <map>
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

std::string table(const std::string& layout, int depth, const std::vector<std::string>& engines,
                  const std::map<std::string, Pooled>& results, int frames) {
  std::ostringstream out;
  char line[512];
  std::snprintf(line, sizeof line, "\n### %s, depth %d, %d frames\n\n", layout.c_str(), depth,
                frames);
  out << line;
  out << "| engine | median ms/step | steps/s | × sphys median | mean ms/step | × sphys mean | "
         "contacts/step | deepest (m) | deepest, last second (m) | overlap at end (m) | "
         "KE at end (J) | moving at end | below plane | peak memory (MiB) |\n"
      << "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | "
         "---: | ---: |\n";
  const auto reference = results.find("sphys");
  const double sphys_median = reference == results.end() ? 0.0 : median(reference->second.step_ms);
  const double sphys_mean = reference == results.end() ? 0.0 : mean(reference->second.step_ms);
  for (const std::string& engine : engines) {
    const Pooled& pooled = results.at(engine);
    if (pooled.step_ms.empty()) {
      out << "| " << engine << " | " << pooled.runs.front().warnings
          << " | | | | | | | | | | | | |\n";
      continue;
    }
    const double ms = median(pooled.step_ms);
    const double mean_ms = mean(pooled.step_ms);
    // The plausibility figures are the worst over the runs.
    RunResult worst = pooled.runs.front();
    double contacts = 0.0;
    for (const RunResult& run : pooled.runs) {
      worst.deepest = std::max(worst.deepest, run.deepest);
      worst.deepest_last_second = std::max(worst.deepest_last_second, run.deepest_last_second);
      worst.end_overlap = std::max(worst.end_overlap, run.end_overlap);
      worst.kinetic_energy = std::max(worst.kinetic_energy, run.kinetic_energy);
      worst.moving = std::max(worst.moving, run.moving);
      worst.below = std::max(worst.below, run.below);
      if (run.peak_memory_mib) {
        worst.peak_memory_mib = std::max(worst.peak_memory_mib.value_or(0.0), *run.peak_memory_mib);
      }
      contacts += run.contacts_per_step;
      if (!run.warnings.empty()) worst.warnings = run.warnings;
    }
    contacts /= static_cast<double>(pooled.runs.size());
    const auto ratio = [](double value, double reference_value) {
      char text[32] = "";
      if (reference_value > 0.0) std::snprintf(text, sizeof text, "%.2f", value / reference_value);
      return std::string(text);
    };
    std::snprintf(
        line, sizeof line,
        "| %s | %.3f | %.0f | %s | %.3f | %s | %.1f | %.4f | %.4f | %.4f | %.3g | %u of %u "
        "| %u | %s |%s\n",
        engine.c_str(), ms, ms > 0.0 ? 1000.0 / ms : 0.0, ratio(ms, sphys_median).c_str(), mean_ms,
        ratio(mean_ms, sphys_mean).c_str(), contacts, static_cast<double>(worst.deepest),
        static_cast<double>(worst.deepest_last_second), static_cast<double>(worst.end_overlap),
        worst.kinetic_energy, worst.moving, worst.bodies, worst.below,
        memory_text(worst.peak_memory_mib).c_str(),
        worst.warnings.empty() ? "" : (" " + worst.warnings).c_str());
    out << line;
  }
  return out.str();
}

int run(const Options& options) {
  std::string report = "# sphys-compare\n\ncommand: `" + options.command +
                       "`\n\nmachine: " + tools::machine_description() +
                       "; one thread per engine (sphys:T: T threads); runs per engine: " +
                       std::to_string(options.runs) + "\n";
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
            result = run_engine(engine, scene, options.frames);
          } catch (const std::exception& error) {
            // One engine failing (e.g. out of memory for its contacts) leaves the others' rows.
            result.warnings = std::string("failed: ") + error.what();
          }
          Pooled& pooled = results[engine];
          pooled.step_ms.insert(pooled.step_ms.end(), result.step_ms.begin(), result.step_ms.end());
          pooled.runs.push_back(std::move(result));
          std::fprintf(stderr, "%s d%d %s run %d done\n", layout.c_str(), depth, engine.c_str(),
                       r + 1);
        }
      }
      const std::string part = table(layout, depth, options.engines, results, options.frames);
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
  app.add_option("--out", options.out, "Also write the tables (Markdown) to this file");
  CLI11_PARSE(app, argc, argv);
  options.command = "sphys-compare";
  for (int i = 1; i < argc; ++i) options.command += std::string(" ") + argv[i];
  try {
    if (options.frames < 1 || options.runs < 1)
      throw sphys::Error("--frames and --runs must be at least 1");
    return sphys::compare::run(options);
  } catch (const sphys::Error& error) {
    std::fprintf(stderr, "sphys-compare: error: %s\n", error.what());
    return 2;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "sphys-compare: %s\n", error.what());
    return 1;
  }
}
