#include "sphys/tools/primitives.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <tuple>
#include <utility>

#include <gtest/gtest.h>

#include "sphys/error.h"

namespace sphys::tools {
namespace {

// Closed and consistently oriented: every directed edge is used exactly once, and its reverse
// exactly once by a neighbour.
bool closed_and_oriented(const TriangleMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const Triangle& t : mesh.triangles) {
    for (std::size_t k = 0; k < 3; ++k) ++uses[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : uses) {
    const auto reverse = uses.find({edge.second, edge.first});
    if (count != 1 || reverse == uses.end() || reverse->second != 1) return false;
  }
  return true;
}

// No two vertices at the same position.
bool welded(const TriangleMesh& mesh) {
  std::map<std::tuple<double, double, double>, int> seen;
  for (const Vec3d& v : mesh.vertices) {
    if (++seen[{v.x(), v.y(), v.z()}] > 1) return false;
  }
  return true;
}

Vec3d centroid(const TriangleMesh& mesh, std::size_t t) {
  return (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0;
}

// For a convex solid around the origin: every normal points away from the centre.
bool outward_from_origin(const TriangleMesh& mesh) {
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (mesh.area_normal(t).dot(centroid(mesh, t)) <= 0.0) return false;
  }
  return true;
}

TEST(Primitives, BoxHasTwelveOutwardTrianglesAndTheGivenSides) {
  const TriangleMesh box = make_box(Vec3d(2.0, 3.0, 5.0));
  EXPECT_EQ(box.vertices.size(), 8u);
  EXPECT_EQ(box.triangles.size(), 12u);
  EXPECT_TRUE(closed_and_oriented(box));
  EXPECT_TRUE(outward_from_origin(box));
  EXPECT_TRUE(box.bounds().min().isApprox(Vec3d(-1.0, -1.5, -2.5)));
  EXPECT_TRUE(box.bounds().max().isApprox(Vec3d(1.0, 1.5, 2.5)));
  // Each face's two triangles together have the face's area.
  double area = 0.0;
  for (std::size_t t = 0; t < box.triangles.size(); ++t) area += 0.5 * box.area_normal(t).norm();
  EXPECT_NEAR(area, 2.0 * (2.0 * 3.0 + 3.0 * 5.0 + 5.0 * 2.0), 1e-12);
}

TEST(Primitives, IcosphereIsSubdividedWeldedAndOnTheSphere) {
  for (int s = 0; s <= 4; ++s) {
    SCOPED_TRACE(s);
    const TriangleMesh sphere = make_icosphere(2.5, s);
    const auto four_to_the_s = static_cast<std::size_t>(1) << (2 * s);
    EXPECT_EQ(sphere.triangles.size(), 20 * four_to_the_s);
    // Euler: V − E + F = 2 with E = 3F/2, so V = F/2 + 2 for a closed, welded mesh.
    EXPECT_EQ(sphere.vertices.size(), 10 * four_to_the_s + 2);
    EXPECT_TRUE(welded(sphere));
    EXPECT_TRUE(closed_and_oriented(sphere));
    EXPECT_TRUE(outward_from_origin(sphere));
    for (const Vec3d& v : sphere.vertices) EXPECT_NEAR(v.norm(), 2.5, 1e-12);
  }
}

TEST(Primitives, IcosahedronHasEqualEdges) {
  const TriangleMesh ico = make_icosphere(1.0, 0);
  // Circumradius of the regular icosahedron with edge a is a·sin(2π/5).
  const double edge = 1.0 / std::sin(2.0 * std::numbers::pi / 5.0);
  for (const Triangle& t : ico.triangles) {
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_NEAR((ico.vertices[t[k]] - ico.vertices[t[(k + 1) % 3]]).norm(), edge, 1e-12);
    }
  }
}

TEST(Primitives, TorusIsAClosedOutwardGridAroundY) {
  const double major = 1.5;
  const double minor = 0.5;
  const TriangleMesh torus = make_torus(major, minor, 16, 8);
  EXPECT_EQ(torus.vertices.size(), 16u * 8u);
  EXPECT_EQ(torus.triangles.size(), 2u * 16u * 8u);
  EXPECT_TRUE(welded(torus));
  EXPECT_TRUE(closed_and_oriented(torus));
  for (const Vec3d& v : torus.vertices) {
    const double rho = std::hypot(v.x(), v.z());  // distance from the y axis
    EXPECT_NEAR(std::hypot(rho - major, v.y()), minor, 1e-12);
  }
  // Outward: away from the tube's centre line (the circle of radius `major` in the x–z plane).
  for (std::size_t t = 0; t < torus.triangles.size(); ++t) {
    const Vec3d c = centroid(torus, t);
    const Vec3d axis_point = major * Vec3d(c.x(), 0.0, c.z()).normalized();
    EXPECT_GT(torus.area_normal(t).dot(c - axis_point), 0.0);
  }
}

TEST(Primitives, RejectImpossibleParameters) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)make_box(Vec3d(1.0, 0.0, 1.0)), Error);
  EXPECT_THROW((void)make_box(Vec3d(1.0, nan, 1.0)), Error);
  EXPECT_THROW((void)make_icosphere(-1.0, 2), Error);
  EXPECT_THROW((void)make_icosphere(1.0, -1), Error);
  EXPECT_THROW((void)make_icosphere(1.0, 9), Error);
  EXPECT_THROW((void)make_torus(0.5, 1.0, 16, 8), Error);
  EXPECT_THROW((void)make_torus(1.0, 0.0, 16, 8), Error);
  EXPECT_THROW((void)make_torus(1.0, 0.5, 2, 8), Error);
  EXPECT_THROW((void)make_torus(1.0, 0.5, 16, 2), Error);
}

}  // namespace
}  // namespace sphys::tools
