#pragma once

// The bytes of one sphere-tree cache entry (docs/sphere-trees.md, "Files and cache"): what the
// tree was built from, the tree's own figures, a checksum over all of it, and the tree as a .sph
// text. An entry whose bytes changed, were cut short, or were made for another request never
// decodes, so a damaged entry is rebuilt rather than used.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "sphys/sphere_tree.h"
#include "sphys/tools/build_tree.h"

namespace sphys::tools {

// What a tree was built from. The cache entry's name is a hash of it.
struct TreeOrigin {
  std::string method;           // method_name()
  int branching = 0;            // as requested
  int depth = 0;                // as requested
  std::uint64_t seed = 0;       // as requested
  std::uint64_t mesh_hash = 0;  // FNV-1a of the mesh's vertices and triangles
  int builder = 0;              // the builders' version: bumped when a builder's output changes
  std::string version;          // sphys's

  bool operator==(const TreeOrigin&) const = default;
};

// The origin of a tree built from this mesh with these options by this sphys.
[[nodiscard]] TreeOrigin origin_of(const TriangleMesh& mesh, const BuildOptions& options);

// "<method>-b<branching>-d<depth>-<16 hex digits>.sphcache", the hex a hash of the whole origin:
// any change to the mesh, the parameters or the program misses.
[[nodiscard]] std::string entry_name(const TreeOrigin& origin);
// Whether a file name has the form of entry_name's (or of the plain .sph entries of earlier
// versions, which are never read).
[[nodiscard]] bool is_entry_name(std::string_view name);

// The entry's bytes.
[[nodiscard]] std::string encode_entry(const TreeOrigin& origin, const SphereTree& tree);

struct DecodedEntry {
  TreeOrigin origin;
  SphereTree tree;
};

// The entry in `bytes`, stored under the file name `name`. Throws sphys::Error naming `path` and
// the first check it fails: the format, the checksum, the .sph text, the tree's depth, branching
// or count against those recorded, or a name that is not the one its origin gives (another
// entry's bytes under this name).
[[nodiscard]] DecodedEntry decode_entry(std::string_view bytes, const std::filesystem::path& path);

}  // namespace sphys::tools
