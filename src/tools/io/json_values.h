#pragma once

// The values of a JSON document as sphys reads them: each of the type asked for and within its
// range, else sphys::Error naming the value's JSON pointer, what it must be and what it is
// ("/bodies/0/density: must be between 0.001 and 1000000 kg/m³, got -2").

#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "input_file.h"
#include "json_node.h"
#include "sphys/math.h"

namespace sphys::tools {

// A physical figure's valid values, [min, max] in `unit`.
struct PhysicalRange {
  double min;
  double max;
  std::string_view unit;
};

// Finite: parse_json refuses everything else.
[[nodiscard]] double read_number(const JsonNode& node);
[[nodiscard]] double read_positive(const JsonNode& node);
[[nodiscard]] double read_non_negative(const JsonNode& node);
[[nodiscard]] double read_between(const JsonNode& node, double low, double high);
// A positive figure within `range`.
[[nodiscard]] double read_physical(const JsonNode& node, const PhysicalRange& range);
// The same, or nothing for null.
[[nodiscard]] std::optional<double> read_optional_physical(const JsonNode& node,
                                                           const PhysicalRange& range);
// A number within [-limit, limit] (unit).
[[nodiscard]] double read_bounded(const JsonNode& node, double limit, std::string_view unit);

// `value`, the node's number, in single precision; refused where it would round to infinity.
[[nodiscard]] float to_single(const JsonNode& node, double value);
// A friction coefficient, a speed, a length: a single-precision figure that must not be negative.
[[nodiscard]] float read_non_negative_single(const JsonNode& node);
// A restitution or another fraction from 0 to 1, in single precision.
[[nodiscard]] float read_fraction(const JsonNode& node);

// An integral number (2 and 2.0 alike, as JSON Schema has it) within [low, high].
[[nodiscard]] long long read_integer(const JsonNode& node, long long low, long long high);

[[nodiscard]] std::string read_string(const JsonNode& node);
[[nodiscard]] bool read_bool(const JsonNode& node);
// The index of the node's string among `names`.
[[nodiscard]] std::size_t read_choice_index(const JsonNode& node,
                                            std::span<const std::string_view> names);

// Three numbers [x, y, z].
[[nodiscard]] std::array<double, 3> read_triple(const JsonNode& node);
// The same in single precision.
[[nodiscard]] Vec3 read_vec3(const JsonNode& node);
// Three numbers each within [-limit, limit] (unit), in single precision.
[[nodiscard]] Vec3 read_bounded_vec3(const JsonNode& node, double limit, std::string_view unit);

// The path of a file that must exist, as written; it resolves against the document's folder
// (JsonSource::base_directory). The input gate's checks (input_file.h) run now, so a named pipe
// or an oversized file is named at its JSON path.
[[nodiscard]] std::filesystem::path read_existing_file(const JsonNode& node, std::string_view what,
                                                       InputKind kind);

}  // namespace sphys::tools
