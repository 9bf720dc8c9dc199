#include "collision/tree_descent.h"

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/contact.h"
#include "sphys/error.h"
#include "sphys/tools/build_tree.h"
#include "sphys/tools/primitives.h"

namespace sphys {
namespace {

using Rng = std::mt19937;

float uniform(Rng& rng, float lo, float hi) {
  return std::uniform_real_distribution<float>(lo, hi)(rng);
}

Transform random_pose(Rng& rng, float spread) {
  std::normal_distribution<float> normal;
  Transform pose;
  pose.rotation = Quat(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
  pose.translation = Vec3(uniform(rng, -spread, spread), uniform(rng, -spread, spread),
                          uniform(rng, -spread, spread));
  return pose;
}

// World centre exactly as the descent computes it, so that the oracle rounds the same way.
Vec3 place(const Transform& pose, const Vec3& body_point) {
  return pose.rotation.toRotationMatrix() * body_point + pose.translation;
}

Sphere world_sphere(const SphereTree& tree, const Transform& pose, std::uint32_t node) {
  return {place(pose, tree.sphere(node).center), tree.sphere(node).radius};
}

bool overlap(const Sphere& a, const Sphere& b) {
  return spheres_overlap(a.center, a.radius, b.center, b.radius);
}

// The oracle: every leaf of one (truncated) tree against every leaf of the other.
std::vector<NodePair> brute_force(const SphereTree& tree_a, const Transform& pose_a, int depth_a,
                                  const SphereTree& tree_b, const Transform& pose_b, int depth_b) {
  const auto leaves = [](const SphereTree& tree, int depth) {
    return depth > 0 ? tree.truncated(depth).leaves() : tree.leaves();
  };
  std::vector<NodePair> out;
  for (std::uint32_t na : leaves(tree_a, depth_a)) {
    for (std::uint32_t nb : leaves(tree_b, depth_b)) {
      if (overlap(world_sphere(tree_a, pose_a, na), world_sphere(tree_b, pose_b, nb))) {
        out.push_back({na, nb});
      }
    }
  }
  return out;
}

std::vector<NodePair> sorted(std::vector<NodePair> pairs) {
  std::ranges::sort(pairs);
  return pairs;
}

// A random tree whose children stick out of their parents (up to 1.5 parent radii away), with
// uneven child counts, so that only subtree bounds may prune.
SphereTree random_tree(Rng& rng, int branching, int depth) {
  std::vector<SphereTreeNode> nodes{{{Vec3::Zero(), 1.0f}, -1}};
  std::size_t level_begin = 0;
  for (int level = 1; level < depth; ++level) {
    const std::size_t level_end = nodes.size();
    for (std::size_t p = level_begin; p < level_end; ++p) {
      const int children = std::uniform_int_distribution<int>(0, branching)(rng);
      for (int c = 0; c < children; ++c) {
        const Sphere& parent = nodes[p].sphere;
        const Vec3 direction =
            Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)).normalized();
        const Vec3 center = parent.center + direction * uniform(rng, 0.0f, 1.5f) * parent.radius;
        nodes.push_back(
            {{center, uniform(rng, 0.3f, 0.8f) * parent.radius}, static_cast<std::int32_t>(p)});
      }
    }
    level_begin = level_end;
  }
  return SphereTree::from_nodes(nodes, branching);
}

SphereTree octree_tree(const tools::TriangleMesh& mesh) {
  tools::BuildOptions options;
  options.method = tools::BuildMethod::Octree;
  options.depth = 3;
  return tools::build_sphere_tree(mesh, options);
}

// Octree trees of a torus and a box, built once for the whole suite.
const SphereTree& torus_tree() {
  static const SphereTree tree = octree_tree(tools::make_torus(1.0, 0.35, 32, 16));
  return tree;
}
const SphereTree& box_tree() {
  static const SphereTree tree = octree_tree(tools::make_box({1.6, 0.8, 1.2}));
  return tree;
}

class TreeDescentTest : public testing::Test {
 protected:
  const SphereTree& torus_ = torus_tree();
  const SphereTree& box_ = box_tree();

  // Checks the descent against the oracle over random poses; returns the pairs found in all.
  static std::size_t expect_exact(const SphereTree& tree_a, const SphereTree& tree_b, int depth_a,
                                  int depth_b, Rng& rng, int poses, float spread) {
    TreeDescent descent;
    DescentSettings settings;
    settings.depth_a = depth_a;
    settings.depth_b = depth_b;
    std::size_t found = 0;
    std::vector<NodePair> pairs;
    for (int i = 0; i < poses; ++i) {
      const Transform pose_a = random_pose(rng, spread);
      const Transform pose_b = random_pose(rng, spread);
      pairs.clear();
      const DescentStats stats = descent.descend(tree_a, pose_a, tree_b, pose_b, settings, pairs);
      EXPECT_EQ(sorted(pairs), brute_force(tree_a, pose_a, depth_a, tree_b, pose_b, depth_b))
          << "pose " << i << ", depths " << depth_a << " " << depth_b;
      EXPECT_EQ(stats.leaf_pairs, pairs.size());
      EXPECT_EQ(stats.cut_short_pairs, 0u);
      EXPECT_EQ(stats.internal_pairs, 0u);
      EXPECT_GE(stats.sphere_tests, 1u);
      found += pairs.size();
    }
    return found;
  }
};

TEST_F(TreeDescentTest, OctreeTreesGiveExactlyTheBruteForceLeafPairs) {
  ASSERT_EQ(torus_.depth(), 3);
  ASSERT_EQ(box_.depth(), 3);
  Rng rng(20080316);
  for (int depth : {0, 2, 1}) {
    EXPECT_GT(expect_exact(torus_, box_, depth, depth, rng, 40, 0.8f), 0u);
    EXPECT_GT(expect_exact(torus_, torus_, depth, depth, rng, 40, 0.8f), 0u);
    EXPECT_GT(expect_exact(box_, box_, depth, depth, rng, 20, 0.8f), 0u);
  }
  // Different depths on the two sides (a detailed body against a coarse one).
  EXPECT_GT(expect_exact(torus_, box_, 2, 3, rng, 30, 0.8f), 0u);
  EXPECT_GT(expect_exact(box_, torus_, 3, 2, rng, 30, 0.8f), 0u);
}

TEST(TreeDescent, RandomTreesWithProtrudingChildrenGiveExactlyTheBruteForceLeafPairs) {
  Rng rng(7);
  TreeDescent descent;
  std::vector<NodePair> pairs;
  std::size_t found = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int branching = std::uniform_int_distribution<int>(2, 8)(rng);
    const SphereTree tree_a = random_tree(rng, branching, 4);
    const SphereTree tree_b = random_tree(rng, branching, 3);
    const Transform pose_a = random_pose(rng, 1.5f);
    const Transform pose_b = random_pose(rng, 1.5f);
    for (const auto& [depth_a, depth_b] : {std::pair{0, 0}, {2, 0}, {3, 2}, {1, 3}}) {
      DescentSettings settings;
      settings.depth_a = depth_a;
      settings.depth_b = depth_b;
      pairs.clear();
      descent.descend(tree_a, pose_a, tree_b, pose_b, settings, pairs);
      ASSERT_EQ(sorted(pairs), brute_force(tree_a, pose_a, depth_a, tree_b, pose_b, depth_b))
          << "trial " << trial << ", depths " << depth_a << " " << depth_b;
      found += pairs.size();
    }
  }
  EXPECT_GT(found, 1000u);
}

// The children are placed and tested in lanes: every lane set this processor has returns the
// pairs the plain floats return, in the same order, with the same world centres and counts.
TEST(TreeDescent, EveryLaneSetReturnsTheSamePairsInTheSameOrder) {
  Rng rng(11);
  std::vector<TreeDescent> descents;
  descents.emplace_back(SolverLanes::kPortable);
  for (const SolverLanes lanes : {SolverLanes::kSse2, SolverLanes::kAvx2}) {
    try {
      descents.emplace_back(lanes);
    } catch (const Error& error) {
      // Only AVX2 may be missing, and then the message says so.
      EXPECT_EQ(lanes, SolverLanes::kAvx2) << error.what();
      EXPECT_NE(std::string(error.what()).find("avx2"), std::string::npos) << error.what();
    }
  }
  std::size_t found = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int branching = std::uniform_int_distribution<int>(2, 8)(rng);
    const SphereTree tree_a = random_tree(rng, branching, 4);
    const SphereTree tree_b = random_tree(rng, branching, 3);
    const Transform pose_a = random_pose(rng, 1.5f);
    const Transform pose_b = random_pose(rng, 1.5f);
    DescentSettings settings;
    settings.depth_a = trial % 3;
    settings.margin = uniform(rng, 0.0f, 0.2f);
    // Every fourth trial with a budget that cuts the descent short.
    settings.max_sphere_tests = trial % 4 == 0 ? 40 : 0;
    std::vector<NodePair> expected;
    const DescentStats expected_stats =
        descents[0].descend(tree_a, pose_a, tree_b, pose_b, settings, expected);
    found += expected.size();
    for (std::size_t d = 1; d < descents.size(); ++d) {
      std::vector<NodePair> pairs;
      const DescentStats stats =
          descents[d].descend(tree_a, pose_a, tree_b, pose_b, settings, pairs);
      ASSERT_EQ(pairs, expected) << "trial " << trial << ", lane set " << d;
      EXPECT_EQ(stats.sphere_tests, expected_stats.sphere_tests);
      EXPECT_EQ(stats.internal_pairs, expected_stats.internal_pairs);
      for (const NodePair& pair : pairs) {
        EXPECT_EQ(descents[d].world_sphere_a(tree_a, pair.node_a).center,
                  descents[0].world_sphere_a(tree_a, pair.node_a).center);
        EXPECT_EQ(descents[d].world_sphere_b(tree_b, pair.node_b).center,
                  descents[0].world_sphere_b(tree_b, pair.node_b).center);
      }
    }
  }
  EXPECT_GT(found, 400u);
}

TEST(TreeDescent, SeparatedTreesCostOneTest) {
  Rng rng(3);
  const SphereTree tree = random_tree(rng, 8, 3);
  Transform far;
  far.translation = Vec3(100, 0, 0);
  TreeDescent descent;
  std::vector<NodePair> pairs;
  const DescentStats stats = descent.descend(tree, Transform{}, tree, far, {}, pairs);
  EXPECT_TRUE(pairs.empty());
  EXPECT_EQ(stats.sphere_tests, 1u);
  EXPECT_EQ(stats.leaf_pairs, 0u);
}

TEST(TreeDescent, SingleSphereTreesAreTheirOwnLeaves) {
  const std::vector<SphereTreeNode> one{{{Vec3::Zero(), 1.0f}, -1}};
  const SphereTree tree = SphereTree::from_nodes(one, 8);
  Transform near;
  near.translation = Vec3(1.5f, 0, 0);
  TreeDescent descent;
  std::vector<NodePair> pairs{{9, 9}};  // appended to, never cleared
  const DescentStats stats = descent.descend(tree, Transform{}, tree, near, {}, pairs);
  EXPECT_EQ(pairs, (std::vector<NodePair>{{9, 9}, {0, 0}}));
  EXPECT_EQ(stats.leaf_pairs, 1u);
  EXPECT_EQ(stats.sphere_tests, 1u);
}

TEST_F(TreeDescentTest, WorldSpheresOfReturnedPairsFollowThePoses) {
  Rng rng(11);
  TreeDescent descent;
  // A small tree first, so that the scratch must grow for the larger ones.
  const SphereTree small = random_tree(rng, 2, 2);
  std::vector<NodePair> pairs;
  descent.descend(small, Transform{}, small, Transform{}, {}, pairs);
  const Transform pose_a = random_pose(rng, 0.5f);
  const Transform pose_b = random_pose(rng, 0.5f);
  pairs.clear();
  descent.descend(torus_, pose_a, box_, pose_b, {}, pairs);
  ASSERT_FALSE(pairs.empty());
  for (const NodePair& pair : pairs) {
    const Sphere a = descent.world_sphere_a(torus_, pair.node_a);
    const Sphere b = descent.world_sphere_b(box_, pair.node_b);
    EXPECT_TRUE(a.center.isApprox(pose_a.apply(torus_.sphere(pair.node_a).center), 1e-5f));
    EXPECT_TRUE(b.center.isApprox(pose_b.apply(box_.sphere(pair.node_b).center), 1e-5f));
    EXPECT_TRUE(overlap(a, b));
  }
}

TEST_F(TreeDescentTest, TimeCriticalWithoutBudgetsEqualsExact) {
  Rng rng(5);
  TreeDescent descent;
  std::vector<NodePair> exact;
  std::vector<NodePair> relaxed;
  for (int i = 0; i < 40; ++i) {
    const Transform pose_a = random_pose(rng, 0.8f);
    const Transform pose_b = random_pose(rng, 0.8f);
    exact.clear();
    const DescentStats exact_stats = descent.descend(torus_, pose_a, box_, pose_b, {}, exact);
    // Budgets far beyond what the trees can use, the clock read at every test.
    DescentSettings generous;
    generous.max_sphere_tests = 1'000'000'000;
    generous.max_microseconds = 1e9;
    generous.clock_check_interval = 1;
    relaxed.clear();
    const DescentStats stats = descent.descend(torus_, pose_a, box_, pose_b, generous, relaxed);
    EXPECT_EQ(relaxed, exact);
    EXPECT_EQ(stats.sphere_tests, exact_stats.sphere_tests);
    EXPECT_EQ(stats.cut_short_pairs, 0u);
    EXPECT_EQ(stats.internal_pairs, 0u);
  }
}

// Checks what the time-critical mode promises after an interruption.
void expect_valid_cut_short(const SphereTree& tree_a, const Transform& pose_a,
                            const SphereTree& tree_b, const Transform& pose_b,
                            const std::vector<NodePair>& pairs, const DescentStats& stats) {
  EXPECT_GT(stats.cut_short_pairs, 0u);
  EXPECT_LE(stats.internal_pairs, stats.cut_short_pairs);
  EXPECT_EQ(stats.leaf_pairs + stats.internal_pairs, pairs.size());
  for (const NodePair& pair : pairs) {
    EXPECT_TRUE(overlap(world_sphere(tree_a, pose_a, pair.node_a),
                        world_sphere(tree_b, pose_b, pair.node_b)));
  }
}

TEST_F(TreeDescentTest, TinyTestBudgetResolvesWaitingPairsAtTheirLevel) {
  Rng rng(13);
  TreeDescent descent;
  std::vector<NodePair> pairs;
  std::size_t returned = 0;
  std::size_t internal = 0;
  for (int i = 0; i < 40; ++i) {
    const Transform pose_a = random_pose(rng, 0.3f);
    const Transform pose_b = random_pose(rng, 0.3f);
    DescentSettings settings;
    settings.max_sphere_tests = 10;
    pairs.clear();
    const DescentStats stats = descent.descend(torus_, pose_a, torus_, pose_b, settings, pairs);
    expect_valid_cut_short(torus_, pose_a, torus_, pose_b, pairs, stats);
    // One expansion may overrun the budget by the branching factor; then one test per waiting pair.
    EXPECT_LE(stats.sphere_tests, 10u + 8u + stats.cut_short_pairs);
    returned += pairs.size();
    internal += stats.internal_pairs;
  }
  EXPECT_GT(returned, 0u);
  EXPECT_GT(internal, 0u);
}

TEST_F(TreeDescentTest, TinyTimeBudgetStopsTheDescent) {
  DescentSettings settings;
  settings.max_microseconds = 1e-3;
  settings.clock_check_interval = 1;
  TreeDescent descent;
  std::vector<NodePair> pairs;
  const DescentStats stats =
      descent.descend(torus_, Transform{}, box_, Transform{}, settings, pairs);
  expect_valid_cut_short(torus_, Transform{}, box_, Transform{}, pairs, stats);
  // The clock is read after the first test, and the time is already spent.
  EXPECT_EQ(stats.cut_short_pairs, 1u);
  EXPECT_EQ(stats.sphere_tests, 2u);
}

}  // namespace
}  // namespace sphys
