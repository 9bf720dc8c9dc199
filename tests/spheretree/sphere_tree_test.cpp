#include "sphys/sphere_tree.h"

#include <limits>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"

namespace sphys {
namespace {

using testing::HasSubstr;

Sphere sphere(float x, float r) { return {Vec3(x, 0, 0), r}; }

// Root; two children; the first child has three children, the second none.
std::vector<SphereTreeNode> uneven_tree() {
  return {{sphere(0, 4), -1}, {sphere(-2, 2), 0}, {sphere(2, 2), 0},
          {sphere(-3, 1), 1}, {sphere(-2, 1), 1}, {sphere(-1, 1), 1}};
}

TEST(SphereTree, PacksLevelsChildRangesAndLeaves) {
  const SphereTree tree = SphereTree::from_nodes(uneven_tree(), 8);
  EXPECT_EQ(tree.size(), 6u);
  EXPECT_EQ(tree.depth(), 3);
  EXPECT_EQ(tree.level_begin(0), 0u);
  EXPECT_EQ(tree.level_end(0), 1u);
  EXPECT_EQ(tree.level_begin(1), 1u);
  EXPECT_EQ(tree.level_end(1), 3u);
  EXPECT_EQ(tree.level_begin(2), 3u);
  EXPECT_EQ(tree.level_end(2), 6u);
  EXPECT_EQ(tree.first_child(0), 1u);
  EXPECT_EQ(tree.child_count(0), 2u);
  EXPECT_EQ(tree.first_child(1), 3u);
  EXPECT_EQ(tree.child_count(1), 3u);
  EXPECT_TRUE(tree.is_leaf(2));  // a leaf above the last level: trees need not be complete
  EXPECT_EQ(tree.leaves(), (std::vector<std::uint32_t>{2, 3, 4, 5}));
  EXPECT_EQ(tree.level(0), 0);
  EXPECT_EQ(tree.level(2), 1);
  EXPECT_EQ(tree.level(5), 2);
  EXPECT_EQ(tree.parent(4), 1);
  EXPECT_EQ(tree.level_spheres(2).size(), 3u);
  EXPECT_EQ(tree.root().radius, 4.0f);
}

TEST(SphereTree, SubtreeRadiusHoldsEveryDescendant) {
  auto nodes = uneven_tree();
  nodes[5].sphere = sphere(3, 1.5f);  // sticks out of its parent (centre -2, radius 2)
  const SphereTree tree = SphereTree::from_nodes(nodes, 8);
  EXPECT_FLOAT_EQ(tree.subtree_radius(5), 1.5f);
  EXPECT_FLOAT_EQ(tree.subtree_radius(2), 2.0f);  // a leaf: its own radius
  EXPECT_FLOAT_EQ(tree.subtree_radius(1), 6.5f);  // |3 - (-2)| + 1.5
  EXPECT_FLOAT_EQ(tree.subtree_radius(0), 8.5f);  // |-2 - 0| + 6.5
}

TEST(SphereTree, TruncatedKeepsTheFirstLevels) {
  const SphereTree tree = SphereTree::from_nodes(uneven_tree(), 8);
  const SphereTree two = tree.truncated(2);
  EXPECT_EQ(two.depth(), 2);
  EXPECT_EQ(two.size(), 3u);
  EXPECT_TRUE(two.is_leaf(1));
  EXPECT_EQ(two.leaves(), (std::vector<std::uint32_t>{1, 2}));
  EXPECT_EQ(tree.truncated(3), tree);
  EXPECT_EQ(tree.truncated(1).size(), 1u);
  EXPECT_THROW((void)tree.truncated(0), Error);
}

void expect_rejected(const std::vector<SphereTreeNode>& nodes, int branching,
                     const std::string& problem) {
  try {
    (void)SphereTree::from_nodes(nodes, branching);
    ADD_FAILURE() << "accepted a tree that should fail with: " << problem;
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(problem));
  }
}

TEST(SphereTree, RejectsMalformedNodeLists) {
  expect_rejected({}, 8, "at least a root");
  expect_rejected(uneven_tree(), 1, "outside 2..8");
  expect_rejected(uneven_tree(), 9, "outside 2..8");
  expect_rejected(uneven_tree(), 2, "node 1: has more than 2 children");

  auto nodes = uneven_tree();
  nodes[0].parent = 0;
  expect_rejected(nodes, 8, "node 0: the root must have no parent");
  nodes = uneven_tree();
  nodes[3].parent = 4;
  expect_rejected(nodes, 8, "node 3: parent 4 does not come before it");
  nodes = uneven_tree();
  nodes[4].parent = 0;  // parents 1, 0, 1: not breadth-first
  expect_rejected(nodes, 8, "node 4: nodes are not in breadth-first order");
  nodes = uneven_tree();
  nodes[2].sphere.radius = 0;
  expect_rejected(nodes, 8, "node 2: radius must be positive");
  nodes[2].sphere.radius = std::numeric_limits<float>::quiet_NaN();
  expect_rejected(nodes, 8, "node 2: radius must be positive");
  nodes = uneven_tree();
  nodes[5].sphere.center.y() = std::numeric_limits<float>::infinity();
  expect_rejected(nodes, 8, "node 5: centre is not finite");
}

}  // namespace
}  // namespace sphys
