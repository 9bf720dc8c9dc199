#include "sphys/tools/mesh_query.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <random>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/primitives.h"
#include "sphys/tools/winding_number.h"

namespace sphys::tools {
namespace {

// Fixed-seed points spread uniformly over a cube of half-side `half` around the origin.
std::vector<Vec3d> random_points(std::size_t count, double half, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  const auto coordinate = [&] {
    const double unit = static_cast<double>(engine() >> 11) * 0x1.0p-53;  // [0, 1)
    return half * (2.0 * unit - 1.0);
  };
  std::vector<Vec3d> points(count);
  for (Vec3d& p : points) {
    const double x = coordinate();
    const double y = coordinate();
    p = Vec3d(x, y, coordinate());
  }
  return points;
}

// Exact signed distance to an axis-aligned box of the given half sides around the origin.
double box_signed_distance(const Vec3d& half, const Vec3d& p) {
  const Vec3d q = p.cwiseAbs() - half;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

// Exact signed distance to the torus make_torus approximates (ring about the y axis).
double torus_signed_distance(double major, double minor, const Vec3d& p) {
  const double ring = std::hypot(p.x(), p.z()) - major;
  return std::hypot(ring, p.y()) - minor;
}

// How far the icosphere's facets sink below its sphere: the largest sagitta over the triangles,
// the sphere's depth at the triangle's circumcentre.
double icosphere_sag(const TriangleMesh& mesh, double radius) {
  double sag = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Vec3d a = mesh.corner(t, 0);
    const Vec3d b = mesh.corner(t, 1);
    const Vec3d c = mesh.corner(t, 2);
    const double circumradius =
        (b - a).norm() * (c - b).norm() * (a - c).norm() / (2.0 * mesh.area_normal(t).norm());
    sag = std::max(sag, radius - std::sqrt(radius * radius - circumradius * circumradius));
  }
  return sag;
}

TEST(MeshQuery, BoxDistancesMatchTheExactBox) {
  const Vec3d half(1.0, 0.5, 0.25);
  const MeshQuery query(make_box(2.0 * half));
  int inside = 0;
  for (const Vec3d& p : random_points(2000, 2.0, 1)) {
    const double expected = box_signed_distance(half, p);
    EXPECT_NEAR(query.signed_distance(p), expected, 1e-12) << p.transpose();
    EXPECT_NEAR(query.distance(p), std::abs(expected), 1e-12);
    EXPECT_EQ(query.inside(p), expected < 0.0);
    const Vec3d closest = query.closest_point(p);
    EXPECT_NEAR(box_signed_distance(half, closest), 0.0, 1e-12);  // on the surface
    EXPECT_NEAR((closest - p).norm(), std::abs(expected), 1e-12);
    inside += expected < 0.0 ? 1 : 0;
  }
  EXPECT_GT(inside, 20);  // both sides were tried
}

TEST(MeshQuery, BoxSurfacePointsAreInsideAtDistanceZero) {
  const MeshQuery query(make_box(Vec3d(2.0, 2.0, 2.0)));
  for (const Vec3d& p : {Vec3d(1.0, 0.3, -0.2), Vec3d(1.0, 1.0, 0.0), Vec3d(1.0, 1.0, 1.0)}) {
    EXPECT_TRUE(query.inside(p)) << p.transpose();
    EXPECT_DOUBLE_EQ(query.signed_distance(p), 0.0);
  }
}

TEST(MeshQuery, IcosphereDistancesMatchTheSphereWithinTheFacetSag) {
  constexpr double kRadius = 1.5;
  const TriangleMesh sphere = make_icosphere(kRadius, 4);
  const double sag = icosphere_sag(sphere, kRadius);
  ASSERT_LT(sag, 0.01);
  const MeshQuery query(sphere);
  for (const Vec3d& p : random_points(2000, 3.0, 2)) {
    const double exact = p.norm() - kRadius;
    // The facets lie between the sphere and `sag` below it, so the mesh's signed distance is
    // the sphere's plus something in [0, sag].
    const double measured = query.signed_distance(p);
    EXPECT_GE(measured, exact - 1e-12) << p.transpose();
    EXPECT_LE(measured, exact + sag + 1e-12) << p.transpose();
    const Vec3d closest = query.closest_point(p);
    EXPECT_NEAR(closest.norm(), kRadius - 0.5 * sag, 0.5 * sag + 1e-12);
  }
}

TEST(MeshQuery, SphereInsideMatchesAnalytic) {
  constexpr double kRadius = 1.0;
  const TriangleMesh sphere = make_icosphere(kRadius, 3);
  const double margin = icosphere_sag(sphere, kRadius) + 1e-9;
  const MeshQuery query(sphere);
  int checked = 0;
  for (const Vec3d& p : random_points(5000, 1.5, 3)) {
    const double exact = p.norm() - kRadius;
    if (exact < 0.0 && exact > -margin) continue;  // between the facets and the sphere
    EXPECT_EQ(query.inside(p), exact < 0.0) << p.transpose();
    ++checked;
  }
  EXPECT_GT(checked, 4500);
}

TEST(MeshQuery, TorusInsideMatchesAnalyticAndItsHoleIsOutside) {
  constexpr double kMajor = 1.0;
  constexpr double kMinor = 0.4;
  constexpr int kRings = 48;
  constexpr int kSides = 24;
  const MeshQuery query(make_torus(kMajor, kMinor, kRings, kSides));
  // The polygonal tube lies within the tube's sag plus the ring's sag of the exact torus.
  const double margin = kMinor * (1.0 - std::cos(std::numbers::pi / kSides)) +
                        (kMajor + kMinor) * (1.0 - std::cos(std::numbers::pi / kRings)) + 1e-9;
  int inside = 0;
  int outside = 0;
  for (const Vec3d& p : random_points(5000, 1.6, 4)) {
    const double exact = torus_signed_distance(kMajor, kMinor, p);
    if (std::abs(exact) < margin) continue;
    EXPECT_EQ(query.inside(p), exact < 0.0) << p.transpose();
    ++(exact < 0.0 ? inside : outside);
  }
  EXPECT_GT(inside, 200);
  EXPECT_GT(outside, 200);
  // The hole: the centre and the axis through it.
  for (const double y : {-0.5, 0.0, 0.3}) {
    const Vec3d p(0.0, y, 0.0);
    EXPECT_FALSE(query.inside(p));
    EXPECT_NEAR(query.signed_distance(p), torus_signed_distance(kMajor, kMinor, p), margin);
  }
}

TEST(MeshQuery, OpenMeshStillClassifiesPointsAwayFromTheHoles) {
  constexpr double kRadius = 1.0;
  TriangleMesh open = make_icosphere(kRadius, 3);
  // Remove a few scattered triangles: the mesh is no longer watertight.
  for (const std::size_t t : {1200u, 900u, 512u, 17u}) {
    open.triangles.erase(open.triangles.begin() + static_cast<std::ptrdiff_t>(t));
  }
  const MeshQuery query(open);
  int checked = 0;
  for (const Vec3d& p : random_points(3000, 3.0, 5)) {
    const double r = p.norm();
    if (r > 0.5 * kRadius && r < 1.5 * kRadius) continue;
    EXPECT_EQ(query.inside(p), r < kRadius) << p.transpose();
    // Holes do not change the distance from points this far in or out by more than the sag.
    EXPECT_NEAR(query.distance(p), std::abs(r - kRadius), 0.02) << p.transpose();
    ++checked;
  }
  EXPECT_GT(checked, 1000);
  EXPECT_TRUE(query.inside(Vec3d::Zero()));
}

TEST(MeshQuery, OpenMeshInsideAgreesWithTheWindingNumber) {
  // A torus with a band of its tube cut away: around the cut the winding number takes every
  // value between 0 and 1, so both the fast path and the exact fallback are exercised.
  constexpr int kRings = 48;
  constexpr int kSides = 24;
  TriangleMesh cut = make_torus(1.0, 0.4, kRings, kSides);
  // Each ring contributes 2 · kSides triangles, in ring order: drop three rings' worth.
  cut.triangles.erase(cut.triangles.begin(), cut.triangles.begin() + 3 * 2 * kSides);
  const MeshQuery query(cut);
  int near_half = 0;
  for (const Vec3d& p : random_points(3000, 1.6, 7)) {
    const double w = winding_number(cut, p);
    EXPECT_EQ(query.inside(p), w >= 0.5) << p.transpose() << " w = " << w;
    near_half += std::abs(w - 0.5) < 0.25 ? 1 : 0;
  }
  EXPECT_GT(near_half, 10);
}

TEST(MeshQuery, CubesSharingOneCornerAreQueriedAsTwoSolids) {
  // Every edge has two triangles, but the shared corner is not a manifold vertex, so the mesh
  // cannot become a halfedge structure: inside tests fall back to the winding number.
  const TriangleMesh unit = make_box(Vec3d(1.0, 1.0, 1.0));
  TriangleMesh pair;
  for (const double side : {-0.5, 0.5}) {
    const auto base = static_cast<std::uint32_t>(pair.vertices.size());
    for (const Vec3d& v : unit.vertices) pair.vertices.push_back(v + Vec3d::Constant(side));
    for (Triangle t : unit.triangles) {
      for (std::uint32_t& v : t) v += base;
      pair.triangles.push_back(t);
    }
  }
  // Weld the second cube's corner at the origin (vertex 0 of make_box) onto the first's (7).
  pair.vertices.erase(pair.vertices.begin() + 8);
  for (std::size_t t = 12; t < pair.triangles.size(); ++t) {
    for (std::uint32_t& v : pair.triangles[t]) v = v == 8 ? 7 : (v > 8 ? v - 1 : v);
  }
  ASSERT_EQ(pair.vertices[7], Vec3d::Zero());

  const MeshQuery query(pair);
  EXPECT_TRUE(query.inside(Vec3d(-0.5, -0.5, -0.5)));
  EXPECT_TRUE(query.inside(Vec3d(0.5, 0.5, 0.5)));
  EXPECT_FALSE(query.inside(Vec3d(0.5, -0.5, 0.5)));
  EXPECT_FALSE(query.inside(Vec3d(-0.5, 0.5, 0.5)));
  EXPECT_NEAR(query.signed_distance(Vec3d(0.5, 0.5, 0.4)), -0.4, 1e-12);
  EXPECT_NEAR(query.signed_distance(Vec3d(0.5, -0.5, 0.5)), 0.5, 1e-12);
}

TEST(MeshQuery, ConcurrentQueriesMatchSerialOnes) {
  const MeshQuery watertight(make_torus(1.0, 0.4, 32, 16));
  TriangleMesh holed = make_icosphere(1.0, 2);
  holed.triangles.erase(holed.triangles.begin() + 7);
  const MeshQuery open(holed);
  const std::vector<Vec3d> points = random_points(2000, 1.6, 6);

  struct Answer {
    Vec3d closest;
    bool inside = false;
    double signed_distance = 0.0;
  };
  const auto answer = [&](const MeshQuery& query, std::size_t i) {
    return Answer{query.closest_point(points[i]), query.inside(points[i]),
                  query.signed_distance(points[i])};
  };
  for (const MeshQuery* query : {&watertight, &open}) {
    std::vector<Answer> serial(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) serial[i] = answer(*query, i);

    constexpr std::size_t kThreads = 4;
    std::vector<Answer> parallel(points.size());
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < kThreads; ++k) {
      // Interleaved, so that the threads query neighbouring points at the same time.
      threads.emplace_back([&, k] {
        for (std::size_t i = k; i < points.size(); i += kThreads) parallel[i] = answer(*query, i);
      });
    }
    for (std::thread& thread : threads) thread.join();
    for (std::size_t i = 0; i < points.size(); ++i) {
      EXPECT_EQ(parallel[i].closest, serial[i].closest) << i;
      EXPECT_EQ(parallel[i].inside, serial[i].inside) << i;
      EXPECT_EQ(parallel[i].signed_distance, serial[i].signed_distance) << i;
    }
  }
}

TEST(MeshQuery, OwnsACopyOfTheMeshAndSurvivesAMove) {
  TriangleMesh box = make_box(Vec3d(2.0, 2.0, 2.0));
  MeshQuery query(box);
  box.vertices.clear();
  const MeshQuery moved(std::move(query));
  EXPECT_EQ(moved.mesh().vertices.size(), 8u);
  EXPECT_EQ(moved.mesh().name, "box");
  EXPECT_DOUBLE_EQ(moved.distance(Vec3d(3.0, 0.0, 0.0)), 2.0);
}

TEST(MeshQuery, RejectsMeshesItCannotQuery) {
  TriangleMesh empty;
  empty.name = "empty.obj";
  EXPECT_THROW({ const MeshQuery query(empty); }, Error);

  TriangleMesh bad_index = make_box(Vec3d(1.0, 1.0, 1.0));
  bad_index.triangles[3][1] = 99;
  EXPECT_THROW({ const MeshQuery query(bad_index); }, Error);

  TriangleMesh not_finite = make_box(Vec3d(1.0, 1.0, 1.0));
  not_finite.vertices[2].x() = std::nan("");
  EXPECT_THROW({ const MeshQuery query(not_finite); }, Error);
}

}  // namespace
}  // namespace sphys::tools
