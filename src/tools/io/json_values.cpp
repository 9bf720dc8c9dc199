#include "json_values.h"

#include <cmath>

#include "sphys/settings_table.h"

namespace sphys::tools {
namespace {

// A double from here on rounds to infinity as a float: FLT_MAX plus half its ulp.
constexpr double kFloatOverflow = 0x1.ffffffp127;

}  // namespace

double read_number(const JsonNode& node) {
  if (!node.json().is_number()) fail_type(node, "a number");
  return node.json().get<double>();
}

double read_positive(const JsonNode& node) {
  const double value = read_number(node);
  if (value <= 0.0) node.fail("must be positive, got " + shown_value(node.json()));
  return value;
}

double read_physical(const JsonNode& node, const PhysicalRange& range) {
  const double value = read_positive(node);
  if (value < range.min || value > range.max) {
    node.fail("must be between " + number_text(range.min) + " and " + number_text(range.max) + " " +
              std::string(range.unit) + ", got " + shown_value(node.json()));
  }
  return value;
}

std::optional<double> read_optional_physical(const JsonNode& node, const PhysicalRange& range) {
  if (node.json().is_null()) return std::nullopt;
  return read_physical(node, range);
}

double read_non_negative(const JsonNode& node) {
  const double value = read_number(node);
  if (value < 0.0) node.fail("must not be negative, got " + shown_value(node.json()));
  return value;
}

double read_between(const JsonNode& node, double low, double high) {
  const double value = read_number(node);
  if (value < low || value > high) {
    node.fail("must be between " + number_text(low) + " and " + number_text(high) + ", got " +
              shown_value(node.json()));
  }
  return value;
}

float to_single(const JsonNode& node, double value) {
  if (std::abs(value) >= kFloatOverflow) {
    node.fail("does not fit in single precision, got " + shown_value(node.json()));
  }
  return static_cast<float>(value);
}

float read_non_negative_single(const JsonNode& node) {
  return to_single(node, read_non_negative(node));
}

float read_fraction(const JsonNode& node) {
  return static_cast<float>(read_between(node, 0.0, 1.0));
}

long long read_integer(const JsonNode& node, long long low, long long high) {
  const double value = read_number(node);
  if (value != std::floor(value)) node.fail("must be an integer, got " + shown_value(node.json()));
  // Compared as doubles: the bounds are exact in a double, the value may be beyond a long long.
  if (value < static_cast<double>(low) || value > static_cast<double>(high)) {
    node.fail("must be between " + std::to_string(low) + " and " + std::to_string(high) + ", got " +
              shown_value(node.json()));
  }
  return static_cast<long long>(value);
}

std::string read_string(const JsonNode& node) {
  if (!node.json().is_string()) fail_type(node, "a string");
  return node.json().get<std::string>();
}

bool read_bool(const JsonNode& node) {
  if (!node.json().is_boolean()) fail_type(node, "true or false");
  return node.json().get<bool>();
}

std::size_t read_choice_index(const JsonNode& node, std::span<const std::string_view> names) {
  const std::string name = read_string(node);
  std::string valid;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return i;
    valid += (valid.empty() ? "\"" : ", \"") + std::string(names[i]) + "\"";
  }
  node.fail("unknown value " + shown_value(node.json()) + " (valid: " + valid + ")");
}

std::array<double, 3> read_triple(const JsonNode& node) {
  if (!node.json().is_array()) fail_type(node, "an array of 3 numbers");
  if (node.json().size() != 3) {
    node.fail("expected 3 numbers [x, y, z], got " + std::to_string(node.json().size()));
  }
  return {read_number(node.element(0)), read_number(node.element(1)), read_number(node.element(2))};
}

Vec3 read_vec3(const JsonNode& node) {
  const std::array<double, 3> values = read_triple(node);
  Vec3 out;
  for (std::size_t k = 0; k < 3; ++k) {
    out[static_cast<int>(k)] = to_single(node.element(k), values[k]);
  }
  return out;
}

double read_bounded(const JsonNode& node, double limit, std::string_view unit) {
  const double value = read_number(node);
  if (std::abs(value) > limit) {
    node.fail("must be between " + number_text(-limit) + " and " + number_text(limit) + " " +
              std::string(unit) + ", got " + shown_value(node.json()));
  }
  return value;
}

Vec3 read_bounded_vec3(const JsonNode& node, double limit, std::string_view unit) {
  const Vec3 out = read_vec3(node);
  for (std::size_t k = 0; k < 3; ++k) (void)read_bounded(node.element(k), limit, unit);
  return out;
}

std::filesystem::path read_existing_file(const JsonNode& node, std::string_view what,
                                         InputKind kind) {
  const std::string written = read_string(node);
  if (written.empty()) node.fail("expected the path of " + std::string(what) + ", got \"\"");
  const std::filesystem::path resolved =
      node.source().base_directory / std::filesystem::path(written);
  if (const auto problem = input_file_problem(resolved, kind)) {
    node.fail(*problem + ": " + resolved.string());
  }
  return written;
}

}  // namespace sphys::tools
