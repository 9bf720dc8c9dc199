#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sphys::tools {

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

// The scalar types of PLY, under either of their two names (char / int8, ...).
enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

// unit: bytes
[[nodiscard]] std::size_t ply_type_size(PlyType type);
[[nodiscard]] bool ply_type_is_integer(PlyType type);
[[nodiscard]] std::string_view ply_type_name(PlyType type);

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;  // for a list, the type of its items
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;  // lists only: the type of the item count before them
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  std::size_t line = 0;  // the header line that declared it, for messages

  // The fewest numbers one record holds (a list counts as its item count alone).
  [[nodiscard]] std::uint64_t min_numbers() const;
  // The fewest bytes one binary record takes (lists empty). unit: bytes
  [[nodiscard]] std::uint64_t min_bytes() const;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  std::size_t body_offset = 0;  // the first byte after the end_header line
  std::size_t body_line = 0;    // the line the body starts on (ASCII)
};

// Reads the header at the start of `bytes` (the whole file). Throws sphys::Error naming `path`
// and the header line when it is not a PLY header, uses an unknown keyword or type, or ends
// before end_header.
[[nodiscard]] PlyHeader parse_ply_header(std::string_view bytes, const std::filesystem::path& path);

}  // namespace sphys::tools
