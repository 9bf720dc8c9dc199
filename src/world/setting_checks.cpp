// A setting's value checked against its range, and the texts its messages, the command line's help
// and the docs say it with.

#include <array>
#include <charconv>
#include <cmath>

#include "sphys/error.h"
#include "sphys/settings_table.h"
#include "sphys/world.h"

namespace sphys {
namespace {

// What a value must be, for messages: "between 1 and 64", "finite and not negative".
std::string requirement(const Setting& setting) {
  const SettingRange& range = setting.range;
  if (setting.kind == SettingKind::kEnum) return "one of " + choices_text(setting);
  if (range.has_min() && range.has_max()) {
    return "between " + number_text(range.min) + " and " + number_text(range.max) +
           (setting.kind == SettingKind::kVector3 ? " in each component" : "");
  }
  std::string text;
  if (range.has_min()) {
    if (range.min == 0.0) {
      text = range.min_inclusive ? "finite and not negative" : "positive and finite";
    } else {
      text = range.min_inclusive ? "at least " : "above ";
      text += number_text(range.min);
    }
  } else {
    text = "finite";
  }
  return text;
}

std::string with_unit(std::string text, std::string_view unit) {
  if (!unit.empty() && unit != "dimensionless") {
    text += ' ';
    text += unit;
  }
  return text;
}

std::string vector_text(const Vec3& v) {
  std::string text = "[";
  for (int k = 0; k < 3; ++k) {
    if (k > 0) text += ", ";
    text += number_text(shortest_double(v[k]));
  }
  text += "]";
  return text;
}

// A value of the setting as scene files write it, for messages: "20", "0.0004", "true",
// "plausible", "[0, -9.81, 0]".
std::string value_text(const Setting& setting, const WorldSettings& settings) {
  switch (setting.kind) {
    case SettingKind::kVector3:
      return vector_text(setting.get_vector(settings));
    case SettingKind::kBool:
      return setting.get(settings) != 0.0 ? "true" : "false";
    case SettingKind::kEnum: {
      const double value = setting.get(settings);
      if (value >= 0.0 && value < static_cast<double>(setting.choices.size())) {
        return std::string(setting.choices[static_cast<std::size_t>(value)]);
      }
      return number_text(value);
    }
    case SettingKind::kInteger:
    case SettingKind::kNumber:
      break;
  }
  return number_text(setting.get(settings));
}

void check_setting(const Setting& setting, const WorldSettings& settings) {
  if (setting.kind == SettingKind::kVector3) {
    const Vec3 value = setting.get_vector(settings);
    const auto in_range = [&](float component) {
      return std::isfinite(component) && setting.range.contains(component);
    };
    if (in_range(value.x()) && in_range(value.y()) && in_range(value.z())) return;
  } else if (setting.kind == SettingKind::kBool) {
    return;
  } else {
    const double value = setting.get(settings);
    const bool valid = setting.kind == SettingKind::kEnum
                           ? value >= 0.0 && value < static_cast<double>(setting.choices.size())
                           : std::isfinite(value) && setting.range.contains(value);
    if (valid) return;
  }
  throw Error(std::string(setting.field) + " must be " + requirement(setting) + ", got " +
              with_unit(value_text(setting, settings), setting.unit));
}

}  // namespace

void check_world_settings(const WorldSettings& settings) {
  for (const Setting& setting : settings_table()) check_setting(setting, settings);
}

bool SettingRange::contains(double value) const {
  const bool above_min = min_inclusive ? value >= min : value > min;
  const bool below_max = max_inclusive ? value <= max : value < max;
  return above_min && below_max;
}

std::string choices_text(const Setting& setting) {
  std::string text;
  for (std::size_t i = 0; i < setting.choices.size(); ++i) {
    if (i > 0) text += i + 1 == setting.choices.size() ? " or " : ", ";
    text += setting.choices[i];
  }
  return text;
}

double shortest_double(float value) {
  std::array<char, 32> buffer{};
  const auto printed = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  double shortest = 0.0;
  std::from_chars(buffer.data(), printed.ptr, shortest);
  return static_cast<float>(shortest) == value ? shortest : static_cast<double>(value);
}

std::string number_text(double value) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return {buffer.data(), result.ptr};
}

}  // namespace sphys
