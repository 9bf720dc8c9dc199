#include "tree_cache_entry.h"

#include <charconv>
#include <cstdio>
#include <sstream>

#include "sphys/error.h"
#include "sphys/tools/sph_file.h"

namespace sphys::tools {
namespace {

// Bumped whenever a builder changes what it produces, so old cache entries are not reused.
constexpr int kBuilderVersion = 3;
constexpr std::string_view kMagic = "sphys-tree-cache";
constexpr int kFormatVersion = 1;
constexpr std::string_view kExtension = ".sphcache";
// The entries sphys wrote before entries carried their origin: plain .sph files, never read now.
constexpr std::string_view kPlainExtension = ".sph";

// FNV-1a, 64 bits: stable across platforms and runs, unlike std::hash.
class Fnv1a {
 public:
  void add(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) hash_ = (hash_ ^ bytes[i]) * 0x100000001b3ULL;
  }
  template <typename T>
  void add(const T& value) {
    add(&value, sizeof value);
  }
  void add_text(std::string_view text) {
    add(text.size());
    add(text.data(), text.size());
  }
  [[nodiscard]] std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

std::uint64_t checksum(std::string_view bytes) {
  Fnv1a hash;
  hash.add(bytes.data(), bytes.size());
  return hash.value();
}

std::string hex(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

// Reads the header's lines in order, each "<key> <value>", refusing anything else.
class HeaderReader {
 public:
  HeaderReader(std::string_view bytes, const std::filesystem::path& path)
      : rest_(bytes), path_(path) {}

  std::string_view line() {
    const std::size_t end = rest_.find('\n');
    if (end == std::string_view::npos) fail("cut short in its header");
    const std::string_view text = rest_.substr(0, end);
    rest_.remove_prefix(end + 1);
    return text;
  }
  std::string_view value(std::string_view key) {
    const std::string_view text = line();
    if (!text.starts_with(key) || text.size() <= key.size() || text[key.size()] != ' ') {
      fail("expected '" + std::string(key) + " ...' in its header");
    }
    return text.substr(key.size() + 1);
  }
  template <typename Number>
  Number number(std::string_view key, int base = 10) {
    const std::string_view text = value(key);
    Number result{};
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), result, base);
    if (error != std::errc() || end != text.data() + text.size()) {
      fail("'" + std::string(key) + "' is not a number in its header");
    }
    return result;
  }
  [[nodiscard]] std::string_view rest() const { return rest_; }
  [[noreturn]] void fail(const std::string& problem) const { throw Error::in_file(path_, problem); }

 private:
  std::string_view rest_;
  const std::filesystem::path& path_;
};

}  // namespace

TreeOrigin origin_of(const TriangleMesh& mesh, const BuildOptions& options) {
  Fnv1a mesh_hash;
  for (const Vec3d& v : mesh.vertices) mesh_hash.add(v.data(), 3 * sizeof(double));
  for (const Triangle& t : mesh.triangles) mesh_hash.add(t.data(), 3 * sizeof(std::uint32_t));
  return {std::string(method_name(options.method)),
          options.branching,
          options.depth,
          options.seed,
          mesh_hash.value(),
          kBuilderVersion,
          SPHYS_VERSION_TEXT};
}

std::string entry_name(const TreeOrigin& origin) {
  Fnv1a hash;
  hash.add_text(origin.method);
  hash.add(origin.branching);
  hash.add(origin.depth);
  hash.add(origin.seed);
  hash.add(origin.mesh_hash);
  hash.add(origin.builder);
  hash.add_text(origin.version);
  return origin.method + "-b" + std::to_string(origin.branching) + "-d" +
         std::to_string(origin.depth) + "-" + hex(hash.value()) + std::string(kExtension);
}

bool is_entry_name(std::string_view name) {
  std::string_view stem;
  if (name.ends_with(kExtension)) {
    stem = name.substr(0, name.size() - kExtension.size());
  } else if (name.ends_with(kPlainExtension)) {
    stem = name.substr(0, name.size() - kPlainExtension.size());
  } else {
    return false;
  }
  const std::size_t dash = stem.rfind('-');
  if (dash == std::string_view::npos || stem.size() - dash - 1 != 16) return false;
  return stem.substr(dash + 1).find_first_not_of("0123456789abcdef") == std::string_view::npos;
}

std::string encode_entry(const TreeOrigin& origin, const SphereTree& tree) {
  std::ostringstream body;
  body << "version " << origin.version << "\nbuilder " << origin.builder << "\nmethod "
       << origin.method << "\nbranching " << origin.branching << "\ndepth " << origin.depth
       << "\nseed " << origin.seed << "\nmesh " << hex(origin.mesh_hash) << "\ntree "
       << tree.depth() << ' ' << tree.branching() << ' ' << tree.size() << '\n';
  write_sph(body, tree);
  const std::string rest = body.str();
  return std::string(kMagic) + ' ' + std::to_string(kFormatVersion) + ' ' + hex(checksum(rest)) +
         '\n' + rest;
}

DecodedEntry decode_entry(std::string_view bytes, const std::filesystem::path& path) {
  HeaderReader header(bytes, path);
  const std::string first(header.line());
  const std::string expected_start =
      std::string(kMagic) + ' ' + std::to_string(kFormatVersion) + ' ';
  if (!first.starts_with(expected_start)) {
    header.fail("not a sphere-tree cache entry of this sphys (expected '" + expected_start +
                "<checksum>')");
  }
  const std::string_view after_first = header.rest();
  if (first.substr(expected_start.size()) != hex(checksum(after_first))) {
    header.fail("its checksum does not match its bytes (changed or cut short)");
  }
  TreeOrigin origin;
  origin.version = std::string(header.value("version"));
  origin.builder = header.number<int>("builder");
  origin.method = std::string(header.value("method"));
  origin.branching = header.number<int>("branching");
  origin.depth = header.number<int>("depth");
  origin.seed = header.number<std::uint64_t>("seed");
  origin.mesh_hash = header.number<std::uint64_t>("mesh", 16);
  std::istringstream tree_line{std::string(header.value("tree"))};
  int depth = 0;
  int branching = 0;
  std::size_t count = 0;
  if (!(tree_line >> depth >> branching >> count)) header.fail("its 'tree' line is malformed");
  if (path.filename() != entry_name(origin)) {
    header.fail("made for another mesh or other parameters than its name says");
  }
  std::istringstream sph{std::string(header.rest())};
  DecodedEntry entry{std::move(origin), read_sph(sph, path)};
  const SphereTree& tree = entry.tree;
  if (tree.depth() != depth || tree.branching() != branching || tree.size() != count) {
    header.fail("its tree has depth " + std::to_string(tree.depth()) + ", branching " +
                std::to_string(tree.branching()) + " and " + std::to_string(tree.size()) +
                " spheres; its header says " + std::to_string(depth) + ", " +
                std::to_string(branching) + " and " + std::to_string(count));
  }
  return entry;
}

}  // namespace sphys::tools
