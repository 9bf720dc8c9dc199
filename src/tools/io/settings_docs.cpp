#include "sphys/tools/settings_docs.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/setting_json.h"
#include "sphys/error.h"
#include "sphys/settings_table.h"
#include "sphys/world.h"

namespace sphys::tools {
namespace {

// The committed files' line length, as .clang-format has it for the code.
constexpr std::size_t kColumns = 100;
// Objects of plain values up to this many members stay on one line ({"w": 1, "x": 0, ...}).
constexpr std::size_t kMaxInlineMembers = 4;

// ---- The schema ----

// 1 rather than 1.0: the committed schema writes whole numbers as integers. The bounds and
// defaults of settings are far inside an int.
Json number_json(double value) {
  if (value == std::floor(value) && std::abs(value) <= std::numeric_limits<int>::max()) {
    return static_cast<int>(value);
  }
  return value;
}

Json whole_numbers_as_integers(Json value) {
  if (value.is_number_float()) return number_json(value.get<double>());
  if (value.is_structured()) {
    for (auto& item : value) item = whole_numbers_as_integers(std::move(item));
  }
  return value;
}

// The bounds of a number (or of each component of a vector) as JSON Schema keywords.
Json range_schema(const SettingRange& range) {
  Json out = Json::object();
  if (range.has_min()) {
    out[range.min_inclusive ? "minimum" : "exclusiveMinimum"] = number_json(range.min);
  }
  if (range.has_max()) {
    out[range.max_inclusive ? "maximum" : "exclusiveMaximum"] = number_json(range.max);
  }
  return out;
}

Json setting_schema(const Setting& setting) {
  Json out = Json::object();
  std::string description(setting.doc);
  if (!setting.unit.empty()) description += " unit: " + std::string(setting.unit);
  out["description"] = description;
  switch (setting.kind) {
    case SettingKind::kVector3:
      out["$ref"] = "#/$defs/vector";
      if (const Json bounds = range_schema(setting.range); !bounds.empty()) out["items"] = bounds;
      break;
    case SettingKind::kBool:
      out["type"] = "boolean";
      break;
    case SettingKind::kEnum:
      out["enum"] = Json::array();
      for (const std::string_view choice : setting.choices) out["enum"].push_back(choice);
      break;
    case SettingKind::kInteger:
    case SettingKind::kNumber: {
      out["type"] = setting.kind == SettingKind::kInteger ? "integer" : "number";
      out.update(range_schema(setting.range));
      break;
    }
  }
  out["default"] = whole_numbers_as_integers(setting_json(setting, WorldSettings{}));
  return out;
}

Json& member(Json& object, std::string_view pointer) {
  const Json::json_pointer at{std::string(pointer)};
  if (!object.contains(at)) {
    throw Error("the scene schema has no " + std::string(pointer) + " to put the settings in");
  }
  return object[at];
}

bool plain(const Json& value) { return value.is_primitive(); }

bool plain_list(const Json& value) {
  return value.is_array() && std::all_of(value.begin(), value.end(), plain);
}

// Short lists of plain values and small objects of them without a description, as the committed
// schema writes them: [0, -9.81, 0], {"$ref": "#/$defs/vector"}.
bool inline_form(const Json& value) {
  if (value.is_array()) return plain_list(value);
  if (!value.is_object()) return true;
  return value.size() <= kMaxInlineMembers && !value.contains("description") &&
         std::all_of(value.begin(), value.end(),
                     [](const Json& item) { return plain(item) || plain_list(item); });
}

std::string one_line(const Json& value) {
  if (value.is_primitive()) return value.dump();
  std::string text = value.is_array() ? "[" : "{";
  bool first = true;
  for (const auto& item : value.items()) {
    if (!first) text += ", ";
    first = false;
    if (value.is_object()) text += Json(item.key()).dump() + ": ";
    text += one_line(item.value());
  }
  return text + (value.is_array() ? "]" : "}");
}

// Appends `value`, which follows `prefix` (a key and ": ", or nothing) at `indent`.
void print(const Json& value, std::size_t indent, const std::string& prefix, bool last,
           std::string& out) {
  const std::string margin(indent, ' ');
  const std::string comma = last ? "" : ",";
  const std::string line = margin + prefix + one_line(value) + comma;
  const bool empty = value.is_structured() && value.empty();
  if (!value.is_structured() || empty || (inline_form(value) && line.size() <= kColumns)) {
    out += line + "\n";
    return;
  }
  out += margin + prefix + (value.is_array() ? "[" : "{") + "\n";
  std::size_t left = value.size();
  for (const auto& item : value.items()) {
    const std::string key = value.is_object() ? Json(item.key()).dump() + ": " : "";
    print(item.value(), indent + 2, key, --left == 0, out);
  }
  out += margin + (value.is_array() ? "]" : "}") + comma + "\n";
}

// ---- docs/scenes.md ----

// Cells of a Markdown table cannot hold a bare "|".
std::string cell(std::string_view text) {
  std::string out;
  for (const char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

std::string code(std::string_view text) { return "`" + std::string(text) + "`"; }

// The page's cells continue a sentence: "`>= 0`: penetration left alone, ..." without a full stop.
std::string clause(std::string_view doc) {
  std::string text = cell(doc);
  if (text.ends_with('.')) text.pop_back();
  if (text.size() > 1 && std::isupper(static_cast<unsigned char>(text[0])) != 0 &&
      std::isupper(static_cast<unsigned char>(text[1])) == 0) {
    text[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(text[0])));
  }
  return text;
}

std::string type_text(const Setting& setting) {
  switch (setting.kind) {
    case SettingKind::kInteger:
      return "integer";
    case SettingKind::kNumber:
      return "number";
    case SettingKind::kBool:
      return "boolean";
    case SettingKind::kEnum:
      return "string";
    case SettingKind::kVector3:
      break;
  }
  return "[x, y, z]";
}

// The "allowed" column: the valid values, then what the setting does.
std::string allowed_text(const Setting& setting) {
  const SettingRange& range = setting.range;
  std::string values;
  switch (setting.kind) {
    case SettingKind::kBool:
      break;
    case SettingKind::kEnum:
      for (std::size_t i = 0; i < setting.choices.size(); ++i) {
        if (i > 0) values += i + 1 == setting.choices.size() ? " or " : ", ";
        values += code("\"" + std::string(setting.choices[i]) + "\"");
      }
      break;
    case SettingKind::kVector3:
    case SettingKind::kInteger:
    case SettingKind::kNumber:
      if (range.has_min() && range.has_max()) {
        values = code(number_text(range.min)) + " to " + code(number_text(range.max));
        if (setting.kind == SettingKind::kVector3) values += " each";
      } else if (range.has_min()) {
        values = code((range.min_inclusive ? ">= " : "> ") + number_text(range.min));
      } else if (range.has_max()) {
        values = code((range.max_inclusive ? "<= " : "< ") + number_text(range.max));
      } else {
        values = "finite";
      }
      break;
  }
  return values.empty() ? clause(setting.doc) : values + ": " + clause(setting.doc);
}

std::string doc_row(const Setting& setting) {
  const Json value = whole_numbers_as_integers(setting_json(setting, WorldSettings{}));
  const std::string unit = setting.unit.empty() ? "" : " " + std::string(setting.unit);
  return "| " + code(setting.key) + " | " + type_text(setting) + " | " + code(one_line(value)) +
         " |" + unit + " | " + allowed_text(setting) + " |";
}

// The key of a table row "| `key` | ...", or nothing.
std::string_view row_key(std::string_view line) {
  constexpr std::string_view kStart = "| `";
  if (!line.starts_with(kStart)) return {};
  line.remove_prefix(kStart.size());
  return line.substr(0, line.find('`'));
}

std::vector<std::string> lines_of(std::string_view text) {
  std::vector<std::string> lines;
  std::size_t begin = 0;
  while (begin < text.size()) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    lines.emplace_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  return lines;
}

// Replaces, in the section under `heading`, the run of rows of `object`'s settings by the
// table's.
void replace_rows(std::vector<std::string>& lines, std::string_view heading,
                  std::string_view object) {
  std::vector<const Setting*> settings;
  for (const Setting& setting : settings_table()) {
    if (setting.in_scene && setting.object == object) settings.push_back(&setting);
  }
  const auto is_setting = [&](std::string_view key) {
    return std::any_of(settings.begin(), settings.end(),
                       [&](const Setting* setting) { return setting->key == key; });
  };
  const auto begin = std::find(lines.begin(), lines.end(), heading);
  if (begin == lines.end())
    throw Error("docs/scenes.md has no section \"" + std::string(heading) + "\"");
  const auto end = std::find_if(begin + 1, lines.end(),
                                [](const std::string& line) { return line.starts_with("## "); });
  auto first =
      std::find_if(begin, end, [&](const std::string& line) { return is_setting(row_key(line)); });
  if (first == end) {
    throw Error("docs/scenes.md: no row of a setting under \"" + std::string(heading) + "\"");
  }
  auto last = first;
  for (auto line = first; line != end; ++line) {
    if (is_setting(row_key(line->c_str()))) last = line;
  }
  for (auto line = first; line != last; ++line) {
    if (!is_setting(row_key(line->c_str()))) {
      throw Error("docs/scenes.md: under \"" + std::string(heading) + "\", the row \"" + *line +
                  "\" lies among the settings' rows");
    }
  }
  std::vector<std::string> rows;
  for (const Setting* setting : settings) rows.push_back(doc_row(*setting));
  const auto at = lines.erase(first, last + 1);
  lines.insert(at, rows.begin(), rows.end());
}

}  // namespace

std::string scene_schema_with_settings(std::string_view schema) {
  Json document;
  try {
    document = Json::parse(schema);
  } catch (const Json::exception& error) {
    throw Error(std::string("the scene schema is not JSON: ") + error.what());
  }
  for (const std::string_view object : {"solver", "sleep"}) {
    member(document, "/$defs/" + std::string(object) + "/properties") = Json::object();
  }
  for (const Setting& setting : settings_table()) {
    if (!setting.in_scene) continue;
    const std::string properties = setting.object.empty()
                                       ? "/properties"
                                       : "/$defs/" + std::string(setting.object) + "/properties";
    member(document, properties)[std::string(setting.key)] = setting_schema(setting);
  }
  std::string out;
  print(document, 0, "", true, out);
  return out;
}

std::string scenes_doc_with_settings(std::string_view doc) {
  std::vector<std::string> lines = lines_of(doc);
  constexpr std::array<std::pair<std::string_view, std::string_view>, 4> kSections = {{
      {"## Top level", ""},
      {"## Solver", "solver"},
      {"## Sleep", "sleep"},
      {"## Ground", "ground"},
  }};
  for (const auto& [heading, object] : kSections) replace_rows(lines, heading, object);
  std::string out;
  for (const std::string& line : lines) out += line + "\n";
  return out;
}

}  // namespace sphys::tools
