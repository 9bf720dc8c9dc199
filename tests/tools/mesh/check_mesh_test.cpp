#include "sphys/tools/check_mesh.h"

#include <limits>

#include <gtest/gtest.h>

namespace sphys::tools {
namespace {

TriangleMesh tetrahedron() {
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return mesh;
}

TEST(CheckMesh, ClosedTetrahedronIsWatertight) {
  const MeshReport report = check_mesh(tetrahedron());
  EXPECT_TRUE(report.watertight());
  EXPECT_EQ(report.boundary_edges, 0u);
  EXPECT_EQ(report.non_manifold_edges, 0u);
  EXPECT_EQ(report.misoriented_edges, 0u);
  EXPECT_EQ(report.degenerate_triangles, 0u);
}

TEST(CheckMesh, MissingTriangleLeavesThreeBoundaryEdges) {
  TriangleMesh mesh = tetrahedron();
  mesh.triangles.pop_back();
  const MeshReport report = check_mesh(mesh);
  EXPECT_FALSE(report.watertight());
  EXPECT_EQ(report.boundary_edges, 3u);
}

TEST(CheckMesh, FlippedTriangleIsMisoriented) {
  TriangleMesh mesh = tetrahedron();
  std::swap(mesh.triangles[3][1], mesh.triangles[3][2]);
  const MeshReport report = check_mesh(mesh);
  EXPECT_FALSE(report.watertight());
  EXPECT_EQ(report.misoriented_edges, 3u);
  EXPECT_EQ(report.boundary_edges, 0u);
}

TEST(CheckMesh, FinSharedByThreeTrianglesIsNonManifold) {
  TriangleMesh mesh = tetrahedron();
  mesh.vertices.emplace_back(1, 1, -1);
  mesh.triangles.push_back({0, 1, 4});  // a third triangle on edge 0-1
  const MeshReport report = check_mesh(mesh);
  EXPECT_EQ(report.non_manifold_edges, 1u);
  EXPECT_EQ(report.boundary_edges, 2u);
  EXPECT_FALSE(report.watertight());
}

TEST(CheckMesh, DegenerateNonFiniteAndUnused) {
  TriangleMesh mesh = tetrahedron();
  mesh.vertices.emplace_back(0.5, 0, 0);  // on edge 0-1: a zero-area triangle
  mesh.vertices.emplace_back(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  mesh.vertices.emplace_back(7, 7, 7);  // used by nothing
  mesh.triangles.push_back({0, 1, 4});
  mesh.triangles.push_back({2, 2, 3});
  mesh.triangles.push_back({0, 5, 1});
  const MeshReport report = check_mesh(mesh);
  EXPECT_EQ(report.degenerate_triangles, 3u);  // collinear, repeated corner, NaN corner
  EXPECT_EQ(report.non_finite_vertices, 1u);
  EXPECT_EQ(report.unused_vertices, 1u);
  EXPECT_FALSE(report.watertight());
}

}  // namespace
}  // namespace sphys::tools
