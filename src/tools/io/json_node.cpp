#include "json_node.h"

#include <algorithm>
#include <vector>

#include "shown_text.h"
#include "sphys/error.h"

namespace sphys::tools {
namespace {

// Longer values are cut short in messages.
constexpr std::size_t kMaxShown = 40;

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
std::optional<std::string_view> meant_key(std::string_view key,
                                          std::span<const std::string_view> valid) {
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

}  // namespace

JsonNode JsonNode::required(const std::string& key, std::string_view why) const {
  if (const auto member = find(key)) return *member;
  throw Error::at_json_path(source_.name, pointer_ + "/" + key, "missing; " + std::string(why));
}

void JsonNode::fail(std::string_view problem) const {
  throw Error::at_json_path(source_.name, pointer_, problem);
}

std::string shown_value(const Json& value) {
  std::string text = value.dump();
  if (text.size() <= kMaxShown) return text;
  std::size_t cut = kMaxShown;
  // Not inside a UTF-8 sequence.
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0U) == 0x80U) --cut;
  text.resize(cut);
  return text + "...";
}

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
  return kind + " " + shown_value(value);
}

void fail_type(const JsonNode& node, std::string_view expected) {
  node.fail("expected " + std::string(expected) + ", got " + described(node.json()));
}

bool has_any(const JsonNode& node, std::span<const std::string_view> keys) {
  return std::any_of(keys.begin(), keys.end(),
                     [&](std::string_view key) { return node.json().contains(key); });
}

void check_keys(const JsonNode& node, std::span<const std::string_view> valid) {
  if (!node.json().is_object()) fail_type(node, "an object");
  for (const auto& item : node.json().items()) {
    const std::string& key = item.key();
    if (std::find(valid.begin(), valid.end(), key) != valid.end()) continue;
    const std::optional<std::string_view> meant = meant_key(key, valid);
    node.child(key).fail(meant ? "unknown key; did you mean \"" + std::string(*meant) + "\"?"
                               : "unknown key (valid: " + joined(valid) + ")");
  }
}

}  // namespace sphys::tools
