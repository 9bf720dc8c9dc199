// Burst reduction (Bradshaw & O'Sullivan 2004, §4.3): spheres are removed ("burst") one at a
// time and their points absorbed by neighbouring spheres, which grow to take them in. The
// sphere burst next is the one whose removal leaves the least error behind.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

#include "reducers_impl.h"

namespace sphys::tools::build {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Spheres that overlap nothing get this many of their nearest as neighbours.
constexpr std::size_t kBurstNeighbours = 8;

struct BurstCandidate {
  double cost;
  std::uint32_t cluster;
  std::uint32_t stamp;

  bool operator<(const BurstCandidate& other) const {
    if (cost != other.cost) return cost > other.cost;
    return cluster > other.cluster;
  }
};

// Where a burst sphere's points go: each to the neighbour that takes it in with least error
// (centres stay, radii grow).
struct Burst {
  double cost = kInfinity;  // the worst error among the spheres that grew
  std::vector<std::pair<std::uint32_t, std::uint32_t>> moves;  // (point, new owner)
};

class Burster {
 public:
  Burster(std::vector<Cluster> clusters, const Region& region)
      : clusters_(std::move(clusters)),
        region_(region),
        alive_(clusters_.size(), true),
        stamp_(clusters_.size(), 0),
        dirty_(clusters_.size(), false),
        neighbours_(clusters_.size()) {
    const auto count = static_cast<std::uint32_t>(clusters_.size());
    for (std::uint32_t a = 0; a < count; ++a) {
      for (std::uint32_t b = a + 1; b < count; ++b) {
        if (overlap(a, b)) {
          neighbours_[a].push_back(b);
          neighbours_[b].push_back(a);
        }
      }
    }
  }

  std::vector<Cluster> reduce(int max_balls) {
    auto alive_count = static_cast<int>(clusters_.size());
    for (std::uint32_t a = 0; a < clusters_.size(); ++a) push(a);
    while (alive_count > max_balls) {
      // Void entries go first, so that only a live sphere with no neighbours connects them.
      while (!queue_.empty() && !valid(queue_.top())) queue_.pop();
      if (queue_.empty() || queue_.top().cost == kInfinity) connect_all();
      const BurstCandidate top = queue_.top();
      queue_.pop();
      if (!valid(top)) continue;
      // Lazy greedy: a sphere whose neighbours changed is costed again only when it comes up.
      // Neighbours only grow, so its cost only rises, and if it is still the cheapest it goes.
      if (dirty_[top.cluster]) {
        dirty_[top.cluster] = false;
        push(top.cluster);
        continue;
      }
      apply(top.cluster, plan(top.cluster));
      --alive_count;
    }
    std::vector<Cluster> result;
    for (std::uint32_t a = 0; a < clusters_.size(); ++a) {
      if (alive_[a]) result.push_back(std::move(clusters_[a]));
    }
    return result;
  }

 private:
  bool overlap(std::uint32_t a, std::uint32_t b) const {
    const double reach =
        clusters_[a].ball.radius + clusters_[b].ball.radius + 1e-3 * region_.radius;
    return (clusters_[a].ball.center - clusters_[b].ball.center).squaredNorm() <= reach * reach;
  }

  bool valid(const BurstCandidate& candidate) const {
    return alive_[candidate.cluster] && stamp_[candidate.cluster] == candidate.stamp;
  }

  Burst plan(std::uint32_t s) const {
    Burst burst;
    if (neighbours_[s].empty()) return burst;
    std::vector<double> grown;
    grown.reserve(neighbours_[s].size());
    for (const std::uint32_t n : neighbours_[s]) grown.push_back(clusters_[n].ball.radius);
    for (const std::uint32_t m : clusters_[s].members) {
      const Vec3d& p = region_.points[m];
      std::size_t best = 0;
      double best_error = kInfinity;
      for (std::size_t k = 0; k < neighbours_[s].size(); ++k) {
        const Cluster& n = clusters_[neighbours_[s][k]];
        const double error = std::max(grown[k], (p - n.ball.center).norm()) + n.offset;
        if (error < best_error) {
          best_error = error;
          best = k;
        }
      }
      grown[best] = best_error - clusters_[neighbours_[s][best]].offset;
      burst.moves.emplace_back(m, neighbours_[s][best]);
    }
    burst.cost = -kInfinity;
    for (const auto& [m, owner] : burst.moves) {
      const Cluster& c = clusters_[owner];
      burst.cost = std::max(burst.cost, (region_.points[m] - c.ball.center).norm() + c.offset);
      burst.cost = std::max(burst.cost, c.error());
    }
    return burst;
  }

  void push(std::uint32_t a) { queue_.push({plan(a).cost, a, stamp_[a]}); }

  void apply(std::uint32_t s, const Burst& burst) {
    alive_[s] = false;
    std::vector<std::uint32_t> grown;
    for (const auto& [m, owner] : burst.moves) {
      Cluster& c = clusters_[owner];
      c.members.push_back(m);
      c.ball.radius = std::max(c.ball.radius, (region_.points[m] - c.ball.center).norm());
      grown.push_back(owner);
    }
    std::sort(grown.begin(), grown.end());
    grown.erase(std::unique(grown.begin(), grown.end()), grown.end());
    // A sphere that grew may now overlap more spheres; the burst sphere's neighbours lose it.
    std::vector<std::uint32_t> stale = neighbours_[s];
    for (const std::uint32_t n : neighbours_[s]) std::erase(neighbours_[n], s);
    neighbours_[s].clear();
    for (const std::uint32_t g : grown) {
      for (std::uint32_t u = 0; u < clusters_.size(); ++u) {
        if (u == g || !alive_[u] || !overlap(g, u)) continue;
        if (std::find(neighbours_[g].begin(), neighbours_[g].end(), u) == neighbours_[g].end()) {
          neighbours_[g].push_back(u);
          neighbours_[u].push_back(g);
        }
      }
      stale.insert(stale.end(), neighbours_[g].begin(), neighbours_[g].end());
    }
    // Every sphere whose burst would send points to a grown sphere has a new cost.
    std::sort(stale.begin(), stale.end());
    stale.erase(std::unique(stale.begin(), stale.end()), stale.end());
    for (const std::uint32_t u : stale) dirty_[u] = true;
  }

  // Left with spheres that touch nothing (a disconnected mesh, a thin part): each neighbours its
  // nearest ones now too. Making every pair neighbours would cost the cube of the sphere count.
  void connect_all() {
    const std::vector<std::vector<std::uint32_t>> nearest =
        nearest_clusters(clusters_, alive_, kBurstNeighbours);
    for (std::uint32_t a = 0; a < clusters_.size(); ++a) {
      std::vector<std::uint32_t>& list = neighbours_[a];
      list.insert(list.end(), nearest[a].begin(), nearest[a].end());
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
    }
    for (std::uint32_t a = 0; a < clusters_.size(); ++a) {
      if (!alive_[a]) continue;
      ++stamp_[a];
      dirty_[a] = false;
      push(a);
    }
  }

  std::vector<Cluster> clusters_;
  const Region& region_;
  std::vector<bool> alive_;
  std::vector<std::uint32_t> stamp_;  // entries of a sphere pushed before the last reset are void
  std::vector<bool> dirty_;
  std::vector<std::vector<std::uint32_t>> neighbours_;
  std::priority_queue<BurstCandidate> queue_;
};

}  // namespace

std::vector<Cluster> burst_clusters(std::vector<Cluster> clusters, const Region& region,
                                    int max_balls) {
  std::erase_if(clusters, [](const Cluster& c) { return c.members.empty(); });
  if (static_cast<int>(clusters.size()) <= max_balls) return clusters;
  return Burster(std::move(clusters), region).reduce(max_balls);
}

}  // namespace sphys::tools::build
