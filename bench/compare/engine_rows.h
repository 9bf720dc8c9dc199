#pragma once

// One row per engine of a scene's runs: the figures sphys-compare reports, worked out once for
// both its outputs (the Markdown tables and the CSV beside them).

#include <cstddef>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "run_engine.h"

namespace sphys::compare {

// All runs of one engine on one scene, pooled.
struct Pooled {
  std::vector<double> step_ms;
  std::vector<RunResult> runs;
};

struct EngineRow {
  std::string engine;
  bool ran = false;  // false: every run failed; worst.warnings says why
  std::size_t fewest_frames = 0;
  std::size_t most_frames = 0;
  bool stopped = false;  // a run stopped at the time limit
  double median_ms = 0.0;
  double mean_ms = 0.0;
  // This engine's median and mean step time over the reference engine's (reference_engine()),
  // over `ratio_frames` frames: all of them, or the first ones both ran when a run stopped.
  std::optional<double> median_ratio;
  std::optional<double> mean_ratio;
  std::size_t ratio_frames = 0;
  double us_per_body = 0.0;        // mean step time per body. unit: µs
  double contacts_per_step = 0.0;  // mean over the runs
  RunResult worst;                 // the plausibility figures: the worst over the runs
};

struct SceneRows {
  std::string layout;  // SxN, or a jointed scene's name
  int depth = 0;
  int frames = 0;         // asked for
  std::string reference;  // the engine the ratios divide by; empty: none ran
  std::vector<EngineRow> rows;
  std::vector<std::string> stops;  // the runs stopped at the time limit, in words
  bool jointed = false;            // the scene has joints: its rows' joint gaps mean something
  bool robot = false;  // the scene has a robot: its rows' tracking errors mean something
};

// The engine the ratios divide by: single-threaded sphys, else the first sphys:T listed (e.g. a
// scale series on two threads); empty if neither runs.
[[nodiscard]] std::string reference_engine(const std::vector<std::string>& engines);

// `results` holds an entry for every engine listed.
[[nodiscard]] SceneRows scene_rows(const std::string& layout, int depth, int frames,
                                   const std::vector<std::string>& engines,
                                   const std::map<std::string, Pooled>& results);

// printf's formatting into a string.
template <class... Values>
[[nodiscard]] std::string formatted(const char* pattern, Values... values) {
  const int size = std::snprintf(nullptr, 0, pattern, values...);
  if (size <= 0) return {};
  std::string text(static_cast<std::size_t>(size), '\0');
  std::snprintf(text.data(), text.size() + 1, pattern, values...);
  return text;
}

}  // namespace sphys::compare
