#include "scene_schema.h"

#include <vector>

#include "sphys/settings_table.h"

namespace sphys::tools {
namespace {

// The keys of the top level and of "ground" besides the world's settings, which the settings
// table lists.
constexpr std::array<std::string_view, 12> kSceneOwnKeys = {
    "format", "version",  "time_step", "frames",         "solver", "sleep",
    "ground", "defaults", "bodies",    "pair_materials", "joints", "robots"};
constexpr std::array<std::string_view, 5> kGroundOwnKeys = {"type", "height", "size", "thickness",
                                                            "depth"};

// The keys of an object of the document: its own and the world settings it carries.
std::vector<std::string_view> keys_of(std::string_view object,
                                      std::span<const std::string_view> own) {
  std::vector<std::string_view> keys(own.begin(), own.end());
  for (const Setting& setting : settings_table()) {
    if (setting.in_scene && setting.object == object) keys.push_back(setting.key);
  }
  return keys;
}

}  // namespace

std::span<const std::string_view> scene_keys() {
  static const std::vector<std::string_view> keys = keys_of("", kSceneOwnKeys);
  return keys;
}

std::span<const std::string_view> ground_keys() {
  static const std::vector<std::string_view> keys = keys_of("ground", kGroundOwnKeys);
  return keys;
}

std::span<const std::string_view> setting_keys(std::string_view object) {
  static const std::vector<std::string_view> solver = keys_of("solver", {});
  static const std::vector<std::string_view> sleep = keys_of("sleep", {});
  if (object == "solver") return solver;
  return sleep;
}

}  // namespace sphys::tools
