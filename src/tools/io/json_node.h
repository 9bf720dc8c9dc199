#pragma once

// A value of a JSON document with its JSON pointer, so that every message about it names the
// file and the place ("/bodies/3/density"), and the checks of an object's keys that suggest the
// key a misspelt one meant.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "json_document.h"

namespace sphys::tools {

// Which file messages name, and where relative paths in the document resolve.
struct JsonSource {
  std::filesystem::path name;
  std::filesystem::path base_directory;
};

class JsonNode {
 public:
  JsonNode(const Json& value, std::string pointer, const JsonSource& source)
      : value_(value), pointer_(std::move(pointer)), source_(source) {}

  [[nodiscard]] const Json& json() const { return value_; }
  [[nodiscard]] const JsonSource& source() const { return source_; }
  [[nodiscard]] JsonNode child(const std::string& key) const {
    return {value_.at(key), pointer_ + "/" + pointer_token(key), source_};
  }
  [[nodiscard]] JsonNode element(std::size_t index) const {
    return {value_.at(index), pointer_ + "/" + std::to_string(index), source_};
  }
  // The member `key` of this object, if present.
  [[nodiscard]] std::optional<JsonNode> find(const std::string& key) const {
    if (!value_.contains(key)) return std::nullopt;
    return child(key);
  }
  // The member `key` of this object, which must be present; else "<pointer>/<key>: missing;
  // <why>".
  [[nodiscard]] JsonNode required(const std::string& key, std::string_view why) const;
  [[noreturn]] void fail(std::string_view problem) const;

 private:
  const Json& value_;
  std::string pointer_;
  const JsonSource& source_;
};

// The value as a message shows it: "-2", "\"octree\"", cut short when long.
[[nodiscard]] std::string shown_value(const Json& value);

// "a string \"abc\"", "an object", "null", for "expected ..., got ..." messages.
[[nodiscard]] std::string described(const Json& value);

// "expected <expected>, got <the value described>".
[[noreturn]] void fail_type(const JsonNode& node, std::string_view expected);

// Whether the object has any of `keys`.
[[nodiscard]] bool has_any(const JsonNode& node, std::span<const std::string_view> keys);

// Requires an object whose keys are all among `valid`; an unknown key is refused with the valid
// key it most likely meant ("did you mean \"density\"?"), else with the list of valid keys.
void check_keys(const JsonNode& node, std::span<const std::string_view> valid);

}  // namespace sphys::tools
