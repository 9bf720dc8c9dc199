#pragma once

// An independent check of the builders' coverage promise, shared by their tests.

#include <cstddef>

#include "sphys/sphere_tree.h"
#include "sphys/tools/triangle_mesh.h"

namespace sphys::test {

// Points of a barycentric grid on every triangle (corners, edges and inside; `steps` divisions
// per edge) that no sphere of the tree's level holds, tested in float as the runtime will use
// the spheres.
inline std::size_t uncovered_points(const SphereTree& tree, int level,
                                    const tools::TriangleMesh& mesh, int steps = 6) {
  std::size_t uncovered = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int u = 0; u <= steps; ++u) {
      for (int v = 0; u + v <= steps; ++v) {
        const tools::Vec3d p = mesh.corner(t, 0) +
                               (mesh.corner(t, 1) - mesh.corner(t, 0)) * u / steps +
                               (mesh.corner(t, 2) - mesh.corner(t, 0)) * v / steps;
        const Vec3 q = p.cast<float>();
        bool inside = false;
        for (const Sphere& s : tree.level_spheres(level)) {
          if ((q - s.center).squaredNorm() <= s.radius * s.radius) {
            inside = true;
            break;
          }
        }
        if (!inside) ++uncovered;
      }
    }
  }
  return uncovered;
}

}  // namespace sphys::test
