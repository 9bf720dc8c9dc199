#include "sphys/tools/decimate.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/check_mesh.h"
#include "sphys/tools/load_mesh.h"
#include "sphys/tools/mass_properties.h"
#include "sphys/tools/model.h"
#include "sphys/tools/primitives.h"

namespace sphys::tools {
namespace {

double volume(const TriangleMesh& mesh) { return compute_mass_properties(mesh).volume; }

TEST(Decimate, BunnyAt2000TrianglesStaysClosedAndKeepsItsVolume) {
  const TriangleMesh full = load_mesh(bunny_path());
  ASSERT_EQ(full.triangles.size(), 69666u);
  ASSERT_EQ(full.vertices.size(), 34835u);
  ASSERT_TRUE(check_mesh(full).watertight());

  const TriangleMesh small = decimate(full, 2000);
  EXPECT_LE(small.triangles.size(), 2000u);
  EXPECT_GE(small.triangles.size(), 1900u);
  const MeshReport report = check_mesh(small);
  EXPECT_TRUE(report.watertight());
  EXPECT_EQ(report.unused_vertices, 0u);
  // Euler: a closed genus-0 triangle mesh has V = T/2 + 2.
  EXPECT_EQ(small.vertices.size(), small.triangles.size() / 2 + 2);
  EXPECT_NEAR(volume(small) / volume(full), 1.0, 0.02);
}

TEST(Decimate, LoadModelNamesTheBunnyAndDecimatesByDefault) {
  const TriangleMesh bunny = load_model("bunny");
  EXPECT_EQ(bunny.name, "bunny");
  EXPECT_LE(bunny.triangles.size(), kBunnyDefaultTriangles);
  EXPECT_GE(bunny.triangles.size(), 1900u);
  EXPECT_EQ(load_model("bunny", 0).triangles.size(), 69666u);
}

TEST(Decimate, SphereKeepsItsVolumeAndClosedness) {
  const TriangleMesh sphere = make_icosphere(1.0, 5);  // 20480 triangles
  const TriangleMesh small = decimate(sphere, 1000);
  EXPECT_LE(small.triangles.size(), 1000u);
  EXPECT_TRUE(check_mesh(small).watertight());
  EXPECT_NEAR(volume(small) / volume(sphere), 1.0, 0.03);
}

TEST(Decimate, OpenMeshKeepsItsBorder) {
  TriangleMesh sphere = make_icosphere(1.0, 4);
  sphere.triangles.resize(sphere.triangles.size() - 40);  // tear a hole
  const std::size_t border_before = check_mesh(sphere).boundary_edges;
  ASSERT_GT(border_before, 0u);
  const TriangleMesh small = decimate(sphere, 800);
  EXPECT_LE(small.triangles.size(), 800u);
  EXPECT_EQ(check_mesh(small).boundary_edges, border_before);
}

TEST(Decimate, TargetAtOrAboveCountIsUnchangedAndBelowATetrahedronIsAnError) {
  TriangleMesh box = make_box({1, 2, 3});
  box.name = "box.obj";
  EXPECT_EQ(decimate(box, 12).triangles, box.triangles);
  EXPECT_EQ(decimate(box, 100).vertices, box.vertices);
  // Fewer than 4 triangles close no surface: refused by the count asked for, not by what the
  // decimated mesh would then lack.
  for (const std::size_t target : {0, 1, 3}) {
    try {
      (void)decimate(box, target);
      ADD_FAILURE() << "no error for " << target;
    } catch (const Error& error) {
      EXPECT_EQ(std::string(error.what()), "box.obj: cannot decimate to " + std::to_string(target) +
                                               " triangles: a closed surface needs at least 4");
    }
  }
}

}  // namespace
}  // namespace sphys::tools
