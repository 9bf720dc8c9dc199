#include "sphys/tools/load_mesh.h"

#include <cstring>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/check_mesh.h"
#include "support/temp_file.h"

namespace sphys::tools {
namespace {

using testing::AllOf;
using testing::HasSubstr;

// A unit right tetrahedron, outward-oriented, in each format.
constexpr const char* kTetObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
constexpr const char* kTetOff =
    "OFF\n# a comment\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
    "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
constexpr const char* kTetPly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
constexpr const char* kTetStl =
    "solid t\n"
    "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
    "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
    "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
    "facet normal 0 0 0\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\n"
    "endsolid t\n";

// Binary STL: 80-byte header, triangle count, then per triangle a normal, 3 corners, 2 spare bytes.
std::string binary_stl_tetrahedron() {
  const float corners[4][3][3] = {{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}},
                                  {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}},
                                  {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                                  {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  std::string data(80, ' ');
  const std::uint32_t count = 4;
  data.append(reinterpret_cast<const char*>(&count), sizeof count);
  for (const auto& triangle : corners) {
    const float normal[3] = {0, 0, 0};
    data.append(reinterpret_cast<const char*>(normal), sizeof normal);
    data.append(reinterpret_cast<const char*>(triangle), sizeof triangle);
    data.append(2, '\0');
  }
  return data;
}

void expect_welded_closed_tetrahedron(const TriangleMesh& mesh) {
  EXPECT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.triangles.size(), 4u);
  EXPECT_TRUE(check_mesh(mesh).watertight());
  EXPECT_EQ(mesh.bounds().min(), Vec3d(0, 0, 0));
  EXPECT_EQ(mesh.bounds().max(), Vec3d(1, 1, 1));
}

TEST(LoadMesh, ReadsEveryFormatAndWeldsVertices) {
  const test::TempDir dir;
  expect_welded_closed_tetrahedron(load_mesh(dir.write("tet.obj", kTetObj)));
  expect_welded_closed_tetrahedron(load_mesh(dir.write("tet.off", kTetOff)));
  expect_welded_closed_tetrahedron(load_mesh(dir.write("tet.ply", kTetPly)));
  expect_welded_closed_tetrahedron(load_mesh(dir.write("tet.stl", kTetStl)));
  expect_welded_closed_tetrahedron(load_mesh(dir.write("binary.stl", binary_stl_tetrahedron())));
}

TEST(LoadMesh, TriangulatesPolygonsAndKeepsTheName) {
  const test::TempDir dir;
  const auto path = dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const TriangleMesh mesh = load_mesh(path);
  EXPECT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.name, path.string());
  EXPECT_EQ(check_mesh(mesh).boundary_edges, 4u);
}

// Every bad input is an Error whose message names the file and says what is wrong.
void expect_error(const std::filesystem::path& path, const std::string& problem) {
  try {
    (void)load_mesh(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr(path.string()), HasSubstr(problem)));
  }
}

TEST(LoadMesh, MissingFile) {
  const test::TempDir dir;
  expect_error(dir.path() / "absent.obj", "no such file");
}

TEST(LoadMesh, Directory) {
  const test::TempDir dir;
  expect_error(dir.path(), "is a directory");
}

TEST(LoadMesh, EmptyFile) {
  const test::TempDir dir;
  expect_error(dir.write("empty.obj", ""), "file is empty");
  expect_error(dir.write("empty.stl", ""), "file is empty");
}

TEST(LoadMesh, BinaryGarbage) {
  const test::TempDir dir;
  std::string garbage;
  std::uint32_t state = 12345;
  for (int i = 0; i < 3000; ++i) {
    state = state * 1664525u + 1013904223u;
    garbage.push_back(static_cast<char>(state >> 24));
  }
  expect_error(dir.write("garbage.obj", garbage), "no mesh found");
  expect_error(dir.write("garbage.ply", garbage), ":1: not a PLY file");
  expect_error(dir.write("garbage.stl", garbage), "STL");
  expect_error(dir.write("garbage.off", garbage), ":1: not an OFF file");
  expect_error(dir.write("garbage.xyz", garbage), "");  // unknown format: still an Error
}

TEST(LoadMesh, NonFiniteCoordinates) {
  const test::TempDir dir;
  expect_error(dir.write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"),
               "non-finite coordinate (nan, 0, 0)");
  expect_error(dir.write("inf.obj", "v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n"),
               "non-finite coordinate (1, inf, 0)");
  expect_error(dir.write("nan.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"),
               "nan.off:4: non-finite coordinate 'nan'");
}

TEST(LoadMesh, FaceIndexOutOfRange) {
  const test::TempDir dir;
  expect_error(dir.write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
               "vertex index out of range");
  expect_error(dir.write("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"),
               "bad.off:6: face index 7 is out of range (the file has 3 vertices)");
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n";
  expect_error(dir.write("bad.ply", ply), "out of range");
}

TEST(LoadMesh, NoTriangles) {
  const test::TempDir dir;
  expect_error(dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), "no triangles");
  expect_error(dir.write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n"), "no triangles");
  expect_error(dir.write("none.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"), "no triangles");
}

TEST(LoadMesh, TruncatedOff) {
  const test::TempDir dir;
  expect_error(dir.write("cut.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n"),
               "cut.off:7: file ends early: expected a face");
}

TEST(WeldVertices, MergesEqualPositionsIncludingSignedZero) {
  TriangleMesh soup;
  soup.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-0.0, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  soup.triangles = {{0, 1, 2}, {3, 4, 5}};
  const TriangleMesh welded = weld_vertices(soup);
  EXPECT_EQ(welded.vertices.size(), 4u);
  EXPECT_EQ(welded.triangles[1][0], welded.triangles[0][0]);
  EXPECT_EQ(welded.triangles[1][1], welded.triangles[0][2]);
}

}  // namespace
}  // namespace sphys::tools
