#include "sphys/tools/tree_quality.h"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "sphys/error.h"
#include "sphys/tools/mass_properties.h"
#include "sphys/tools/primitives.h"

namespace sphys::tools {
namespace {

const double kSqrt3 = std::sqrt(3.0);

double sphere_volume(double radius) { return 4.0 / 3.0 * std::numbers::pi * std::pow(radius, 3); }

// Five standard errors of the Monte Carlo outside_volume: `volume_samples` points in a box of
// volume `box_volume`, of which a fraction `outside_volume · mesh_volume / box_volume` is expected
// to count. A fixed seed makes the figure reproducible; the margin keeps the test honest for any
// seed.
double outside_volume_tolerance(double outside_volume, double mesh_volume, double box_volume,
                                std::size_t volume_samples) {
  const double p = outside_volume * mesh_volume / box_volume;
  return 5.0 * box_volume / mesh_volume *
         std::sqrt(p * (1.0 - p) / static_cast<double>(volume_samples));
}

// How much the lattice of `count` points on a sphere can miss the sphere's farthest point by:
// each direction lies within sqrt(4π / count) of a lattice point (the lattice's covering angle
// is about 2.7 / sqrt(count)), and the distance falls off as radius · (1 - cos angle).
double lattice_shortfall(double radius, std::size_t count) {
  return radius * (1.0 - std::cos(std::sqrt(4.0 * std::numbers::pi / static_cast<double>(count))));
}

// A float radius no smaller than `radius`, so that a sphere meant to touch the corners holds them.
float radius_at_least(double radius) {
  float r = static_cast<float>(radius);
  while (static_cast<double>(r) < radius) r = std::nextafter(r, 2.0f * r);
  return r;
}

void expect_identical(const LevelQuality& a, const LevelQuality& b) {
  EXPECT_EQ(a.level, b.level);
  EXPECT_EQ(a.spheres, b.spheres);
  EXPECT_EQ(a.coverage, b.coverage);
  EXPECT_EQ(a.worst_gap, b.worst_gap);
  EXPECT_EQ(a.outside_volume, b.outside_volume);
  EXPECT_EQ(a.worst_protrusion, b.worst_protrusion);
}

TEST(TreeQuality, SphereCircumscribingTheUnitCube) {
  const MeshQuery cube(make_box(Vec3d(1.0, 1.0, 1.0)));
  const Sphere sphere{Vec3::Zero(), radius_at_least(kSqrt3 / 2.0)};
  const double r = sphere.radius;
  const QualityOptions options;
  const LevelQuality quality = measure_level(std::span(&sphere, 1), cube, options);

  EXPECT_EQ(quality.spheres, 1u);
  EXPECT_EQ(quality.coverage, 1.0);
  EXPECT_EQ(quality.worst_gap, 0.0);

  const double outside_volume = sphere_volume(r) - 1.0;  // the cube's volume is 1
  EXPECT_NEAR(
      quality.outside_volume, outside_volume,
      outside_volume_tolerance(outside_volume, 1.0, std::pow(2.0 * r, 3), options.volume_samples));

  // The sphere's farthest point from the cube is over a face centre, r - 1/2 out.
  const double protrusion = (r - 0.5) / kSqrt3;
  EXPECT_LE(quality.worst_protrusion, protrusion + 1e-12);
  EXPECT_GE(quality.worst_protrusion,
            protrusion - lattice_shortfall(r, options.boundary_samples) / kSqrt3);
}

TEST(TreeQuality, TooSmallSphereLeavesTheCornersUncovered) {
  const MeshQuery cube(make_box(Vec3d(1.0, 1.0, 1.0)));
  constexpr double kRadius = 0.8;  // between the edge midpoints (0.707) and the corners (0.866)
  const Sphere sphere{Vec3::Zero(), static_cast<float>(kRadius)};
  const double r = sphere.radius;
  const QualityOptions options;
  const LevelQuality quality = measure_level(std::span(&sphere, 1), cube, options);

  // Each face is covered where the sphere cuts it: a disk of radius rho around the face centre,
  // clipped by the four sides of the face at distance h = 1/2.
  const double rho = std::sqrt(r * r - 0.25);
  const double h = 0.5;
  const double segment = rho * rho * std::acos(h / rho) - h * std::sqrt(rho * rho - h * h);
  const double coverage = std::numbers::pi * rho * rho - 4.0 * segment;  // the face's area is 1
  EXPECT_NEAR(
      quality.coverage, coverage,
      5.0 * std::sqrt(coverage * (1.0 - coverage) / static_cast<double>(options.surface_samples)));

  // The farthest uncovered points are the corners, |corner| - r from the sphere. Some sample
  // lands within δ of a corner unless all miss the 8 corner patches (3πδ²/4 each, of the
  // cube's area 6): probability exp(-samples · πδ²), about e^-31 for δ = 0.01.
  const double gap = (kSqrt3 / 2.0 - r) / kSqrt3;
  EXPECT_LE(quality.worst_gap, gap + 1e-12);
  EXPECT_GE(quality.worst_gap, gap - 0.01 / kSqrt3);

  const double protrusion = (r - 0.5) / kSqrt3;
  EXPECT_LE(quality.worst_protrusion, protrusion + 1e-12);
  EXPECT_GE(quality.worst_protrusion,
            protrusion - lattice_shortfall(r, options.boundary_samples) / kSqrt3);
}

TEST(TreeQuality, EnlargedSphereAroundAnIcosphereGivesTheShellVolume) {
  const TriangleMesh mesh = make_icosphere(1.0, 3);
  const MeshQuery query(mesh);
  constexpr double kRadius = 1.05;
  const Sphere sphere{Vec3::Zero(), static_cast<float>(kRadius)};
  const double r = sphere.radius;
  const QualityOptions options;
  const LevelQuality quality = measure_level(std::span(&sphere, 1), query, options);

  EXPECT_EQ(quality.coverage, 1.0);
  EXPECT_EQ(quality.worst_gap, 0.0);

  // The facets lie inside the sphere, so the union outside the mesh is the sphere less the
  // polyhedron, whose volume is exact.
  const double mesh_volume = compute_mass_properties(mesh).volume;
  const double outside_volume = (sphere_volume(r) - mesh_volume) / mesh_volume;
  EXPECT_NEAR(quality.outside_volume, outside_volume,
              outside_volume_tolerance(outside_volume, mesh_volume, std::pow(2.0 * r, 3),
                                       options.volume_samples));

  // Every boundary point is at least r - 1 from the mesh (its vertices are on the unit sphere)
  // and at most that plus the facets' depth below the unit sphere.
  const double diagonal = mesh.bounds().diagonal().norm();
  double sag = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Vec3d centroid = (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0;
    sag = std::max(sag, 1.0 - centroid.norm());
  }
  EXPECT_GE(quality.worst_protrusion, (r - 1.0) / diagonal);
  EXPECT_LE(quality.worst_protrusion, (r - 1.0 + sag) / diagonal);
}

// Eight spheres around a ring, a little thinner than the torus's tube, and one that reaches out
// of it: every figure is neither 0 nor trivial.
std::vector<Sphere> ring_of_spheres() {
  std::vector<Sphere> spheres;
  for (int k = 0; k < 8; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / 8.0;
    spheres.push_back(
        {Vec3(static_cast<float>(std::cos(angle)), 0.0f, static_cast<float>(std::sin(angle))),
         0.5f});
  }
  spheres.push_back({Vec3(1.0f, 0.3f, 0.0f), 0.6f});
  return spheres;
}

TEST(TreeQuality, SameInputsGiveIdenticalFiguresOnAnyThreadCount) {
  const MeshQuery torus(make_torus(1.0, 0.4, 48, 24));
  const std::vector<Sphere> spheres = ring_of_spheres();
  QualityOptions options;
  options.surface_samples = 20000;
  options.volume_samples = 50000;

  const LevelQuality first = measure_level(spheres, torus, options);
  EXPECT_GT(first.coverage, 0.5);
  EXPECT_LT(first.coverage, 1.0);
  EXPECT_GT(first.worst_gap, 0.0);
  EXPECT_GT(first.outside_volume, 0.0);
  EXPECT_GT(first.worst_protrusion, 0.0);

  expect_identical(measure_level(spheres, torus, options), first);
  for (const int threads : {1, 2}) {
    tbb::task_arena arena(threads);
    arena.execute([&] { expect_identical(measure_level(spheres, torus, options), first); });
  }

  // Another seed samples other points: close figures, not the same ones.
  QualityOptions reseeded = options;
  reseeded.seed = options.seed + 1;
  const LevelQuality other = measure_level(spheres, torus, reseeded);
  EXPECT_NE(other.outside_volume, first.outside_volume);
  EXPECT_NEAR(other.coverage, first.coverage, 0.02);
}

TEST(TreeQuality, ManySpheresOfAnOctreeLevelCoverTheBox) {
  // Level 3 of an octree over the unit cube: 512 cells, each in its circumscribed sphere.
  const MeshQuery cube(make_box(Vec3d(1.0, 1.0, 1.0)));
  constexpr int kCells = 8;
  constexpr double kSide = 1.0 / kCells;
  const float radius = radius_at_least(kSqrt3 / 2.0 * kSide);
  std::vector<Sphere> spheres;
  for (int i = 0; i < kCells; ++i) {
    for (int j = 0; j < kCells; ++j) {
      for (int k = 0; k < kCells; ++k) {
        const Vec3d center = (Vec3d(i, j, k) + Vec3d::Constant(0.5)) * kSide;
        spheres.push_back({(center - Vec3d::Constant(0.5)).cast<float>(), radius});
      }
    }
  }
  QualityOptions options;
  options.volume_samples = 100000;
  const LevelQuality quality = measure_level(spheres, cube, options);
  EXPECT_EQ(quality.spheres, 512u);
  EXPECT_EQ(quality.coverage, 1.0);
  EXPECT_EQ(quality.worst_gap, 0.0);
  // Only the outer cells stick out, each by its sphere's radius less half a cell.
  const double protrusion = (radius - 0.5 * kSide) / kSqrt3;
  EXPECT_LE(quality.worst_protrusion, protrusion + 1e-12);
  EXPECT_GE(quality.worst_protrusion,
            protrusion - lattice_shortfall(radius, options.boundary_samples) / kSqrt3);
}

TEST(TreeQuality, ManySpheresFindTheNearestForTheGap) {
  // Small spheres at the centres of the cube's faces only: the gap is from a corner to the
  // nearest face sphere, whichever it is.
  const MeshQuery cube(make_box(Vec3d(1.0, 1.0, 1.0)));
  constexpr double kRadius = 0.3;
  std::vector<Sphere> spheres;
  for (int axis = 0; axis < 3; ++axis) {
    for (const float side : {-0.5f, 0.5f}) {
      Vec3 center = Vec3::Zero();
      center[axis] = side;
      spheres.push_back({center, static_cast<float>(kRadius)});
    }
  }
  const LevelQuality quality = measure_level(spheres, cube);
  const double corner_to_face_centre = std::sqrt(0.5);
  const double gap = (corner_to_face_centre - static_cast<float>(kRadius)) / kSqrt3;
  EXPECT_LE(quality.worst_gap, gap + 1e-9);
  EXPECT_GE(quality.worst_gap, gap - 0.01 / kSqrt3);  // as for the single sphere
  EXPECT_LT(quality.coverage, 1.0);
}

TEST(TreeQuality, MeasureTreeGivesOneEntryPerLevel) {
  // The cube's circumscribed sphere, then one sphere per octant.
  const MeshQuery cube(make_box(Vec3d(1.0, 1.0, 1.0)));
  std::vector<SphereTreeNode> nodes{{{Vec3::Zero(), radius_at_least(kSqrt3 / 2.0)}, -1}};
  const float child_radius = radius_at_least(kSqrt3 / 4.0);
  for (int octant = 0; octant < 8; ++octant) {
    const Vec3 center((octant & 1) != 0 ? 0.25f : -0.25f, (octant & 2) != 0 ? 0.25f : -0.25f,
                      (octant & 4) != 0 ? 0.25f : -0.25f);
    nodes.push_back({{center, child_radius}, 0});
  }
  const SphereTree tree = SphereTree::from_nodes(nodes, 8);
  QualityOptions options;
  options.volume_samples = 100000;
  const std::vector<LevelQuality> levels = measure_tree(tree, cube, options);

  ASSERT_EQ(levels.size(), 2u);
  EXPECT_EQ(levels[0].level, 0);
  EXPECT_EQ(levels[1].level, 1);
  EXPECT_EQ(levels[0].spheres, 1u);
  EXPECT_EQ(levels[1].spheres, 8u);
  for (const LevelQuality& level : levels) {
    EXPECT_EQ(level.coverage, 1.0);
    EXPECT_EQ(level.worst_gap, 0.0);
  }
  EXPECT_LT(levels[1].outside_volume, levels[0].outside_volume);
  // From a centre inside a convex solid, a sphere sticks out farthest along the normal of the
  // nearest face: by its radius less that face's distance (1/4 for an octant's centre).
  const double protrusion = (child_radius - 0.25) / kSqrt3;
  EXPECT_LE(levels[1].worst_protrusion, protrusion + 1e-12);
  EXPECT_GE(levels[1].worst_protrusion,
            protrusion - lattice_shortfall(child_radius, options.boundary_samples) / kSqrt3);

  // The root level alone measures as measure_level does, apart from the level number.
  expect_identical(levels[0], measure_level(tree.level_spheres(0), cube, options));
}

TEST(TreeQuality, RejectsWhatItCannotMeasure) {
  const MeshQuery cube(make_box(Vec3d(1.0, 1.0, 1.0)));
  const Sphere sphere{Vec3::Zero(), 1.0f};
  EXPECT_THROW((void)measure_level({}, cube), Error);
  QualityOptions no_samples;
  no_samples.volume_samples = 0;
  EXPECT_THROW((void)measure_level(std::span(&sphere, 1), cube, no_samples), Error);
  const Sphere bad{Vec3(std::nanf(""), 0.0f, 0.0f), 1.0f};
  EXPECT_THROW((void)measure_level(std::span(&bad, 1), cube), Error);
}

}  // namespace
}  // namespace sphys::tools
