#include "io/setting_json.h"

#include <cstddef>
#include <cstdint>
#include <string>

#include "io/json_values.h"
#include "io/scene_schema.h"

namespace sphys::tools {
namespace {

// "must not be negative", "must be positive", "must be between 0 and 1": what a figure in
// `range` must be, as the messages of the other figures say it.
std::string range_requirement(const SettingRange& range) {
  if (range.has_min() && range.has_max()) {
    return "must be between " + number_text(range.min) + " and " + number_text(range.max);
  }
  if (range.has_min() && range.min == 0.0) {
    return range.min_inclusive ? "must not be negative" : "must be positive";
  }
  if (range.has_min()) {
    return (range.min_inclusive ? "must be at least " : "must be above ") + number_text(range.min);
  }
  return "must be at most " + number_text(range.max);
}

// A setting's figure. Scene files carry floats only: the range is checked on the value as stored,
// so that a positive figure that rounds to 0 in single precision is refused here, not by World.
double read_setting_number(const JsonNode& node, const SettingRange& range) {
  const float value = to_single(node, read_number(node));
  if (!range.contains(value)) {
    node.fail(range_requirement(range) + ", got " + shown_value(node.json()));
  }
  return value;
}

void read_setting(const JsonNode& node, const Setting& setting, WorldSettings& settings) {
  switch (setting.kind) {
    case SettingKind::kVector3: {
      const Vec3 value = read_vec3(node);
      for (std::size_t k = 0; k < 3; ++k) (void)read_setting_number(node.element(k), setting.range);
      setting.set_vector(settings, value);
      return;
    }
    case SettingKind::kBool:
      setting.set(settings, read_bool(node) ? 1.0 : 0.0);
      return;
    case SettingKind::kEnum:
      setting.set(settings, static_cast<double>(read_choice_index(node, setting.choices)));
      return;
    case SettingKind::kInteger:
      setting.set(settings,
                  static_cast<double>(read_integer(node, static_cast<long long>(setting.range.min),
                                                   static_cast<long long>(setting.range.max))));
      return;
    case SettingKind::kNumber:
      setting.set(settings, read_setting_number(node, setting.range));
      return;
  }
}

}  // namespace

Json setting_json(const Setting& setting, const WorldSettings& settings) {
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

Json settings_json(std::string_view object, const WorldSettings& settings) {
  Json out = Json::object();
  for (const Setting& setting : settings_table()) {
    if (setting.in_scene && setting.object == object) {
      out[std::string(setting.key)] = setting_json(setting, settings);
    }
  }
  return out;
}

void read_settings(const JsonNode& node, std::string_view object, WorldSettings& settings) {
  for (const Setting& setting : settings_table()) {
    if (!setting.in_scene || setting.object != object) continue;
    if (const auto n = node.find(std::string(setting.key))) read_setting(*n, setting, settings);
  }
}

void refuse_removed_settings(const JsonNode& node, std::string_view object) {
  if (!node.json().is_object()) return;
  for (const auto& item : node.json().items()) {
    const std::string field = object.empty() ? item.key() : std::string(object) + "." + item.key();
    if (const RemovedSetting* removed = removed_setting(field)) {
      node.child(item.key()).fail(removed_setting_message(*removed));
    }
  }
}

void read_settings_object(const JsonNode& node, std::string_view object, WorldSettings& settings) {
  refuse_removed_settings(node, object);
  check_keys(node, setting_keys(object));
  read_settings(node, object, settings);
}

}  // namespace sphys::tools
