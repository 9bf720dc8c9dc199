#include "cover_starts.h"

#include <algorithm>
#include <limits>
#include <random>
#include <utility>

#include <Eigen/Eigenvalues>

namespace sphys::tools::build {
namespace {

// Lloyd's rounds after seeding; they end sooner once no point changes cluster.
constexpr int kLloydRounds = 30;

std::vector<Ball> enclosing_balls(const std::vector<std::vector<Vec3d>>& clusters) {
  std::vector<Ball> balls;
  for (const std::vector<Vec3d>& cluster : clusters) {
    if (cluster.empty()) continue;
    Ball ball = min_enclosing_ball(cluster);
    ball.radius = padded_radius(ball.radius);
    balls.push_back(ball);
  }
  return balls;
}

// k-means++ seeding (each new centre drawn with probability proportional to the squared
// distance to the nearest chosen one), then Lloyd's rounds. Returns the clusters' points.
std::vector<std::vector<Vec3d>> k_means(std::span<const Vec3d> points, std::size_t count,
                                        std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::vector<Vec3d> centres{
      points[std::uniform_int_distribution<std::size_t>(0, points.size() - 1)(random)]};
  std::vector<double> nearest(points.size(), std::numeric_limits<double>::infinity());
  while (centres.size() < count) {
    for (std::size_t p = 0; p < points.size(); ++p) {
      nearest[p] = std::min(nearest[p], (points[p] - centres.back()).squaredNorm());
    }
    // Every point on a centre already: no more clusters to be had.
    if (*std::max_element(nearest.begin(), nearest.end()) == 0.0) break;
    std::discrete_distribution<std::size_t> pick(nearest.begin(), nearest.end());
    centres.push_back(points[pick(random)]);
  }
  count = centres.size();
  std::vector<std::size_t> cluster_of(points.size(), count);
  for (int round = 0; round < kLloydRounds; ++round) {
    bool changed = false;
    for (std::size_t p = 0; p < points.size(); ++p) {
      std::size_t best = 0;
      for (std::size_t c = 1; c < count; ++c) {
        if ((points[p] - centres[c]).squaredNorm() < (points[p] - centres[best]).squaredNorm()) {
          best = c;
        }
      }
      changed |= cluster_of[p] != best;
      cluster_of[p] = best;
    }
    if (!changed) break;
    std::vector<Vec3d> sum(count, Vec3d::Zero());
    std::vector<std::size_t> size(count, 0);
    for (std::size_t p = 0; p < points.size(); ++p) {
      sum[cluster_of[p]] += points[p];
      ++size[cluster_of[p]];
    }
    for (std::size_t c = 0; c < count; ++c) {
      if (size[c] > 0) centres[c] = sum[c] / static_cast<double>(size[c]);
    }
  }
  std::vector<std::vector<Vec3d>> clusters(count);
  for (std::size_t p = 0; p < points.size(); ++p) clusters[cluster_of[p]].push_back(points[p]);
  std::erase_if(clusters, [](const std::vector<Vec3d>& c) { return c.empty(); });
  return clusters;
}

}  // namespace

std::vector<Ball> clustered_start(std::span<const Vec3d> points, std::size_t count,
                                  std::uint64_t seed) {
  if (points.empty() || count == 0) return {};
  return enclosing_balls(k_means(points, std::min(count, points.size()), seed));
}

std::vector<Ball> merged_start(std::span<const Vec3d> points, std::size_t count, std::size_t over,
                               const ExteriorLattice& lattice, std::span<const Vec3d> directions,
                               double limit, std::uint64_t seed) {
  if (points.empty() || count == 0) return {};
  std::vector<std::vector<Vec3d>> clusters =
      k_means(points, std::min(over * count, points.size()), seed);
  std::vector<Ball> balls = enclosing_balls(clusters);
  const auto outside_points = [&](const Ball& ball) {
    std::size_t n = 0;
    lattice.for_each_outside(ball, [&](std::size_t, double) { ++n; });
    return static_cast<double>(n);
  };
  std::vector<double> own(balls.size());
  for (std::size_t i = 0; i < balls.size(); ++i) own[i] = outside_points(balls[i]);

  // Each pair's merged ball, its protrusion and the outside points it adds; kept between merges
  // and worked out again only for pairs with the newly merged cluster.
  struct Pair {
    Ball merged;
    double protrusion = 0.0;  // unit: m
    double added = 0.0;       // lattice points
  };
  const std::size_t n = balls.size();
  std::vector<Pair> pairs(n * n);
  const auto evaluate = [&](std::size_t i, std::size_t j) {
    std::vector<Vec3d> both = clusters[i];
    both.insert(both.end(), clusters[j].begin(), clusters[j].end());
    Pair& pair = pairs[i * n + j];
    pair.merged = min_enclosing_ball(both);
    pair.merged.radius = padded_radius(pair.merged.radius);
    pair.protrusion = lattice.protrusion(pair.merged, directions);
    pair.added = outside_points(pair.merged) - own[i] - own[j];
  };
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) evaluate(i, j);
  }
  std::vector<bool> alive(n, true);
  for (std::size_t left = n; left > count; --left) {
    std::pair<std::size_t, std::size_t> within{n, n};
    std::pair<std::size_t, std::size_t> least_out{n, n};
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) {
        if (!alive[i] || !alive[j]) continue;
        const Pair& pair = pairs[i * n + j];
        if (pair.protrusion <= limit) {
          if (within.first == n || pair.added < pairs[within.first * n + within.second].added) {
            within = {i, j};
          }
        } else if (least_out.first == n ||
                   pair.protrusion < pairs[least_out.first * n + least_out.second].protrusion) {
          least_out = {i, j};
        }
      }
    }
    const auto [a, b] = within.first != n ? within : least_out;
    clusters[a].insert(clusters[a].end(), clusters[b].begin(), clusters[b].end());
    clusters[b].clear();
    balls[a] = pairs[a * n + b].merged;
    own[a] = outside_points(balls[a]);
    alive[b] = false;
    for (std::size_t j = 0; j < n; ++j) {
      if (j != a && alive[j]) evaluate(std::min(a, j), std::max(a, j));
    }
  }
  std::vector<Ball> kept;
  for (std::size_t i = 0; i < n; ++i) {
    if (alive[i]) kept.push_back(balls[i]);
  }
  return kept;
}

std::vector<std::vector<Ball>> slab_starts(std::span<const Vec3d> points, std::size_t count) {
  if (points.empty() || count == 0) return {};
  Vec3d centroid = Vec3d::Zero();
  for (const Vec3d& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Vec3d& p : points) scatter += (p - centroid) * (p - centroid).transpose();
  // Eigenvalues come in increasing order: the longest axis is the last column.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  const Eigen::Matrix3d axes = solver.eigenvectors().rowwise().reverse();
  std::vector<Vec3d> local(points.size());
  Vec3d low = Vec3d::Constant(std::numeric_limits<double>::infinity());
  Vec3d high = -low;
  for (std::size_t p = 0; p < points.size(); ++p) {
    local[p] = axes.transpose() * (points[p] - centroid);
    low = low.cwiseMin(local[p]);
    high = high.cwiseMax(local[p]);
  }
  std::vector<std::vector<Ball>> starts;
  for (std::size_t a = 1; a <= count; ++a) {
    for (std::size_t b = 1; b <= a; ++b) {
      if (count % (a * b) != 0) continue;
      const std::size_t c = count / (a * b);
      if (c > a) continue;
      const std::size_t cuts[3] = {a, b, c};
      std::vector<std::vector<Vec3d>> slabs(count);
      for (std::size_t p = 0; p < points.size(); ++p) {
        std::size_t index = 0;
        for (int axis = 0; axis < 3; ++axis) {
          const double width = high[axis] - low[axis];
          const double at = width > 0.0 ? (local[p][axis] - low[axis]) / width : 0.0;
          const auto slab = std::min(static_cast<std::size_t>(at * static_cast<double>(cuts[axis])),
                                     cuts[axis] - 1);
          index = index * cuts[axis] + slab;
        }
        slabs[index].push_back(points[p]);
      }
      starts.push_back(enclosing_balls(slabs));
    }
  }
  return starts;
}

}  // namespace sphys::tools::build
