// The outside-volume pass of the Tight method (ours, not the toolkit's): the reductions minimise
// how far their balls poke out; this pass then trades that for the volume the union of a node's
// balls adds outside the mesh, the figure users compare trees by, without letting any sample go
// uncovered or any ball poke out farther than the reduction's did.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "reducers_impl.h"

namespace sphys::tools::build {
namespace {

// At most this many rounds over the balls; the pass ends sooner once a round changes nothing.
constexpr int kMaxRounds = 20;
// Pattern search: a ball's first step is this fraction of its radius; the search ends when the
// step falls below this fraction of the lattice spacing.
constexpr double kFirstStep = 0.25;
constexpr double kLastStep = 0.25;
// A ball's candidates are counted against the free lattice points within this many radii of
// it (gathered again when a candidate may reach past them), and in chunks of kCountChunk points
// between checks against the best so far.
constexpr double kGatherReach = 1.6;
constexpr std::size_t kCountChunk = 512;
// Directions at which a ball's boundary is checked against the protrusion limit.
constexpr std::size_t kBoundaryDirections = 96;
// 2-means iterations when a ball is split to give a ball that covers nothing of its own work.
constexpr int kSplitIterations = 10;

// What a ball costs: first the points of its boundary (at the checked directions) farther out
// than the limit, a constraint; then the outside lattice points no other ball holds.
struct Cost {
  std::size_t beyond = 0;
  std::size_t outside = 0;

  [[nodiscard]] bool operator<(const Cost& other) const {
    return beyond != other.beyond ? beyond < other.beyond : outside < other.outside;
  }
};

// The 26 unit directions to the neighbours of a cube in a cubic lattice.
std::array<Vec3d, 26> search_directions() {
  std::array<Vec3d, 26> directions;
  std::size_t k = 0;
  for (int x = -1; x <= 1; ++x) {
    for (int y = -1; y <= 1; ++y) {
      for (int z = -1; z <= 1; ++z) {
        if (x != 0 || y != 0 || z != 0) directions[k++] = Vec3d(x, y, z).normalized();
      }
    }
  }
  return directions;
}

// The lattice points a ball's candidates are counted against: outside the mesh, held by no other
// ball, within a ball around the candidates. Kept as flat arrays so that each count is one loop
// the compiler vectorises.
struct FreePoints {
  Ball reach;
  std::vector<float> x;
  std::vector<float> y;
  std::vector<float> z;

  void clear(const Ball& around) {
    reach = around;
    x.clear();
    y.clear();
    z.clear();
  }
  void add(const Vec3d& p) {
    x.push_back(static_cast<float>(p.x()));
    y.push_back(static_cast<float>(p.y()));
    z.push_back(static_cast<float>(p.z()));
  }
  [[nodiscard]] bool reaches(const Ball& ball) const {
    return (ball.center - reach.center).norm() + ball.radius <= reach.radius;
  }

  // How many lie in the ball; nullopt once the count reaches `limit`.
  [[nodiscard]] std::optional<std::size_t> count_inside(const Ball& ball, std::size_t limit) const {
    const auto cx = static_cast<float>(ball.center.x());
    const auto cy = static_cast<float>(ball.center.y());
    const auto cz = static_cast<float>(ball.center.z());
    const auto r2 = static_cast<float>(ball.radius * ball.radius);
    std::size_t count = 0;
    for (std::size_t begin = 0; begin < x.size(); begin += kCountChunk) {
      const std::size_t end = std::min(x.size(), begin + kCountChunk);
      std::uint32_t inside = 0;
      for (std::size_t i = begin; i < end; ++i) {
        const float dx = x[i] - cx;
        const float dy = y[i] - cy;
        const float dz = z[i] - cz;
        inside += dx * dx + dy * dy + dz * dz <= r2 ? 1U : 0U;
      }
      count += inside;
      if (count >= limit) return std::nullopt;
    }
    return count;
  }
};

// Coordinate descent over the balls of one node. Each ball in turn is asked to cover only the
// points no other ball holds; its centre moves by pattern search to where the smallest ball
// around those points adds the least outside volume to the others'. Balls left with nothing of
// their own are re-placed by splitting the costliest ball.
class VolumeDescent {
 public:
  VolumeDescent(const ExteriorLattice& lattice, std::span<const Vec3d> directions,
                std::vector<Vec3d> points, std::vector<Ball> balls, double limit)
      : lattice_(&lattice),
        directions_(directions),
        points_(std::move(points)),
        balls_(std::move(balls)),
        limit_(limit),
        holders_(lattice.size(), 0),
        covered_(points_.size(), 0) {
    for (const Ball& ball : balls_) add(ball, 1);
  }

  void run() {
    std::size_t splits_left = 2 * balls_.size();
    std::vector<std::size_t> idle;
    for (int round = 0; round < kMaxRounds; ++round) {
      bool improved = false;
      for (const std::size_t i : idle) {
        if (splits_left > 0 && split_costliest_into(i)) {
          --splits_left;
          improved = true;
        }
      }
      idle.clear();
      for (std::size_t i = 0; i < balls_.size(); ++i) {
        if (balls_[i].radius == 0.0) continue;
        add(balls_[i], -1);
        const std::vector<Vec3d> own = uncovered();
        if (own.empty()) {
          balls_[i].radius = 0.0;
          idle.push_back(i);
          improved = true;
          continue;
        }
        improved |= search(balls_[i], own);
        add(balls_[i], 1);
      }
      if (!improved) break;
    }
  }

  [[nodiscard]] Cost total() const {
    Cost cost;
    for (std::size_t i = 0; i < holders_.size(); ++i) {
      if (holders_[i] > 0) ++cost.outside;
    }
    for (const Ball& ball : balls_) cost.beyond += beyond(ball);
    return cost;
  }

  [[nodiscard]] const std::vector<Ball>& balls() const { return balls_; }

 private:
  // How many of the ball's boundary directions lie farther out than the limit.
  [[nodiscard]] std::size_t beyond(const Ball& ball) const {
    std::size_t count = 0;
    for (const Vec3d& u : directions_) {
      if (lattice_->distance_at(ball.center + ball.radius * u) > limit_) ++count;
    }
    return count;
  }

  // The outside lattice points no other ball holds, around the ball's neighbourhood: what its
  // candidates are counted against, kept as a flat list so that each count is one tight loop.
  void gather_free(const Ball& ball) {
    free_.clear({ball.center, kGatherReach * ball.radius + lattice_->spacing()});
    lattice_->for_each_outside_at(free_.reach, [&](std::size_t index, const Vec3d& p) {
      if (holders_[index] == 0) free_.add(p);
    });
  }

  void add(const Ball& ball, int sign) {
    lattice_->for_each_outside(ball, [&](std::size_t index, double) {
      holders_[index] = static_cast<std::uint16_t>(holders_[index] + sign);
    });
    for (std::size_t p = 0; p < points_.size(); ++p) {
      if (ball.contains(points_[p])) {
        covered_[p] = static_cast<std::uint16_t>(covered_[p] + sign);
      }
    }
  }

  [[nodiscard]] std::vector<Vec3d> uncovered() const {
    std::vector<Vec3d> own;
    for (std::size_t p = 0; p < points_.size(); ++p) {
      if (covered_[p] == 0) own.push_back(points_[p]);
    }
    return own;
  }

  // The smallest ball centred at `center` around `own`, and what it costs beside the others;
  // nullopt as soon as the cost is known to be no lower than `bound`.
  [[nodiscard]] std::optional<std::pair<Ball, Cost>> fit(const Vec3d& center,
                                                         const std::vector<Vec3d>& own,
                                                         const Cost& bound) const {
    double r2 = 0.0;
    for (const Vec3d& p : own) r2 = std::max(r2, (p - center).squaredNorm());
    const Ball ball{center, padded_radius(std::sqrt(r2))};
    Cost cost;
    cost.beyond = beyond(ball);
    if (cost.beyond > bound.beyond) return std::nullopt;
    const std::size_t limit =
        cost.beyond < bound.beyond ? std::numeric_limits<std::size_t>::max() : bound.outside;
    const auto count = free_.count_inside(ball, limit);
    if (!count) return std::nullopt;
    cost.outside = *count;
    return std::pair{ball, cost};
  }

  // Pattern search for the ball's centre; returns whether it found a better one.
  bool search(Ball& ball, const std::vector<Vec3d>& own) {
    static const std::array<Vec3d, 26> kDirections = search_directions();
    constexpr std::size_t kAny = std::numeric_limits<std::size_t>::max();
    gather_free(ball);
    auto [best, best_cost] = *fit(ball.center, own, {kAny, kAny});
    bool moved = false;
    for (double step = kFirstStep * best.radius; step > kLastStep * lattice_->spacing();) {
      bool found = false;
      for (const Vec3d& direction : kDirections) {
        const Vec3d center = best.center + step * direction;
        if (!free_.reaches({center, best.radius + step})) gather_free({center, best.radius});
        const auto candidate = fit(center, own, best_cost);
        if (candidate && candidate->second < best_cost) {
          std::tie(best, best_cost) = *candidate;
          found = true;
          moved = true;
          break;
        }
      }
      if (!found) step *= 0.5;
    }
    ball = best;
    return moved;
  }

  // Gives the idle ball half of the work of the ball that adds the most outside volume of its
  // own: that ball's own points split in two by 2-means, each half to the smallest ball around
  // it. Returns false when no ball has two points of its own to split.
  bool split_costliest_into(std::size_t idle) {
    std::size_t costliest = balls_.size();
    Cost highest;
    for (std::size_t j = 0; j < balls_.size(); ++j) {
      if (balls_[j].radius == 0.0) continue;
      add(balls_[j], -1);
      Cost own_cost;
      lattice_->for_each_outside(balls_[j], [&](std::size_t index, double) {
        if (holders_[index] == 0) ++own_cost.outside;
      });
      add(balls_[j], 1);
      if (costliest == balls_.size() || highest < own_cost) {
        costliest = j;
        highest = own_cost;
      }
    }
    if (costliest == balls_.size()) return false;
    add(balls_[costliest], -1);
    const std::vector<Vec3d> own = uncovered();
    if (own.size() < 2) {
      add(balls_[costliest], 1);
      return false;
    }
    // Seeds: the point farthest from the first, and the point farthest from that one.
    const auto farthest = [&](const Vec3d& from) {
      std::size_t best = 0;
      for (std::size_t p = 1; p < own.size(); ++p) {
        if ((own[p] - from).squaredNorm() > (own[best] - from).squaredNorm()) best = p;
      }
      return own[best];
    };
    Vec3d seed_b = farthest(own.front());
    Vec3d seed_a = farthest(seed_b);
    std::vector<Vec3d> half_a;
    std::vector<Vec3d> half_b;
    for (int iteration = 0; iteration < kSplitIterations; ++iteration) {
      half_a.clear();
      half_b.clear();
      for (const Vec3d& p : own) {
        ((p - seed_a).squaredNorm() <= (p - seed_b).squaredNorm() ? half_a : half_b).push_back(p);
      }
      if (half_a.empty() || half_b.empty()) break;
      seed_a = mean(half_a);
      seed_b = mean(half_b);
    }
    if (half_a.empty() || half_b.empty()) {
      add(balls_[costliest], 1);
      return false;
    }
    for (auto [index, half] : {std::pair{costliest, &half_a}, std::pair{idle, &half_b}}) {
      Ball ball = min_enclosing_ball(*half);
      ball.radius = padded_radius(ball.radius);
      balls_[index] = ball;
      add(ball, 1);
    }
    return true;
  }

  static Vec3d mean(const std::vector<Vec3d>& points) {
    Vec3d sum = Vec3d::Zero();
    for (const Vec3d& p : points) sum += p;
    return sum / static_cast<double>(points.size());
  }

  const ExteriorLattice* lattice_;
  std::span<const Vec3d> directions_;  // where a ball's boundary is checked against the limit
  std::vector<Vec3d> points_;
  std::vector<Ball> balls_;
  double limit_;                        // unit: m
  std::vector<std::uint16_t> holders_;  // balls holding each lattice point (outside ones)
  std::vector<std::uint16_t> covered_;  // balls holding each point
  FreePoints free_;
};

}  // namespace

Cover shrink_outside_volume(const BuildContext& context, const ExteriorLattice& lattice,
                            std::span<const std::uint32_t> samples, Cover start) {
  if (start.balls.size() < 2) return start;
  std::vector<Vec3d> points;
  points.reserve(samples.size());
  for (const std::uint32_t s : samples) points.push_back(context.samples.points[s]);
  // No ball may poke out farther than the start's did.
  static const std::vector<Vec3d> kBoundary = evenly_spread_directions(kBoundaryDirections);
  double limit = -std::numeric_limits<double>::infinity();
  for (const Ball& ball : start.balls) {
    limit = std::max(limit, lattice.protrusion(ball, kBoundary));
  }
  // Nor beyond the lattice, where the pass would not see the volume a ball adds.
  limit = std::min(limit, lattice.margin() - lattice.spacing());
  VolumeDescent descent(lattice, kBoundary, points, start.balls, limit);
  const Cost start_cost = descent.total();
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
