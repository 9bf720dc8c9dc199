#include "tools/build/exterior_lattice.h"

#include <cmath>
#include <cstddef>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/tools/mesh_query.h"
#include "sphys/tools/primitives.h"
#include "tools/build/ball.h"

namespace sphys::tools::build {
namespace {

// The unit sphere as 1,280 triangles: its signed distance is |p| - 1 up to the facets' sag.
struct UnitSphere {
  TriangleMesh mesh = make_icosphere(1.0, 3);
  MeshQuery query{mesh};
  ExteriorLattice lattice{query, 20000, 0.5};
};

// Every outside lattice point, with its position and its stored distance, from a ball that holds
// the whole lattice.
std::vector<std::pair<Vec3d, double>> all_outside_points(const ExteriorLattice& lattice) {
  std::vector<std::pair<Vec3d, double>> points;
  const Ball everything{Vec3d::Zero(), 100.0};
  lattice.for_each_outside_at(everything, [&](std::size_t, const Vec3d& p) {
    points.emplace_back(p, lattice.distance_at(p));
  });
  return points;
}

TEST(ExteriorLattice, StoresTheSignedDistanceOfEachPoint) {
  const UnitSphere s;
  const auto points = all_outside_points(s.lattice);
  ASSERT_GT(points.size(), 1000U);
  for (const auto& [p, distance] : points) {
    // At a lattice point the interpolation is the stored value, a float of the query's answer.
    EXPECT_NEAR(distance, s.query.signed_distance(p), 1e-6);
    EXPECT_GT(distance, 0.0);
  }
}

TEST(ExteriorLattice, VisitsExactlyTheOutsidePointsInABall) {
  const UnitSphere s;
  const auto points = all_outside_points(s.lattice);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coordinate(-1.2, 1.2);
  std::uniform_real_distribution<double> radius(0.1, 0.9);
  for (int trial = 0; trial < 20; ++trial) {
    const Ball ball{Vec3d(coordinate(rng), coordinate(rng), coordinate(rng)), radius(rng)};
    std::size_t visited = 0;
    double largest = 0.0;
    s.lattice.for_each_outside(ball, [&](std::size_t index, double distance) {
      EXPECT_LT(index, s.lattice.size());
      ++visited;
      largest = std::max(largest, distance);
    });
    std::size_t expected = 0;
    double expected_largest = 0.0;
    for (const auto& [p, distance] : points) {
      if ((p - ball.center).squaredNorm() <= ball.radius * ball.radius) {
        ++expected;
        expected_largest = std::max(expected_largest, distance);
      }
    }
    EXPECT_EQ(visited, expected) << "trial " << trial;
    EXPECT_NEAR(largest, expected_largest, 1e-6) << "trial " << trial;
  }
}

// The signed distance is 1-Lipschitz, so between lattice points its interpolation is off by at
// most the distance to the farthest corner of the cell, √3 spacings.
TEST(ExteriorLattice, InterpolatesTheDistanceBetweenPoints) {
  const UnitSphere s;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coordinate(-1.4, 1.4);
  for (int k = 0; k < 2000; ++k) {
    const Vec3d p(coordinate(rng), coordinate(rng), coordinate(rng));
    EXPECT_NEAR(s.lattice.distance_at(p), s.query.signed_distance(p),
                std::sqrt(3.0) * s.lattice.spacing());
  }
  EXPECT_TRUE(std::isinf(s.lattice.distance_at(Vec3d(5.0, 0.0, 0.0))));
}

TEST(ExteriorLattice, ARefinedLatticeAgreesWithItsParent) {
  const UnitSphere s;
  const Box3d region(Vec3d(-0.2, 0.3, -0.4), Vec3d(0.6, 1.3, 0.5));
  const ExteriorLattice fine = s.lattice.refined(3, region);
  EXPECT_NEAR(fine.spacing(), s.lattice.spacing() / 3.0, 1e-15);
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> t(0.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    const Vec3d p = region.min() + Vec3d(t(rng), t(rng), t(rng)).cwiseProduct(region.sizes());
    // Both are interpolations of the same distances: the fine lattice's points carry the
    // parent's interpolated values, so the two differ by the parent's curvature within a cell.
    EXPECT_NEAR(fine.distance_at(p), s.lattice.distance_at(p), s.lattice.spacing());
    EXPECT_NEAR(fine.distance_at(p), s.query.signed_distance(p),
                std::sqrt(3.0) * s.lattice.spacing());
  }
  // Outside the region the fine lattice knows nothing.
  EXPECT_TRUE(std::isinf(fine.distance_at(Vec3d(-0.9, -0.9, -0.9))));
}

TEST(ExteriorLattice, MeasuresHowFarABallPokesOut) {
  const UnitSphere s;
  const std::vector<Vec3d> directions = evenly_spread_directions(200);
  // Centred: it pokes out by 0.3 everywhere. Off centre by 0.2: by 0.5 on the far side.
  EXPECT_NEAR(s.lattice.protrusion({Vec3d::Zero(), 1.3}, directions), 0.3, s.lattice.spacing());
  EXPECT_NEAR(s.lattice.protrusion({Vec3d(0.2, 0.0, 0.0), 1.3}, directions), 0.5,
              s.lattice.spacing());
  // Inside: negative, the depth of its deepest boundary point's shortfall.
  EXPECT_NEAR(s.lattice.protrusion({Vec3d::Zero(), 0.5}, directions), -0.5, s.lattice.spacing());
}

}  // namespace
}  // namespace sphys::tools::build
