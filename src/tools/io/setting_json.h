#pragma once

// A world setting as scene files write it, shared by the scene writer and the JSON Schema's
// defaults so that both show the same figure.

#include <string_view>

#include <nlohmann/json.hpp>

#include "sphys/settings_table.h"
#include "sphys/world.h"

namespace sphys::tools {

// 20, 0.0004 (a float in its shortest decimal form), true, "plausible", [0, -9.81, 0].
[[nodiscard]] nlohmann::ordered_json setting_json(const Setting& setting,
                                                  const WorldSettings& settings);

// The scene settings `object` carries ("" for the top level, "solver", ...), in table order.
[[nodiscard]] nlohmann::ordered_json settings_json(std::string_view object,
                                                   const WorldSettings& settings);

}  // namespace sphys::tools
