#include <gtest/gtest.h>

#include "sphys/math.h"

namespace sphys {
namespace {

TEST(Aabb, DefaultIsEmptyAndFirstExtendSetsIt) {
  Aabb box;
  EXPECT_TRUE(box.empty());
  box.extend(Vec3(1, 2, 3));
  EXPECT_FALSE(box.empty());
  EXPECT_EQ(box.min, Vec3(1, 2, 3));
  EXPECT_EQ(box.max, Vec3(1, 2, 3));
}

TEST(Aabb, OverlapIsClosedOnEveryAxis) {
  const Aabb a{Vec3(0, 0, 0), Vec3(1, 1, 1)};
  EXPECT_TRUE(a.overlaps(Aabb{Vec3(1, 1, 1), Vec3(2, 2, 2)}));  // touching corner
  EXPECT_TRUE(a.overlaps(Aabb{Vec3(0.5f, -1, 0.5f), Vec3(0.6f, 2, 0.6f)}));
  EXPECT_FALSE(a.overlaps(Aabb{Vec3(0, 0, 1.01f), Vec3(1, 1, 2)}));    // apart on z only
  EXPECT_FALSE(a.overlaps(Aabb{Vec3(-2, 0, 0), Vec3(-0.01f, 1, 1)}));  // apart on x only
}

TEST(Aabb, AroundSphereAndContains) {
  const Aabb box = Aabb::around_sphere(Vec3(1, 0, -1), 0.5f);
  EXPECT_EQ(box.size(), Vec3(1, 1, 1));
  EXPECT_EQ(box.center(), Vec3(1, 0, -1));
  EXPECT_TRUE(box.contains(Vec3(1.5f, 0.5f, -0.5f)));
  EXPECT_FALSE(box.contains(Vec3(1.6f, 0, -1)));
}

TEST(Transform, RotatesThenTranslates) {
  Transform t;
  t.rotation = Quat(Eigen::AngleAxisf(static_cast<float>(EIGEN_PI) / 2, Vec3::UnitY()));
  t.translation = Vec3(0, 1, 0);
  const Vec3 p = t.apply(Vec3(1, 0, 0));
  EXPECT_NEAR(p.x(), 0.0f, 1e-6f);
  EXPECT_NEAR(p.y(), 1.0f, 1e-6f);
  EXPECT_NEAR(p.z(), -1.0f, 1e-6f);
}

}  // namespace
}  // namespace sphys
