#include "volume_descent.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>

namespace sphys::tools::build {
namespace {

// Pattern search: a ball's first step is this fraction of its radius.
constexpr double kFirstStep = 0.25;
// A ball's candidates are counted against the free lattice points within this many radii of
// it (gathered again when a candidate may reach past them), and in chunks of kCountChunk points
// between checks against the best so far.
constexpr double kGatherReach = 1.6;
constexpr std::size_t kCountChunk = 512;
// 2-means iterations when a ball is split to give a ball that covers nothing of its own work.
constexpr int kSplitIterations = 10;

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

Vec3d mean(const std::vector<Vec3d>& points) {
  Vec3d sum = Vec3d::Zero();
  for (const Vec3d& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

}  // namespace

void FreePoints::clear(const Ball& around) {
  reach = around;
  x.clear();
  y.clear();
  z.clear();
}

void FreePoints::add(const Vec3d& p) {
  x.push_back(static_cast<float>(p.x()));
  y.push_back(static_cast<float>(p.y()));
  z.push_back(static_cast<float>(p.z()));
}

bool FreePoints::reaches(const Ball& ball) const {
  return (ball.center - reach.center).norm() + ball.radius <= reach.radius;
}

std::optional<std::size_t> FreePoints::count_inside(const Ball& ball, std::size_t limit) const {
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

VolumeDescent::VolumeDescent(const ExteriorLattice& lattice, std::span<const Vec3d> directions,
                             std::vector<Vec3d> points, std::vector<Ball> balls, double limit,
                             DescentEffort effort)
    : lattice_(&lattice),
      directions_(directions),
      points_(std::move(points)),
      balls_(std::move(balls)),
      limit_(limit),
      effort_(effort),
      holders_(lattice.size(), 0),
      covered_(points_.size(), 0) {
  for (const Ball& ball : balls_) add(ball, 1);
}

void VolumeDescent::run() {
  std::size_t splits_left = 2 * balls_.size();
  std::vector<std::size_t> idle;
  for (int round = 0; round < effort_.max_rounds; ++round) {
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

void VolumeDescent::grow_to_cover() {
  std::vector<Ball> grown = balls_;
  for (std::size_t p = 0; p < points_.size(); ++p) {
    if (covered_[p] != 0) continue;
    std::size_t nearest = balls_.size();
    double least_gap = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < balls_.size(); ++b) {
      if (balls_[b].radius == 0.0) continue;
      const double gap = (points_[p] - grown[b].center).norm() - grown[b].radius;
      if (gap < least_gap) {
        least_gap = gap;
        nearest = b;
      }
    }
    if (nearest == balls_.size()) return;  // no ball to grow
    if (least_gap > 0.0) {
      grown[nearest].radius = padded_radius((points_[p] - grown[nearest].center).norm());
    }
  }
  for (std::size_t b = 0; b < balls_.size(); ++b) {
    if (grown[b].radius == balls_[b].radius) continue;
    add(balls_[b], -1);
    balls_[b] = grown[b];
    add(balls_[b], 1);
  }
}

DescentCost VolumeDescent::total() const {
  DescentCost cost;
  for (const std::uint16_t holders : holders_) {
    if (holders > 0) ++cost.outside;
  }
  for (const Ball& ball : balls_) cost.beyond += beyond(ball);
  return cost;
}

std::size_t VolumeDescent::beyond(const Ball& ball) const {
  std::size_t count = 0;
  for (const Vec3d& u : directions_) {
    if (lattice_->distance_at(ball.center + ball.radius * u) > limit_) ++count;
  }
  return count;
}

void VolumeDescent::gather_free(const Ball& ball) {
  free_.clear({ball.center, kGatherReach * ball.radius + lattice_->spacing()});
  lattice_->for_each_outside_at(free_.reach, [&](std::size_t index, const Vec3d& p) {
    if (holders_[index] == 0) free_.add(p);
  });
}

void VolumeDescent::add(const Ball& ball, int sign) {
  lattice_->for_each_outside(ball, [&](std::size_t index, double) {
    holders_[index] = static_cast<std::uint16_t>(holders_[index] + sign);
  });
  for (std::size_t p = 0; p < points_.size(); ++p) {
    if (ball.contains(points_[p])) {
      covered_[p] = static_cast<std::uint16_t>(covered_[p] + sign);
    }
  }
}

std::vector<Vec3d> VolumeDescent::uncovered() const {
  std::vector<Vec3d> own;
  for (std::size_t p = 0; p < points_.size(); ++p) {
    if (covered_[p] == 0) own.push_back(points_[p]);
  }
  return own;
}

// The smallest ball centred at `center` around `own`, and what it costs beside the others;
// nullopt as soon as the cost is known to be no lower than `bound`.
std::optional<std::pair<Ball, DescentCost>> VolumeDescent::fit(const Vec3d& center,
                                                               const std::vector<Vec3d>& own,
                                                               const DescentCost& bound) const {
  double r2 = 0.0;
  for (const Vec3d& p : own) r2 = std::max(r2, (p - center).squaredNorm());
  const Ball ball{center, padded_radius(std::sqrt(r2))};
  DescentCost cost;
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
bool VolumeDescent::search(Ball& ball, const std::vector<Vec3d>& own) {
  static const std::array<Vec3d, 26> kDirections = search_directions();
  constexpr std::size_t kAny = std::numeric_limits<std::size_t>::max();
  gather_free(ball);
  auto [best, best_cost] = *fit(ball.center, own, {kAny, kAny});
  bool moved = false;
  for (double step = kFirstStep * best.radius; step > effort_.last_step * lattice_->spacing();) {
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
bool VolumeDescent::split_costliest_into(std::size_t idle) {
  std::size_t costliest = balls_.size();
  DescentCost highest;
  for (std::size_t j = 0; j < balls_.size(); ++j) {
    if (balls_[j].radius == 0.0) continue;
    add(balls_[j], -1);
    DescentCost own_cost;
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

}  // namespace sphys::tools::build
