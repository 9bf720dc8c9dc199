#include "sphys/tools/tree_cache.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "sphys/error.h"
#include "sphys/tools/sph_file.h"

namespace sphys::tools {
namespace {

// Bumped whenever a builder changes what it produces, so old cache entries are not reused.
constexpr int kBuilderVersion = 2;

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
  [[nodiscard]] std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

}  // namespace

std::filesystem::path default_cache_dir() {
  if (const char* dir = std::getenv("SPHYS_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    return std::filesystem::path(xdg) / "sphys";
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return std::filesystem::path(home) / ".cache" / "sphys";
  }
  return std::filesystem::temp_directory_path() / "sphys-cache";
}

std::filesystem::path cache_path(const std::filesystem::path& dir, const TriangleMesh& mesh,
                                 const BuildOptions& options) {
  Fnv1a hash;
  for (const Vec3d& v : mesh.vertices) hash.add(v.data(), 3 * sizeof(double));
  for (const Triangle& t : mesh.triangles) hash.add(t.data(), 3 * sizeof(std::uint32_t));
  hash.add(kBuilderVersion);
  hash.add(static_cast<int>(options.method));
  hash.add(options.branching);
  hash.add(options.depth);
  hash.add(options.seed);
  char name[64];
  std::snprintf(name, sizeof name, "%s-b%d-d%d-%016llx.sph",
                std::string(method_name(options.method)).c_str(), options.branching, options.depth,
                static_cast<unsigned long long>(hash.value()));
  return dir / name;
}

CachedTree build_sphere_tree_cached(const TriangleMesh& mesh, const BuildOptions& options,
                                    const std::optional<std::filesystem::path>& dir) {
  if (!dir) return {build_sphere_tree(mesh, options), false};
  const std::filesystem::path path = cache_path(*dir, mesh, options);
  if (std::filesystem::exists(path)) {
    try {
      return {read_sph(path), true};
    } catch (const Error&) {
      // A damaged entry (an interrupted disk, a foreign file): rebuild and overwrite it.
    }
  }
  CachedTree built{build_sphere_tree(mesh, options), false};
  std::error_code ec;
  std::filesystem::create_directories(*dir, ec);
  try {
    write_sph(path, built.tree);
  } catch (const Error&) {
    // A read-only or full cache only costs the next run a rebuild.
  }
  return built;
}

}  // namespace sphys::tools
