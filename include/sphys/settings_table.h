#pragma once

// The world's settings, each declared once: its name in scene files, kind, unit, valid range,
// one line of documentation and where it lives in WorldSettings. The default is what a
// default-constructed WorldSettings holds. Validation (check_world_settings), the scene reader and
// writer, the command line's --help, docs/scene.schema.json and the tables of docs/scenes.md all
// come from this table, so that a setting cannot mean one thing in one place and another
// elsewhere. The settings as a person types and reads them (--set, --help) are the tools'
// (sphys/tools/setting_text.h).

#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <string_view>

#include "sphys/math.h"
#include "sphys/setting_limits.h"

namespace sphys {

struct WorldSettings;

// What kind of value a setting holds, which says how files and the command line write it.
enum class SettingKind {
  kInteger,  // an unsigned count, exact in a double
  kNumber,   // a float or double figure
  kBool,     // a flag: 0 or 1 as a double
  kEnum,     // one of `choices`, by the enum's value (0, 1, ...)
  kVector3,  // [x, y, z], each component finite
};

// The values a setting may take: a closed, open or half-open interval. An infinite end is no
// bound; every number must be finite besides.
struct SettingRange {
  double min = -std::numeric_limits<double>::infinity();  // low end, in the setting's unit
  double max = std::numeric_limits<double>::infinity();   // high end, in the setting's unit
  bool min_inclusive = true;                              // min itself is a valid value
  bool max_inclusive = true;                              // max itself is a valid value

  // True when the low end bounds (it is finite).
  [[nodiscard]] bool has_min() const { return min > -std::numeric_limits<double>::infinity(); }
  // True when the high end bounds (it is finite).
  [[nodiscard]] bool has_max() const { return max < std::numeric_limits<double>::infinity(); }
  // Whether `value` lies between the ends, each inclusive or not as said; NaN never does.
  // Finiteness is not checked here.
  [[nodiscard]] bool contains(double value) const;
};

// One world setting, as the table declares it (the top of this file says who reads it).
struct Setting {
  // Where scene files carry it: the object ("" for the top level, "solver", "sleep", "ground")
  // and the key inside it. Settings a scene does not carry (`in_scene` false) have no object.
  std::string_view object{};
  std::string_view key{};  // the key inside `object` ("soft_substeps")
  bool in_scene = true;    // false for a setting scene files do not carry
  // The field of WorldSettings, as C++ names it ("solver.soft_substeps"); messages of the
  // runtime name the setting so.
  std::string_view field{};
  SettingKind kind = SettingKind::kNumber;  // how its value is written and read
  std::string_view unit{};                  // "" for a dimensionless figure, a flag or a choice
  SettingRange range{};  // kInteger, kNumber: the values it may take; kVector3: each component
  std::span<const std::string_view> choices{};  // kEnum: the names, in the order of the values
  std::string_view doc{};                       // one sentence or two, what it does and why
  // The field's value as a double: a count, 0 or 1, an enum's value; a float as the double of
  // its shortest decimal form (shortest_double), so that 0.3f reads "0.3". Not for kVector3.
  double (*get)(const WorldSettings&) = nullptr;
  void (*set)(WorldSettings&, double) = nullptr;  // stores a value as `get` gives it
  // kVector3 only.
  Vec3 (*get_vector)(const WorldSettings&) = nullptr;
  void (*set_vector)(WorldSettings&, const Vec3&) = nullptr;  // kVector3: stores the vector
};

// A setting sphys had and no longer has, with what replaced it: a scene file or --set that names
// it is refused with this note rather than read as something it no longer means.
struct RemovedSetting {
  std::string_view field;        // as Setting::field named it ("solver.shock_speed")
  std::string_view replacement;  // what to set instead, and why
};
// The removed setting of this field, or null when it is not one.
[[nodiscard]] const RemovedSetting* removed_setting(std::string_view field);
// "<field> was removed: <replacement>", for the messages that refuse it.
[[nodiscard]] std::string removed_setting_message(const RemovedSetting& removed);

// Every setting, in the order scene files and docs/scenes.md list them: the top level, then
// "solver", "sleep", "ground", then those scene files do not carry.
[[nodiscard]] std::span<const Setting> settings_table();

// The setting of this WorldSettings field ("collision_passes", "solver.contacts"). Throws
// std::out_of_range when there is none: a caller's mistake, not bad input.
[[nodiscard]] const Setting& setting_of(std::string_view field);

// Throws sphys::Error for the first setting outside its range, naming the field, the range and
// the value with its unit ("solver.manifold_points must be between 1 and 8, got 9 contacts").
void check_world_settings(const WorldSettings& settings);

// "paper or plausible", "a, b or c": the choices of an enum setting as a person reads them.
[[nodiscard]] std::string choices_text(const Setting& setting);

// The shortest decimal form of a float, as a double: 0.3f gives 0.3 rather than
// 0.30000001192092896. It rounds back to the same float for every finite float but one pair
// (±7.038531e-26, where rounding twice lands on a neighbour); those give the float's exact value.
[[nodiscard]] double shortest_double(float value);
// The shortest decimal text that reads back to this double ("0.0004", "1", "1e+39").
[[nodiscard]] std::string number_text(double value);

}  // namespace sphys
