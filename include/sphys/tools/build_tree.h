#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>

#include "sphys/sphere_tree.h"
#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// The construction algorithms of Bradshaw's Sphere-Tree Construction Toolkit (Bradshaw &
// O'Sullivan, ACM TOG 23(1), 2004), our own implementations.
enum class BuildMethod {
  Octree,    // Hubbard-style subdivision of the bounding cube
  Grid,      // spheres of a regular grid, reduced (Bradshaw §5)
  Spawn,     // spheres grown from seeds until the error bound (Bradshaw §5)
  Hubbard,   // static medial-axis approximation, greedy merging (Hubbard 1996)
  Merge,     // adaptive medial axis, reduced by merging (Bradshaw §4.2)
  Burst,     // adaptive medial axis, reduced by bursting (Bradshaw §4.3)
  Expand,    // adaptive medial axis, reduced by expanding and selecting (Bradshaw §4.4)
  Combined,  // per node, the best of Merge, Burst and Expand (Bradshaw §4.5)
  Tight,     // Merge, then the outside volume shrunk under the coverage and protrusion (ours)
};

// The method's name in scene files and on the command line ("combined"), as parse_method reads it.
[[nodiscard]] std::string_view method_name(BuildMethod method);
// Throws sphys::Error listing the valid names.
[[nodiscard]] BuildMethod parse_method(std::string_view name);

// How build_sphere_tree builds a tree.
struct BuildOptions {
  BuildMethod method = BuildMethod::Combined;  // the construction algorithm
  int branching = 8;                           // children per node, 2..8
  int depth = 3;           // levels including the root (the paper's depths are 2 and 3)
  std::uint64_t seed = 1;  // every random choice derives from it: same seed, same tree
  // Called with the fraction done (0..1) now and then, for progress bars.
  std::function<void(double)> progress;
};

// Builds a sphere-tree in which every level covers the whole surface of the mesh (not only sample
// points: see docs/sphere-trees.md). The mesh should be closed or nearly so. Throws sphys::Error
// for impossible options.
[[nodiscard]] SphereTree build_sphere_tree(const TriangleMesh& mesh, const BuildOptions& options);

}  // namespace sphys::tools
