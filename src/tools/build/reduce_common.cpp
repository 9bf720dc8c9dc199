// The node's problem as every reduction sees it: representatives, clusters, the medial axis.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "reducers_impl.h"
#include "shrinking_ball.h"

namespace sphys::tools::build {
namespace {

// Adaptive refinement of a node's medial axis (Bradshaw §3.3): a few dozen points where the
// spheres poke out most, until the worst pokes out by less than this fraction of the node's
// radius. The representatives are already dense, so a small budget suffices.
constexpr int kRefinementPoints = 96;
constexpr double kRefinementTolerance = 0.01;

std::uint64_t cell_key(const Vec3d& p, const Vec3d& origin, double cell) {
  const Eigen::Array3d q = ((p - origin) / cell).array().floor();
  const auto coordinate = [](double v) {
    return static_cast<std::uint64_t>(std::clamp(v, 0.0, 2097151.0));
  };
  return coordinate(q.x()) | coordinate(q.y()) << 21 | coordinate(q.z()) << 42;
}

// One sample per occupied cell: the smallest index, given (key, index) pairs sorted.
std::vector<std::uint32_t> one_per_cell(
    std::vector<std::pair<std::uint64_t, std::uint32_t>>& keyed) {
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> picked;
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    if (i == 0 || keyed[i].first != keyed[i - 1].first) picked.push_back(keyed[i].second);
  }
  std::sort(picked.begin(), picked.end());
  return picked;
}

}  // namespace

Region make_region(const BuildContext& context, std::span<const std::uint32_t> samples,
                   std::size_t max_points) {
  const std::vector<Vec3d>& all = context.samples.points;
  Region region;
  Box3d box;
  for (const std::uint32_t s : samples) box.extend(all[s]);
  if (samples.size() <= max_points) {
    region.samples.assign(samples.begin(), samples.end());
    std::sort(region.samples.begin(), region.samples.end());
  } else {
    // The cell side from the count: occupied cells grow as 1/side² on a surface. A few rounds
    // of correction land near the target whatever the shape.
    const double extent = std::max(box.sizes().maxCoeff(), 1e-12);
    double cell = extent / std::sqrt(static_cast<double>(max_points));
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(samples.size());
    for (int round = 0; round < 6; ++round) {
      for (std::size_t i = 0; i < samples.size(); ++i) {
        keyed[i] = {cell_key(all[samples[i]], box.min(), cell), samples[i]};
      }
      region.samples = one_per_cell(keyed);
      const double ratio =
          static_cast<double>(region.samples.size()) / static_cast<double>(max_points);
      if (region.samples.size() <= max_points && ratio > 0.8) break;
      cell *= std::sqrt(ratio) * (ratio > 1.0 ? 1.02 : 1.0);
    }
  }
  for (const std::uint32_t s : region.samples) {
    region.points.push_back(all[s]);
    region.normals.push_back(
        context.mesh.area_normal(context.samples.triangle[s]).stableNormalized());
  }
  region.radius = min_enclosing_ball(region.points, context.seed).radius;
  return region;
}

Cluster fit_cluster(const Region& region, const ErrorMeasure& measure,
                    std::vector<std::uint32_t> members) {
  std::vector<Vec3d> points;
  points.reserve(members.size());
  for (const std::uint32_t m : members) points.push_back(region.points[m]);
  Cluster cluster;
  cluster.ball = min_enclosing_ball(points);
  cluster.offset = measure.signed_distance(cluster.ball.center);
  cluster.members = std::move(members);
  return cluster;
}

MedialAxis region_medial_axis(const Region& region, std::span<const Vec3d> context,
                              const ErrorMeasure& measure, bool adaptive) {
  std::vector<Vec3d> points = region.points;
  points.insert(points.end(), context.begin(), context.end());
  MedialAxisOptions options;
  if (adaptive) {
    options.max_added_points = kRefinementPoints;
    options.tolerance = kRefinementTolerance * region.radius;
  }
  MedialAxis axis = approximate_medial_axis(points, region.points.size(), measure, options);
  // Where the part is thinner than the spacing of the points (a plate, a wire), no Voronoi
  // vertex lies inside it and its points touch no sphere; each gets the medial sphere tangent
  // to it instead, so that the reductions have spheres to work with there too.
  for (std::uint32_t i = 0; i < region.points.size(); ++i) {
    if (!axis.point_spheres[i].empty()) continue;
    if (const std::optional<MedialSphere> sphere =
            shrinking_ball(region.points[i], region.normals[i], i, region.radius, measure)) {
      axis.point_spheres[i].push_back(static_cast<std::uint32_t>(axis.spheres.size()));
      axis.spheres.push_back(*sphere);
    }
  }
  return axis;
}

std::vector<std::vector<std::uint32_t>> nearest_clusters(std::span<const Cluster> clusters,
                                                         const std::vector<bool>& alive,
                                                         std::size_t count) {
  std::vector<std::vector<std::uint32_t>> nearest(clusters.size());
  std::vector<std::pair<double, std::uint32_t>> gaps;
  for (std::uint32_t a = 0; a < clusters.size(); ++a) {
    if (!alive[a]) continue;
    gaps.clear();
    for (std::uint32_t b = 0; b < clusters.size(); ++b) {
      if (b == a || !alive[b]) continue;
      const Ball& x = clusters[a].ball;
      const Ball& y = clusters[b].ball;
      gaps.emplace_back((x.center - y.center).norm() - x.radius - y.radius, b);
    }
    const std::size_t kept = std::min(count, gaps.size());
    std::partial_sort(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(kept), gaps.end());
    for (std::size_t k = 0; k < kept; ++k) {
      nearest[a].push_back(gaps[k].second);
      nearest[gaps[k].second].push_back(a);
    }
  }
  for (std::vector<std::uint32_t>& list : nearest) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return nearest;
}

std::vector<Cluster> medial_clusters(const Region& region, const MedialAxis& axis,
                                     const ErrorMeasure& measure) {
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> cluster_of_sphere(axis.spheres.size(), kNone);
  std::vector<Cluster> clusters;
  std::vector<std::uint32_t> orphans;
  for (std::uint32_t i = 0; i < region.points.size(); ++i) {
    std::uint32_t best = kNone;
    for (const std::uint32_t s : axis.point_spheres[i]) {
      if (best == kNone || axis.spheres[s].error < axis.spheres[best].error) best = s;
    }
    if (best == kNone) {
      orphans.push_back(i);
      continue;
    }
    if (cluster_of_sphere[best] == kNone) {
      cluster_of_sphere[best] = static_cast<std::uint32_t>(clusters.size());
      const MedialSphere& sphere = axis.spheres[best];
      clusters.push_back({sphere.ball, sphere.error - sphere.ball.radius, {}});
    }
    Cluster& cluster = clusters[cluster_of_sphere[best]];
    cluster.members.push_back(i);
    // The point is on the sphere; rounding may leave it a hair outside.
    cluster.ball.radius =
        std::max(cluster.ball.radius, (region.points[i] - cluster.ball.center).norm());
  }
  if (clusters.empty()) {
    std::vector<std::uint32_t> all(region.points.size());
    for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
    return {fit_cluster(region, measure, std::move(all))};
  }
  // A point no medial sphere touches (rare: a sliver region) joins the sphere that grows least.
  for (const std::uint32_t i : orphans) {
    Cluster* best = nullptr;
    double best_error = std::numeric_limits<double>::infinity();
    for (Cluster& cluster : clusters) {
      const double grown =
          std::max(cluster.ball.radius, (region.points[i] - cluster.ball.center).norm());
      if (grown + cluster.offset < best_error) {
        best_error = grown + cluster.offset;
        best = &cluster;
      }
    }
    best->members.push_back(i);
    best->ball.radius = best_error - best->offset;
  }
  return clusters;
}

}  // namespace sphys::tools::build
