#pragma once

// The world's settings as scene files carry them: written by the scene writer and the JSON
// Schema's defaults, so that both show the same figure, and read by the scene reader.

#include <string_view>

#include "io/json_node.h"
#include "sphys/settings_table.h"
#include "sphys/world.h"

namespace sphys::tools {

// 20, 0.0004 (a float in its shortest decimal form), true, "plausible", [0, -9.81, 0].
[[nodiscard]] Json setting_json(const Setting& setting, const WorldSettings& settings);

// The scene settings `object` carries ("" for the top level, "solver", ...), in table order.
[[nodiscard]] Json settings_json(std::string_view object, const WorldSettings& settings);

// Applies the settings that the object at `node` carries as `object` over `settings`; other keys
// are the caller's to check.
void read_settings(const JsonNode& node, std::string_view object, WorldSettings& settings);

// Fails naming the first key of the object at `node` (`object` as in read_settings) that is a
// setting sphys no longer has, with what replaced it.
void refuse_removed_settings(const JsonNode& node, std::string_view object);

// "solver" and "sleep": objects of world settings only. A setting sphys no longer has is refused
// with what replaced it.
void read_settings_object(const JsonNode& node, std::string_view object, WorldSettings& settings);

}  // namespace sphys::tools
