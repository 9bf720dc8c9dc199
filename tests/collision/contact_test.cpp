#include "sphys/contact.h"

#include <array>

#include <gtest/gtest.h>

#include "collision/broad_phase.h"
#include "support/vec_near.h"

namespace sphys {
namespace {

Contact contact_of(const Sphere& a, const Sphere& b, bool expect_coincident = false) {
  Contact contact;
  EXPECT_EQ(sphere_sphere_contact(a, b, Vec3::UnitY(), contact), expect_coincident);
  return contact;
}

TEST(SphereSphereContact, TouchingSpheresHaveZeroDepth) {
  const Sphere a{Vec3(0, 0, 0), 1.0f};
  const Sphere b{Vec3(3, 0, 0), 2.0f};
  EXPECT_TRUE(spheres_overlap(a.center, a.radius, b.center, b.radius));
  const Contact c = contact_of(a, b);
  expect_vec_near(c.normal, Vec3(1, 0, 0));
  expect_vec_near(c.point, Vec3(1, 0, 0));  // eq. 3: C1 + 1/3 · (3, 0, 0)
  EXPECT_FLOAT_EQ(c.depth, 0.0f);
}

TEST(SphereSphereContact, DeepOverlapOfEqualSpheresMeetsHalfway) {
  const Contact c = contact_of({Vec3(1, 2, 3), 2.0f}, {Vec3(1, 2, 4), 2.0f});
  expect_vec_near(c.normal, Vec3(0, 0, 1));
  expect_vec_near(c.point, Vec3(1, 2, 3.5f));
  EXPECT_FLOAT_EQ(c.depth, 3.0f);
}

TEST(SphereSphereContact, DifferentRadiiSplitTheCentreLineInTheirRatio) {
  // |v| = 5, r1 = 2, r2 = 6: P = C1 + 2/8 · v (eq. 3), depth 8 - 5.
  const Contact c = contact_of({Vec3(0, 0, 0), 2.0f}, {Vec3(0, 3, 4), 6.0f});
  expect_vec_near(c.normal, Vec3(0, 0.6f, 0.8f));
  expect_vec_near(c.point, Vec3(0, 0.75f, 1.0f));
  EXPECT_FLOAT_EQ(c.depth, 3.0f);
}

TEST(SphereSphereContact, NormalPointsFromTheFirstSphereToTheSecond) {
  const Contact c = contact_of({Vec3(0, 0, 0), 1.0f}, {Vec3(-1, 0, 0), 1.0f});
  expect_vec_near(c.normal, Vec3(-1, 0, 0));
  expect_vec_near(c.point, Vec3(-0.5f, 0, 0));
  EXPECT_FLOAT_EQ(c.depth, 1.0f);
}

TEST(SphereSphereContact, SeparatedSpheresHaveNegativeDepth) {
  const Sphere a{Vec3(0, 0, 0), 1.0f};
  const Sphere b{Vec3(0, 0, 5), 1.0f};
  EXPECT_FALSE(spheres_overlap(a.center, a.radius, b.center, b.radius));
  EXPECT_FLOAT_EQ(contact_of(a, b).depth, -3.0f);
}

TEST(SphereSphereContact, CoincidentCentresUseTheFallbackNormalAndSaySo) {
  const Sphere a{Vec3(1, 1, 1), 1.0f};
  const Sphere b{Vec3(1, 1, 1), 0.5f};
  const Vec3 fallback = fallback_normal(Vec3(0, 0, 0), Vec3(0, 0, -2), 1);
  expect_vec_near(fallback, Vec3(0, 0, -1));
  Contact c;
  EXPECT_TRUE(sphere_sphere_contact(a, b, fallback, c));
  EXPECT_EQ(c.normal, fallback);
  expect_vec_near(c.point, Vec3(1, 1, 1));
  EXPECT_FLOAT_EQ(c.depth, 1.5f);
}

TEST(SphereSphereContact, NearlyCoincidentCentresCountAsCoincident) {
  const Sphere a{Vec3(1, 1, 1), 1.0f};
  Contact c;
  EXPECT_TRUE(sphere_sphere_contact(a, {Vec3(1, 1, 1.0000001f), 1.0f}, Vec3::UnitY(), c));
  EXPECT_EQ(c.normal, Vec3::UnitY());
  // A thousandth of the radii apart is a real direction.
  EXPECT_FALSE(sphere_sphere_contact(a, {Vec3(1, 1, 1.002f), 1.0f}, Vec3::UnitY(), c));
  expect_vec_near(c.normal, Vec3(0, 0, 1), 1e-4f);
}

TEST(FallbackNormal, IsTheCentresOfMassDirectionOrOneDrawnFromThePair) {
  expect_vec_near(fallback_normal(Vec3(1, 0, 0), Vec3(1, 0, 3), 7), Vec3(0, 0, 1));
  const Vec3 drawn = fallback_normal(Vec3(2, 3, 4), Vec3(2, 3, 4), 7);
  EXPECT_NEAR(drawn.norm(), 1.0f, 1e-6f);
  EXPECT_EQ(drawn, fallback_normal(Vec3(2, 3, 4), Vec3(2, 3, 4), 7));
  EXPECT_NE(drawn, fallback_normal(Vec3(2, 3, 4), Vec3(2, 3, 4), 8));
  // Uniform over the sphere: 10,000 seeds' directions average to about nothing (each component's
  // mean has a standard deviation of 0.006) and fill each octant with about 1,250 (sd 33).
  constexpr int kSeeds = 10000;
  Vec3 sum = Vec3::Zero();
  std::array<int, 8> octants{};
  for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
    const Vec3 n = fallback_normal(Vec3::Zero(), Vec3::Zero(), pair_key(0, 1) + seed * 131);
    ASSERT_NEAR(n.norm(), 1.0f, 1e-6f);
    sum += n;
    ++octants[(n.x() > 0 ? 1 : 0) + (n.y() > 0 ? 2 : 0) + (n.z() > 0 ? 4 : 0)];
  }
  EXPECT_LT((sum / kSeeds).norm(), 0.03f);
  for (const int count : octants) {
    EXPECT_GT(count, 1100);
    EXPECT_LT(count, 1400);
  }
}

TEST(SpherePlaneContact, PenetratingSphere) {
  Contact c;
  sphere_plane_contact(0.5f, {Vec3(1, 0.8f, -2), 0.5f}, c);
  EXPECT_EQ(c.normal, Vec3::UnitY());
  expect_vec_near(c.point, Vec3(1, 0.3f, -2));  // the sphere's lowest point
  EXPECT_NEAR(c.depth, 0.2f, 1e-6f);
}

TEST(SpherePlaneContact, TouchingAndSeparatedSpheres) {
  Contact c;
  sphere_plane_contact(0.0f, {Vec3(0, 2, 0), 2.0f}, c);
  EXPECT_FLOAT_EQ(c.depth, 0.0f);
  expect_vec_near(c.point, Vec3(0, 0, 0));
  sphere_plane_contact(-1.0f, {Vec3(5, 2, 7), 1.0f}, c);
  EXPECT_FLOAT_EQ(c.depth, -2.0f);
  expect_vec_near(c.point, Vec3(5, 1, 7));
}

TEST(SpherePlaneContact, SphereBelowThePlaneIsDeeperThanItsDiameter) {
  Contact c;
  sphere_plane_contact(1.0f, {Vec3(0, -3, 0), 1.0f}, c);
  EXPECT_FLOAT_EQ(c.depth, 5.0f);
  EXPECT_EQ(c.normal, Vec3::UnitY());
}

TEST(Contact, SphereContactLeavesTheIdsAlone) {
  Contact c;
  c.body_a = 3;
  c.body_b = 7;
  c.leaf_a = 11;
  c.leaf_b = 13;
  EXPECT_FALSE(
      sphere_sphere_contact({Vec3(0, 0, 0), 1.0f}, {Vec3(1, 0, 0), 1.0f}, Vec3::UnitY(), c));
  sphere_plane_contact(0.0f, {Vec3(0, 0, 0), 1.0f}, c);
  EXPECT_EQ(c.body_a, 3u);
  EXPECT_EQ(c.body_b, 7u);
  EXPECT_EQ(c.leaf_a, 11u);
  EXPECT_EQ(c.leaf_b, 13u);
}

}  // namespace
}  // namespace sphys
