// The outside-volume pass of the Tight method (ours, not the toolkit's): the reductions minimise
// how far their balls poke out; this pass then trades that for the volume the union of a node's
// balls adds outside the mesh, the figure users compare trees by, without letting any sample go
// uncovered or any ball poke out farther than the reduction's did. A descent keeps its start's
// structure (which part of the surface each ball answers for), so at the first level it also
// descends starts of other structure and keeps the best.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "cover_starts.h"
#include "reducers_impl.h"
#include "volume_descent.h"

namespace sphys::tools::build {
namespace {

// Directions at which a ball's boundary is checked against the protrusion limit.
constexpr std::size_t kBoundaryDirections = 96;

// The search of other starts (first level only). Each start is descended on kSearchPoints
// representatives of the samples and on the coarse lattice, a few milliseconds each; the
// kFinalists best are descended again with every sample, and the best of those (or the reduction's
// start, descended the same way) once more on the fine lattice.
constexpr std::size_t kSearchPoints = 1000;
// k-means starts, half of them plain and half over-clustered by kOverClustering and merged under
// the protrusion limit; their seeds are the build's seed plus 0, 1, ...
constexpr std::size_t kClusteredStarts = 12;
constexpr std::size_t kOverClustering = 2;
constexpr std::size_t kFinalists = 3;
// Enough to rank starts: a few rounds, each ball's search ending at a whole lattice spacing.
constexpr DescentEffort kQuickEffort{4, 1.0};

struct Descended {
  DescentCost cost;
  std::vector<Ball> balls;
};

const std::vector<Vec3d>& boundary_directions() {
  static const std::vector<Vec3d> kBoundary = evenly_spread_directions(kBoundaryDirections);
  return kBoundary;
}

// Other starts than the reduction's, each descended on the coarse lattice; returns the balls of
// the best, descended there with every point (the reduction's start competing).
std::vector<Ball> search_starts(const BuildContext& context, const ExteriorLattice& coarse,
                                std::span<const std::uint32_t> samples,
                                const std::vector<Vec3d>& points, const std::vector<Ball>& start,
                                double limit) {
  const std::vector<Vec3d>& boundary = boundary_directions();
  const std::vector<Vec3d> few = make_region(context, samples, kSearchPoints).points;
  const std::size_t count = start.size();
  std::vector<std::vector<Ball>> starts = slab_starts(few, count);
  for (std::size_t k = 0; k < kClusteredStarts; ++k) {
    const std::uint64_t seed = context.seed + k;
    starts.push_back(
        k % 2 == 0 ? clustered_start(few, count, seed)
                   : merged_start(few, count, kOverClustering, coarse, boundary, limit, seed));
  }
  std::vector<Descended> quick;
  for (std::vector<Ball>& balls : starts) {
    VolumeDescent descent(coarse, boundary, few, std::move(balls), limit, kQuickEffort);
    descent.run();
    quick.push_back({descent.total(), descent.balls()});
  }
  std::sort(quick.begin(), quick.end(),
            [](const Descended& a, const Descended& b) { return a.cost < b.cost; });

  VolumeDescent best(coarse, boundary, points, start, limit);
  best.run();
  for (std::size_t k = 0; k < std::min(kFinalists, quick.size()); ++k) {
    VolumeDescent finalist(coarse, boundary, points, std::move(quick[k].balls), limit);
    finalist.grow_to_cover();
    finalist.run();
    if (finalist.total() < best.total()) best = std::move(finalist);
  }
  return best.balls();
}

}  // namespace

Cover shrink_outside_volume(const BuildContext& context, const ExteriorLattice& lattice,
                            std::span<const std::uint32_t> samples, Cover start,
                            const ExteriorLattice* search_lattice) {
  if (start.balls.size() < 2) return start;
  std::vector<Vec3d> points;
  points.reserve(samples.size());
  for (const std::uint32_t s : samples) points.push_back(context.samples.points[s]);
  // No ball may poke out farther than the start's did.
  const std::vector<Vec3d>& boundary = boundary_directions();
  double limit = -std::numeric_limits<double>::infinity();
  for (const Ball& ball : start.balls) {
    limit = std::max(limit, lattice.protrusion(ball, boundary));
  }
  // Nor beyond the lattice, where the pass would not see the volume a ball adds.
  limit = std::min(limit, lattice.margin() - lattice.spacing());
  // With a search, the best start (the reduction's competing) is settled on the fine lattice.
  VolumeDescent descent(lattice, boundary, points,
                        search_lattice != nullptr ? search_starts(context, *search_lattice, samples,
                                                                  points, start.balls, limit)
                                                  : start.balls,
                        limit);
  const DescentCost start_cost =
      VolumeDescent(lattice, boundary, points, start.balls, limit).total();
  descent.run();
  if (!(descent.total() < start_cost)) return start;

  // Each sample to the ball that holds it most centrally; every ball then shrinks to its own.
  const std::vector<Ball>& balls = descent.balls();
  std::vector<std::vector<std::uint32_t>> members(balls.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    std::size_t best = balls.size();
    double best_ratio = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < balls.size(); ++b) {
      if (balls[b].radius == 0.0 || !balls[b].contains(points[k])) continue;
      const double ratio = (points[k] - balls[b].center).norm() / balls[b].radius;
      if (ratio < best_ratio) {
        best = b;
        best_ratio = ratio;
      }
    }
    if (best == balls.size()) return start;  // cannot happen: the descent covers every point
    members[best].push_back(samples[k]);
  }
  Cover cover;
  for (std::size_t b = 0; b < balls.size(); ++b) {
    if (members[b].empty()) continue;
    Ball ball{balls[b].center, 0.0};
    for (const std::uint32_t s : members[b]) {
      ball.radius = std::max(ball.radius, (context.samples.points[s] - ball.center).norm());
    }
    ball.radius = padded_radius(ball.radius);
    cover.balls.push_back(ball);
    cover.samples.push_back(std::move(members[b]));
  }
  return cover;
}

}  // namespace sphys::tools::build
