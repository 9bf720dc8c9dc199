#pragma once

// What the reduction algorithms share: a node's problem (representative points), the error
// measure, the clusters they pass around, and the refinement every method's result goes through.

#include <cstdint>
#include <span>
#include <vector>

#include "ball.h"
#include "error_measure.h"
#include "exterior_lattice.h"
#include "medial_axis.h"
#include "reducer.h"

namespace sphys::tools::build {

// A node's samples as the reductions see them: at most a few thousand representatives spread
// evenly over the node's part of the surface, so that the work scales with the region and not
// with the mesh's triangle count.
struct Region {
  std::vector<std::uint32_t> samples;  // indices into BuildContext::samples
  std::vector<Vec3d> points;           // their positions
  std::vector<Vec3d> normals;          // outward unit normals of their triangles
  double radius = 0.0;                 // of the smallest ball around them: the node's scale
};

// Picks one sample per cell of a grid sized so that about `max_points` cells are occupied (the
// lowest sample index in each cell, so the choice is deterministic).
[[nodiscard]] Region make_region(const BuildContext& context,
                                 std::span<const std::uint32_t> samples, std::size_t max_points);

// A ball and the representatives (indices into Region::points) it answers for.
struct Cluster {
  Ball ball;
  double offset = 0.0;  // signed distance of the centre: error = radius + offset
  std::vector<std::uint32_t> members;

  [[nodiscard]] double error() const { return ball.radius + offset; }
};

// The smallest ball around the members, with its error.
[[nodiscard]] Cluster fit_cluster(const Region& region, const ErrorMeasure& measure,
                                  std::vector<std::uint32_t> members);

// For each alive cluster, the `count` other alive clusters whose balls are nearest to its own (by
// the gap between them), the relation made symmetric; dead clusters get none. The neighbours of
// last resort of the Merge and Burst reductions when balls overlap nothing: the parts of a
// disconnected mesh, or the small medial balls of a thin part, which lie a sample spacing apart.
[[nodiscard]] std::vector<std::vector<std::uint32_t>> nearest_clusters(
    std::span<const Cluster> clusters, const std::vector<bool>& alive, std::size_t count);

// The medial spheres as a partition of the representatives: each point joins the least-error
// sphere it lies on (Bradshaw §4.1, the starting set of the Merge and Burst reductions).
[[nodiscard]] std::vector<Cluster> medial_clusters(const Region& region, const MedialAxis& axis,
                                                   const ErrorMeasure& measure);

// The medial axis of the region: its points in focus, `context` (a coarse sampling of the whole
// surface) around them.
[[nodiscard]] MedialAxis region_medial_axis(const Region& region, std::span<const Vec3d> context,
                                            const ErrorMeasure& measure, bool adaptive);

// The reductions (each returns at most max_balls non-empty clusters that partition the
// representatives, every member inside its ball).
[[nodiscard]] std::vector<Cluster> merge_clusters(std::vector<Cluster> clusters,
                                                  const Region& region, const ErrorMeasure& measure,
                                                  int max_balls);
[[nodiscard]] std::vector<Cluster> burst_clusters(std::vector<Cluster> clusters,
                                                  const Region& region, int max_balls);
[[nodiscard]] std::vector<Cluster> expand_clusters(const Region& region, const MedialAxis& axis,
                                                   const ErrorMeasure& measure, int max_balls);
[[nodiscard]] std::vector<Cluster> spawn_clusters(const Region& region, const ErrorMeasure& measure,
                                                  int max_balls);
[[nodiscard]] std::vector<Cluster> grid_clusters(const Region& region, const ErrorMeasure& measure,
                                                 int max_balls);

// The refinement every method's result goes through, then the hand-over of every sample (not
// only the representatives): Lloyd-like rounds of (1) moving each ball's centre to where it
// needs the least error for its points and (2) giving each point to the least-error ball that
// contains it. Every sample ends inside its ball.
[[nodiscard]] Cover refine_cover(const BuildContext& context, const ErrorMeasure& measure,
                                 std::span<const std::uint32_t> samples, const Region& region,
                                 std::vector<Cluster> clusters);

// The Tight method's last pass: moves and resizes the cover's balls so that their union adds less
// volume outside the mesh (as the lattice counts it), every sample of the node staying inside
// some ball and no ball reaching lattice points farther out than the start's did; then hands each
// sample to the ball that holds it most centrally. Returns the start when it finds nothing better.
// With a `search_lattice` (a coarser lattice over the node), starts of other structure
// (cover_starts.h) are descended on it too, and the best of them competes with the start's.
[[nodiscard]] Cover shrink_outside_volume(const BuildContext& context,
                                          const ExteriorLattice& lattice,
                                          std::span<const std::uint32_t> samples, Cover start,
                                          const ExteriorLattice* search_lattice = nullptr);

// The largest error of a cover's balls.
[[nodiscard]] double worst_error(const Cover& cover, const ErrorMeasure& measure);

}  // namespace sphys::tools::build
