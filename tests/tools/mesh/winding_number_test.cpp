#include "sphys/tools/winding_number.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/tools/primitives.h"
#include "support/mesh_edit.h"

namespace sphys::tools {
namespace {

// Fixed-seed points spread uniformly over a cube of half-side `half` around the origin.
std::vector<Vec3d> random_points(std::size_t count, double half) {
  std::mt19937 engine(20240611);
  std::uniform_real_distribution<double> coordinate(-half, half);
  std::vector<Vec3d> points(count);
  for (Vec3d& p : points) p = Vec3d(coordinate(engine), coordinate(engine), coordinate(engine));
  return points;
}

using test::without_triangles;

Vec3d centroid(const TriangleMesh& mesh, std::size_t t) {
  return (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0;
}

// Every point of `points` away from the surface (margin > 0) reads exactly 1 inside, 0 outside.
void expect_exact_inside_outside(const TriangleMesh& mesh, const std::vector<Vec3d>& points,
                                 const std::function<double(const Vec3d&)>& signed_distance) {
  int inside = 0;
  int outside = 0;
  for (const Vec3d& p : points) {
    const double distance = signed_distance(p);  // negative inside
    if (std::abs(distance) < 0.03) continue;     // the facets lie within 0.01 of the surface
    const double expected = distance < 0.0 ? 1.0 : 0.0;
    ++(distance < 0.0 ? inside : outside);
    EXPECT_NEAR(winding_number(mesh, p), expected, 1e-9) << p.transpose();
    EXPECT_EQ(is_inside(mesh, p), distance < 0.0);
  }
  // Both kinds were actually tried.
  EXPECT_GT(inside, 50);
  EXPECT_GT(outside, 50);
}

TEST(WindingNumber, OctantTriangleSubtendsAnEighthOfTheSphere) {
  // The triangle on the three unit axes cuts one octant; its normal (1,1,1) faces away from the
  // origin, so the origin is behind it and the angle is positive.
  TriangleMesh octant;
  octant.vertices = {Vec3d::UnitX(), Vec3d::UnitY(), Vec3d::UnitZ()};
  octant.triangles = {{0, 1, 2}};
  EXPECT_NEAR(winding_number(octant, Vec3d::Zero()), 1.0 / 8.0, 1e-15);
  octant.triangles = {{0, 2, 1}};
  EXPECT_NEAR(winding_number(octant, Vec3d::Zero()), -1.0 / 8.0, 1e-15);
}

TEST(WindingNumber, OneInsideZeroOutsideAClosedIcosphere) {
  const TriangleMesh sphere = make_icosphere(1.0, 3);
  expect_exact_inside_outside(sphere, random_points(500, 1.5),
                              [](const Vec3d& p) { return p.norm() - 1.0; });
}

TEST(WindingNumber, OneInsideZeroOutsideAClosedTorusAndItsHole) {
  const double major = 1.0;
  const double minor = 0.4;
  const TriangleMesh torus = make_torus(major, minor, 48, 24);
  const auto tube_distance = [&](const Vec3d& p) {
    return std::hypot(std::hypot(p.x(), p.z()) - major, p.y()) - minor;
  };
  expect_exact_inside_outside(torus, random_points(1000, 1.6), tube_distance);
  // The hole in the middle is outside, and so is a point on the axis above it.
  EXPECT_NEAR(winding_number(torus, Vec3d::Zero()), 0.0, 1e-12);
  EXPECT_NEAR(winding_number(torus, Vec3d(0.0, 0.3, 0.0)), 0.0, 1e-12);
  EXPECT_NEAR(winding_number(torus, Vec3d(major, 0.0, 0.0)), 1.0, 1e-12);
}

TEST(WindingNumber, OnTheSurfaceReadsTheFractionOfSolidAngleInside) {
  // Unit box: half a sphere on a face, a quarter on an edge, an eighth at a corner.
  const TriangleMesh box = make_box(Vec3d(1.0, 1.0, 1.0));
  EXPECT_NEAR(winding_number(box, Vec3d(0.5, 0.1, 0.2)), 0.5, 1e-12);
  EXPECT_NEAR(winding_number(box, Vec3d(0.5, 0.5, 0.1)), 0.25, 1e-12);
  EXPECT_NEAR(winding_number(box, Vec3d(0.5, 0.5, 0.5)), 0.125, 1e-12);
  EXPECT_NEAR(winding_number(box, Vec3d(1e3, -2e3, 5e2)), 0.0, 1e-12);
}

TEST(WindingNumber, FiniteNextToAndOnVertices) {
  const TriangleMesh sphere = make_icosphere(1.0, 2);
  for (const Vec3d& v : sphere.vertices) {
    for (const double offset : {0.0, 1e-300, 1e-12}) {
      const double w = winding_number(sphere, v * (1.0 - offset));
      EXPECT_TRUE(std::isfinite(w));
      EXPECT_GE(w, -1e-9);
      EXPECT_LE(w, 1.0 + 1e-9);
    }
  }
}

TEST(WindingNumber, HalfAcrossTheHoleOfARemovedTriangle) {
  const TriangleMesh sphere = make_icosphere(1.0, 2);
  // At the centroid of the missing triangle the rest of the sphere covers exactly half of the
  // directions (what the closed sphere reads on its surface).
  const TriangleMesh one_missing = without_triangles(sphere, {0});
  EXPECT_NEAR(winding_number(one_missing, centroid(sphere, 0)), 0.5, 1e-12);
  // Three adjacent triangles missing (0 and 1 share an edge each with 3): about 1/2 at the
  // middle one's centroid, less the little the missing neighbours subtend (measured 0.479).
  const TriangleMesh three_missing = without_triangles(sphere, {0, 1, 3});
  EXPECT_NEAR(winding_number(three_missing, centroid(sphere, 3)), 0.5, 0.03);
}

TEST(WindingNumber, DegradesGracefullyAroundASmallHole) {
  const TriangleMesh sphere = make_icosphere(1.0, 2);
  const TriangleMesh holed = without_triangles(sphere, {0, 1, 3});
  for (const Vec3d& p : random_points(400, 3.0)) {
    if (p.norm() < 0.5) {
      EXPECT_GE(winding_number(holed, p), 0.9) << p.transpose();
    } else if (p.norm() > 2.0) {
      EXPECT_LE(std::abs(winding_number(holed, p)), 0.1) << p.transpose();
    }
  }
  // Deep inside, right below the hole: the hole subtends the most there.
  const Vec3d toward_hole = centroid(sphere, 3).normalized();
  EXPECT_GE(winding_number(holed, 0.5 * toward_hole), 0.9);
  EXPECT_LE(winding_number(holed, 2.0 * toward_hole), 0.1);
}

}  // namespace
}  // namespace sphys::tools
