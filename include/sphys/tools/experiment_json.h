#pragma once

// The experiment's results as JSON text: what `sphys experiment --json` prints and the Python
// module's RowResult.summary() and statistics dicts hold, under the same names.

#include <string>

#include "sphys/tools/experiment.h"

namespace sphys::tools {

// One row run: its Table 1 figures (contacts per frame, frame time, FPS, shares), its bodies and
// its plausibility figures. A figure a run cannot give (no frame came to rest) is null.
[[nodiscard]] std::string row_result_json(const RowResult& result);

// The §5 statistics (ours or the paper's); a correlation without spread (NaN) is null.
[[nodiscard]] std::string statistics_json(const ExperimentStatistics& statistics);

}  // namespace sphys::tools
