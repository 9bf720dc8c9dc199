#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "sphys/sphere_tree.h"
#include "sphys/tools/mesh_query.h"

namespace sphys::tools {

// How well one level of a sphere-tree approximates the mesh. Distances are fractions of the
// mesh's bounding-box diagonal; volumes are multiples of the mesh's volume. The figures look at
// the spheres and the mesh only, never at how the spheres were built, so trees from any tool
// (Bradshaw's toolkit, Wang's sphere sets) are judged alike.
//
// All four are sampled: coverage and gap from area-weighted random points on the surface, the
// outside volume by Monte Carlo in the union's bounding box (standard error about
// box volume / mesh volume · sqrt(p(1-p) / volume_samples), p the fraction counted), protrusion
// over an evenly spread lattice of boundary_samples points on every sphere (it can only
// underestimate, by at most about radius · (1 - cos sqrt(4π / boundary_samples))). A point on the
// union's boundary is one that no other sphere holds strictly inside.
struct LevelQuality {
  int level = 0;                  // 0 = root
  std::size_t spheres = 0;        // in the level
  double coverage = 0.0;          // fraction of surface samples inside some sphere (want 1)
  double worst_gap = 0.0;         // largest distance from an uncovered sample to the nearest sphere
  double outside_volume = 0.0;    // volume of the union of spheres outside the mesh / mesh volume
  double worst_protrusion = 0.0;  // largest distance from the union's boundary outside the mesh
                                  // to the mesh surface
  // The last two in metres and cubic metres, for users who need absolute figures (a robot link).
  double outside_volume_m3 = 0.0;
  double worst_protrusion_m = 0.0;  // unit: m
};

// How many samples measure_level takes, and from which seed.
struct QualityOptions {
  std::size_t surface_samples = 100000;  // for coverage and gap. unit: count
  std::size_t volume_samples = 400000;   // Monte Carlo points for the outside volume. unit: count
  std::size_t boundary_samples = 400;    // per sphere, for protrusion. unit: count
  std::uint64_t seed = 2008;             // fixed: the same tree and mesh give the same figures
  // Whether the mesh must enclose a volume. When false, an open or flat mesh is measured too
  // (inside and outside by its winding number) and outside_volume, the ratio, is NaN for it.
  bool require_volume = true;
};

// Measures one set of spheres (level is left 0). The figures depend only on the spheres, the
// mesh and the options, not on the number of threads. Throws sphys::Error when there are no
// spheres, a sphere is not finite or has a negative radius, a sample count is 0, or the mesh
// encloses no volume while options.require_volume is set.
[[nodiscard]] LevelQuality measure_level(std::span<const Sphere> spheres, const MeshQuery& mesh,
                                         const QualityOptions& options = {});
// One entry per level of the tree, with the same surface samples for every level.
[[nodiscard]] std::vector<LevelQuality> measure_tree(const SphereTree& tree, const MeshQuery& mesh,
                                                     const QualityOptions& options = {});
// The same for levels given as sets of spheres (any number per level: a flat sphere set of 64
// read from a file is level 1 of two).
[[nodiscard]] std::vector<LevelQuality> measure_levels(std::span<const std::vector<Sphere>> levels,
                                                       const MeshQuery& mesh,
                                                       const QualityOptions& options = {});

}  // namespace sphys::tools
