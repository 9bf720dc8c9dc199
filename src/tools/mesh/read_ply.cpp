#include "read_ply.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "io/input_file.h"
#include "io/shown_text.h"
#include "ply_header.h"
#include "sphys/error.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

// The fewest bytes a number takes in an ASCII body: one digit and one separator. unit: bytes
constexpr std::uint64_t kMinAsciiNumberBytes = 2;

constexpr std::array<std::string_view, 2> kIndexListNames = {"vertex_indices", "vertex_index"};
constexpr std::array<std::string_view, 3> kCoordinateNames = {"x", "y", "z"};

// Where the body is, for messages: the record being read.
struct Place {
  const PlyElement* element = nullptr;
  std::uint64_t record = 0;

  [[nodiscard]] std::string record_text() const {
    return "record " + std::to_string(record) + " of element '" + element->name + "'";
  }
  [[nodiscard]] std::string ends_early() const {
    return "file ends early in " + record_text() + " (the header announces " +
           std::to_string(element->count) + ")";
  }
};

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

// The numbers of an ASCII body, one whitespace-separated word at a time.
class AsciiBody {
 public:
  AsciiBody(std::string_view bytes, std::size_t first_line, const fs::path& path)
      : bytes_(bytes), path_(path), line_(first_line), word_line_(first_line) {}

  void at(const PlyElement& element, std::uint64_t record) { place_ = {&element, record}; }

  double read(PlyType type) {
    const std::string_view word = next_word();
    std::string_view digits = word;
    if (digits.size() > 1 && digits.front() == '+') digits.remove_prefix(1);
    const char* const end = digits.data() + digits.size();
    if (ply_type_is_integer(type)) {
      long long value = 0;
      const auto [stop, error] = std::from_chars(digits.data(), end, value);
      if (error != std::errc() || stop != end) {
        throw this->error(shown(word) + " is not an integer (the property is " +
                          std::string(ply_type_name(type)) + ")");
      }
      check_range(value, type, word);
      return static_cast<double>(value);
    }
    double value = 0.0;
    const auto [stop, error] = std::from_chars(digits.data(), end, value);
    if (error != std::errc() || stop != end) throw this->error(shown(word) + " is not a number");
    return value;
  }

  // How many more numbers the body could hold at most.
  [[nodiscard]] std::uint64_t capacity() const {
    return (bytes_.size() - pos_ + 1) / kMinAsciiNumberBytes;
  }

  // At the line of the last word read: a file that ends early is named at its last line.
  [[nodiscard]] Error error(const std::string& problem) const {
    return Error::at_line(path_, word_line_, problem);
  }

 private:
  std::string_view next_word() {
    while (pos_ < bytes_.size() && is_space(bytes_[pos_])) {
      if (bytes_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ == bytes_.size()) throw error(place_.ends_early());
    word_line_ = line_;
    const std::size_t begin = pos_;
    while (pos_ < bytes_.size() && !is_space(bytes_[pos_])) ++pos_;
    return bytes_.substr(begin, pos_ - begin);
  }

  void check_range(long long value, PlyType type, std::string_view word) const {
    const auto bits = static_cast<int>(8 * ply_type_size(type));
    const bool is_signed =
        type == PlyType::kInt8 || type == PlyType::kInt16 || type == PlyType::kInt32;
    const long long low = is_signed ? -(1LL << (bits - 1)) : 0;
    const long long high = is_signed ? (1LL << (bits - 1)) - 1 : (1LL << bits) - 1;
    if (value < low || value > high) {
      throw error(shown(word) + " is out of range for " + std::string(ply_type_name(type)));
    }
  }

  std::string_view bytes_;
  const fs::path& path_;
  std::size_t pos_ = 0;
  std::size_t line_;
  std::size_t word_line_;
  Place place_;
};

// The numbers of a binary body, in the file's byte order.
class BinaryBody {
 public:
  BinaryBody(std::string_view bytes, bool big_endian, const fs::path& path)
      : bytes_(bytes),
        swap_(big_endian != (std::endian::native == std::endian::big)),
        path_(path) {}

  void at(const PlyElement& element, std::uint64_t record) { place_ = {&element, record}; }

  double read(PlyType type) {
    const std::size_t size = ply_type_size(type);
    if (size > bytes_.size() - pos_) throw Error::in_file(path_, place_.ends_early());
    std::array<unsigned char, 8> raw{};
    std::memcpy(raw.data(), bytes_.data() + pos_, size);
    pos_ += size;
    if (swap_) std::reverse(raw.begin(), raw.begin() + static_cast<std::ptrdiff_t>(size));
    switch (type) {
      case PlyType::kInt8:
        return as<std::int8_t>(raw);
      case PlyType::kUint8:
        return as<std::uint8_t>(raw);
      case PlyType::kInt16:
        return as<std::int16_t>(raw);
      case PlyType::kUint16:
        return as<std::uint16_t>(raw);
      case PlyType::kInt32:
        return as<std::int32_t>(raw);
      case PlyType::kUint32:
        return as<std::uint32_t>(raw);
      case PlyType::kFloat32:
        return as<float>(raw);
      case PlyType::kFloat64:
        return as<double>(raw);
    }
    return 0.0;
  }

  // How many more numbers of `type` the body could hold at most.
  [[nodiscard]] std::uint64_t capacity(PlyType type) const {
    return (bytes_.size() - pos_) / ply_type_size(type);
  }

  [[nodiscard]] Error error(const std::string& problem) const {
    return Error::in_file(path_, place_.record_text() + ": " + problem);
  }

 private:
  template <typename T>
  static double as(const std::array<unsigned char, 8>& raw) {
    T value{};
    std::memcpy(&value, raw.data(), sizeof value);
    return static_cast<double>(value);
  }

  std::string_view bytes_;
  bool swap_;
  const fs::path& path_;
  std::size_t pos_ = 0;
  Place place_;
};

// Which element and properties hold the mesh.
struct Layout {
  const PlyElement* vertex = nullptr;
  std::array<std::size_t, 3> xyz{};
  const PlyElement* face = nullptr;
  std::size_t indices = 0;
};

Layout find_layout(const PlyHeader& header, const fs::path& path) {
  Layout layout;
  for (const PlyElement& element : header.elements) {
    if (element.name == "vertex" && layout.vertex == nullptr) layout.vertex = &element;
    if (element.name == "face" && layout.face == nullptr) layout.face = &element;
  }
  if (layout.vertex == nullptr) throw Error::in_file(path, "the header has no vertex element");
  if (layout.vertex->count > std::numeric_limits<std::uint32_t>::max()) {
    throw Error::at_line(path, layout.vertex->line, "more vertices than sphys can index (2^32)");
  }
  const auto& vertex_properties = layout.vertex->properties;
  for (std::size_t k = 0; k < 3; ++k) {
    const auto found =
        std::find_if(vertex_properties.begin(), vertex_properties.end(),
                     [&](const PlyProperty& p) { return p.name == kCoordinateNames[k]; });
    if (found == vertex_properties.end() || found->is_list) {
      throw Error::at_line(
          path, layout.vertex->line,
          "the vertex element has no number property '" + std::string(kCoordinateNames[k]) + "'");
    }
    layout.xyz[k] = static_cast<std::size_t>(found - vertex_properties.begin());
  }
  if (layout.face == nullptr) return layout;
  const auto& face_properties = layout.face->properties;
  const auto found =
      std::find_if(face_properties.begin(), face_properties.end(), [](const auto& p) {
        return std::find(kIndexListNames.begin(), kIndexListNames.end(), p.name) !=
               kIndexListNames.end();
      });
  if (found == face_properties.end() || !found->is_list) {
    throw Error::at_line(path, layout.face->line,
                         "the face element has no list property 'vertex_indices' (or "
                         "'vertex_index')");
  }
  if (!ply_type_is_integer(found->type)) {
    throw Error::at_line(
        path, layout.face->line,
        "vertex indices must have an integer type, not " + std::string(ply_type_name(found->type)));
  }
  layout.indices = static_cast<std::size_t>(found - face_properties.begin());
  return layout;
}

// Refuses a header whose counts the file cannot hold, before anything is allocated for them.
void check_counts(const PlyHeader& header, std::uint64_t body_bytes, const fs::path& path) {
  const bool ascii = header.format == PlyFormat::kAscii;
  // The last number of an ASCII body needs no separator after it.
  std::uint64_t left = ascii ? body_bytes + 1 : body_bytes;
  for (const PlyElement& element : header.elements) {
    const std::uint64_t record =
        ascii ? kMinAsciiNumberBytes * element.min_numbers() : element.min_bytes();
    if (record == 0) continue;
    const std::uint64_t room = left / record;
    if (element.count > room) {
      throw Error::at_line(path, element.line,
                           "the header announces " + std::to_string(element.count) + " '" +
                               element.name + "' records of at least " + std::to_string(record) +
                               " bytes each, but the file has room for at most " +
                               std::to_string(room) + " (" + std::to_string(body_bytes) +
                               " bytes after the header)");
    }
    left -= element.count * record;
  }
}

std::string point_text(const Vec3d& p) {
  std::ostringstream out;
  out << '(' << p.x() << ", " << p.y() << ", " << p.z() << ')';
  return out.str();
}

template <typename Body>
std::uint64_t capacity_for(const Body& body, PlyType type) {
  if constexpr (std::is_same_v<Body, AsciiBody>) {
    return body.capacity();
  } else {
    return body.capacity(type);
  }
}

// Reads one record; `item` gets the items of the face's index list, every other value is read
// and dropped (vertex coordinates go to `values`).
template <typename Body, typename OnItem>
void read_record(Body& body, const PlyElement& element, std::array<double, 3>* coordinates,
                 const Layout& layout, std::size_t list, OnItem on_item) {
  for (std::size_t p = 0; p < element.properties.size(); ++p) {
    const PlyProperty& property = element.properties[p];
    if (!property.is_list) {
      const double value = body.read(property.type);
      if (coordinates != nullptr) {
        for (std::size_t k = 0; k < 3; ++k) {
          if (layout.xyz[k] == p) (*coordinates)[k] = value;
        }
      }
      continue;
    }
    const double length = body.read(property.count_type);
    if (length < 0) {
      throw body.error("a list has a negative length " +
                       std::to_string(static_cast<long long>(length)));
    }
    const auto items = static_cast<std::uint64_t>(length);
    if (items > capacity_for(body, property.type)) {
      throw body.error("a list of " + std::to_string(items) +
                       " items runs past the end of the file");
    }
    for (std::uint64_t i = 0; i < items; ++i) {
      const double value = body.read(property.type);
      if (p == list) on_item(value);
    }
  }
}

template <typename Body>
TriangleMesh read_body(Body& body, const PlyHeader& header, const Layout& layout,
                       const fs::path& path) {
  TriangleMesh mesh;
  mesh.name = path.string();
  const std::uint64_t vertex_count = layout.vertex->count;
  mesh.vertices.reserve(static_cast<std::size_t>(vertex_count));
  std::vector<std::uint32_t> corners;
  const auto add_corner = [&](double index) {
    if (!(index >= 0 && index < static_cast<double>(vertex_count))) {
      throw body.error("vertex index " + std::to_string(static_cast<long long>(index)) +
                       " is out of range (the file has " + std::to_string(vertex_count) +
                       " vertices)");
    }
    corners.push_back(static_cast<std::uint32_t>(index));
  };
  const auto ignore = [](double) {};
  constexpr std::size_t kNoList = std::numeric_limits<std::size_t>::max();
  for (const PlyElement& element : header.elements) {
    // Records of no properties take no bytes: nothing to read however many there are.
    if (element.properties.empty()) continue;
    const bool is_vertex = &element == layout.vertex;
    const bool is_face = &element == layout.face;
    for (std::uint64_t r = 0; r < element.count; ++r) {
      body.at(element, r);
      if (is_vertex) {
        std::array<double, 3> xyz{};
        read_record(body, element, &xyz, layout, kNoList, ignore);
        const Vec3d p(xyz[0], xyz[1], xyz[2]);
        if (!p.allFinite())
          throw body.error("a vertex has a non-finite coordinate " + point_text(p));
        mesh.vertices.push_back(p);
      } else if (is_face) {
        corners.clear();
        read_record(body, element, nullptr, layout, layout.indices, add_corner);
        // Points and lines carry no surface; polygons become a fan of triangles.
        for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
          mesh.triangles.push_back({corners[0], corners[k], corners[k + 1]});
        }
      } else {
        read_record(body, element, nullptr, layout, kNoList, ignore);
      }
    }
  }
  return mesh;
}

}  // namespace

TriangleMesh read_ply(const fs::path& path) {
  const std::string bytes = read_input_file(path, InputKind::kMesh);
  const PlyHeader header = parse_ply_header(bytes, path);
  const std::string_view body = std::string_view(bytes).substr(header.body_offset);
  check_counts(header, body.size(), path);
  const Layout layout = find_layout(header, path);
  if (header.format == PlyFormat::kAscii) {
    AsciiBody ascii(body, header.body_line, path);
    return read_body(ascii, header, layout, path);
  }
  BinaryBody binary(body, header.format == PlyFormat::kBinaryBigEndian, path);
  return read_body(binary, header, layout, path);
}

}  // namespace sphys::tools
