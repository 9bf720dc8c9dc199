// Distance queries: the smallest gap between the leaf spheres of two bodies (or of a body and a
// point), best first: node pairs wait in a heap ordered by a lower bound of the gap of any leaf
// pair below them, so the first leaf pair to come out of the heap is the closest one. A budget
// stops the descent early; the heap's smallest bound is then a lower bound of the answer (the
// paper's time-critical descent, §3.2, turned to distances).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "query/body_filter.h"
#include "query/checked_input.h"
#include "query/snapshot.h"
#include "sphys/error.h"
#include "sphys/world_query.h"

namespace sphys {
namespace {

using query_detail::LeafRange;

// Subtree bounds are grown by this much relative slack: world centres and subtree radii are
// rounded to float, and a bound must never exceed the gap of a leaf pair below it by that
// rounding. Leaf spheres are measured exactly. unit: dimensionless
constexpr float kBoundSlack = 1.0f + 1e-5f;

// Sphere tests between two readings of the clock under a time budget. unit: sphere tests
constexpr std::uint64_t kClockInterval = 32;

// One side of a distance query: a posed tree, or a point (one leaf of radius 0).
class Side {
 public:
  Side(const SphereTree& tree, const Transform& pose, int depth)
      : tree_(&tree),
        rotation_(pose.rotation.toRotationMatrix()),
        translation_(pose.translation),
        range_(query_detail::leaf_range(tree, depth)) {}
  explicit Side(const Vec3& point) : translation_(point) {}

  [[nodiscard]] bool leaf(std::uint32_t node) const {
    return tree_ == nullptr || query_detail::acts_as_leaf(*tree_, range_, node);
  }
  [[nodiscard]] Vec3 centre(std::uint32_t node) const {
    return tree_ == nullptr ? translation_
                            : Vec3(rotation_ * tree_->sphere(node).center + translation_);
  }
  [[nodiscard]] float radius(std::uint32_t node) const {
    return tree_ == nullptr ? 0.0f : tree_->sphere(node).radius;
  }
  // Holds every leaf sphere in use below the node. unit: m
  [[nodiscard]] float bound(std::uint32_t node) const {
    return leaf(node) ? radius(node) : tree_->subtree_radius(node);
  }
  [[nodiscard]] std::uint32_t first_child(std::uint32_t node) const {
    return tree_->first_child(node);
  }
  [[nodiscard]] std::uint32_t child_count(std::uint32_t node) const {
    return tree_->child_count(node);
  }

 private:
  const SphereTree* tree_ = nullptr;
  Mat3 rotation_ = Mat3::Identity();
  Vec3 translation_ = Vec3::Zero();
  LeafRange range_;
};

struct Waiting {
  float bound = 0.0f;  // no leaf pair below is closer than this. unit: m
  std::uint32_t a = 0;
  std::uint32_t b = 0;
  bool leaves = false;  // both nodes act as leaves: `bound` is their gap
};

DistanceResult closest(const Side& a, const Side& b, const DistanceBudget& budget) {
  DistanceResult result;
  const auto start = std::chrono::steady_clock::now();
  const bool timed = budget.max_microseconds > 0.0;
  const std::chrono::duration<double, std::micro> time_budget(budget.max_microseconds);
  const auto waiting = [&](std::uint32_t na, std::uint32_t nb) {
    ++result.sphere_tests;
    const float gap = (a.centre(na) - b.centre(nb)).norm();
    const bool leaves = a.leaf(na) && b.leaf(nb);
    const float reach =
        leaves ? a.radius(na) + b.radius(nb) : (a.bound(na) + b.bound(nb)) * kBoundSlack;
    return Waiting{gap - reach, na, nb, leaves};
  };
  const auto later = [](const Waiting& x, const Waiting& y) {
    return x.bound > y.bound || (x.bound == y.bound && x.leaves < y.leaves);
  };
  std::vector<Waiting> heap{waiting(0, 0)};
  std::uint64_t next_clock = kClockInterval;
  while (!heap.front().leaves) {
    bool out_of_time = false;
    if (timed && result.sphere_tests >= next_clock) {
      out_of_time = std::chrono::steady_clock::now() - start >= time_budget;
      next_clock = result.sphere_tests + kClockInterval;
    }
    if (out_of_time ||
        (budget.max_sphere_tests > 0 && result.sphere_tests >= budget.max_sphere_tests)) {
      result.exact = false;
      break;
    }
    std::ranges::pop_heap(heap, later);
    const Waiting pair = heap.back();
    heap.pop_back();
    // The side with the larger bound is split, as in the narrow phase's descent.
    const bool split_a = !a.leaf(pair.a) && (b.leaf(pair.b) || a.bound(pair.a) >= b.bound(pair.b));
    const Side& split = split_a ? a : b;
    const std::uint32_t node = split_a ? pair.a : pair.b;
    const std::uint32_t first = split.first_child(node);
    for (std::uint32_t c = first; c < first + split.child_count(node); ++c) {
      heap.push_back(split_a ? waiting(c, pair.b) : waiting(pair.a, c));
      std::ranges::push_heap(heap, later);
    }
  }
  const Waiting& best = heap.front();
  const Vec3 ca = a.centre(best.a);
  const Vec3 cb = b.centre(best.b);
  const Vec3 offset = cb - ca;
  const float length = offset.norm();
  // Coincident centres have no direction between them; any unit vector serves.
  const Vec3 unit = length > 0.0f ? Vec3(offset / length) : Vec3(Vec3::UnitY());
  result.distance = best.bound;
  result.leaf_a = best.a;
  result.leaf_b = best.b;
  result.point_a = ca + a.radius(best.a) * unit;
  result.point_b = cb - b.radius(best.b) * unit;
  return result;
}

void check_budget(const DistanceBudget& budget) {
  if (!(budget.max_microseconds >= 0.0) || !std::isfinite(budget.max_microseconds)) {
    throw Error("budget.max_microseconds: must be finite and >= 0 (µs)");
  }
}

}  // namespace

DistanceResult WorldQuery::distance(BodyId a, BodyId b, const DistanceBudget& budget) const {
  const std::uint32_t slot_a = query_detail::checked_slot(*snapshot_, a, "body_a");
  const std::uint32_t slot_b = query_detail::checked_slot(*snapshot_, b, "body_b");
  if (slot_a == slot_b) throw Error("body_b: the same body as body_a");
  check_budget(budget);
  const int depth = snapshot_->tree_depth;
  return closest(Side(*snapshot_->trees[slot_a], snapshot_->poses[slot_a], depth),
                 Side(*snapshot_->trees[slot_b], snapshot_->poses[slot_b], depth), budget);
}

DistanceResult WorldQuery::distance(BodyId body, const Vec3& point,
                                    const DistanceBudget& budget) const {
  const std::uint32_t slot = query_detail::checked_slot(*snapshot_, body, "body");
  query_detail::check_finite(point, "point");
  check_budget(budget);
  return closest(Side(*snapshot_->trees[slot], snapshot_->poses[slot], snapshot_->tree_depth),
                 Side(point), budget);
}

}  // namespace sphys
