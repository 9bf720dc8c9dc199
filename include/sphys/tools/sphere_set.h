#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "sphys/sphere_tree.h"
#include "sphys/tools/build_tree.h"
#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// Flat sets of spheres, any number of them, whose union covers the whole surface of a mesh
// (certified on the triangles, as every level of a sphere-tree is): what a motion planner's list
// of spheres per link needs. The set starts as one sphere and is refined a sphere at a time: the
// one that pokes out farthest (Bradshaw's error: radius plus the centre's signed distance) is
// replaced by the children the method's reducer finds for its part of the surface, as a
// sphere-tree node is split, so the set is a cut through an adaptive tree and each refinement
// costs one node's reduction.
class SphereSetBuilder {
 public:
  // Any point-set method (every method but Octree). Throws sphys::Error for a mesh without
  // triangles or with a non-finite vertex, or for the Octree method.
  explicit SphereSetBuilder(const TriangleMesh& mesh, BuildMethod method = BuildMethod::Combined,
                            std::uint64_t seed = 1);
  ~SphereSetBuilder();
  SphereSetBuilder(const SphereSetBuilder&) = delete;
  SphereSetBuilder& operator=(const SphereSetBuilder&) = delete;

  // Spheres in the set now.
  [[nodiscard]] std::size_t size() const;
  // Splits the sphere that pokes out farthest into at most `max_children` (2..8). Returns false,
  // changing nothing, when no sphere can be split (each answers for a single surface sample).
  bool refine(int max_children = 8);
  // The set, grown where needed so that it covers every point of every triangle.
  [[nodiscard]] std::vector<Sphere> spheres() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sphys::tools
