// Spawn reduction (Bradshaw & O'Sullivan 2004, §5): spheres are spawned on the surface at the
// point farthest from those already placed and grown inward, along the surface normal, as far
// as an error bound allows; the bound is searched for the smallest that needs no more than the
// allowed number of spheres. No medial axis is involved.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "reducers_impl.h"

namespace sphys::tools::build {
namespace {

// How far inward a sphere's centre may move from its seed: kDepthSteps steps of
// kStepFraction times the node's radius, i.e. up to the whole node's diameter.
constexpr int kDepthSteps = 32;
constexpr double kStepFraction = 1.0 / 16.0;
// Bisection steps on the error bound.
constexpr int kSpawnSearchSteps = 20;

class Spawner {
 public:
  Spawner(const Region& region, const ErrorMeasure& measure)
      : region_(region),
        measure_(measure),
        step_(kStepFraction * region.radius),
        depth_(region.points.size() * (kDepthSteps + 1), std::numeric_limits<double>::quiet_NaN()) {
    Vec3d centroid = Vec3d::Zero();
    for (const Vec3d& p : region.points) centroid += p;
    centroid /= static_cast<double>(region.points.size());
    double farthest = -1.0;
    for (std::uint32_t i = 0; i < region.points.size(); ++i) {
      const double d = (region.points[i] - centroid).squaredNorm();
      if (d > farthest) {
        farthest = d;
        first_seed_ = i;
      }
    }
  }

  std::vector<Cluster> reduce(int max_balls) {
    // A sphere of radius 2R at any point takes in the whole node: the search's upper end.
    double low = 0.0;
    double high = 2.0 * region_.radius;
    std::vector<Cluster> best = *attempt(high, max_balls);
    for (int step = 0; step < kSpawnSearchSteps; ++step) {
      const double middle = 0.5 * (low + high);
      if (std::optional<std::vector<Cluster>> clusters = attempt(middle, max_balls)) {
        high = middle;
        best = std::move(*clusters);
      } else {
        low = middle;
      }
    }
    return best;
  }

 private:
  Vec3d centre(std::uint32_t seed, int k) const {
    return region_.points[seed] - (k * step_) * region_.normals[seed];
  }

  // Depth of the centre k steps in from the seed; the same for every bound, so kept.
  double depth(std::uint32_t seed, int k) {
    double& d = depth_[seed * (kDepthSteps + 1) + static_cast<std::size_t>(k)];
    if (std::isnan(d)) d = -measure_.signed_distance(centre(seed, k));
    return d;
  }

  // Covers the points with spheres of error at most `bound`, or fails past max_balls spheres.
  std::optional<std::vector<Cluster>> attempt(double bound, int max_balls) {
    const std::size_t n = region_.points.size();
    std::vector<bool> covered(n, false);
    // How far each point is outside the spheres placed so far: the next seed is the worst off.
    std::vector<double> gap(n, std::numeric_limits<double>::infinity());
    std::size_t remaining = n;
    std::uint32_t seed = first_seed_;
    std::vector<Cluster> clusters;
    while (remaining > 0) {
      if (static_cast<int>(clusters.size()) == max_balls) return std::nullopt;
      // The sphere of error `bound` at depth step k has radius depth + bound; it must still
      // reach its seed, k steps away. Of those, the one taking in most uncovered points wins.
      int best_k = 0;
      std::size_t best_count = 0;
      for (int k = 0; k <= kDepthSteps; ++k) {
        const double radius = depth(seed, k) + bound;
        if (radius < k * step_) break;
        const Vec3d c = centre(seed, k);
        std::size_t count = 0;
        for (std::size_t i = 0; i < n; ++i) {
          if (!covered[i] && (region_.points[i] - c).squaredNorm() <= radius * radius) ++count;
        }
        if (count > best_count) {
          best_count = count;
          best_k = k;
        }
      }
      const Vec3d c = centre(seed, best_k);
      const double radius = std::max(depth(seed, best_k) + bound, best_k * step_);
      Cluster cluster{{c, 0.0}, -depth(seed, best_k), {}};
      for (std::uint32_t i = 0; i < n; ++i) {
        const double distance = (region_.points[i] - c).norm();
        if (!covered[i] && (distance <= radius || i == seed)) {
          covered[i] = true;
          --remaining;
          cluster.members.push_back(i);
          cluster.ball.radius = std::max(cluster.ball.radius, distance);
        }
        gap[i] = std::min(gap[i], distance - radius);
      }
      clusters.push_back(std::move(cluster));
      double worst = -std::numeric_limits<double>::infinity();
      for (std::uint32_t i = 0; i < n; ++i) {
        if (!covered[i] && gap[i] > worst) {
          worst = gap[i];
          seed = i;
        }
      }
    }
    return clusters;
  }

  const Region& region_;
  const ErrorMeasure& measure_;
  double step_;
  std::vector<double> depth_;
  std::uint32_t first_seed_ = 0;
};

}  // namespace

std::vector<Cluster> spawn_clusters(const Region& region, const ErrorMeasure& measure,
                                    int max_balls) {
  return Spawner(region, measure).reduce(max_balls);
}

}  // namespace sphys::tools::build
