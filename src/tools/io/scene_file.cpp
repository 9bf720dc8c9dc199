#include "sphys/tools/scene_file.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "input_file.h"
#include "io/setting_json.h"
#include "sphys/error.h"
#include "sphys/material.h"
#include "sphys/settings_table.h"
#include "sphys/tools/model.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;
// Objects keep their keys in document order, so that a written scene reads in the order of
// docs/scenes.md.
using Json = nlohmann::ordered_json;

constexpr std::string_view kFormat = "sphys-scene";
constexpr long long kVersion = 1;

constexpr long long kMaxFrames = 10'000'000;
constexpr long long kMaxTriangles = 4'294'967'295;  // 2^32 - 1, beyond any mesh sphys loads
constexpr long long kMinTriangles = 4;              // a tetrahedron, the smallest closed mesh
constexpr long long kMaxGroundDepth = 7;
constexpr long long kMaxTreeDepth = 6;

// The physical figures a scene may give, [min, max] in `unit`: wide enough for any rigid body
// from a grain (1 mm, 1 mg) to a building (1 km, 10^9 kg), narrow enough that every product the
// simulation forms from them (a mass from density and volume, an inertia from mass and size
// squared, a step's travel from speed and time step) stays finite and normal in single precision,
// so nothing accepted here fails later (docs/scenes.md lists them).
struct PhysicalRange {
  double min;
  double max;
  std::string_view unit;
};
constexpr PhysicalRange kTimeStepRange{1e-6, 1.0, "s"};
constexpr PhysicalRange kBodySizeRange{1e-3, 1e3, "m"};
constexpr PhysicalRange kDensityRange{1e-3, 1e6, "kg/m³"};
constexpr PhysicalRange kMassRange{kMinBodyMass, kMaxBodyMass, "kg"};
constexpr PhysicalRange kGroundSizeRange{1e-2, 1e5, "m"};
constexpr PhysicalRange kGroundThicknessRange{1e-3, 1e4, "m"};
// Coordinates beyond this lose centimetres in single precision. unit: m
constexpr double kMaxCoordinate = 1e5;
// Beyond any rigid body's speed (a rifle bullet: 1,000 m/s). unit: m/s; rad/s for spin
constexpr double kMaxSpeed = 1e4;
// A double from here on rounds to infinity as a float: FLT_MAX plus half its ulp.
constexpr double kFloatOverflow = 0x1.ffffffp127;
// A quaternion whose length is within this of 1 is kept as written: dividing floats that already
// make a unit quaternion by their length would move their last bits, and a written scene must
// read back exactly. Anything further from 1 is normalised.
constexpr double kUnitTolerance = 1e-6;
// Longer values are cut short in messages.
constexpr std::size_t kMaxShown = 40;
// Arrays and objects nested deeper are refused as they open. A scene's deepest value, a body's
// orientation axis, is 5 deep; each open container keeps its JSON pointer, so without a bound
// 10^5 unclosed '[' (100 kB) took 30 s and 9.8 GB.
constexpr std::size_t kMaxNesting = 16;

// The keys of the top level and of "ground" besides the world's settings, which the settings
// table lists (sphys/settings_table.h).
constexpr std::array<std::string_view, 10> kSceneOwnKeys = {
    "format", "version", "time_step", "frames", "solver",
    "sleep",  "ground",  "defaults",  "bodies", "pair_materials"};
constexpr std::array<std::string_view, 5> kGroundOwnKeys = {"type", "height", "size", "thickness",
                                                            "depth"};
// Every integer up to here is exact in a double, as a JSON number is read.
constexpr long long kMaxExactInteger = 9'007'199'254'740'992;  // 2^53
constexpr std::array<std::string_view, 3> kPairMaterialKeys = {"bodies", "friction", "restitution"};
constexpr std::array<std::string_view, 13> kBodyKeys = {"mesh",
                                                        "triangles",
                                                        "size",
                                                        "sphere_tree",
                                                        "position",
                                                        "orientation",
                                                        "linear_velocity",
                                                        "angular_velocity",
                                                        "density",
                                                        "mass",
                                                        "restitution",
                                                        "friction",
                                                        "static"};
// Set per body only: a shared position or orientation would stack every body in one place.
constexpr std::array<std::string_view, 2> kPerBodyKeys = {"position", "orientation"};
constexpr std::array<std::string_view, 3> kTreeKeys = {"method", "branching", "depth"};
constexpr std::array<std::string_view, 4> kQuaternionKeys = {"w", "x", "y", "z"};
constexpr std::array<std::string_view, 1> kYawKeys = {"yaw_degrees"};
constexpr std::array<std::string_view, 2> kAxisAngleKeys = {"axis", "angle_degrees"};
constexpr std::array<std::string_view, 7> kOrientationKeys = {
    "w", "x", "y", "z", "yaw_degrees", "axis", "angle_degrees"};

template <typename Enum, std::size_t N>
using NameTable = std::array<std::pair<Enum, std::string_view>, N>;

constexpr NameTable<GroundSpec::Kind, 3> kGroundKinds{{
    {GroundSpec::Kind::kOctreeBox, "octree-box"},
    {GroundSpec::Kind::kPlane, "plane"},
    {GroundSpec::Kind::kNone, "none"},
}};

template <typename Enum, std::size_t N>
std::string_view name_of(Enum value, const NameTable<Enum, N>& table) {
  for (const auto& [entry, name] : table) {
    if (entry == value) return name;
  }
  return "unknown";
}

// The keys of an object of the document: its own and the world settings it carries.
std::vector<std::string_view> keys_of(std::string_view object,
                                      std::span<const std::string_view> own) {
  std::vector<std::string_view> keys(own.begin(), own.end());
  for (const Setting& setting : settings_table()) {
    if (setting.in_scene && setting.object == object) keys.push_back(setting.key);
  }
  return keys;
}

const std::vector<std::string_view>& scene_keys() {
  static const std::vector<std::string_view> keys = keys_of("", kSceneOwnKeys);
  return keys;
}

const std::vector<std::string_view>& ground_keys() {
  static const std::vector<std::string_view> keys = keys_of("ground", kGroundOwnKeys);
  return keys;
}

const std::vector<std::string_view>& setting_keys(std::string_view object) {
  static const std::vector<std::string_view> solver = keys_of("solver", {});
  static const std::vector<std::string_view> sleep = keys_of("sleep", {});
  return object == "solver" ? solver : sleep;
}

std::string joined(const auto& names) {
  std::string out;
  for (const std::string_view name : names) {
    if (!out.empty()) out += ", ";
    out += name;
  }
  return out;
}

// A JSON pointer reference token (RFC 6901); control characters become '?' so that a message
// stays on one line.
std::string pointer_token(std::string_view key) {
  std::string out;
  for (const char c : key) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += std::iscntrl(static_cast<unsigned char>(c)) != 0 ? '?' : c;
    }
  }
  return out;
}

// The line and column (both from 1) of the character at `offset`, or of the last one when the
// offset is past the end.
std::pair<std::size_t, std::size_t> line_and_column(std::string_view text, std::size_t offset) {
  if (text.empty()) return {1, 1};
  offset = std::min(offset, text.size() - 1);
  const std::string_view before = text.substr(0, offset);
  const std::size_t line =
      1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
  const std::size_t newline = before.rfind('\n');
  const std::size_t line_start = newline == std::string_view::npos ? 0 : newline + 1;
  return {line, offset - line_start + 1};
}

// The word of letters around `offset` with the sign before it, and where it begins: what a writer
// of "NaN" or "-Infinity" meant as a number.
struct Word {
  std::size_t begin = 0;
  std::string text;
};

Word word_at(std::string_view text, std::size_t offset) {
  const auto is_letter = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; };
  std::size_t begin = std::min(offset, text.size());
  while (begin > 0 && is_letter(text[begin - 1])) --begin;
  if (begin > 0 && (text[begin - 1] == '-' || text[begin - 1] == '+')) --begin;
  std::size_t end = std::min(offset, text.size());
  while (end < text.size() && is_letter(text[end])) ++end;
  return {begin, std::string(text.substr(begin, end - begin))};
}

bool names_non_finite(std::string word) {
  if (!word.empty() && (word.front() == '-' || word.front() == '+')) word.erase(0, 1);
  for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return word == "nan" || word == "inf" || word == "infinity";
}

// nlohmann's explanation without its "[json.exception...] parse error at line L, column C: "
// prefix, which our message replaces.
std::string nlohmann_reason(std::string_view what) {
  if (what.starts_with('[')) what.remove_prefix(std::min(what.find("] ") + 2, what.size()));
  if (what.starts_with("parse error")) {
    const std::size_t colon = what.find(": ");
    if (colon != std::string_view::npos) what.remove_prefix(colon + 2);
  }
  return std::string(what);
}

// Builds the document as nlohmann's own parser does, and in addition refuses duplicate keys
// (JSON leaves their meaning open and nlohmann keeps the last one silently) and reports every
// syntax error, NaN and Infinity included, and every number beyond a double with its line and
// column.
class DocumentBuilder final : public nlohmann::json_sax<Json> {
 public:
  DocumentBuilder(std::string_view text, const fs::path& name) : text_(text), name_(name) {}

  [[nodiscard]] Json take() { return std::move(root_); }

  bool null() override { return add(nullptr); }
  bool boolean(bool value) override { return add(value); }
  bool number_integer(number_integer_t value) override { return add(value); }
  bool number_unsigned(number_unsigned_t value) override { return add(value); }
  bool number_float(number_float_t value, const string_t& /*text*/) override { return add(value); }
  bool string(string_t& value) override { return add(std::move(value)); }
  bool binary(binary_t& value) override { return add(std::move(value)); }
  bool start_object(std::size_t /*size*/) override { return open(Json::object()); }
  bool start_array(std::size_t /*size*/) override { return open(Json::array()); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }

  bool key(string_t& key) override {
    const Container& object = open_.back();
    if (object.value->contains(key)) {
      throw Error::at_json_path(name_, object.pointer + "/" + pointer_token(key), "duplicate key");
    }
    key_ = std::move(key);
    return true;
  }

  bool parse_error(std::size_t position, const std::string& token,
                   const Json::exception& error) override {
    constexpr int kNumberOverflow = 406;
    // nlohmann's position counts the characters read, the offending one included; for a number
    // beyond a double it is the index of the character after the number.
    std::size_t offset = position == 0 ? 0 : position - 1;
    std::string reason;
    if (error.id == kNumberOverflow) {
      offset = position >= token.size() ? position - token.size() : 0;
      reason = "the number " + token + " is beyond the range of a double";
    } else if (const Word word = word_at(text_, offset); names_non_finite(word.text)) {
      offset = word.begin;
      reason = word.text + " is not a number in JSON; every number must be finite";
    } else {
      reason = "not valid JSON: " + nlohmann_reason(error.what());
    }
    const auto [line, column] = line_and_column(text_, offset);
    throw Error::at_line(name_, line, "column " + std::to_string(column) + ": " + reason);
  }

 private:
  struct Container {
    Json* value;
    std::string pointer;
  };

  // Puts a value where the parser is: the root, the next element of the innermost array or the
  // value of the key just read; returns it with its JSON pointer.
  Container place(Json value) {
    if (open_.empty()) {
      root_ = std::move(value);
      return {&root_, ""};
    }
    const Container& parent = open_.back();
    if (parent.value->is_array()) {
      // Counted as they are read, so that a file of millions of bodies stops here, at once.
      if (parent.pointer == "/bodies" && parent.value->size() == kMaxSceneBodies) {
        throw Error::at_json_path(name_, parent.pointer,
                                  "more than " + std::to_string(kMaxSceneBodies) +
                                      " bodies; a scene holds at most that many");
      }
      const std::string pointer = parent.pointer + "/" + std::to_string(parent.value->size());
      parent.value->push_back(std::move(value));
      return {&parent.value->back(), pointer};
    }
    Json& slot = (*parent.value)[key_];
    slot = std::move(value);
    return {&slot, parent.pointer + "/" + pointer_token(key_)};
  }

  bool add(Json value) {
    place(std::move(value));
    return true;
  }
  // Only the innermost container grows, so the pointers to the enclosing ones stay valid.
  bool open(Json container) {
    Container placed = place(std::move(container));
    if (open_.size() == kMaxNesting) {
      throw Error::at_json_path(
          name_, placed.pointer,
          "arrays and objects nested more than " + std::to_string(kMaxNesting) + " deep");
    }
    open_.push_back(std::move(placed));
    return true;
  }
  bool close() {
    open_.pop_back();
    return true;
  }

  std::string_view text_;
  const fs::path& name_;
  Json root_;
  std::vector<Container> open_;
  std::string key_;
};

// Where relative paths in the document resolve and which file messages name.
struct Source {
  fs::path name;
  fs::path base_directory;
};

// A value in the document with its JSON pointer, for messages.
class Node {
 public:
  Node(const Json& value, std::string pointer, const Source& source)
      : value_(value), pointer_(std::move(pointer)), source_(source) {}

  [[nodiscard]] const Json& json() const { return value_; }
  [[nodiscard]] const Source& source() const { return source_; }
  [[nodiscard]] Node child(const std::string& key) const {
    return {value_.at(key), pointer_ + "/" + pointer_token(key), source_};
  }
  [[nodiscard]] Node element(std::size_t index) const {
    return {value_.at(index), pointer_ + "/" + std::to_string(index), source_};
  }
  // The member `key` of this object, if present.
  [[nodiscard]] std::optional<Node> find(const std::string& key) const {
    if (!value_.contains(key)) return std::nullopt;
    return child(key);
  }
  [[noreturn]] void fail(std::string_view problem) const {
    throw Error::at_json_path(source_.name, pointer_, problem);
  }
  // For a key that must be present in this object.
  [[noreturn]] void fail_missing(std::string_view key, std::string_view why) const {
    throw Error::at_json_path(source_.name, pointer_ + "/" + std::string(key),
                              "missing; " + std::string(why));
  }

 private:
  const Json& value_;
  std::string pointer_;
  const Source& source_;
};

// The value as a message shows it: "-2", "\"octree\"", cut short when long.
std::string shown(const Json& value) {
  std::string text = value.dump();
  if (text.size() <= kMaxShown) return text;
  std::size_t cut = kMaxShown;
  // Not inside a UTF-8 sequence.
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0U) == 0x80U) --cut;
  text.resize(cut);
  return text + "...";
}

// "a string \"abc\"", "an object", "null", for "expected ..., got ..." messages.
std::string described(const Json& value) {
  if (value.is_null()) return "null";
  std::string kind;
  if (value.is_object()) {
    kind = "an object";
  } else if (value.is_array()) {
    kind = "an array";
  } else if (value.is_string()) {
    kind = "a string";
  } else if (value.is_boolean()) {
    kind = "a boolean";
  } else {
    kind = "a number";
  }
  return kind + " " + shown(value);
}

[[noreturn]] void fail_type(const Node& node, std::string_view expected) {
  node.fail("expected " + std::string(expected) + ", got " + described(node.json()));
}

// Edit distance, for suggesting the key a misspelt one meant.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitution});
    }
  }
  return row[b.size()];
}

// The valid key a misspelt or shortened one most likely meant ("yaw" for "yaw_degrees",
// "densty" for "density"), if any is close enough.
std::optional<std::string_view> meant_key(std::string_view key, const auto& valid) {
  constexpr std::size_t kMinPrefix = 3;
  if (key.size() >= kMinPrefix) {
    const auto extended = std::find_if(
        valid.begin(), valid.end(), [&](std::string_view name) { return name.starts_with(key); });
    if (extended != valid.end()) return *extended;
  }
  const auto nearest = std::min_element(valid.begin(), valid.end(), [&](auto a, auto b) {
    return edit_distance(key, a) < edit_distance(key, b);
  });
  // A slip of about one character in three; more makes another word.
  const std::size_t slip = std::max<std::size_t>(1, key.size() / 3);
  if (edit_distance(key, *nearest) <= slip) return *nearest;
  return std::nullopt;
}

// Requires an object whose keys are all among `valid`.
void check_keys(const Node& node, const auto& valid) {
  if (!node.json().is_object()) fail_type(node, "an object");
  for (const auto& item : node.json().items()) {
    const std::string& key = item.key();
    if (std::find(valid.begin(), valid.end(), key) != valid.end()) continue;
    const std::optional<std::string_view> meant = meant_key(key, valid);
    node.child(key).fail(meant ? "unknown key; did you mean \"" + std::string(*meant) + "\"?"
                               : "unknown key (valid: " + joined(valid) + ")");
  }
}

double read_number(const Node& node) {
  if (!node.json().is_number()) fail_type(node, "a number");
  // Finite: the document builder refuses everything else.
  return node.json().get<double>();
}

double read_positive(const Node& node) {
  const double value = read_number(node);
  if (value <= 0.0) node.fail("must be positive, got " + shown(node.json()));
  return value;
}

// A positive figure within `range`.
double read_physical(const Node& node, const PhysicalRange& range) {
  const double value = read_positive(node);
  if (value < range.min || value > range.max) {
    node.fail("must be between " + number_text(range.min) + " and " + number_text(range.max) + " " +
              std::string(range.unit) + ", got " + shown(node.json()));
  }
  return value;
}

double read_non_negative(const Node& node) {
  const double value = read_number(node);
  if (value < 0.0) node.fail("must not be negative, got " + shown(node.json()));
  return value;
}

double read_between(const Node& node, double low, double high) {
  const double value = read_number(node);
  if (value < low || value > high) {
    node.fail("must be between " + number_text(low) + " and " + number_text(high) + ", got " +
              shown(node.json()));
  }
  return value;
}

float to_single(const Node& node, double value) {
  if (std::abs(value) >= kFloatOverflow) {
    node.fail("does not fit in single precision, got " + shown(node.json()));
  }
  return static_cast<float>(value);
}

// A friction coefficient, a speed, a length: a single-precision figure that must not be negative.
float read_non_negative_single(const Node& node) {
  return to_single(node, read_non_negative(node));
}

// A restitution or another fraction from 0 to 1, in single precision.
float read_fraction(const Node& node) { return static_cast<float>(read_between(node, 0.0, 1.0)); }

// An integral number (2 and 2.0 alike, as JSON Schema has it) within [low, high].
long long read_integer(const Node& node, long long low, long long high) {
  const double value = read_number(node);
  if (value != std::floor(value)) node.fail("must be an integer, got " + shown(node.json()));
  // Compared as doubles: the bounds are exact in a double, the value may be beyond a long long.
  if (value < static_cast<double>(low) || value > static_cast<double>(high)) {
    node.fail("must be between " + std::to_string(low) + " and " + std::to_string(high) + ", got " +
              shown(node.json()));
  }
  return static_cast<long long>(value);
}

std::string read_string(const Node& node) {
  if (!node.json().is_string()) fail_type(node, "a string");
  return node.json().get<std::string>();
}

bool read_bool(const Node& node) {
  if (!node.json().is_boolean()) fail_type(node, "true or false");
  return node.json().get<bool>();
}

// The index of the name among `names`.
std::size_t read_choice_index(const Node& node, std::span<const std::string_view> names) {
  const std::string name = read_string(node);
  std::string valid;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return i;
    valid += (valid.empty() ? "\"" : ", \"") + std::string(names[i]) + "\"";
  }
  node.fail("unknown value " + shown(node.json()) + " (valid: " + valid + ")");
}

template <typename Enum, std::size_t N>
Enum read_choice(const Node& node, const NameTable<Enum, N>& table) {
  std::array<std::string_view, N> names{};
  for (std::size_t i = 0; i < N; ++i) names[i] = table[i].second;
  return table[read_choice_index(node, names)].first;
}

std::array<double, 3> read_triple(const Node& node) {
  if (!node.json().is_array()) fail_type(node, "an array of 3 numbers");
  if (node.json().size() != 3) {
    node.fail("expected 3 numbers [x, y, z], got " + std::to_string(node.json().size()));
  }
  return {read_number(node.element(0)), read_number(node.element(1)), read_number(node.element(2))};
}

Vec3 read_vec3(const Node& node) {
  const std::array<double, 3> values = read_triple(node);
  Vec3 out;
  for (std::size_t k = 0; k < 3; ++k) {
    out[static_cast<int>(k)] = to_single(node.element(k), values[k]);
  }
  return out;
}

// A number within [-limit, limit] (unit).
double read_bounded(const Node& node, double limit, std::string_view unit) {
  const double value = read_number(node);
  if (std::abs(value) > limit) {
    node.fail("must be between " + number_text(-limit) + " and " + number_text(limit) + " " +
              std::string(unit) + ", got " + shown(node.json()));
  }
  return value;
}

// Three numbers each within [-limit, limit] (unit).
Vec3 read_bounded_vec3(const Node& node, double limit, std::string_view unit) {
  const Vec3 out = read_vec3(node);
  for (std::size_t k = 0; k < 3; ++k) (void)read_bounded(node.element(k), limit, unit);
  return out;
}

// The path of a file that must exist, as written; it resolves against the scene's folder. The
// input gate's checks run now, so a named pipe or an oversized file is named at its JSON path.
fs::path read_existing_file(const Node& node, std::string_view what, InputKind kind) {
  const std::string written = read_string(node);
  if (written.empty()) node.fail("expected the path of " + std::string(what) + ", got \"\"");
  const fs::path resolved = node.source().base_directory / fs::path(written);
  if (const auto problem = input_file_problem(resolved, kind)) {
    node.fail(*problem + ": " + resolved.string());
  }
  return written;
}

std::string read_mesh(const Node& node) {
  if (node.json().is_string() && node.json().get<std::string>() == kBunnyName) {
    return std::string(kBunnyName);
  }
  return read_existing_file(node, "a mesh file", InputKind::kMesh).string();
}

std::optional<std::size_t> read_triangles(const Node& node) {
  if (node.json().is_null()) return std::nullopt;
  const long long triangles = read_integer(node, 0, kMaxTriangles);
  if (triangles > 0 && triangles < kMinTriangles) {
    node.fail("must be 0 (keep every triangle) or at least " + std::to_string(kMinTriangles) +
              ", got " + shown(node.json()));
  }
  return static_cast<std::size_t>(triangles);
}

std::optional<double> read_optional_physical(const Node& node, const PhysicalRange& range) {
  if (node.json().is_null()) return std::nullopt;
  return read_physical(node, range);
}

TreeSpec read_tree(const Node& node, const TreeSpec& start) {
  if (node.json().is_string()) {
    TreeSpec tree;
    tree.sph_file = read_existing_file(node, "a .sph file", InputKind::kSphereTree);
    return tree;
  }
  if (!node.json().is_object()) {
    fail_type(node, "an object {\"method\", \"branching\", \"depth\"} or the path of a .sph file");
  }
  check_keys(node, kTreeKeys);
  TreeSpec tree = start;
  tree.sph_file.reset();
  if (const auto method = node.find("method")) {
    const std::string name = read_string(*method);
    try {
      tree.method = parse_method(name);
    } catch (const Error& error) {
      method->fail(error.what());
    }
  }
  if (const auto branching = node.find("branching")) {
    tree.branching = static_cast<int>(read_integer(*branching, 2, 8));
  }
  if (const auto depth = node.find("depth")) {
    tree.depth = static_cast<int>(read_integer(*depth, 1, kMaxTreeDepth));
  }
  return tree;
}

// Divides by the length, computed without overflow or underflow for any finite input; nothing
// when the length is zero.
template <std::size_t N>
std::optional<std::array<double, N>> normalised(std::array<double, N> values) {
  double largest = 0.0;
  for (const double v : values) largest = std::max(largest, std::abs(v));
  if (largest == 0.0) return std::nullopt;
  double squares = 0.0;
  for (double& v : values) {
    v /= largest;
    squares += v * v;
  }
  const double length = std::sqrt(squares);
  for (double& v : values) v /= length;
  return values;
}

double length_of(const std::array<double, 4>& values) {
  double squares = 0.0;
  for (const double v : values) squares += v * v;
  return std::sqrt(squares);
}

Quat quaternion(double w, double x, double y, double z) {
  return {static_cast<float>(w), static_cast<float>(x), static_cast<float>(y),
          static_cast<float>(z)};
}

Quat rotation_about(const std::array<double, 3>& unit_axis, double degrees) {
  const double half = degrees * std::numbers::pi / 360.0;
  const double s = std::sin(half);
  return quaternion(std::cos(half), unit_axis[0] * s, unit_axis[1] * s, unit_axis[2] * s);
}

bool has_any(const Node& node, const auto& keys) {
  return std::any_of(keys.begin(), keys.end(),
                     [&](std::string_view key) { return node.json().contains(key); });
}

Node required(const Node& node, const std::string& key, std::string_view why) {
  if (const auto child = node.find(key)) return *child;
  node.fail_missing(key, why);
}

Quat read_orientation(const Node& node) {
  check_keys(node, kOrientationKeys);
  const bool as_quaternion = has_any(node, kQuaternionKeys);
  const bool as_yaw = has_any(node, kYawKeys);
  const bool as_axis_angle = has_any(node, kAxisAngleKeys);
  constexpr std::string_view kForms =
      "{\"w\", \"x\", \"y\", \"z\"}, {\"yaw_degrees\"} or {\"axis\", \"angle_degrees\"}";
  if (int{as_quaternion} + int{as_yaw} + int{as_axis_angle} != 1) {
    node.fail((as_quaternion || as_yaw || as_axis_angle ? "mixes forms; give one of "
                                                        : "expected one of ") +
              std::string(kForms));
  }
  if (as_yaw) {
    // About +y, the up axis: counter-clockwise seen from above.
    return rotation_about({0.0, 1.0, 0.0}, read_number(node.child("yaw_degrees")));
  }
  if (as_axis_angle) {
    const Node axis = required(node, "axis", "an angle needs an axis");
    const Node angle = required(node, "angle_degrees", "an axis needs an angle");
    const auto unit_axis = normalised(read_triple(axis));
    if (!unit_axis) axis.fail("a zero-length axis has no direction");
    return rotation_about(*unit_axis, read_number(angle));
  }
  std::array<double, 4> wxyz{};
  for (std::size_t k = 0; k < 4; ++k) {
    const std::string key(kQuaternionKeys[k]);
    wxyz[k] = read_number(required(node, key, "a quaternion needs w, x, y and z"));
  }
  const auto unit = normalised(wxyz);
  if (!unit) node.fail("a zero-length quaternion is no rotation");
  const std::array<double, 4>& kept =
      std::abs(length_of(wxyz) - 1.0) <= kUnitTolerance ? wxyz : *unit;
  return quaternion(kept[0], kept[1], kept[2], kept[3]);
}

// Applies the keys of a body over `body`, which holds the defaults.
void read_body(const Node& node, BodySpec& body) {
  check_keys(node, kBodyKeys);
  if (const auto n = node.find("mesh")) body.mesh = read_mesh(*n);
  if (const auto n = node.find("triangles")) body.triangles = read_triangles(*n);
  if (const auto n = node.find("size")) body.size = read_optional_physical(*n, kBodySizeRange);
  if (const auto n = node.find("sphere_tree")) body.tree = read_tree(*n, body.tree);
  if (const auto n = node.find("position")) {
    body.position = read_bounded_vec3(*n, kMaxCoordinate, "m");
  }
  if (const auto n = node.find("orientation")) body.orientation = read_orientation(*n);
  if (const auto n = node.find("linear_velocity")) {
    body.linear_velocity = read_bounded_vec3(*n, kMaxSpeed, "m/s");
  }
  if (const auto n = node.find("angular_velocity")) {
    body.angular_velocity = read_bounded_vec3(*n, kMaxSpeed, "rad/s");
  }
  if (const auto n = node.find("density")) body.density = read_physical(*n, kDensityRange);
  if (const auto n = node.find("mass")) body.mass = read_optional_physical(*n, kMassRange);
  if (const auto n = node.find("restitution")) body.restitution = read_fraction(*n);
  if (const auto n = node.find("friction")) body.friction = read_non_negative_single(*n);
  if (const auto n = node.find("static")) body.is_static = read_bool(*n);
}

// "defaults": the keys of a body but those set per body.
BodySpec read_defaults(const Node& node) {
  check_keys(node, kBodyKeys);
  for (const std::string_view key : kPerBodyKeys) {
    if (const auto child = node.find(std::string(key))) {
      child->fail("set per body, not in \"defaults\"");
    }
  }
  BodySpec defaults;
  read_body(node, defaults);
  return defaults;
}

// The ground's own keys; its material is among the world's settings (read_settings).
GroundSpec read_ground(const Node& node) {
  check_keys(node, ground_keys());
  GroundSpec ground;
  if (const auto n = node.find("type")) ground.kind = read_choice(*n, kGroundKinds);
  if (const auto n = node.find("height")) ground.height = read_bounded(*n, kMaxCoordinate, "m");
  if (const auto n = node.find("size")) ground.size = read_physical(*n, kGroundSizeRange);
  if (const auto n = node.find("thickness")) {
    ground.thickness = read_physical(*n, kGroundThicknessRange);
  }
  if (const auto n = node.find("depth")) {
    ground.depth = static_cast<int>(read_integer(*n, 1, kMaxGroundDepth));
  }
  return ground;
}

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
double read_setting_number(const Node& node, const SettingRange& range) {
  const float value = to_single(node, read_number(node));
  if (!range.contains(value)) node.fail(range_requirement(range) + ", got " + shown(node.json()));
  return value;
}

void read_setting(const Node& node, const Setting& setting, WorldSettings& settings) {
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

// Applies the world settings that `object` ("" for the top level, "solver", ...) carries over
// `settings`.
void read_settings(const Node& node, std::string_view object, WorldSettings& settings) {
  for (const Setting& setting : settings_table()) {
    if (!setting.in_scene || setting.object != object) continue;
    if (const auto n = node.find(std::string(setting.key))) read_setting(*n, setting, settings);
  }
}

// "solver" and "sleep": objects of world settings only.
void read_settings_object(const Node& node, std::string_view object, WorldSettings& settings) {
  if (node.json().is_object()) {
    for (const auto& item : node.json().items()) {
      const std::string field = std::string(object) + "." + item.key();
      if (const RemovedSetting* removed = removed_setting(field)) {
        node.child(item.key()).fail(removed_setting_message(*removed));
      }
    }
  }
  check_keys(node, setting_keys(object));
  read_settings(node, object, settings);
}

// An index into the scene's bodies.
std::size_t read_body_index(const Node& node, std::size_t body_count) {
  const auto index = static_cast<std::size_t>(read_integer(node, 0, kMaxExactInteger));
  if (index >= body_count) {
    node.fail("no body " + std::to_string(index) + "; /bodies has " + std::to_string(body_count) +
              " (indices from 0)");
  }
  return index;
}

std::array<std::size_t, 2> read_body_pair(const Node& node, std::size_t body_count) {
  if (!node.json().is_array()) fail_type(node, "an array of 2 body indices [i, j]");
  if (node.json().size() != 2) {
    node.fail("expected 2 body indices [i, j], got " + std::to_string(node.json().size()));
  }
  const std::array<std::size_t, 2> pair = {read_body_index(node.element(0), body_count),
                                           read_body_index(node.element(1), body_count)};
  if (pair[0] == pair[1]) node.fail("a pair needs two different bodies, got " + shown(node.json()));
  return pair;
}

// Each pair's material, defaulting to the mix of the two bodies' own. A pair given twice (in
// either order) is refused: the runtime would keep the last silently, hiding a slip.
std::vector<PairMaterialSpec> read_pair_materials(const Node& node,
                                                  const std::vector<BodySpec>& bodies) {
  if (!node.json().is_array()) fail_type(node, "an array of pair materials");
  std::vector<PairMaterialSpec> pairs;
  for (std::size_t k = 0; k < node.json().size(); ++k) {
    const Node entry = node.element(k);
    check_keys(entry, kPairMaterialKeys);
    const Node bodies_node = required(entry, "bodies", "a pair material names its two bodies");
    PairMaterialSpec pair;
    pair.bodies = read_body_pair(bodies_node, bodies.size());
    const auto same_pair = [&](const PairMaterialSpec& other) {
      return std::is_permutation(other.bodies.begin(), other.bodies.end(), pair.bodies.begin());
    };
    if (const auto earlier = std::find_if(pairs.begin(), pairs.end(), same_pair);
        earlier != pairs.end()) {
      bodies_node.fail("this pair already has a material, at /pair_materials/" +
                       std::to_string(earlier - pairs.begin()));
    }
    const BodySpec& a = bodies[pair.bodies[0]];
    const BodySpec& b = bodies[pair.bodies[1]];
    pair.material = {mix_friction(a.friction, b.friction),
                     mix_restitution(a.restitution, b.restitution)};
    if (const auto n = entry.find("friction")) {
      pair.material.friction = read_non_negative_single(*n);
    }
    if (const auto n = entry.find("restitution")) pair.material.restitution = read_fraction(*n);
    pairs.push_back(pair);
  }
  return pairs;
}

void read_header(const Node& root) {
  const Node format =
      required(root, "format", "a scene file starts with \"format\": \"sphys-scene\"");
  if (!format.json().is_string() || format.json().get<std::string>() != kFormat) {
    fail_type(format, "\"" + std::string(kFormat) + "\"");
  }
  const Node version = required(root, "version", "this build reads \"version\": 1");
  if (read_number(version) != static_cast<double>(kVersion)) {
    version.fail("unsupported version " + shown(version.json()) + "; this build reads version " +
                 std::to_string(kVersion));
  }
}

Scene read_scene(const Json& document, const fs::path& name) {
  const Source source{name, name.parent_path()};
  if (!document.is_object()) {
    throw Error::in_file(name,
                         "expected a JSON object at the top level, got " + described(document));
  }
  const Node root(document, "", source);
  read_header(root);
  check_keys(root, scene_keys());

  Scene scene;
  scene.name = name.filename().string();
  scene.base_directory = source.base_directory;
  if (const auto n = root.find("time_step")) {
    scene.time_step = read_physical(*n, kTimeStepRange);
  }
  if (const auto n = root.find("frames")) {
    scene.frames = static_cast<int>(read_integer(*n, 1, kMaxFrames));
  }
  WorldSettings settings = world_settings(scene);
  read_settings(root, "", settings);
  if (const auto n = root.find("solver")) read_settings_object(*n, "solver", settings);
  if (const auto n = root.find("sleep")) read_settings_object(*n, "sleep", settings);
  if (const auto n = root.find("ground")) {
    scene.ground = read_ground(*n);
    read_settings(*n, "ground", settings);
  }
  set_world_settings(scene, settings);

  const BodySpec defaults =
      root.find("defaults") ? read_defaults(root.child("defaults")) : BodySpec{};
  const Node bodies = required(root, "bodies", "a scene lists its bodies (the list may be empty)");
  if (!bodies.json().is_array()) fail_type(bodies, "an array of bodies");
  for (std::size_t i = 0; i < bodies.json().size(); ++i) {
    BodySpec body = defaults;
    read_body(bodies.element(i), body);
    scene.bodies.push_back(std::move(body));
  }
  if (const auto n = root.find("pair_materials")) {
    scene.pair_materials = read_pair_materials(*n, scene.bodies);
  }
  return scene;
}

// Floats are written in their shortest decimal form (shortest_double), so that 0.3f is written
// "0.3" rather than "0.30000001192092896" and reads back bit for bit.
Json vec3_json(const Vec3& v) {
  return Json::array({shortest_double(v.x()), shortest_double(v.y()), shortest_double(v.z())});
}

template <typename T>
Json optional_json(const std::optional<T>& value) {
  return value ? Json(*value) : Json(nullptr);
}

Json tree_json(const TreeSpec& tree) {
  if (tree.sph_file) return tree.sph_file->generic_string();
  Json out = Json::object();
  out["method"] = method_name(tree.method);
  out["branching"] = tree.branching;
  out["depth"] = tree.depth;
  return out;
}

Json body_json(const BodySpec& body) {
  Json out = Json::object();
  out["mesh"] = body.mesh;
  out["triangles"] = optional_json(body.triangles);
  out["size"] = optional_json(body.size);
  out["sphere_tree"] = tree_json(body.tree);
  out["position"] = vec3_json(body.position);
  const Quat& q = body.orientation;
  out["orientation"] = {{"w", shortest_double(q.w())},
                        {"x", shortest_double(q.x())},
                        {"y", shortest_double(q.y())},
                        {"z", shortest_double(q.z())}};
  out["linear_velocity"] = vec3_json(body.linear_velocity);
  out["angular_velocity"] = vec3_json(body.angular_velocity);
  out["density"] = body.density;
  out["mass"] = optional_json(body.mass);
  out["restitution"] = shortest_double(body.restitution);
  out["friction"] = shortest_double(body.friction);
  out["static"] = body.is_static;
  return out;
}

Json ground_json(const GroundSpec& ground) {
  Json out = Json::object();
  out["type"] = name_of(ground.kind, kGroundKinds);
  out["height"] = ground.height;
  out["size"] = ground.size;
  out["thickness"] = ground.thickness;
  out["depth"] = ground.depth;
  return out;
}

Json pair_material_json(const PairMaterialSpec& pair) {
  return {{"bodies", Json::array({pair.bodies[0], pair.bodies[1]})},
          {"friction", shortest_double(pair.material.friction)},
          {"restitution", shortest_double(pair.material.restitution)}};
}

// The index of `name` among the choices of an enum setting, else "unknown <what> '<name>';
// <what>s: a, b", for names given on the command line.
std::size_t parse_name(std::string_view name, const Setting& setting, std::string_view what) {
  const std::span<const std::string_view> names = setting.choices;
  const auto found = std::find(names.begin(), names.end(), name);
  if (found != names.end()) return static_cast<std::size_t>(found - names.begin());
  std::string message = "unknown ";
  message += what;
  message += " '";
  message += name;
  message += "'; ";
  message += what;
  message += "s: ";
  message += joined(names);
  throw Error(message);
}

// The JSON document of a scene's text; errors name `name` and the line and column.
Json parse_document(std::string_view json_text, const fs::path& name) {
  DocumentBuilder builder(json_text, name);
  Json::sax_parse(json_text.begin(), json_text.end(), &builder);
  return builder.take();
}

}  // namespace

Scene parse_scene(std::string_view json_text, const fs::path& name) {
  return read_scene(parse_document(json_text, name), name);
}

Scene parse_recorded_scene(std::string_view json_text, const fs::path& name) {
  Json document = parse_document(json_text, name);
  // A recording made before a setting was removed carries it, written out with all the others: it
  // says how the recording was made, and replaying or exporting needs the shapes and the poses.
  if (document.is_object() && document.contains("solver") && document["solver"].is_object()) {
    Json& solver = document["solver"];
    for (auto item = solver.begin(); item != solver.end();) {
      item =
          removed_setting("solver." + item.key()) != nullptr ? solver.erase(item) : std::next(item);
    }
  }
  return read_scene(document, name);
}

Scene read_scene_file(const fs::path& path) {
  return parse_scene(read_input_file(path, InputKind::kScene), path);
}

std::string_view response_mode_name(ResponseMode mode) {
  return setting_of("response").choices[static_cast<std::size_t>(mode)];
}

ResponseMode parse_response_mode(std::string_view name) {
  return static_cast<ResponseMode>(parse_name(name, setting_of("response"), "response mode"));
}

GroundSpec::Kind parse_ground_option(std::string_view name, std::string_view option) {
  if (name == "octree") return GroundSpec::Kind::kOctreeBox;
  if (name == "plane") return GroundSpec::Kind::kPlane;
  std::string message(option);
  message += " must be octree or plane, got '";
  message += name;
  message += "'";
  throw Error(message);
}

std::string_view contact_set_name(ContactSet contacts) {
  return setting_of("solver.contacts").choices[static_cast<std::size_t>(contacts)];
}

ContactSet parse_contact_set(std::string_view name) {
  return static_cast<ContactSet>(parse_name(name, setting_of("solver.contacts"), "contact set"));
}

std::string scene_to_json(const Scene& scene) {
  Json out = Json::object();
  out["format"] = kFormat;
  out["version"] = kVersion;
  out["time_step"] = scene.time_step;
  out["frames"] = scene.frames;
  const WorldSettings settings = world_settings(scene);
  out.update(settings_json("", settings));
  out["solver"] = settings_json("solver", settings);
  out["sleep"] = settings_json("sleep", settings);
  out["ground"] = ground_json(scene.ground);
  out["ground"].update(settings_json("ground", settings));
  Json bodies = Json::array();
  for (const BodySpec& body : scene.bodies) bodies.push_back(body_json(body));
  out["bodies"] = std::move(bodies);
  Json pairs = Json::array();
  for (const PairMaterialSpec& pair : scene.pair_materials) {
    pairs.push_back(pair_material_json(pair));
  }
  out["pair_materials"] = std::move(pairs);
  return out.dump(2) + "\n";
}

}  // namespace sphys::tools
