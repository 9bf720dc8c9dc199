#include "sphys/tools/check_mesh.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>
#include <utility>

#include "sphys/error.h"

namespace sphys::tools {
namespace {

// Per undirected edge: how many triangles use it, and how many traverse it low -> high.
struct EdgeUse {
  std::uint32_t count = 0;
  std::uint32_t forward = 0;
};

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

}  // namespace

MeshReport check_mesh(const TriangleMesh& mesh) {
  MeshReport report;
  report.triangles = mesh.triangles.size();
  report.vertices = mesh.vertices.size();

  for (const Vec3d& v : mesh.vertices) {
    if (!v.allFinite()) ++report.non_finite_vertices;
  }

  // Relative area threshold: a sliver is degenerate when its area is negligible at the mesh's
  // own scale, whatever units the file uses.
  const double diagonal = mesh.vertices.empty() ? 0.0 : mesh.bounds().diagonal().norm();
  const double min_area2 = 1e-12 * diagonal * diagonal;

  std::vector<bool> used(mesh.vertices.size(), false);
  std::unordered_map<std::uint64_t, EdgeUse> edges;
  edges.reserve(mesh.triangles.size() * 3 / 2);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    for (std::uint32_t i : tri) used[i] = true;
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0] ||
        !(mesh.area_normal(t).norm() > min_area2)) {
      ++report.degenerate_triangles;
    }
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = tri[k];
      const std::uint32_t b = tri[(k + 1) % 3];
      if (a == b) continue;
      EdgeUse& use = edges[edge_key(a, b)];
      ++use.count;
      if (a < b) ++use.forward;
    }
  }

  for (const auto& [key, use] : edges) {
    if (use.count == 1) ++report.boundary_edges;
    if (use.count > 2) ++report.non_manifold_edges;
    if (use.count == 2 && use.forward != 1) ++report.misoriented_edges;
  }
  report.unused_vertices = static_cast<std::size_t>(std::count(used.begin(), used.end(), false));
  return report;
}

void require_usable(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) throw Error::in_file(mesh.name, "has no triangles");
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (!mesh.vertices[i].allFinite()) {
      throw Error::in_file(mesh.name,
                           "vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (const std::uint32_t v : mesh.triangles[t]) {
      if (v >= mesh.vertices.size()) {
        throw Error::in_file(mesh.name, "triangle " + std::to_string(t) + " refers to vertex " +
                                            std::to_string(v) + " of " +
                                            std::to_string(mesh.vertices.size()));
      }
    }
  }
}

}  // namespace sphys::tools
