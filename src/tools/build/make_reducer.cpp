// The point-set reducers: one class, the method choosing how the representatives are reduced;
// every result then goes through the same refinement.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>
#include <utility>
#include <vector>

#include "reducers_impl.h"
#include "sphys/error.h"

namespace sphys::tools::build {
namespace {

// Representatives per node: enough for the medial axis to follow the surface's features at the
// node's scale, few enough that a node costs milliseconds whatever the mesh's triangle count.
constexpr std::size_t kRegionPoints = 1000;
// The coarse sampling of the whole surface that surrounds every node's medial axis.
constexpr std::size_t kContextPoints = 400;
// The Tight method's lattice of the whole mesh: this many points (each costs a distance query)
// over the mesh's box grown on every side by kLatticeMargin of its diagonal, where the
// reductions' balls at 8 per node poke out by about 0.1. A node's lattice is refined from it
// until its balls' mean radius spans kLatticeSpacingsPerRadius spacings (at most kMaxRefinement
// times finer): fewer, and the count of a ball's points moves in steps too coarse to steer by.
constexpr std::size_t kLatticePoints = 80000;
constexpr double kLatticeMargin = 0.15;
// The margin is also at least kMarginOverProtrusion times as wide as the first level's start
// reaches out, read at kMarginDirections points of each of its balls' boundaries.
constexpr double kMarginOverProtrusion = 1.1;
constexpr std::size_t kMarginDirections = 96;
constexpr double kLatticeSpacingsPerRadius = 12.0;
constexpr int kMaxRefinement = 4;

class PointSetReducer final : public Reducer {
 public:
  PointSetReducer(BuildMethod method, const BuildContext& context)
      : method_(method), context_(context), measure_(context.query) {
    std::vector<std::uint32_t> all(context.samples.points.size());
    std::iota(all.begin(), all.end(), 0U);
    context_points_ = make_region(context, all, kContextPoints).points;
  }

  Cover cover(std::span<const std::uint32_t> samples, int max_balls) override {
    if (samples.empty()) return {};
    const Region region = make_region(context_, samples, kRegionPoints);
    if (max_balls <= 1) {
      // One ball: every method agrees on the least-error ball around all the points.
      std::vector<std::uint32_t> all(region.points.size());
      std::iota(all.begin(), all.end(), 0U);
      return finish(samples, region, {fit_cluster(region, measure_, std::move(all))});
    }
    Cover result = method_cover(samples, region, max_balls);
    // A method that found nothing to split by (no medial sphere where the surface encloses no
    // volume, as in an open sheet) would hand back the node's own ball as its only child, and
    // every level below would repeat it. The grid splits by position alone.
    if (result.balls.size() < 2 && region.points.size() >= 2 && method_ != BuildMethod::Grid) {
      result = finish(samples, region, grid_clusters(region, measure_, max_balls));
    }
    return result;
  }

 private:
  Cover method_cover(std::span<const std::uint32_t> samples, const Region& region,
                     int max_balls) const {
    switch (method_) {
      case BuildMethod::Grid:
        return finish(samples, region, grid_clusters(region, measure_, max_balls));
      case BuildMethod::Spawn:
        return finish(samples, region, spawn_clusters(region, measure_, max_balls));
      case BuildMethod::Hubbard:
        return finish(samples, region, merged(region, axis(region, false), max_balls));
      case BuildMethod::Merge:
        return finish(samples, region, merged(region, axis(region, true), max_balls));
      case BuildMethod::Burst:
        return finish(samples, region, burst(region, axis(region, true), max_balls));
      case BuildMethod::Expand:
        return finish(samples, region,
                      expand_clusters(region, axis(region, true), measure_, max_balls));
      case BuildMethod::Combined:
        return combined(samples, region, max_balls);
      case BuildMethod::Tight: {
        Cover start = finish(samples, region, merged(region, axis(region, true), max_balls));
        const ExteriorLattice lattice = node_lattice(samples, start, Resolution::Fine);
        // The first level is one node, and which part of the surface each of its balls answers
        // for shapes every level below: it alone gets the search of other starts.
        if (samples.size() == context_.samples.points.size()) {
          const ExteriorLattice coarse = node_lattice(samples, start, Resolution::Mesh);
          return shrink_outside_volume(context_, lattice, samples, std::move(start), &coarse);
        }
        return shrink_outside_volume(context_, lattice, samples, std::move(start));
      }
      case BuildMethod::Octree:
        break;
    }
    throw Error("the Octree method has no point-set reducer");
  }

  // Fine: refined until the balls' mean radius spans kLatticeSpacingsPerRadius spacings. Mesh:
  // the whole mesh's lattice's own points, for comparing many covers quickly.
  enum class Resolution { Fine, Mesh };

  // A lattice over the node to count the volume of its cover's balls, over the box of the node's
  // samples grown by the largest diameter (a ball outside it counts as poking out too far). The
  // lattice of the whole mesh is built on first use (only the Tight method counts volume); the
  // nodes' are interpolated from it.
  ExteriorLattice node_lattice(std::span<const std::uint32_t> samples, const Cover& cover,
                               Resolution resolution) const {
    if (!mesh_lattice_) {
      const double diagonal = context_.mesh.bounds().diagonal().norm();
      // The first cover asked for is the first level's; the lattice must hold every ball of it
      // whole, or the volume beyond would go uncounted (a thin plate's balls reach out by
      // more than their share of the diagonal).
      static const std::vector<Vec3d> kDirections = evenly_spread_directions(kMarginDirections);
      double margin = kLatticeMargin * diagonal;
      for (const Ball& ball : cover.balls) {
        for (const Vec3d& u : kDirections) {
          margin = std::max(margin, kMarginOverProtrusion * context_.query.signed_distance(
                                                                ball.center + ball.radius * u));
        }
      }
      mesh_lattice_ = std::make_unique<ExteriorLattice>(context_.query, kLatticePoints, margin);
    }
    double mean_radius = 0.0;
    double max_radius = 0.0;
    for (const Ball& ball : cover.balls) {
      mean_radius += ball.radius;
      max_radius = std::max(max_radius, ball.radius);
    }
    mean_radius /= static_cast<double>(std::max<std::size_t>(cover.balls.size(), 1));
    const double wanted = kLatticeSpacingsPerRadius * mesh_lattice_->spacing() / mean_radius;
    const double factor = resolution == Resolution::Mesh
                              ? 1.0
                              : std::clamp(std::ceil(wanted), 1.0, double{kMaxRefinement});
    Box3d region;
    for (const std::uint32_t s : samples) region.extend(context_.samples.points[s]);
    const Vec3d grow = Vec3d::Constant(2.0 * max_radius);
    return mesh_lattice_->refined(static_cast<int>(factor),
                                  Box3d(region.min() - grow, region.max() + grow));
  }

  MedialAxis axis(const Region& region, bool adaptive) const {
    return region_medial_axis(region, context_points_, measure_, adaptive);
  }

  std::vector<Cluster> merged(const Region& region, const MedialAxis& axis, int max_balls) const {
    return merge_clusters(medial_clusters(region, axis, measure_), region, measure_, max_balls);
  }

  std::vector<Cluster> burst(const Region& region, const MedialAxis& axis, int max_balls) const {
    return burst_clusters(medial_clusters(region, axis, measure_), region, max_balls);
  }

  Cover finish(std::span<const std::uint32_t> samples, const Region& region,
               std::vector<Cluster> clusters) const {
    return refine_cover(context_, measure_, samples, region, std::move(clusters));
  }

  // Bradshaw §4.5 keeps, per node, the better of Merge and Burst; Expand joins them here. All
  // three start from the same medial axis, and each result is compared after refinement, so
  // Combined's worst error is never above any of theirs.
  Cover combined(std::span<const std::uint32_t> samples, const Region& region,
                 int max_balls) const {
    const MedialAxis medial = axis(region, true);
    Cover best = finish(samples, region, merged(region, medial, max_balls));
    double best_error = worst_error(best, measure_);
    for (int method = 0; method < 2; ++method) {
      Cover other = finish(samples, region,
                           method == 0 ? burst(region, medial, max_balls)
                                       : expand_clusters(region, medial, measure_, max_balls));
      const double error = worst_error(other, measure_);
      if (error < best_error) {
        best = std::move(other);
        best_error = error;
      }
    }
    return best;
  }

  BuildMethod method_;
  BuildContext context_;
  ErrorMeasure measure_;
  std::vector<Vec3d> context_points_;
  mutable std::unique_ptr<ExteriorLattice> mesh_lattice_;
};

}  // namespace

std::unique_ptr<Reducer> make_reducer(BuildMethod method, const BuildContext& context) {
  if (method == BuildMethod::Octree) {
    throw Error("the Octree method subdivides space and has no point-set reducer");
  }
  return std::make_unique<PointSetReducer>(method, context);
}

}  // namespace sphys::tools::build
