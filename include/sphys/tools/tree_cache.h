#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sphys/sphere_tree.h"
#include "sphys/tools/build_tree.h"

namespace sphys::tools {

// Where built sphere-trees are kept: $SPHYS_CACHE_DIR, else $XDG_CACHE_HOME/sphys, else
// ~/.cache/sphys, else a folder in the system's temporary directory.
[[nodiscard]] std::filesystem::path default_cache_dir();

// The cache file for a tree built from this mesh with these options: named by a hash of the
// mesh's vertices and triangles, the method, branching, depth, seed, the builders' version and
// sphys's, so any change to the mesh, the parameters or the program misses.
[[nodiscard]] std::filesystem::path cache_path(const std::filesystem::path& dir,
                                               const TriangleMesh& mesh,
                                               const BuildOptions& options);

// A tree, and whether the cache gave it.
struct CachedTree {
  SphereTree tree;          // as built, or as stored by an earlier build
  bool from_cache = false;  // read from the cache rather than built
};

// Loads the tree from the cache when it is there and passes every check (its checksum, what it
// was built from, its depth, branching and count), else builds it and stores it (a temporary file
// renamed into place, so concurrent runs never see half an entry). A damaged entry is rebuilt and
// replaced with a note on standard error naming it. A cache folder that cannot be read or written
// is left alone for the rest of the process, with one note. Without a directory, always builds.
[[nodiscard]] CachedTree build_sphere_tree_cached(const TriangleMesh& mesh,
                                                  const BuildOptions& options,
                                                  const std::optional<std::filesystem::path>& dir);

// One file of a cache folder, as `sphys cache --list` and `--verify` show it.
struct CacheEntryCheck {
  std::filesystem::path path;  // the entry's file
  std::uintmax_t bytes = 0;    // its size. unit: bytes
  std::string description;     // "octree, branching 8, depth 3 (73 spheres)", when it decodes
  std::optional<std::string> problem;  // why it would not be used
};

// Every entry of the cache folder, checked, in name order; none when the folder does not exist.
// Throws sphys::Error naming the folder when it cannot be read.
[[nodiscard]] std::vector<CacheEntryCheck> check_cache(const std::filesystem::path& dir);

// Removes every entry and the temporary files of ended processes from the cache folder; returns
// how many entries went. Throws sphys::Error naming what could not be removed.
std::size_t clear_cache(const std::filesystem::path& dir);

}  // namespace sphys::tools
