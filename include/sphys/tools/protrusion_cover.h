#pragma once

#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

#include "sphys/sphere_tree.h"
#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// Flat sets of spheres covering the whole surface of a mesh (certified on the triangles, as every
// level of a sphere-tree is) in which no sphere reaches more than a given distance D out of the
// object: what a motion planner's spheres per link need, where D is the clearance lost.
//
// A sphere centred inside the object at depth t (its distance to the surface) with radius t + D
// pokes out by at most D: a point of it outside lies beyond the surface point where the segment
// from the centre leaves the object, which is at least t from the centre. The candidates are
// such spheres, centred on the inward normal of surface samples at fractions of the depth of the
// medial sphere there (Ma et al.'s shrinking ball) and on the surface itself, the deep ones for
// thick parts, the shallow ones for edges and corners. A greedy set cover (as in Coverage Axis++,
// Wang et al. 2024) picks the candidates that cover the most samples still uncovered, counting a
// sample only when it lies at least the samples' spacing inside, so that the pieces of surface
// between samples are mostly covered too; the certificate then grows the few spheres that must.
class ProtrusionCover {
 public:
  // `finest_bound` (unit: m), when given, is the smallest bound cover() will be asked for: the
  // surface is then sampled densely enough for it. Throws sphys::Error for a mesh without
  // triangles or with a non-finite vertex.
  explicit ProtrusionCover(const TriangleMesh& mesh, double finest_bound = 0.0);
  ~ProtrusionCover();
  // Takes over the other's state; the moved-from cover may only be destroyed or
  // assigned to.
  ProtrusionCover(ProtrusionCover&&) noexcept;
  // As the move constructor.
  ProtrusionCover& operator=(ProtrusionCover&&) noexcept;

  // The spheres for protrusion bound `max_protrusion` (unit: m; positive): the candidates
  // chosen, grown where the certificate needs it, so the measured protrusion may exceed the bound
  // by up to about the samples' spacing. The same bound gives the same spheres.
  [[nodiscard]] std::vector<Sphere> cover(double max_protrusion) const;
  // How many spheres cover() returns for this bound, without certifying them; or, once that is
  // known to be more than `stop_after`, stop_after + 1.
  [[nodiscard]] std::size_t count(
      double max_protrusion,
      std::size_t stop_after = std::numeric_limits<std::size_t>::max()) const;
  // The distance between neighbouring surface samples. unit: m
  [[nodiscard]] double spacing() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sphys::tools
