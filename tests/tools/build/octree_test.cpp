#include "tools/build/octree.h"

#include <gtest/gtest.h>

#include "sphys/tools/primitives.h"

namespace sphys::tools::build {
namespace {

TEST(Octree, UnitCubeSplitsIntoItsOctants) {
  const MeshQuery query(make_box({1, 1, 1}));
  const std::vector<BallNode> nodes = build_octree(query, 3, {});
  // Root, 8 octants, and 8 x 8 sub-octants: every cell of a cube meets the solid.
  ASSERT_EQ(nodes.size(), 1u + 8u + 64u);
  EXPECT_NEAR(nodes[0].ball.radius, std::sqrt(3.0) / 2, 1e-9);
  for (std::size_t i = 1; i < 9; ++i) {
    EXPECT_EQ(nodes[i].parent, 0);
    // A solid octant's ball is its circumscribed ball: half the cube's.
    EXPECT_NEAR(nodes[i].ball.radius, std::sqrt(3.0) / 4, 1e-6);
  }
  for (std::size_t i = 9; i < nodes.size(); ++i) {
    EXPECT_EQ(nodes[i].parent, static_cast<std::int32_t>(1 + (i - 9) / 8));
    EXPECT_NEAR(nodes[i].ball.radius, std::sqrt(3.0) / 8, 1e-6);
  }
}

TEST(Octree, ThinPlateBallsHugTheSolidNotTheCells) {
  // A 1 x 0.1 x 1 plate: its bounding cube has side 1, level-1 cells are 0.5 cubes, but the
  // solid's part of each is 0.5 x 0.05 x 0.5, whose ball is much smaller than the cell's.
  const MeshQuery query(make_box({1, 0.1, 1}));
  const std::vector<BallNode> nodes = build_octree(query, 2, {});
  ASSERT_EQ(nodes.size(), 9u);
  const double solid_part = 0.5 * Vec3d(0.5, 0.05, 0.5).norm();
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    EXPECT_NEAR(nodes[i].ball.radius, solid_part, 1e-6);
  }
}

TEST(Octree, TorusSkipsTheEmptyMiddle) {
  const MeshQuery query(make_torus(1.0, 0.25, 48, 24));
  const std::vector<BallNode> nodes = build_octree(query, 4, {});
  // Level 3 has 8^3 = 512 cells; the torus meets only a ring of them.
  std::size_t level3 = 0;
  for (const BallNode& n : nodes) {
    if (n.parent >= 9) ++level3;
  }
  EXPECT_GT(level3, 0u);
  EXPECT_LT(level3, 512u / 2);
}

}  // namespace
}  // namespace sphys::tools::build
