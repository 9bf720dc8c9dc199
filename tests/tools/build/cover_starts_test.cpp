// The Tight method's other starts and the descent's growing of balls, against covers worked out
// by hand.
#include "tools/build/cover_starts.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/tools/mesh_query.h"
#include "sphys/tools/primitives.h"
#include "tools/build/ball.h"
#include "tools/build/exterior_lattice.h"
#include "tools/build/volume_descent.h"

namespace sphys::tools::build {
namespace {

// `count` points spread over a sphere's surface.
std::vector<Vec3d> sphere_points(const Vec3d& center, double radius, std::size_t count,
                                 std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> gauss;
  std::vector<Vec3d> points;
  for (std::size_t i = 0; i < count; ++i) {
    points.push_back(center +
                     radius * Vec3d(gauss(random), gauss(random), gauss(random)).normalized());
  }
  return points;
}

bool every_point_in_a_ball(const std::vector<Vec3d>& points, const std::vector<Ball>& balls) {
  return std::all_of(points.begin(), points.end(), [&](const Vec3d& p) {
    return std::any_of(balls.begin(), balls.end(), [&](const Ball& b) { return b.contains(p); });
  });
}

// Four small spheres far apart. k-means++ seeding draws each new centre with probability
// proportional to the squared distance to the nearest one drawn, so it almost always puts one in
// each sphere, and Lloyd's rounds then centre one ball on each sphere with its radius; a seed that
// draws two in one sphere ends with a ball across two spheres. Nearly every seed must do the
// former, and every seed must cover every point with four balls.
TEST(ClusteredStart, GivesEachOfFourFarApartSpheresItsOwnBall) {
  const Vec3d centers[] = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}};
  std::vector<Vec3d> points;
  for (std::size_t c = 0; c < 4; ++c) {
    const std::vector<Vec3d> part = sphere_points(centers[c], 1.0, 200, c + 1);
    points.insert(points.end(), part.begin(), part.end());
  }
  int found = 0;
  constexpr int kSeeds = 20;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const std::vector<Ball> balls = clustered_start(points, 4, seed);
    ASSERT_EQ(balls.size(), 4U) << "seed " << seed;
    EXPECT_TRUE(every_point_in_a_ball(points, balls)) << "seed " << seed;
    const bool each_its_own =
        std::all_of(std::begin(centers), std::end(centers), [&](const Vec3d& c) {
          return std::any_of(balls.begin(), balls.end(), [&](const Ball& b) {
            return (b.center - c).norm() < 0.1 && std::abs(b.radius - 1.0) < 0.1;
          });
        });
    if (each_its_own) ++found;
  }
  EXPECT_GE(found, kSeeds - 2);
  // The same seed, the same start.
  const std::vector<Ball> once = clustered_start(points, 4, 7);
  const std::vector<Ball> again = clustered_start(points, 4, 7);
  ASSERT_EQ(once.size(), again.size());
  for (std::size_t k = 0; k < once.size(); ++k) {
    EXPECT_EQ(once[k].center, again[k].center);
    EXPECT_EQ(once[k].radius, again[k].radius);
  }
}

// Fewer distinct points than clusters: as many balls as there are points, each of radius 0.
TEST(ClusteredStart, NeverMakesMoreBallsThanThereAreDistinctPoints) {
  const std::vector<Vec3d> points = {{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 0, 0}};
  const std::vector<Ball> balls = clustered_start(points, 8, 1);
  EXPECT_EQ(balls.size(), 2U);
  EXPECT_TRUE(every_point_in_a_ball(points, balls));
}

// The surface of a rod 7.9 long and 1 across, sampled on a grid of 0.1 along it: the 8×1×1 start
// cuts it into 8 slabs 7.9 / 8 = 0.9875 wide, so slab k holds the grid's points i = ceil(9.875 k)
// ... ceil(9.875 (k + 1)) - 1 (no point lies on a cut; the last slab ends at i = 79), and its ball
// is centred on the middle of those points with the half diagonal of their box as radius. 4×2×1,
// 4×1×2 and 2×2×2 come with it.
TEST(SlabStarts, CutARodIntoEqualSlabsAlongItsLength) {
  std::vector<Vec3d> points;
  for (int i = 0; i < 80; ++i) {
    for (int j = 0; j <= 10; ++j) {
      const double x = -3.95 + 0.1 * i;
      const double t = -0.5 + 0.1 * j;
      for (const Vec3d& p :
           {Vec3d(x, t, -0.5), Vec3d(x, t, 0.5), Vec3d(x, -0.5, t), Vec3d(x, 0.5, t)}) {
        points.push_back(p);
      }
    }
  }
  const std::vector<std::vector<Ball>> starts = slab_starts(points, 8);
  ASSERT_EQ(starts.size(), 4U);
  for (const std::vector<Ball>& start : starts) {
    EXPECT_EQ(start.size(), 8U);
    EXPECT_TRUE(every_point_in_a_ball(points, start));
  }
  // The enumeration ends with the most cuts along the longest axis.
  std::vector<Ball> rod = starts.back();
  ASSERT_EQ(rod.size(), 8U);
  std::sort(rod.begin(), rod.end(),
            [](const Ball& a, const Ball& b) { return a.center.x() < b.center.x(); });
  for (int k = 0; k < 8; ++k) {
    const double first = std::ceil(9.875 * k);
    const double last = k == 7 ? 79.0 : std::ceil(9.875 * (k + 1)) - 1.0;
    const double length = 0.1 * (last - first);
    EXPECT_NEAR(rod[k].center.x(), -3.95 + 0.1 * (first + last) / 2.0, 1e-6) << "slab " << k;
    EXPECT_NEAR(rod[k].center.y(), 0.0, 1e-6);
    EXPECT_NEAR(rod[k].center.z(), 0.0, 1e-6);
    EXPECT_NEAR(rod[k].radius, std::sqrt(length * length / 4.0 + 0.5), 1e-6) << "slab " << k;
  }
}

// Two unit spheres 6 apart, split first into 4 clusters each (over-clustered from 4 to 8), then
// merged down to 2 under a limit that a ball around both spheres breaks: one ball per sphere.
TEST(MergedStart, MergesWithinEachOfTwoSpheresRatherThanAcross) {
  TriangleMesh mesh = make_icosphere(1.0, 3);
  const TriangleMesh other = make_icosphere(1.0, 3);
  const auto offset = static_cast<std::uint32_t>(mesh.vertices.size());
  for (const Vec3d& v : other.vertices) mesh.vertices.push_back(v + Vec3d(6, 0, 0));
  for (const Triangle& t : other.triangles) {
    mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  }
  const MeshQuery query(mesh);
  const ExteriorLattice lattice(query, 40000, 1.5);
  std::vector<Vec3d> points = sphere_points(Vec3d::Zero(), 1.0, 300, 1);
  const std::vector<Vec3d> right = sphere_points(Vec3d(6, 0, 0), 1.0, 300, 2);
  points.insert(points.end(), right.begin(), right.end());
  const std::vector<Vec3d> directions = evenly_spread_directions(96);

  const std::vector<Ball> balls = merged_start(points, 2, 4, lattice, directions, 0.5, 3);
  ASSERT_EQ(balls.size(), 2U);
  EXPECT_TRUE(every_point_in_a_ball(points, balls));
  for (const Vec3d& c : {Vec3d(0, 0, 0), Vec3d(6, 0, 0)}) {
    const bool one_there = std::any_of(balls.begin(), balls.end(), [&](const Ball& b) {
      return (b.center - c).norm() < 0.1 && std::abs(b.radius - 1.0) < 0.1;
    });
    EXPECT_TRUE(one_there) << "no ball around the sphere at x = " << c.x();
  }
}

// Two balls that leave points out: each point in turn goes to the ball it lies least far outside
// of (as grown so far), which grows just enough to hold it; a ball that need not grow keeps its
// size.
TEST(VolumeDescent, GrowsTheNearestBallsJustEnoughToCoverEveryPoint) {
  const TriangleMesh box = make_box({4.0, 1.0, 1.0});
  const MeshQuery query(box);
  const ExteriorLattice lattice(query, 20000, 1.0);
  const std::vector<Vec3d> directions = evenly_spread_directions(96);
  const std::vector<Vec3d> points = {
      {-1.5, 0, 0}, {-1.0, 0, 0}, {1.0, 0, 0}, {2.0, 0, 0}, {0.1, 0, 0}};
  const std::vector<Ball> balls = {{Vec3d(-1.5, 0, 0), 0.6}, {Vec3d(1.5, 0, 0), 0.2}};
  VolumeDescent descent(lattice, directions, points, balls, 10.0);
  descent.grow_to_cover();
  const std::vector<Ball>& grown = descent.balls();
  // (-1.5, 0, 0) and (-1, 0, 0) lie in the left ball. (1, 0, 0) lies 0.3 outside the right ball
  // (1.9 outside the left): the right grows to 0.5, which holds (2, 0, 0). (0.1, 0, 0) then lies
  // 0.9 outside the grown right ball and 1.0 outside the left: the right grows to 1.4.
  EXPECT_EQ(grown[0].radius, 0.6);
  EXPECT_NEAR(grown[1].radius, 1.4, 1e-9);
  EXPECT_EQ(grown[0].center, balls[0].center);
  EXPECT_EQ(grown[1].center, balls[1].center);
  EXPECT_TRUE(every_point_in_a_ball(points, grown));
}

}  // namespace
}  // namespace sphys::tools::build
