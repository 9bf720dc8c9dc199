#include "ply_header.h"

#include <array>
#include <charconv>
#include <optional>
#include <utility>

#include "io/shown_text.h"
#include "sphys/error.h"

namespace sphys::tools {
namespace {

struct TypeName {
  std::string_view name;
  PlyType type;
};

// Both spellings of the specification, the old (char, uchar, ...) and the sized (int8, ...).
constexpr std::array<TypeName, 16> kTypeNames = {{{"char", PlyType::kInt8},
                                                  {"int8", PlyType::kInt8},
                                                  {"uchar", PlyType::kUint8},
                                                  {"uint8", PlyType::kUint8},
                                                  {"short", PlyType::kInt16},
                                                  {"int16", PlyType::kInt16},
                                                  {"ushort", PlyType::kUint16},
                                                  {"uint16", PlyType::kUint16},
                                                  {"int", PlyType::kInt32},
                                                  {"int32", PlyType::kInt32},
                                                  {"uint", PlyType::kUint32},
                                                  {"uint32", PlyType::kUint32},
                                                  {"float", PlyType::kFloat32},
                                                  {"float32", PlyType::kFloat32},
                                                  {"double", PlyType::kFloat64},
                                                  {"float64", PlyType::kFloat64}}};

std::optional<PlyType> parse_type(std::string_view name) {
  for (const TypeName& entry : kTypeNames) {
    if (entry.name == name) return entry.type;
  }
  return std::nullopt;
}

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::vector<std::string_view> words_of(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t pos = 0;
  while (pos < line.size()) {
    while (pos < line.size() && is_blank(line[pos])) ++pos;
    const std::size_t begin = pos;
    while (pos < line.size() && !is_blank(line[pos])) ++pos;
    if (pos > begin) words.push_back(line.substr(begin, pos - begin));
  }
  return words;
}

// Hands out the header's lines with their numbers; the header is text whatever the format.
class HeaderLines {
 public:
  HeaderLines(std::string_view bytes, const std::filesystem::path& path)
      : bytes_(bytes), path_(path) {}

  // The next line's words; throws at the end of the file (a header must end with end_header).
  std::vector<std::string_view> next() {
    if (pos_ >= bytes_.size()) {
      throw Error::at_line(path_, line_, "file ends in the header: no 'end_header' line");
    }
    const std::size_t end = bytes_.find('\n', pos_);
    const std::size_t stop = end == std::string_view::npos ? bytes_.size() : end;
    const std::string_view line = bytes_.substr(pos_, stop - pos_);
    pos_ = end == std::string_view::npos ? bytes_.size() : end + 1;
    ++line_;
    return words_of(line);
  }

  [[nodiscard]] std::size_t line() const { return line_; }
  [[nodiscard]] std::size_t offset() const { return pos_; }
  [[nodiscard]] Error error(const std::string& problem) const {
    return Error::at_line(path_, line_, problem);
  }

 private:
  std::string_view bytes_;
  const std::filesystem::path& path_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
};

PlyType type_word(const HeaderLines& lines, std::string_view word) {
  const std::optional<PlyType> type = parse_type(word);
  if (!type) throw lines.error("unknown property type " + shown(word));
  return *type;
}

PlyProperty parse_property(const HeaderLines& lines, const std::vector<std::string_view>& words) {
  PlyProperty property;
  if (words.size() >= 2 && words[1] == "list") {
    if (words.size() != 5) {
      throw lines.error("expected 'property list <count type> <item type> <name>'");
    }
    property.is_list = true;
    property.count_type = type_word(lines, words[2]);
    if (!ply_type_is_integer(property.count_type)) {
      throw lines.error("a list's item count must have an integer type, not " + shown(words[2]));
    }
    property.type = type_word(lines, words[3]);
    property.name = words[4];
    return property;
  }
  if (words.size() != 3) throw lines.error("expected 'property <type> <name>'");
  property.type = type_word(lines, words[1]);
  property.name = words[2];
  return property;
}

PlyElement parse_element(const HeaderLines& lines, const std::vector<std::string_view>& words) {
  if (words.size() != 3) throw lines.error("expected 'element <name> <count>'");
  PlyElement element;
  element.name = words[1];
  element.line = lines.line();
  const std::string_view count = words[2];
  const auto [end, error] =
      std::from_chars(count.data(), count.data() + count.size(), element.count);
  if (error != std::errc() || end != count.data() + count.size()) {
    throw lines.error("the count of element " + shown(words[1]) +
                      " is not a non-negative integer: " + shown(count));
  }
  return element;
}

PlyFormat parse_format(const HeaderLines& lines, const std::vector<std::string_view>& words) {
  if (words.size() != 3 || words[0] != "format") {
    throw lines.error("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
  }
  if (words[2] != "1.0") throw lines.error("unsupported PLY version " + shown(words[2]));
  if (words[1] == "ascii") return PlyFormat::kAscii;
  if (words[1] == "binary_little_endian") return PlyFormat::kBinaryLittleEndian;
  if (words[1] == "binary_big_endian") return PlyFormat::kBinaryBigEndian;
  throw lines.error("unknown PLY format " + shown(words[1]));
}

}  // namespace

std::size_t ply_type_size(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 0;
}

bool ply_type_is_integer(PlyType type) {
  return type != PlyType::kFloat32 && type != PlyType::kFloat64;
}

std::string_view ply_type_name(PlyType type) {
  for (const TypeName& entry : kTypeNames) {
    if (entry.type == type) return entry.name;
  }
  return "?";
}

std::uint64_t PlyElement::min_numbers() const { return properties.size(); }

std::uint64_t PlyElement::min_bytes() const {
  std::uint64_t bytes = 0;
  for (const PlyProperty& property : properties) {
    bytes += ply_type_size(property.is_list ? property.count_type : property.type);
  }
  return bytes;
}

PlyHeader parse_ply_header(std::string_view bytes, const std::filesystem::path& path) {
  HeaderLines lines(bytes, path);
  const std::vector<std::string_view> magic = lines.next();
  if (magic.size() != 1 || magic[0] != "ply") {
    throw lines.error("not a PLY file: it does not start with the line 'ply'");
  }
  PlyHeader header;
  header.format = parse_format(lines, lines.next());
  for (;;) {
    const std::vector<std::string_view> words = lines.next();
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    if (words[0] == "end_header") {
      if (words.size() != 1) throw lines.error("expected 'end_header' alone on its line");
      break;
    }
    if (words[0] == "element") {
      header.elements.push_back(parse_element(lines, words));
    } else if (words[0] == "property") {
      if (header.elements.empty()) throw lines.error("a property before any element");
      header.elements.back().properties.push_back(parse_property(lines, words));
    } else {
      throw lines.error("unknown header keyword " + shown(words[0]));
    }
  }
  header.body_offset = lines.offset();
  header.body_line = lines.line() + 1;
  return header;
}

}  // namespace sphys::tools
