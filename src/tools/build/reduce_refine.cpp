// The refinement pass every method's result goes through. The toolkit stops at the reduction;
// here each ball is then re-centred for least error and points move to the ball that holds them
// with least error, which is where most of the gain over the toolkit's trees comes from.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "reducers_impl.h"

namespace sphys::tools::build {
namespace {

// Rounds of re-centring and reassignment: the error stops improving noticeably after three.
constexpr int kRefineRounds = 3;

}  // namespace

Cover refine_cover(const BuildContext& context, const ErrorMeasure& measure,
                   std::span<const std::uint32_t> samples, const Region& region,
                   std::vector<Cluster> clusters) {
  std::erase_if(clusters, [](const Cluster& c) { return c.members.empty(); });
  std::vector<Vec3d> points;
  for (int round = 0; round < kRefineRounds; ++round) {
    for (Cluster& cluster : clusters) {
      points.clear();
      for (const std::uint32_t m : cluster.members) points.push_back(region.points[m]);
      cluster.ball = measure.optimise(cluster.ball, points);
      cluster.offset = measure.signed_distance(cluster.ball.center);
    }
    // Each point to the least-error ball that already holds it: balls only lose points, so
    // their radii only shrink.
    std::vector<std::vector<std::uint32_t>> members(clusters.size());
    for (std::size_t c = 0; c < clusters.size(); ++c) {
      for (const std::uint32_t m : clusters[c].members) {
        const Vec3d& p = region.points[m];
        std::size_t best = c;
        for (std::size_t k = 0; k < clusters.size(); ++k) {
          if (clusters[k].error() < clusters[best].error() &&
              clusters[k].ball.contains(p, 1e-12 * clusters[k].ball.radius)) {
            best = k;
          }
        }
        members[best].push_back(m);
      }
    }
    for (std::size_t c = 0; c < clusters.size(); ++c) {
      std::sort(members[c].begin(), members[c].end());
      clusters[c].members = std::move(members[c]);
      double radius = 0.0;
      for (const std::uint32_t m : clusters[c].members) {
        radius = std::max(radius, (region.points[m] - clusters[c].ball.center).norm());
      }
      clusters[c].ball.radius = radius;
    }
    std::erase_if(clusters, [](const Cluster& c) { return c.members.empty(); });
  }

  // Every sample of the node, not only the representatives, to the least-error ball holding it;
  // one a little outside every ball (representatives are a sampling of the samples) grows the
  // ball that then has the least error.
  Cover cover;
  cover.samples.resize(clusters.size());
  for (const std::uint32_t s : samples) {
    const Vec3d& p = context.samples.points[s];
    std::size_t best = 0;
    double best_error = std::numeric_limits<double>::infinity();
    bool best_contains = false;
    for (std::size_t k = 0; k < clusters.size(); ++k) {
      const Cluster& cluster = clusters[k];
      const bool contains = cluster.ball.contains(p);
      const double error =
          std::max(cluster.ball.radius, (p - cluster.ball.center).norm()) + cluster.offset;
      if ((contains && !best_contains) || (contains == best_contains && error < best_error)) {
        best = k;
        best_error = error;
        best_contains = contains;
      }
    }
    cover.samples[best].push_back(s);
  }
  for (std::size_t k = 0; k < clusters.size(); ++k) {
    if (cover.samples[k].empty()) continue;
    Ball ball = clusters[k].ball;
    for (const std::uint32_t s : cover.samples[k]) {
      ball.radius = std::max(ball.radius, (context.samples.points[s] - ball.center).norm());
    }
    ball.radius = padded_radius(ball.radius);
    cover.balls.push_back(ball);
  }
  std::erase_if(cover.samples, [](const std::vector<std::uint32_t>& s) { return s.empty(); });
  return cover;
}

double worst_error(const Cover& cover, const ErrorMeasure& measure) {
  double worst = -std::numeric_limits<double>::infinity();
  for (const Ball& ball : cover.balls) worst = std::max(worst, measure.error(ball));
  return worst;
}

}  // namespace sphys::tools::build
