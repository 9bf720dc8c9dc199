#pragma once

// The edges of a setting's range (sphys/settings_table.h), for tests that check every setting
// takes its bounds and refuses what lies just beyond them.

#include <cmath>
#include <limits>
#include <vector>

#include "sphys/settings_table.h"

namespace sphys::test {

// A value at a bound of a setting's range and one just beyond it, as the field stores them.
struct Edge {
  double at;
  double beyond;
};

// The float just past `value` towards `direction`: a float field cannot hold anything closer.
inline double next_float(double value, double direction) {
  return static_cast<double>(
      std::nextafter(static_cast<float>(value), static_cast<float>(direction)));
}

// Bounds of a count or figure, each with the closest value outside: 0 and -1 for ">= 0", the
// smallest positive float and 0 for "> 0". Counts below 0 cannot be stored and are left out.
inline std::vector<Edge> edges(const Setting& setting) {
  const SettingRange& range = setting.range;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<Edge> out;
  const bool integer = setting.kind == SettingKind::kInteger;
  if (range.has_min()) {
    if (integer) {
      if (range.min > 0.0) out.push_back({range.min, range.min - 1.0});
    } else if (range.min_inclusive) {
      out.push_back({range.min, next_float(range.min, -inf)});
    } else {
      out.push_back({next_float(range.min, inf), range.min});
    }
  }
  if (range.has_max()) {
    if (integer) {
      out.push_back({range.max, range.max + 1.0});
    } else if (range.max_inclusive) {
      out.push_back({range.max, next_float(range.max, inf)});
    } else {
      out.push_back({next_float(range.max, -inf), range.max});
    }
  }
  return out;
}

inline bool has_range(const Setting& setting) {
  return setting.kind == SettingKind::kInteger || setting.kind == SettingKind::kNumber;
}
}  // namespace sphys::test
