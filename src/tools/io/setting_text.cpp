#include "sphys/tools/setting_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <span>
#include <system_error>

#include "sphys/error.h"
#include "sphys/world.h"

namespace sphys {

void set_setting_from_text(WorldSettings& settings, std::string_view field, std::string_view text,
                           std::string_view source) {
  const std::string where = std::string(source) + " " + std::string(field) + ": ";
  const std::span<const Setting> table = settings_table();
  const auto found = std::find_if(table.begin(), table.end(),
                                  [&](const Setting& setting) { return setting.field == field; });
  if (found == table.end()) {
    if (const RemovedSetting* removed = removed_setting(field)) {
      throw Error(std::string(source) + " " + removed_setting_message(*removed));
    }
    throw Error(std::string(source) + ": no setting " + std::string(field));
  }
  const Setting& setting = *found;
  double value = 0.0;
  switch (setting.kind) {
    case SettingKind::kVector3:
      throw Error(where + "a vector is set in a scene file");
    case SettingKind::kBool:
      if (text != "true" && text != "false") throw Error(where + "must be true or false");
      value = text == "true" ? 1.0 : 0.0;
      break;
    case SettingKind::kEnum: {
      const auto choice = std::find(setting.choices.begin(), setting.choices.end(), text);
      if (choice == setting.choices.end()) {
        throw Error(where + "must be " + range_text(setting) + ", got '" + std::string(text) + "'");
      }
      value = static_cast<double>(choice - setting.choices.begin());
      break;
    }
    default: {
      const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
      if (error != std::errc{} || end != text.data() + text.size() || !std::isfinite(value)) {
        throw Error(where + "must be a finite number, got '" + std::string(text) + "'");
      }
      if (setting.kind == SettingKind::kInteger &&
          (value != std::floor(value) || value < 0.0 || value > 4294967295.0)) {
        throw Error(where + "must be a whole number from 0, got '" + std::string(text) + "'");
      }
    }
  }
  setting.set(settings, value);
}

std::string range_text(const Setting& setting) {
  switch (setting.kind) {
    case SettingKind::kBool:
      return "true or false";
    case SettingKind::kEnum:
      return choices_text(setting);
    case SettingKind::kVector3:
    case SettingKind::kInteger:
    case SettingKind::kNumber:
      break;
  }
  const SettingRange& range = setting.range;
  if (range.has_min() && range.has_max()) {
    return number_text(range.min) + " to " + number_text(range.max) +
           (setting.kind == SettingKind::kVector3 ? " each" : "");
  }
  std::string text = "finite";
  if (range.has_min()) {
    text = range.min_inclusive ? ">= " : "> ";
    text += number_text(range.min);
  } else if (range.has_max()) {
    text = range.max_inclusive ? "<= " : "< ";
    text += number_text(range.max);
  }
  return text;
}

std::string option_help(const Setting& setting) {
  std::string text(setting.doc);
  text += " Valid: ";
  text += range_text(setting);
  if (!setting.unit.empty() && setting.unit != "dimensionless") {
    text += "; unit: ";
    text += setting.unit;
  }
  text += ".";
  return text;
}

}  // namespace sphys
