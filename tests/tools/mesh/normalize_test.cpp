#include "sphys/tools/normalize.h"

#include <cstddef>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/primitives.h"

namespace sphys::tools {
namespace {

TriangleMesh skewed_box() {
  const Mat3d rotation =
      Eigen::AngleAxisd(0.6, Vec3d(0.3, 1.0, -0.7).normalized()).toRotationMatrix();
  TriangleMesh box = make_box(Vec3d(2.0, 3.0, 5.0));
  for (Vec3d& v : box.vertices) v = rotation * v + Vec3d(4.0, -1.0, 2.5);
  box.name = "skewed box";
  return box;
}

void expect_normalized(const TriangleMesh& original, const NormalizedMesh& result, double target) {
  EXPECT_EQ(result.mesh.name, original.name);
  EXPECT_EQ(result.mesh.triangles, original.triangles);
  EXPECT_NEAR(result.mesh.bounds().sizes().maxCoeff(), target, 1e-12 * target);
  EXPECT_LT(compute_mass_properties(result.mesh).center_of_mass.norm(), 1e-9 * target);
  ASSERT_EQ(result.mesh.vertices.size(), original.vertices.size());
  for (std::size_t i = 0; i < original.vertices.size(); ++i) {
    const Vec3d mapped = result.scale * original.vertices[i] + result.translation;
    EXPECT_LT((mapped - result.mesh.vertices[i]).norm(), 1e-12 * target);
  }
}

TEST(Normalize, ScalesTheLongestSideAndCentresTheMass) {
  const TriangleMesh box = skewed_box();
  const NormalizedMesh result = normalize(box, 0.25);
  expect_normalized(box, result, 0.25);
  EXPECT_NEAR(result.scale, 0.25 / box.bounds().sizes().maxCoeff(), 1e-15);
}

TEST(Normalize, CentresAnOpenMeshByTheWindingNumberMethod) {
  TriangleMesh holed = make_icosphere(3.0, 3);
  for (Vec3d& v : holed.vertices) v += Vec3d(1.0, 2.0, 3.0);
  holed.triangles.erase(holed.triangles.begin(), holed.triangles.begin() + 2);
  expect_normalized(holed, normalize(holed, 2.0), 2.0);
}

TEST(Normalize, RejectsBadTargetSizes) {
  for (const double target : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                              std::numeric_limits<double>::infinity()}) {
    try {
      (void)normalize(skewed_box(), target);
      ADD_FAILURE() << "no error for target " << target;
    } catch (const Error& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("skewed box"), std::string::npos) << message;
      EXPECT_NE(message.find("target size must be positive and finite"), std::string::npos)
          << message;
    }
  }
}

TEST(Normalize, RejectsAFlatBoundingBox) {
  TriangleMesh point;
  point.name = "point.obj";
  point.vertices = {Vec3d(1.0, 1.0, 1.0), Vec3d(1.0, 1.0, 1.0), Vec3d(1.0, 1.0, 1.0)};
  point.triangles = {{0, 1, 2}};
  EXPECT_THROW((void)normalize(point, 1.0), Error);
  EXPECT_THROW((void)normalize(TriangleMesh{}, 1.0), Error);
}

}  // namespace
}  // namespace sphys::tools
