// inverse_or_zero: inertia tensors across the whole range of bodies a scene may hold.

#include <gtest/gtest.h>

#include "sphys/math.h"

namespace sphys {
namespace {

// A rotated diagonal tensor: principal moments `moments` about axes turned by 0.7 rad about
// (1, 2, 3), so that every entry is non-zero.
Mat3 turned(const Vec3& moments) {
  const Mat3 rotation = Eigen::AngleAxisf(0.7f, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  return rotation * moments.asDiagonal() * rotation.transpose();
}

// The product with the inverse is the identity, to float's precision, from a 1 mm, 1 mg grain
// (moments near 1e-14 kg·m²: the float determinant, 1e-42, is denormal) to a 1 km, 10⁹ kg
// building (near 1e14: the float determinant, 1e42, overflows).
TEST(InverseOrZero, InvertsInertiasFromAGrainToABuilding) {
  for (const float scale : {1e-14f, 1e-6f, 1.0f, 1e6f, 1e14f}) {
    SCOPED_TRACE(scale);
    const Mat3 inertia = turned(scale * Vec3(1.0f, 2.0f, 3.0f));
    const Mat3 inverse = inverse_or_zero(inertia);
    ASSERT_TRUE(inverse.allFinite());
    EXPECT_LT((inertia * inverse - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-5f);
  }
}

TEST(InverseOrZero, ASingularMatrixHasZeroForItsInverse) {
  EXPECT_EQ(inverse_or_zero(Mat3::Zero()), Mat3::Zero());
  // A rod's inertia about its own axis is 0: it cannot be turned about it by this measure.
  EXPECT_EQ(inverse_or_zero(Vec3(1.0f, 1.0f, 0.0f).asDiagonal()), Mat3::Zero());
}

}  // namespace
}  // namespace sphys
