#pragma once

// A vector checked component by component against an expected one, within a tolerance.

#include <gtest/gtest.h>

#include "sphys/math.h"

namespace sphys {

inline void expect_vec_near(const Vec3& actual, const Vec3& expected, float tolerance = 1e-6f) {
  EXPECT_NEAR(actual.x(), expected.x(), tolerance);
  EXPECT_NEAR(actual.y(), expected.y(), tolerance);
  EXPECT_NEAR(actual.z(), expected.z(), tolerance);
}

}  // namespace sphys
