// Parts thinner than the spacing of the surface samples: every method must still split them,
// level by level, and cover them.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/build_tree.h"
#include "sphys/tools/check_mesh.h"
#include "sphys/tools/mesh_query.h"
#include "sphys/tools/primitives.h"
#include "support/level_coverage.h"
#include "support/sanitized_run.h"
#include "tools/build/error_measure.h"
#include "tools/build/shrinking_ball.h"
#include "tools/build/surface_samples.h"

namespace sphys::tools::thin_parts_test {

// A cylinder around the y axis, `sides` quads around, with or without its two end caps (without
// them the surface is open and encloses no volume of its own). Outward-facing.
TriangleMesh cylinder(double radius, double length, int sides, bool caps) {
  TriangleMesh mesh;
  mesh.name = "cylinder";
  for (int k = 0; k < sides; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / sides;
    for (const double y : {-0.5 * length, 0.5 * length}) {
      mesh.vertices.emplace_back(radius * std::cos(angle), y, radius * std::sin(angle));
    }
  }
  const auto bottom = [&](int k) { return static_cast<std::uint32_t>(2 * (k % sides)); };
  const auto top = [&](int k) { return bottom(k) + 1; };
  for (int k = 0; k < sides; ++k) {
    mesh.triangles.push_back({bottom(k), top(k), bottom(k + 1)});
    mesh.triangles.push_back({bottom(k + 1), top(k), top(k + 1)});
  }
  if (caps) {
    const auto centre = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.emplace_back(0.0, -0.5 * length, 0.0);
    mesh.vertices.emplace_back(0.0, 0.5 * length, 0.0);
    for (int k = 0; k < sides; ++k) {
      mesh.triangles.push_back({centre, bottom(k), bottom(k + 1)});
      mesh.triangles.push_back({centre + 1, top(k + 1), top(k)});
    }
  }
  return mesh;
}

// A square sheet of zero thickness: two triangles, no inside at all.
TriangleMesh sheet() {
  TriangleMesh mesh;
  mesh.name = "sheet";
  mesh.vertices = {{-0.5, 0, -0.5}, {0.5, 0, -0.5}, {0.5, 0, 0.5}, {-0.5, 0, 0.5}};
  mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
  return mesh;
}

// Two unit cubes that share one edge only: four triangles meet at it.
TriangleMesh cubes_sharing_an_edge() {
  TriangleMesh mesh = make_box({1, 1, 1});
  const TriangleMesh other = make_box({1, 1, 1});
  const auto offset = static_cast<std::uint32_t>(mesh.vertices.size());
  for (const Vec3d& v : other.vertices) mesh.vertices.push_back(v + Vec3d(1, 1, 0));
  for (const Triangle& t : other.triangles) {
    mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  }
  // Weld the shared corners, as a loaded mesh would have them.
  for (Triangle& t : mesh.triangles) {
    for (std::uint32_t& corner : t) {
      for (std::uint32_t v = 0; v < offset; ++v) {
        if ((mesh.vertices[corner] - mesh.vertices[v]).norm() < 1e-12) corner = v;
      }
    }
  }
  mesh.name = "two cubes";
  return mesh;
}

TEST(ThinParts, TheShrinkingBallOfAPlateIsHalfItsThickness) {
  // A point on the top face of a 2 mm plate, far from its rim: the largest empty ball tangent
  // there reaches the bottom face, so its radius is 1 mm, its centre on the mid-plane and its
  // error (radius + signed distance of the centre) zero.
  const TriangleMesh plate = make_box({1.0, 0.002, 1.0});
  const MeshQuery query(plate);
  const build::ErrorMeasure measure(query);
  const std::optional<build::MedialSphere> ball =
      build::shrinking_ball(Vec3d(0.2, 0.001, -0.1), Vec3d::UnitY(), 7, 0.7, measure);
  ASSERT_TRUE(ball.has_value());
  EXPECT_NEAR(ball->ball.radius, 0.001, 1e-9);
  EXPECT_NEAR((ball->ball.center - Vec3d(0.2, 0.0, -0.1)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(ball->error, 0.0, 1e-9);
  EXPECT_EQ(ball->generators[0], 7u);
}

TEST(ThinParts, TheShrinkingBallStopsAtItsCap) {
  // Tangent at a facet's centre inside a ball of radius 1, the empty balls grow to about 1; the
  // search is capped at 0.4, and the cap is what it gives.
  const TriangleMesh ball_mesh = make_icosphere(1.0, 3);
  const MeshQuery query(ball_mesh);
  const build::ErrorMeasure measure(query);
  const Vec3d centre =
      (ball_mesh.corner(0, 0) + ball_mesh.corner(0, 1) + ball_mesh.corner(0, 2)) / 3.0;
  const std::optional<build::MedialSphere> capped =
      build::shrinking_ball(centre, ball_mesh.area_normal(0), 0, 0.4, measure);
  ASSERT_TRUE(capped.has_value());
  EXPECT_EQ(capped->ball.radius, 0.4);
}

TEST(ThinParts, AConvexCornerHasNoShrinkingBall) {
  // Every ball tangent at a cube's corner along any inward direction cuts the three faces.
  const TriangleMesh cube = make_box({1, 1, 1});
  const MeshQuery query(cube);
  const build::ErrorMeasure measure(query);
  EXPECT_FALSE(
      build::shrinking_ball(Vec3d(0.5, 0.5, 0.5), Vec3d(1, 1, 1), 0, 0.7, measure).has_value());
}

TEST(ThinParts, ASheetHasNoShrinkingBall) {
  const TriangleMesh flat = sheet();
  const MeshQuery query(flat);
  const build::ErrorMeasure measure(query);
  EXPECT_FALSE(build::shrinking_ball(Vec3d(0.1, 0, 0.1), Vec3d::UnitY(), 0, 0.7, measure));
  EXPECT_FALSE(build::shrinking_ball(Vec3d(0.1, 0, 0.1), -Vec3d::UnitY(), 0, 0.7, measure));
}

TEST(ThinParts, AWireCostsSamplesInProportionToItsArea) {
  // A wire 1 m long and 1 mm thick: its sides are slivers 1 m by 0.8 mm. Split n ways along
  // every edge they would bring n² points for n = length / spacing, millions in all.
  const TriangleMesh wire = cylinder(0.001, 1.0, 8, true);
  constexpr std::size_t kTarget = 20000;
  const build::SurfaceSamples samples = build::sample_surface(wire, kTarget);
  EXPECT_LT(samples.points.size(), 4 * kTarget);
  // Brute force: points spread over a side triangle are all within spacing/√2 of a sample.
  double worst = 0.0;
  for (int u = 0; u <= 40; ++u) {
    for (int v = 0; u + v <= 40; ++v) {
      const Vec3d p = wire.corner(0, 0) + (wire.corner(0, 1) - wire.corner(0, 0)) * u / 40.0 +
                      (wire.corner(0, 2) - wire.corner(0, 0)) * v / 40.0;
      double nearest = std::numeric_limits<double>::infinity();
      for (const Vec3d& s : samples.points) nearest = std::min(nearest, (s - p).norm());
      worst = std::max(worst, nearest);
    }
  }
  EXPECT_LE(worst, samples.spacing / std::sqrt(2.0) * (1.0 + 1e-9));
}

// Every level below the root has more than one sphere (the branching allows up to B^level),
// and every level covers the whole surface.
SphereTree expect_split_and_covered(const TriangleMesh& mesh, BuildMethod method, int branching,
                                    int depth) {
  BuildOptions options;
  options.method = method;
  options.branching = branching;
  options.depth = depth;
  SphereTree tree = build_sphere_tree(mesh, options);
  const std::string what = mesh.name + ", " + std::string(method_name(method));
  EXPECT_EQ(tree.depth(), depth) << what;
  for (int level = 1; level < depth; ++level) {
    EXPECT_GT(tree.level_end(level) - tree.level_begin(level), 1u)
        << what << ": level " << level << " is one sphere";
  }
  for (int level = 0; level < depth; ++level) {
    EXPECT_EQ(test::uncovered_points(tree, level, mesh, 24), 0u) << what << ": level " << level;
  }
  return tree;
}

TEST(ThinParts, APlateTwoMillimetresThickIsSplitByEveryMedialMethod) {
  const TriangleMesh plate = make_box({1.0, 0.002, 1.0});
  // Under the sanitizers Combined alone, which runs the Merge, Burst and Expand reductions.
  const std::vector<BuildMethod> methods =
      test::sanitized_run() ? std::vector<BuildMethod>{BuildMethod::Combined}
                            : std::vector<BuildMethod>{BuildMethod::Hubbard,  BuildMethod::Merge,
                                                       BuildMethod::Burst,    BuildMethod::Expand,
                                                       BuildMethod::Combined, BuildMethod::Tight};
  for (const BuildMethod method : methods) {
    const SphereTree tree = expect_split_and_covered(plate, method, 8, 2);
    // Each of the 8 is far smaller than the 0.71 m sphere around the whole plate, which a
    // one-sphere level repeated.
    for (const Sphere& s : tree.level_spheres(1)) EXPECT_LT(s.radius, 0.5f * tree.root().radius);
  }
}

TEST(ThinParts, EveryLevelOfAThinPlateIsSplit) {
  expect_split_and_covered(make_box({1.0, 0.002, 1.0}), BuildMethod::Merge, 4, 3);
}

TEST(ThinParts, AWireIsSplit) {
  const TriangleMesh wire = cylinder(0.001, 0.3, 8, true);
  ASSERT_TRUE(check_mesh(wire).watertight());
  expect_split_and_covered(wire, BuildMethod::Merge, 8, 2);
}

TEST(ThinParts, AnOpenCylinderIsSplit) {
  const TriangleMesh tube = cylinder(0.05, 0.3, 16, false);
  ASSERT_FALSE(check_mesh(tube).watertight());
  expect_split_and_covered(tube, BuildMethod::Merge, 8, 2);
}

TEST(ThinParts, ASheetWithNoInsideFallsBackToTheGrid) {
  const TriangleMesh flat = sheet();
  for (const BuildMethod method : {BuildMethod::Merge, BuildMethod::Expand}) {
    expect_split_and_covered(flat, method, 4, 3);
  }
}

TEST(ThinParts, ANonManifoldEdgeIsSplit) {
  const TriangleMesh cubes = cubes_sharing_an_edge();
  ASSERT_GT(check_mesh(cubes).non_manifold_edges, 0u);
  expect_split_and_covered(cubes, BuildMethod::Merge, 8, 2);
}

}  // namespace sphys::tools::thin_parts_test
