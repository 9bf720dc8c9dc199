#include "io/setting_json.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace sphys::tools {

nlohmann::ordered_json setting_json(const Setting& setting, const WorldSettings& settings) {
  using Json = nlohmann::ordered_json;
  switch (setting.kind) {
    case SettingKind::kVector3: {
      const Vec3 v = setting.get_vector(settings);
      return Json::array({shortest_double(v.x()), shortest_double(v.y()), shortest_double(v.z())});
    }
    case SettingKind::kBool:
      return setting.get(settings) != 0.0;
    case SettingKind::kEnum:
      return setting.choices[static_cast<std::size_t>(setting.get(settings))];
    case SettingKind::kInteger:
      return static_cast<std::uint64_t>(setting.get(settings));
    case SettingKind::kNumber:
      break;
  }
  return setting.get(settings);
}

nlohmann::ordered_json settings_json(std::string_view object, const WorldSettings& settings) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const Setting& setting : settings_table()) {
    if (setting.in_scene && setting.object == object) {
      out[std::string(setting.key)] = setting_json(setting, settings);
    }
  }
  return out;
}

}  // namespace sphys::tools
