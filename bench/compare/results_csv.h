#pragma once

// sphys-compare's results as CSV, one row per engine and scene, each row carrying how and where
// it was measured, so that runs from many machines and dates can be read into one table
// (bench/plot_results.py).

#include <filesystem>
#include <string>
#include <vector>

#include "engine_rows.h"

namespace sphys::compare {

// What every row of a run shares.
struct RunDescription {
  std::string date;         // UTC, YYYY-MM-DD
  std::string command;      // as typed
  std::string build;        // the build type and the options that change speed
  int runs = 1;             // per engine and scene
  double time_limit = 0.0;  // of summed step times per run, 0: none. unit: s
};

// The file is written whole or not at all; throws sphys::Error naming it when it cannot be.
void write_results_csv(const std::filesystem::path& path, const RunDescription& run,
                       const std::vector<SceneRows>& scenes);

}  // namespace sphys::compare
