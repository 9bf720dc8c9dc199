#pragma once

// JSON text read strictly, for every JSON file sphys reads: nlohmann's parser, less what it lets
// through silently (a key given twice) and with every error placed at its line and column.

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace sphys::tools {

// Objects keep their keys in document order, so that a document written from one reads in the
// order its documentation lists them.
using Json = nlohmann::ordered_json;

// An array of the document that may hold at most `max_size` elements, refused as it grows past
// them ("more than <max_size> <refusal>"), so that a file of millions stops at once.
struct ArrayLimit {
  std::string_view pointer;  // the array's JSON pointer ("/bodies")
  std::size_t max_size = 0;
  std::string_view refusal;  // "bodies; a scene holds at most that many"
};

// The document of `text`, as if read from a file at `name`, which messages name. Throws
// sphys::Error for text that is not JSON (NaN, Infinity and numbers beyond a double included),
// with its line and column; for a duplicate key, an array beyond its limit or arrays and objects
// nested too deep, with its JSON pointer.
[[nodiscard]] Json parse_json(std::string_view text, const std::filesystem::path& name,
                              std::span<const ArrayLimit> limits = {});

// A key as a JSON pointer reference token (RFC 6901: "~" as "~0", "/" as "~1"); control
// characters become '?' so that a message stays on one line.
[[nodiscard]] std::string pointer_token(std::string_view key);

}  // namespace sphys::tools
