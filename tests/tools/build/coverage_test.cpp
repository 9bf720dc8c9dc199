#include "tools/build/coverage.h"

#include <gtest/gtest.h>

#include "sphys/tools/primitives.h"

namespace sphys::tools::build {
namespace {

// Brute-force check on a dense barycentric grid of every triangle.
bool covers(const std::vector<Ball>& balls, const TriangleMesh& mesh, int n) {
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int u = 0; u <= n; ++u) {
      for (int v = 0; u + v <= n; ++v) {
        const Vec3d p = mesh.corner(t, 0) + (mesh.corner(t, 1) - mesh.corner(t, 0)) * u / n +
                        (mesh.corner(t, 2) - mesh.corner(t, 0)) * v / n;
        bool inside = false;
        for (const Ball& b : balls) inside = inside || b.contains(p, 1e-12);
        if (!inside) return false;
      }
    }
  }
  return true;
}

TEST(EnsureCoverage, LeavesACoveringSetUnchanged) {
  const TriangleMesh box = make_box({1, 1, 1});
  std::vector<Ball> balls{{Vec3d::Zero(), std::sqrt(3.0) / 2}};
  EXPECT_EQ(ensure_coverage(balls, box, 1e-3), 0u);
  EXPECT_EQ(balls.front().radius, std::sqrt(3.0) / 2);
}

TEST(EnsureCoverage, GrowsTooSmallBallsJustEnough) {
  const TriangleMesh box = make_box({1, 1, 1});
  // Eight balls at the octant centres, too small to reach the cube's edges' midpoints.
  std::vector<Ball> balls;
  for (int c = 0; c < 8; ++c) {
    balls.push_back({Vec3d((c & 1) - 0.5, ((c >> 1) & 1) - 0.5, ((c >> 2) & 1) - 0.5) * 0.5, 0.3});
  }
  ASSERT_FALSE(covers(balls, box, 40));
  EXPECT_GT(ensure_coverage(balls, box, 1e-3), 0u);
  EXPECT_TRUE(covers(balls, box, 40));
  // Each ball must reach at most its octant's farthest surface point: the cube corner at
  // distance √3/4 from the octant centre.
  for (const Ball& b : balls) EXPECT_LE(b.radius, std::sqrt(3.0) / 4 + 1e-9);
}

TEST(EnsureCoverage, CoversASphereWithFarBalls) {
  const TriangleMesh sphere = make_icosphere(1.0, 2);
  std::vector<Ball> balls{{Vec3d(5, 0, 0), 0.1}, {Vec3d(-0.5, 0, 0), 0.2}};
  ensure_coverage(balls, sphere, 1e-3);
  EXPECT_TRUE(covers(balls, sphere, 12));
}

}  // namespace
}  // namespace sphys::tools::build
