#pragma once

#include <cstddef>

#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// What check_mesh found. An edge is an unordered pair of vertex indices.
struct MeshReport {
  std::size_t triangles = 0;             // how many the mesh has
  std::size_t vertices = 0;              // how many the mesh has
  std::size_t degenerate_triangles = 0;  // a repeated vertex, or area below 1e-12 of bounds²
  std::size_t non_finite_vertices = 0;   // NaN or infinite coordinates
  std::size_t boundary_edges = 0;        // used by exactly one triangle: the mesh has holes
  std::size_t non_manifold_edges = 0;    // used by three or more triangles
  std::size_t misoriented_edges = 0;     // two triangles traverse it the same way
  std::size_t unused_vertices = 0;       // in no triangle

  // Closed, manifold and consistently oriented: the volume it encloses is well defined.
  [[nodiscard]] bool watertight() const {
    return boundary_edges == 0 && non_manifold_edges == 0 && misoriented_edges == 0 &&
           non_finite_vertices == 0 && triangles > 0;
  }
};

// Counts what is wrong with a mesh, throwing nothing; its triangle indices must be in range
// (require_usable checks them).
[[nodiscard]] MeshReport check_mesh(const TriangleMesh& mesh);

// What every computation on a mesh needs before it starts: at least one triangle, finite
// vertices, and triangle indices in range. Throws sphys::Error naming the mesh and the first
// problem found.
void require_usable(const TriangleMesh& mesh);

}  // namespace sphys::tools
