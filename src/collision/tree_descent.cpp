#include "collision/tree_descent.h"

#include <algorithm>
#include <chrono>
#include <limits>

#include "sphys/contact.h"

namespace sphys {
namespace {

// Subtree bounds are tested with this much relative slack on the sum of radii: world centres and
// subtree radii are rounded to float, and a bound must never cut away a leaf pair that overlaps by
// less than that rounding. Leaf spheres are tested exactly. unit: dimensionless
constexpr float kBoundSlack = 1.0f + 1e-5f;

constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();

// One tree at its pose, cut to the levels in use.
struct PosedTree {
  PosedTree(const SphereTree& t, const Transform& pose, int depth_used)
      : tree(t), rotation(pose.rotation.toRotationMatrix()), translation(pose.translation) {
    leaf_from = t.level_begin(t.last_level(depth_used));
  }

  // The nodes of the last used level act as leaves even when they have children.
  [[nodiscard]] bool acts_as_leaf(std::uint32_t node) const {
    return node >= leaf_from || tree.is_leaf(node);
  }
  [[nodiscard]] Vec3 place(const Vec3& body_point) const {
    return rotation * body_point + translation;
  }

  const SphereTree& tree;
  Mat3 rotation;
  Vec3 translation;
  std::uint32_t leaf_from = 0;
};

}  // namespace

DescentStats TreeDescent::descend(const SphereTree& tree_a, const Transform& pose_a,
                                  const SphereTree& tree_b, const Transform& pose_b,
                                  const DescentSettings& settings, std::vector<NodePair>& pairs) {
  DescentStats stats;
  if (tree_a.empty() || tree_b.empty()) return stats;

  if (++stamp_ == 0) {
    // The stamp wrapped: forget every old mark so that none can pass for the new one.
    std::ranges::fill(world_a_.children_placed, 0u);
    std::ranges::fill(world_b_.children_placed, 0u);
    stamp_ = 1;
  }
  // Grows only while ever larger trees come: in steady state nothing is allocated.
  const auto fit = [](WorldCenters& world, std::size_t size) {
    if (world.centers.size() < size) {
      world.centers.resize(size);
      world.children_placed.resize(size, 0u);
    }
  };
  fit(world_a_, tree_a.size());
  fit(world_b_, tree_b.size());

  const PosedTree a(tree_a, pose_a, settings.depth_a);
  const PosedTree b(tree_b, pose_b, settings.depth_b);
  Vec3* const world_a = world_a_.centers.data();
  Vec3* const world_b = world_b_.centers.data();
  const auto place_children = [this](const PosedTree& posed, WorldCenters& world,
                                     std::uint32_t node) {
    if (world.children_placed[node] == stamp_) return;
    world.children_placed[node] = stamp_;
    const std::uint32_t first = posed.tree.first_child(node);
    const std::uint32_t end = first + posed.tree.child_count(node);
    for (std::uint32_t c = first; c < end; ++c) {
      world.centers[c] = posed.place(posed.tree.sphere(c).center);
    }
  };

  // Tests one pair: two leaves with their own spheres (a leaf pair found), anything else with the
  // subtree bounds (the pair waits on the stack to be expanded). Inlined always: it is the
  // descent's inner loop, and whether the optimiser inlined it turned with changes elsewhere in
  // the program (out of line, the descent took 18% longer).
  const auto visit = [&](std::uint32_t na, std::uint32_t nb) __attribute__((always_inline)) {
    ++stats.sphere_tests;
    const float distance_squared = (world_b[nb] - world_a[na]).squaredNorm();
    const bool leaf_a = a.acts_as_leaf(na);
    const bool leaf_b = b.acts_as_leaf(nb);
    if (leaf_a && leaf_b) {
      const float reach = tree_a.sphere(na).radius + tree_b.sphere(nb).radius + settings.margin;
      if (distance_squared <= reach * reach) {
        pairs.push_back({na, nb});
        ++stats.leaf_pairs;
      }
      return;
    }
    const float bound_a = leaf_a ? tree_a.sphere(na).radius : tree_a.subtree_radius(na);
    const float bound_b = leaf_b ? tree_b.sphere(nb).radius : tree_b.subtree_radius(nb);
    const float reach = (bound_a + bound_b + settings.margin) * kBoundSlack;
    if (distance_squared <= reach * reach) stack_.push_back({na, nb});
  };

  // Budgets are checked only when the test count reaches next_check, so the exact mode and the
  // steps between clock readings pay one comparison per expansion.
  const std::uint64_t test_budget =
      settings.max_sphere_tests > 0 ? settings.max_sphere_tests : kNever;
  const bool timed = settings.max_microseconds > 0.0;
  const std::uint64_t clock_interval = std::max<std::uint32_t>(settings.clock_check_interval, 1);
  const auto start =
      timed ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
  const std::chrono::duration<double, std::micro> time_budget(settings.max_microseconds);
  std::uint64_t next_clock = timed ? clock_interval : kNever;
  std::uint64_t next_check = std::min(test_budget, next_clock);

  stack_.clear();
  world_a[0] = a.place(tree_a.root().center);
  world_b[0] = b.place(tree_b.root().center);
  visit(0, 0);

  // Paper §3.2: while two nodes' bounds overlap, the children of one meet the other, down to the
  // leaves. The node with the larger subtree bound is split, which keeps the two sides' spheres of
  // similar size and the number of tests small.
  while (!stack_.empty()) {
    if (stats.sphere_tests >= next_check) {
      bool out_of_time = false;
      if (timed && stats.sphere_tests >= next_clock) {
        out_of_time = std::chrono::steady_clock::now() - start >= time_budget;
        next_clock = stats.sphere_tests + clock_interval;
      }
      if (out_of_time || stats.sphere_tests >= test_budget) break;
      next_check = std::min(test_budget, next_clock);
    }
    const NodePair pair = stack_.back();
    stack_.pop_back();
    const bool split_a = !a.acts_as_leaf(pair.node_a) &&
                         (b.acts_as_leaf(pair.node_b) ||
                          tree_a.subtree_radius(pair.node_a) >= tree_b.subtree_radius(pair.node_b));
    if (split_a) {
      place_children(a, world_a_, pair.node_a);
      const std::uint32_t first = tree_a.first_child(pair.node_a);
      const std::uint32_t end = first + tree_a.child_count(pair.node_a);
      for (std::uint32_t c = first; c < end; ++c) visit(c, pair.node_b);
    } else {
      place_children(b, world_b_, pair.node_b);
      const std::uint32_t first = tree_b.first_child(pair.node_b);
      const std::uint32_t end = first + tree_b.child_count(pair.node_b);
      for (std::uint32_t c = first; c < end; ++c) visit(pair.node_a, c);
    }
  }

  // Time-critical mode: the pairs still waiting are resolved at the level they reached, with the
  // nodes' own spheres, so that every pair returned is an overlapping pair of spheres.
  stats.cut_short_pairs = static_cast<std::uint32_t>(stack_.size());
  for (const NodePair& pair : stack_) {
    ++stats.sphere_tests;
    if (spheres_overlap(world_a[pair.node_a], tree_a.sphere(pair.node_a).radius + settings.margin,
                        world_b[pair.node_b], tree_b.sphere(pair.node_b).radius)) {
      pairs.push_back(pair);
      ++stats.internal_pairs;
    }
  }
  stack_.clear();
  return stats;
}

}  // namespace sphys
