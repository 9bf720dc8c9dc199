#pragma once

// Meshes made wrong on purpose, for the tests of what copes with them.

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <vector>

#include "sphys/tools/triangle_mesh.h"

namespace sphys::test {

// The mesh with the triangles of these indices taken out: holes in a closed surface.
inline tools::TriangleMesh without_triangles(tools::TriangleMesh mesh,
                                             std::vector<std::size_t> removed) {
  std::sort(removed.rbegin(), removed.rend());
  for (const std::size_t t : removed) {
    mesh.triangles.erase(mesh.triangles.begin() + static_cast<std::ptrdiff_t>(t));
  }
  return mesh;
}

}  // namespace sphys::test
