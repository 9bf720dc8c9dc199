#pragma once

#include <filesystem>
#include <optional>

#include "sphys/sphere_tree.h"
#include "sphys/tools/build_tree.h"

namespace sphys::tools {

// Where built sphere-trees are kept: $SPHYS_CACHE_DIR, else $XDG_CACHE_HOME/sphys, else
// ~/.cache/sphys, else a folder in the system's temporary directory.
[[nodiscard]] std::filesystem::path default_cache_dir();

// The cache file for a tree built from this mesh with these options: named by a hash of the
// mesh's vertices and triangles, the method, branching, depth, seed and the builders' version,
// so any change to the mesh or the parameters misses.
[[nodiscard]] std::filesystem::path cache_path(const std::filesystem::path& dir,
                                               const TriangleMesh& mesh,
                                               const BuildOptions& options);

struct CachedTree {
  SphereTree tree;
  bool from_cache = false;
};

// Loads the tree from the cache when it is there (a corrupt entry is rebuilt, not trusted), else
// builds it and stores it. Without a directory, always builds.
[[nodiscard]] CachedTree build_sphere_tree_cached(const TriangleMesh& mesh,
                                                  const BuildOptions& options,
                                                  const std::optional<std::filesystem::path>& dir);

}  // namespace sphys::tools
