// Merge reduction (Bradshaw & O'Sullivan 2004, §4.2): repeatedly replace the pair of
// neighbouring spheres whose merged sphere has the least error by that sphere.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

#include "reducers_impl.h"

namespace sphys::tools::build {
namespace {

// Spheres that overlap nothing may merge with this many of their nearest.
constexpr std::size_t kMergeNeighbours = 8;

struct MergeCandidate {
  double cost;
  std::uint32_t a;
  std::uint32_t b;
  std::uint32_t version_a;
  std::uint32_t version_b;

  // std::priority_queue keeps the largest on top: the cheapest merge wins, ties by index.
  bool operator<(const MergeCandidate& other) const {
    if (cost != other.cost) return cost > other.cost;
    return std::pair(a, b) > std::pair(other.a, other.b);
  }
};

bool overlap(const Cluster& a, const Cluster& b, double slack) {
  const double reach = a.ball.radius + b.ball.radius + slack;
  return (a.ball.center - b.ball.center).squaredNorm() <= reach * reach;
}

// The error of covering both clusters' points from one of the two centres: the cost by which
// merges are ranked. Medial centres are deep, so one of them is usually a good centre for the
// union, and ranking this way needs no distance queries.
double merge_cost(const Cluster& a, const Cluster& b, const Region& region) {
  double best = std::numeric_limits<double>::infinity();
  for (const Cluster* own : {&a, &b}) {
    double radius = 0.0;
    for (const Cluster* part : {&a, &b}) {
      for (const std::uint32_t m : part->members) {
        radius = std::max(radius, (region.points[m] - own->ball.center).squaredNorm());
      }
    }
    best = std::min(best, std::sqrt(radius) + own->offset);
  }
  return best;
}

// The merged sphere itself: the better of the two own centres and the union's smallest
// enclosing ball, whose centre wins where the two parts sit side by side along the surface.
Cluster merged(const Cluster& a, const Cluster& b, const Region& region,
               const ErrorMeasure& measure) {
  std::vector<std::uint32_t> members;
  members.reserve(a.members.size() + b.members.size());
  std::merge(a.members.begin(), a.members.end(), b.members.begin(), b.members.end(),
             std::back_inserter(members));
  Cluster best = fit_cluster(region, measure, std::move(members));
  for (const Cluster* own : {&a, &b}) {
    double radius = 0.0;
    for (const std::uint32_t m : best.members) {
      radius = std::max(radius, (region.points[m] - own->ball.center).norm());
    }
    if (radius + own->offset < best.error()) {
      best.ball = {own->ball.center, radius};
      best.offset = own->offset;
    }
  }
  return best;
}

}  // namespace

std::vector<Cluster> merge_clusters(std::vector<Cluster> clusters, const Region& region,
                                    const ErrorMeasure& measure, int max_balls) {
  std::erase_if(clusters, [](const Cluster& c) { return c.members.empty(); });
  for (Cluster& c : clusters) std::sort(c.members.begin(), c.members.end());
  const auto count = static_cast<std::uint32_t>(clusters.size());
  std::uint32_t alive_count = count;
  if (alive_count <= static_cast<std::uint32_t>(max_balls)) return clusters;

  // Neighbours are spheres that overlap (or nearly touch): Bradshaw merges only those, which
  // keeps the candidate pairs near linear in the sphere count.
  const double slack = 1e-3 * region.radius;
  std::vector<bool> alive(count, true);
  std::vector<std::uint32_t> version(count, 0);
  std::vector<std::vector<std::uint32_t>> neighbours(count);
  for (std::uint32_t a = 0; a < count; ++a) {
    for (std::uint32_t b = a + 1; b < count; ++b) {
      if (overlap(clusters[a], clusters[b], slack)) {
        neighbours[a].push_back(b);
        neighbours[b].push_back(a);
      }
    }
  }
  std::priority_queue<MergeCandidate> queue;
  const auto consider = [&](std::uint32_t a, std::uint32_t b) {
    if (a > b) std::swap(a, b);
    queue.push({merge_cost(clusters[a], clusters[b], region), a, b, version[a], version[b]});
  };
  for (std::uint32_t a = 0; a < count; ++a) {
    for (const std::uint32_t b : neighbours[a]) {
      if (a < b) consider(a, b);
    }
  }

  while (alive_count > static_cast<std::uint32_t>(max_balls)) {
    if (queue.empty()) {
      // Spheres that overlap nothing (a disconnected mesh, a thin part): each may now merge
      // with its nearest ones. Every pair would cost the square of the sphere count.
      const std::vector<std::vector<std::uint32_t>> nearest =
          nearest_clusters(clusters, alive, kMergeNeighbours);
      for (std::uint32_t a = 0; a < count; ++a) {
        for (const std::uint32_t b : nearest[a]) {
          if (std::find(neighbours[a].begin(), neighbours[a].end(), b) == neighbours[a].end()) {
            neighbours[a].push_back(b);
          }
          if (a < b) consider(a, b);
        }
      }
    }
    const MergeCandidate top = queue.top();
    queue.pop();
    if (!alive[top.a] || !alive[top.b] || version[top.a] != top.version_a ||
        version[top.b] != top.version_b) {
      continue;
    }
    clusters[top.a] = merged(clusters[top.a], clusters[top.b], region, measure);
    clusters[top.b].members.clear();
    alive[top.b] = false;
    ++version[top.a];
    --alive_count;
    // The merged sphere neighbours whatever either part did, and whatever it now overlaps.
    std::vector<std::uint32_t> around;
    for (std::uint32_t u = 0; u < count; ++u) {
      if (u != top.a && alive[u] && overlap(clusters[top.a], clusters[u], slack)) {
        around.push_back(u);
      }
    }
    for (const std::uint32_t part : {top.a, top.b}) {
      for (const std::uint32_t u : neighbours[part]) {
        if (u != top.a && alive[u]) around.push_back(u);
      }
    }
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    neighbours[top.a] = around;
    neighbours[top.b].clear();
    for (const std::uint32_t u : around) {
      std::vector<std::uint32_t>& list = neighbours[u];
      std::erase(list, top.b);
      if (std::find(list.begin(), list.end(), top.a) == list.end()) list.push_back(top.a);
      consider(top.a, u);
    }
  }
  std::vector<Cluster> result;
  for (std::uint32_t a = 0; a < count; ++a) {
    if (alive[a]) result.push_back(std::move(clusters[a]));
  }
  return result;
}

}  // namespace sphys::tools::build
