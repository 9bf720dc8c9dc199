#include "sphys/tools/sph_file.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <istream>
#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "atomic_file.h"
#include "input_file.h"
#include "shown_text.h"
#include "sphys/error.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

// Node lines of a complete tree, above which we refuse a file (or a tree to write) rather than
// reading or allocating for it: 8 levels of branching 8 are 2.4 million, far beyond any
// sphere-tree the narrow phase can use.
constexpr std::uint64_t kMaxSlots = 10'000'000;

// The branching factors a SphereTree takes, and the most a file may state: a complete tree of two
// levels must fit in kMaxSlots.
constexpr long long kMaxTreeBranching = 8;
constexpr long long kMaxFileBranching = static_cast<long long>(kMaxSlots) - 1;

// A double from here on rounds to infinity as a float: FLT_MAX plus half its ulp. Below it a
// conversion to float is defined and finite.
constexpr double kFloatOverflow = 0x1.ffffffp127;

constexpr std::array<const char*, 4> kFieldNames = {"x", "y", "z", "radius"};

// The occupancy we write; the toolkit initialises every slot with 1 and readers ignore it.
constexpr std::string_view kOccupancy = "1";
constexpr std::string_view kUnusedLine = "0 0 0 -1 1\n";

// The number of slots of a complete tree, or nothing when it exceeds kMaxSlots.
std::optional<std::uint64_t> complete_tree_size(long long levels, long long branching) {
  std::uint64_t total = 0;
  std::uint64_t level_size = 1;
  for (long long level = 0; level < levels; ++level) {
    total += level_size;
    if (total > kMaxSlots) return std::nullopt;
    level_size *= static_cast<std::uint64_t>(branching);
  }
  return total;
}

// Field separators. '\r' among them reads files with Windows line ends.
constexpr std::string_view kBlanks = " \t\r\v\f";

// The characters of kBlanks, tested without a search: this runs for every character of a file.
bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Hands out the file's non-blank lines split into fields, counting lines for messages.
class LineReader {
 public:
  LineReader(std::istream& in, const fs::path& name) : in_(in), name_(name) {}

  // Moves to the next line that is not blank; false at the end of the input.
  bool next() {
    while (std::getline(in_, text_)) {
      ++line_;
      split();
      if (!fields_.empty()) return true;
    }
    return false;
  }

  [[nodiscard]] std::size_t line() const { return line_; }
  [[nodiscard]] const std::vector<std::string_view>& fields() const { return fields_; }
  // The line without surrounding blanks.
  [[nodiscard]] std::string_view text() const {
    const std::string_view text = text_;
    const std::size_t begin = text.find_first_not_of(kBlanks);
    return text.substr(begin, text.find_last_not_of(kBlanks) + 1 - begin);
  }
  [[nodiscard]] Error error(std::string_view problem) const {
    return Error::at_line(name_, line_, problem);
  }
  [[nodiscard]] Error error_at(std::size_t line, std::string_view problem) const {
    return Error::at_line(name_, line, problem);
  }

 private:
  void split() {
    fields_.clear();
    const std::string_view text = text_;
    std::size_t pos = 0;
    while (pos < text.size()) {
      while (pos < text.size() && is_blank(text[pos])) ++pos;
      const std::size_t begin = pos;
      while (pos < text.size() && !is_blank(text[pos])) ++pos;
      if (pos > begin) fields_.push_back(text.substr(begin, pos - begin));
    }
  }

  std::istream& in_;
  const fs::path& name_;
  std::string text_;
  std::vector<std::string_view> fields_;
  std::size_t line_ = 0;
};

struct Header {
  int levels = 0;
  int branching = 0;
  std::uint64_t slots = 0;  // node lines that follow
};

// A whole field as an integer; out-of-range values saturate so that the range checks report them.
std::optional<long long> parse_integer(std::string_view field) {
  long long value = 0;
  const char* last = field.data() + field.size();
  const auto [end, ec] = std::from_chars(field.data(), last, value);
  if (end != last) return std::nullopt;
  if (ec == std::errc::result_out_of_range) {
    return field.front() == '-' ? std::numeric_limits<long long>::min()
                                : std::numeric_limits<long long>::max();
  }
  if (ec != std::errc()) return std::nullopt;
  return value;
}

Header read_header(const LineReader& reader, long long max_branching) {
  const auto& fields = reader.fields();
  std::optional<long long> levels;
  std::optional<long long> branching;
  if (fields.size() == 2) {
    levels = parse_integer(fields[0]);
    branching = parse_integer(fields[1]);
  }
  if (!levels || !branching) {
    throw reader.error("the header must be two integers '<levels> <branching>', got " +
                       shown(reader.text()));
  }
  if (*levels < 1) {
    throw reader.error("levels must be at least 1 (the root), got " + std::to_string(*levels));
  }
  if (*branching < 2) {
    throw reader.error("branching factor " + std::to_string(*branching) + " is below 2");
  }
  if (*branching > max_branching) {
    throw reader.error("branching factor " + std::to_string(*branching) + " is above " +
                       std::to_string(max_branching) +
                       (max_branching == kMaxTreeBranching
                            ? ", the most a sphere-tree may have (a flat set of that many "
                              "spheres can be measured with `sphys tree-info`)"
                            : ", the most a sphere file may have"));
  }
  const std::optional<std::uint64_t> slots = complete_tree_size(*levels, *branching);
  if (!slots) {
    throw reader.error(std::to_string(*levels) + " levels with branching " +
                       std::to_string(*branching) + " need more than " + std::to_string(kMaxSlots) +
                       " node lines, more than a sphere-tree file may have");
  }
  // Both fit in an int: levels is at most 23 once the size check passed, and branching is at most
  // kMaxSlots.
  return {static_cast<int>(*levels), static_cast<int>(*branching), *slots};
}

// A whole field as a double. Streams and strtod depend on the locale; from_chars does not. A
// leading '+' is accepted, which from_chars alone would reject.
double parse_number(const LineReader& reader, std::size_t index) {
  const std::string_view field = reader.fields()[index];
  std::string_view digits = field;
  if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-') digits.remove_prefix(1);
  double value = 0.0;
  const char* last = digits.data() + digits.size();
  const auto [end, ec] = std::from_chars(digits.data(), last, value);
  const std::string name = kFieldNames[index];
  if (end == last && ec == std::errc::result_out_of_range) {
    throw reader.error(name + " " + shown(field) + " is outside the range of a double");
  }
  if (end != last || ec != std::errc()) {
    throw reader.error(name + " is not a number: " + shown(field));
  }
  return value;
}

// Converts a finite double to float, or nothing when it would overflow.
std::optional<float> to_float(double value) {
  if (std::abs(value) >= kFloatOverflow) return std::nullopt;
  return static_cast<float>(value);
}

// The sphere of a used slot (its radius is positive) in single precision, shifted.
Sphere used_sphere(const LineReader& reader, const std::array<double, 4>& values,
                   const Vec3d& shift) {
  for (std::size_t k = 0; k < 4; ++k) {
    if (!std::isfinite(values[k])) {
      throw reader.error(std::string(kFieldNames[k]) +
                         " of a used sphere is not finite: " + shown(reader.fields()[k]));
    }
  }
  Sphere sphere;
  for (std::size_t k = 0; k < 3; ++k) {
    const std::optional<float> coordinate = to_float(values[k] + shift[static_cast<int>(k)]);
    if (!coordinate) {
      throw reader.error(std::string(kFieldNames[k]) + " " + shown(reader.fields()[k]) +
                         " does not fit in single precision");
    }
    sphere.center[static_cast<int>(k)] = *coordinate;
  }
  const std::optional<float> radius = to_float(values[3]);
  if (!radius) {
    throw reader.error("radius " + shown(reader.fields()[3]) + " does not fit in single precision");
  }
  if (*radius <= 0.0f) {
    throw reader.error("radius " + shown(reader.fields()[3]) +
                       " is positive but rounds to zero in single precision");
  }
  sphere.radius = *radius;
  return sphere;
}

// One slot of the level just read: the compact index of its sphere (-1 when unused) and the line
// it came from, for messages about its children.
struct Slot {
  std::int32_t node = -1;
  std::size_t line = 0;
};

// Why the tree cannot be written as a .sph file, or nothing.
std::optional<std::string> unwritable_reason(const SphereTree& tree) {
  if (tree.empty()) return "cannot write an empty sphere-tree";
  if (!complete_tree_size(tree.depth(), tree.branching())) {
    return "a sphere-tree of depth " + std::to_string(tree.depth()) + " with branching " +
           std::to_string(tree.branching()) + " needs more than " + std::to_string(kMaxSlots) +
           " node lines as a complete tree, more than a sphere-tree file may have";
  }
  return std::nullopt;
}

void append_number(std::string& line, float value) {
  // Nine significant digits bring every float back exactly, also through a double.
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                    std::chars_format::general, 9);
  line.append(buffer.data(), result.ptr);
  line += ' ';
}

// Writes a tree that unwritable_reason() accepts.
void write_slots(std::ostream& out, const SphereTree& tree) {
  const auto branching = static_cast<std::size_t>(tree.branching());
  std::string line = std::to_string(tree.depth()) + " " + std::to_string(tree.branching()) + "\n";
  out << line;
  // The compact node in each slot of the current level, -1 for an unused slot.
  std::vector<std::int32_t> level{0};
  for (int depth = 0; depth < tree.depth(); ++depth) {
    for (const std::int32_t node : level) {
      if (node < 0) {
        out << kUnusedLine;
        continue;
      }
      const Sphere& sphere = tree.sphere(static_cast<std::uint32_t>(node));
      line.clear();
      for (int k = 0; k < 3; ++k) append_number(line, sphere.center[k]);
      append_number(line, sphere.radius);
      line += kOccupancy;
      line += '\n';
      out << line;
    }
    if (depth + 1 == tree.depth()) break;
    // Children take the first slots of their parent's block, in order.
    std::vector<std::int32_t> next(level.size() * branching, -1);
    for (std::size_t j = 0; j < level.size(); ++j) {
      if (level[j] < 0) continue;
      const auto node = static_cast<std::uint32_t>(level[j]);
      for (std::uint32_t c = 0; c < tree.child_count(node); ++c) {
        next[j * branching + c] = static_cast<std::int32_t>(tree.first_child(node) + c);
      }
    }
    level = std::move(next);
  }
}

// Reads the file's used spheres; a header whose branching factor exceeds `max_branching` is
// refused before anything is allocated.
SphSpheres read_spheres(std::istream& in, const fs::path& name, const SphReadOptions& options,
                        long long max_branching) {
  if (!options.shift.allFinite()) {
    throw Error::in_file(name, "the shift to add to the centres is not finite");
  }
  LineReader reader(in, name);
  if (!reader.next()) {
    throw Error::at_line(name, 1, "file is empty; expected the header '<levels> <branching>'");
  }
  const Header header = read_header(reader, max_branching);
  const auto branching = static_cast<std::size_t>(header.branching);

  std::vector<SphereTreeNode> nodes;
  std::vector<Slot> parents;
  std::vector<Slot> slots;
  std::uint64_t node_lines = 0;
  for (int level = 0; level < header.levels; ++level) {
    const std::size_t level_size = level == 0 ? 1 : parents.size() * branching;
    slots.clear();
    slots.reserve(level_size);
    for (std::size_t j = 0; j < level_size; ++j) {
      if (!reader.next()) {
        throw reader.error_at(reader.line() + 1,
                              "file ends early: " + std::to_string(header.levels) +
                                  " levels with branching " + std::to_string(header.branching) +
                                  " need " + std::to_string(header.slots) +
                                  " node lines after the header, and node line " +
                                  std::to_string(node_lines + 1) + " is missing");
      }
      ++node_lines;
      // Fields are checked before their count: text where a node line belongs (a truncated
      // file followed by the options block) then reads as such.
      const std::size_t field_count = reader.fields().size();
      std::array<double, 4> values{};
      for (std::size_t k = 0; k < std::min<std::size_t>(field_count, 4); ++k) {
        values[k] = parse_number(reader, k);
      }
      if (field_count < 4) {
        throw reader.error("a node line needs at least 4 numbers 'x y z radius', got " +
                           std::to_string(field_count));
      }
      // The unused-slot test needs a number; garbage in the centre of an unused slot is fine.
      if (std::isnan(values[3])) {
        throw reader.error("radius is NaN; it must be a number (<= 0 marks an unused slot)");
      }
      const bool used = values[3] > 0.0;

      // Slot j of a level is child j % B of slot j / B of the level above.
      const Slot* parent = level == 0 ? nullptr : &parents[j / branching];
      if (parent == nullptr) {
        if (!used) throw reader.error("the root sphere is unused (radius <= 0)");
      } else if (used && parent->node < 0) {
        throw reader.error("used sphere under an unused parent (line " +
                           std::to_string(parent->line) + ")");
      }

      // The toolkit leaves unused slots between used siblings; only the used ones become nodes,
      // in slot order, so siblings stay adjacent and in their order.
      Slot slot{-1, reader.line()};
      if (used) {
        slot.node = static_cast<std::int32_t>(nodes.size());
        nodes.push_back(
            {used_sphere(reader, values, options.shift), parent == nullptr ? -1 : parent->node});
      }
      slots.push_back(slot);
    }
    std::swap(parents, slots);
  }
  return {header.branching, std::move(nodes)};
}

}  // namespace

SphereTree read_sph(std::istream& in, const fs::path& name, const SphReadOptions& options) {
  const SphSpheres spheres = read_spheres(in, name, options, kMaxTreeBranching);
  return SphereTree::from_nodes(spheres.nodes, spheres.branching);
}

SphSpheres read_sph_spheres(const fs::path& path, const SphReadOptions& options) {
  InputFile file = open_input_file(path, InputKind::kSphereTree);
  return read_sph_spheres(file.stream, path, options);
}

SphSpheres read_sph_spheres(std::istream& in, const fs::path& name, const SphReadOptions& options) {
  return read_spheres(in, name, options, kMaxFileBranching);
}

std::vector<std::vector<Sphere>> SphSpheres::levels() const {
  std::vector<std::vector<Sphere>> result;
  std::vector<std::size_t> level(nodes.size(), 0);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].parent >= 0) level[i] = level[static_cast<std::size_t>(nodes[i].parent)] + 1;
    if (level[i] == result.size()) result.emplace_back();
    result[level[i]].push_back(nodes[i].sphere);
  }
  return result;
}

SphereTree read_sph(const fs::path& path, const SphReadOptions& options) {
  // Binary mode: a '\r' of a Windows line end is a blank to the field splitter anyway.
  InputFile file = open_input_file(path, InputKind::kSphereTree);
  return read_sph(file.stream, path, options);
}

void write_sph(std::ostream& out, const SphereTree& tree) {
  if (const auto reason = unwritable_reason(tree)) throw Error(*reason);
  write_slots(out, tree);
}

void write_sph(const fs::path& path, const SphereTree& tree) {
  if (const auto reason = unwritable_reason(tree)) throw Error::in_file(path, *reason);
  write_file_atomically(path, [&tree](std::ostream& out) { write_slots(out, tree); });
}

}  // namespace sphys::tools
