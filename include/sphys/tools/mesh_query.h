#pragma once

#include <memory>

#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// Fast geometric queries against one mesh: closest point, distance and inside tests. Built once
// (an AABB tree over the triangles, on a copy of the mesh), then thread-safe for concurrent const
// queries.
//
// Inside tests are exact (ray parity via the tree, with exact predicates) for watertight meshes;
// for meshes with holes, non-manifold edges or vertices, or misoriented triangles they use the
// generalized winding number (w >= 1/2), which is robust but slower: a tree of triangle clusters
// (Barill et al. 2018) answers in logarithmic time, and the exact sum settles points where it
// reads near 1/2, so the answer is is_inside()'s. A point on the surface counts as inside.
class MeshQuery {
 public:
  // Throws sphys::Error, naming the mesh, when it has no triangles, a vertex is not finite or a
  // triangle refers to a missing vertex.
  explicit MeshQuery(const TriangleMesh& mesh);
  ~MeshQuery();
  // Takes over the other's state; the moved-from query may only be destroyed or assigned to.
  MeshQuery(MeshQuery&&) noexcept;
  // As the move constructor.
  MeshQuery& operator=(MeshQuery&&) noexcept;

  // The point of the mesh's surface nearest to `p`, in the mesh's units.
  [[nodiscard]] Vec3d closest_point(const Vec3d& p) const;
  // Unsigned distance from `p` to the surface: |closest_point(p) - p|, in the mesh's units.
  [[nodiscard]] double distance(const Vec3d& p) const;
  // Whether `p` is inside the solid (the class comment says how; the surface counts as inside).
  [[nodiscard]] bool inside(const Vec3d& p) const;
  // Negative inside, positive outside. unit: m
  [[nodiscard]] double signed_distance(const Vec3d& p) const;
  // The query's own copy of the mesh.
  [[nodiscard]] const TriangleMesh& mesh() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sphys::tools
