#include "collision/tree_descent.h"

#include <algorithm>
#include <bit>
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

// One tree at its pose, cut to the levels in use, with its columns for the child-test kernel.
struct PosedTree {
  PosedTree(const SphereTree& t, const Transform& pose, int depth_used, float* world_x,
            float* world_y, float* world_z)
      : tree(t), rotation(pose.rotation.toRotationMatrix()), translation(pose.translation) {
    leaf_from = t.level_begin(t.last_level(depth_used));
    const SphereColumns spheres = t.columns();
    columns = {.x = spheres.x,
               .y = spheres.y,
               .z = spheres.z,
               .radius = spheres.radius,
               .subtree_radius = spheres.subtree_radius,
               .rotation = {},
               .translation = {translation.x(), translation.y(), translation.z()},
               .world_x = world_x,
               .world_y = world_y,
               .world_z = world_z};
    std::copy_n(rotation.data(), 9, columns.rotation);
  }

  // The nodes of the last used level act as leaves even when they have children.
  [[nodiscard]] bool acts_as_leaf(std::uint32_t node) const {
    return node >= leaf_from || tree.is_leaf(node);
  }
  // Bit i set where the node's child i acts as a leaf: all of them on the last used level (a
  // node's children share a level), else those without children.
  [[nodiscard]] std::uint32_t leaf_children(std::uint32_t node) const {
    return tree.first_child(node) >= leaf_from ? (1u << tree.child_count(node)) - 1u
                                               : tree.childless_children(node);
  }
  [[nodiscard]] Vec3 place(const Vec3& body_point) const {
    return rotation * body_point + translation;
  }

  const SphereTree& tree;
  Mat3 rotation;
  Vec3 translation;
  std::uint32_t leaf_from = 0;
  PosedColumns columns;
};

}  // namespace

DescentStats TreeDescent::descend(const SphereTree& tree_a, const Transform& pose_a,
                                  const SphereTree& tree_b, const Transform& pose_b,
                                  const DescentSettings& settings, std::vector<NodePair>& pairs) {
  DescentStats stats;
  if (tree_a.empty() || tree_b.empty()) return stats;

  // Grows only while ever larger trees come: in steady state nothing is allocated.
  const auto fit = [](WorldCenters& world, std::size_t size) {
    if (world.x.size() < size + kChildLanes) {
      for (std::vector<float>* column : {&world.x, &world.y, &world.z}) {
        column->resize(size + kChildLanes);
      }
    }
  };
  fit(world_a_, tree_a.size());
  fit(world_b_, tree_b.size());

  const PosedTree a(tree_a, pose_a, settings.depth_a, world_a_.x.data(), world_a_.y.data(),
                    world_a_.z.data());
  const PosedTree b(tree_b, pose_b, settings.depth_b, world_b_.x.data(), world_b_.y.data(),
                    world_b_.z.data());

  // Places the children of `node` (of `side`, with world centres `world`) and tests each against
  // node `other` of the other side, all in one kernel call (child_test.h): a pair of leaves found
  // is returned, any other overlapping pair waits on the stack, both in the children's order.
  const auto expand = [&](const PosedTree& side, std::uint32_t node, const PosedTree& other_side,
                          const WorldCenters& other_world, std::uint32_t other,
                          bool children_of_a) {
    const std::uint32_t first = side.tree.first_child(node);
    const std::uint32_t count = side.tree.child_count(node);
    const bool other_leaf = other_side.acts_as_leaf(other);
    const float other_radius = other_side.tree.sphere(other).radius;
    const OtherNode against{
        .center = {other_world.x[other], other_world.y[other], other_world.z[other]},
        .radius = other_radius,
        .bound = other_leaf ? other_radius : other_side.tree.subtree_radius(other),
        .margin = settings.margin,
        .slack = kBoundSlack};
    const ChildHits hits = test_children_(side.columns, first, against);
    const std::uint32_t leaves = side.leaf_children(node);
    std::uint32_t hit = ((leaves & (other_leaf ? hits.leaf_pair : hits.leaf_bound)) |
                         (~leaves & hits.subtree_bound)) &
                        ((1u << count) - 1u);
    stats.sphere_tests += count;
    for (; hit != 0; hit &= hit - 1) {
      const auto i = static_cast<std::uint32_t>(std::countr_zero(hit));
      const NodePair pair = children_of_a ? NodePair{first + i, other} : NodePair{other, first + i};
      if (other_leaf && ((leaves >> i) & 1u)) {
        pairs.push_back(pair);
        ++stats.leaf_pairs;
      } else {
        stack_.push_back(pair);
      }
    }
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
  world_a_.set(0, a.place(tree_a.root().center));
  world_b_.set(0, b.place(tree_b.root().center));
  ++stats.sphere_tests;
  {
    // The roots, as any pair: two leaves with their own spheres, else the subtree bounds.
    const float distance_squared = (world_b_.center(0) - world_a_.center(0)).squaredNorm();
    const bool leaf_a = a.acts_as_leaf(0);
    const bool leaf_b = b.acts_as_leaf(0);
    if (leaf_a && leaf_b) {
      const float reach = tree_a.root().radius + tree_b.root().radius + settings.margin;
      if (distance_squared <= reach * reach) {
        pairs.push_back({0, 0});
        ++stats.leaf_pairs;
      }
    } else {
      const float bound_a = leaf_a ? tree_a.root().radius : tree_a.subtree_radius(0);
      const float bound_b = leaf_b ? tree_b.root().radius : tree_b.subtree_radius(0);
      const float reach = (bound_a + bound_b + settings.margin) * kBoundSlack;
      if (distance_squared <= reach * reach) stack_.push_back({0, 0});
    }
  }

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
      expand(a, pair.node_a, b, world_b_, pair.node_b, true);
    } else {
      expand(b, pair.node_b, a, world_a_, pair.node_a, false);
    }
  }

  // Time-critical mode: the pairs still waiting are resolved at the level they reached, with the
  // nodes' own spheres, so that every pair returned is an overlapping pair of spheres.
  stats.cut_short_pairs = static_cast<std::uint32_t>(stack_.size());
  for (const NodePair& pair : stack_) {
    ++stats.sphere_tests;
    if (spheres_overlap(world_a_.center(pair.node_a),
                        tree_a.sphere(pair.node_a).radius + settings.margin,
                        world_b_.center(pair.node_b), tree_b.sphere(pair.node_b).radius)) {
      pairs.push_back(pair);
      ++stats.internal_pairs;
    }
  }
  stack_.clear();
  return stats;
}

}  // namespace sphys
