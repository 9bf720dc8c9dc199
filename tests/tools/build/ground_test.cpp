#include "sphys/tools/ground.h"

#include <gtest/gtest.h>

#include "sphys/error.h"

namespace sphys::tools {
namespace {

bool covered(const SphereTree& tree, int level, const Vec3& p) {
  for (const Sphere& s : tree.level_spheres(level)) {
    if ((p - s.center).norm() <= s.radius) return true;
  }
  return false;
}

TEST(Ground, FiveLevelOctreeCoversTheTopFace) {
  GroundOptions options;
  options.size = 8.0;
  options.thickness = 0.25;
  const SphereTree tree = build_ground_tree(options);
  EXPECT_EQ(tree.depth(), 5);
  EXPECT_EQ(tree.branching(), 8);
  const TriangleMesh box = make_ground_box(options);
  EXPECT_FLOAT_EQ(static_cast<float>(box.bounds().max().y()), 0.0f);
  EXPECT_FLOAT_EQ(static_cast<float>(box.bounds().min().y()), -0.25f);
  // Every level covers the top face: check a grid of points on it.
  for (int level = 0; level < tree.depth(); ++level) {
    for (int i = 0; i <= 40; ++i) {
      for (int k = 0; k <= 40; ++k) {
        const Vec3 p(-4.0f + 0.2f * static_cast<float>(i), 0.0f,
                     -4.0f + 0.2f * static_cast<float>(k));
        ASSERT_TRUE(covered(tree, level, p)) << "level " << level << " at " << p.transpose();
      }
    }
  }
  // Leaves are small: the level-4 cells of the 8 m cube are 0.5 m wide.
  for (const Sphere& s : tree.level_spheres(4))
    EXPECT_LE(s.radius, 0.5f * std::sqrt(3.0f) / 2 + 1e-4f);
}

TEST(Ground, RejectsImpossibleSizes) {
  GroundOptions options;
  options.thickness = 0.0;
  EXPECT_THROW((void)build_ground_tree(options), Error);
  options.thickness = 0.5;
  options.size = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)build_ground_tree(options), Error);
}

}  // namespace
}  // namespace sphys::tools
