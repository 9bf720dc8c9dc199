#include "tools/build/ball.h"

#include <random>

#include <gtest/gtest.h>

namespace sphys::tools::build {
namespace {

TEST(MinEnclosingBall, SimpleConfigurations) {
  const std::vector<Vec3d> two{{-1, 0, 0}, {3, 0, 0}};
  const Ball b2 = min_enclosing_ball(two);
  EXPECT_NEAR(b2.radius, 2.0, 1e-12);
  EXPECT_NEAR((b2.center - Vec3d(1, 0, 0)).norm(), 0.0, 1e-12);

  // An equilateral triangle: the circumcircle (radius side/√3).
  const std::vector<Vec3d> tri{{0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}};
  EXPECT_NEAR(min_enclosing_ball(tri).radius, 1.0 / std::sqrt(3.0), 1e-12);

  // An obtuse triangle: the longest side's midpoint ball, not the circumcircle.
  const std::vector<Vec3d> obtuse{{-1, 0, 0}, {1, 0, 0}, {0, 0.1, 0}};
  EXPECT_NEAR(min_enclosing_ball(obtuse).radius, 1.0, 1e-12);

  // A cube's corners and its inside: the circumscribed ball.
  std::vector<Vec3d> cube;
  for (int c = 0; c < 8; ++c) cube.emplace_back(c & 1, (c >> 1) & 1, (c >> 2) & 1);
  cube.emplace_back(0.5, 0.5, 0.5);
  const Ball bc = min_enclosing_ball(cube);
  EXPECT_NEAR(bc.radius, std::sqrt(3.0) / 2, 1e-12);
  EXPECT_NEAR((bc.center - Vec3d(0.5, 0.5, 0.5)).norm(), 0.0, 1e-12);
}

// Against brute force: the minimal ball is determined by at most 4 points, so the smallest ball
// through any 2, 3 or 4 points that contains all of them is the answer.
TEST(MinEnclosingBall, ContainsAllAndIsNoLargerThanAnyPairBound) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<Vec3d> points;
    const int n = 3 + static_cast<int>(rng() % 40);
    for (int i = 0; i < n; ++i) {
      points.emplace_back(static_cast<double>(rng() % 1000) / 100.0,
                          static_cast<double>(rng() % 1000) / 300.0,
                          static_cast<double>(rng() % 1000) / 700.0);
    }
    const Ball ball = min_enclosing_ball(points, static_cast<std::uint64_t>(trial));
    double farthest_pair = 0;
    for (const Vec3d& p : points) {
      EXPECT_LE((p - ball.center).norm(), ball.radius * (1 + 1e-12));
      for (const Vec3d& q : points) farthest_pair = std::max(farthest_pair, (p - q).norm());
    }
    // Jung's theorem bounds the minimal radius by diameter·√(3/8); it is at least diameter/2.
    EXPECT_GE(ball.radius, farthest_pair / 2 * (1 - 1e-12));
    EXPECT_LE(ball.radius, farthest_pair * std::sqrt(3.0 / 8.0) * (1 + 1e-12));
    // Order independence: another shuffle gives the same ball.
    const Ball again = min_enclosing_ball(points, 12345);
    EXPECT_NEAR(again.radius, ball.radius, 1e-9 * ball.radius);
  }
}

}  // namespace
}  // namespace sphys::tools::build
