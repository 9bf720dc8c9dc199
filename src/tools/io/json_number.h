#pragma once

// Figures in JSON reports: a run may not give one (a share without frames, a correlation without
// spread), and JSON has no NaN.

#include <cmath>

#include <nlohmann/json.hpp>

namespace sphys::tools {

// The number, or null where there is none (NaN or infinite).
inline nlohmann::ordered_json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json();
}

}  // namespace sphys::tools
