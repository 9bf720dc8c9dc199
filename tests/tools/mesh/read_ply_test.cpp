#include <bit>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/check_mesh.h"
#include "sphys/tools/load_mesh.h"
#include "sphys/tools/mass_properties.h"
#include "support/temp_file.h"

namespace sphys::tools {
namespace {

using testing::HasSubstr;

// A 2 x 3 x 4 box from the origin, quads wound outwards: 8 vertices, 6 faces, 12 triangles,
// volume 24.
constexpr double kBox[8][3] = {{0, 0, 0}, {2, 0, 0}, {2, 3, 0}, {0, 3, 0},
                               {0, 0, 4}, {2, 0, 4}, {2, 3, 4}, {0, 3, 4}};
constexpr int kQuads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                              {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
constexpr double kBoxVolume = 24.0;

// The box in ASCII PLY, with a colour per vertex, an extra element and comments to skip.
std::string ascii_box() {
  std::string text =
      "ply\r\nformat ascii 1.0\ncomment a box\nobj_info made by hand\nelement vertex 8\n"
      "property double x\nproperty float y\nproperty float z\nproperty uchar red\n"
      "element face 6\nproperty list uchar int vertex_indices\nproperty list uint8 float uv\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  for (const auto& v : kBox) {
    text +=
        std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + " 255\n";
  }
  for (const auto& q : kQuads) {
    text += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) +
            " " + std::to_string(q[3]) + " 2 0.5 0.25\n";
  }
  return text + "0 1\n";
}

template <typename T>
void put_value(std::string& out, T value, bool big_endian) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) {
    std::reverse(bytes, bytes + sizeof(T));
  }
  out.append(bytes, sizeof(T));
}

// The box in binary PLY: float coordinates with a double to skip, int face lists, a skipped
// element with a list before the faces.
std::string binary_box(bool big_endian) {
  std::string data = "ply\nformat ";
  data += big_endian ? "binary_big_endian" : "binary_little_endian";
  data +=
      " 1.0\nelement vertex 8\nproperty float x\nproperty double confidence\nproperty float y\n"
      "property float z\nelement material 2\nproperty list ushort short ids\n"
      "element face 6\nproperty list uchar uint vertex_index\nend_header\n";
  for (const auto& v : kBox) {
    put_value(data, static_cast<float>(v[0]), big_endian);
    put_value(data, 0.5, big_endian);
    put_value(data, static_cast<float>(v[1]), big_endian);
    put_value(data, static_cast<float>(v[2]), big_endian);
  }
  for (std::uint16_t m = 0; m < 2; ++m) {
    put_value(data, m, big_endian);  // m items
    for (std::uint16_t i = 0; i < m; ++i)
      put_value(data, static_cast<std::int16_t>(-1), big_endian);
  }
  for (const auto& q : kQuads) {
    put_value(data, std::uint8_t{4}, big_endian);
    for (const int corner : q) put_value(data, static_cast<std::uint32_t>(corner), big_endian);
  }
  return data;
}

void expect_box(const TriangleMesh& mesh) {
  EXPECT_EQ(mesh.vertices.size(), 8u);
  EXPECT_EQ(mesh.triangles.size(), 12u);
  EXPECT_TRUE(check_mesh(mesh).watertight());
  EXPECT_NEAR(compute_mass_properties(mesh, {}).volume, kBoxVolume, 1e-12);
  EXPECT_EQ(mesh.bounds().max(), Vec3d(2, 3, 4));
}

std::string load_error(const std::filesystem::path& path) {
  try {
    (void)load_mesh(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(ReadPly, AsciiBoxWithPropertiesAndElementsToSkip) {
  const test::TempDir dir;
  expect_box(load_mesh(dir.write("box.ply", ascii_box())));
}

TEST(ReadPly, BinaryBoxInBothByteOrders) {
  const test::TempDir dir;
  expect_box(load_mesh(dir.write("little.ply", binary_box(false))));
  expect_box(load_mesh(dir.write("big.PLY", binary_box(true))));
}

// A tetrahedron with the header's counts as given.
std::string tetrahedron_ply(int vertices, int faces) {
  return "ply\nformat ascii 1.0\nelement vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
         std::to_string(faces) +
         "\nproperty list uchar int vertex_indices\nend_header\n"
         "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
}

TEST(ReadPly, AVertexCountOneTooLowIsAnErrorNotAnAbort) {
  const test::TempDir dir;
  // assimp's reader aborted the process on this one (ai_assert in TriangulateProcess.cpp).
  const auto aborted = dir.write("aborted.ply", tetrahedron_ply(3, 1));
  EXPECT_EQ(load_error(aborted), aborted.string() + ": the mesh has no triangles");
  // The fourth vertex line is read as faces: "0" and "0" corners, then "1" corner: "3".
  const auto tet = dir.write("tet.ply", tetrahedron_ply(3, 4));
  EXPECT_EQ(load_error(tet),
            tet.string() + ":14: vertex index 3 is out of range (the file has 3 vertices)");
  std::string text = ascii_box();
  text.replace(text.find("element vertex 8"), 16, "element vertex 7");
  const auto path = dir.write("low.ply", text);
  // The last vertex line is read as the first face, its first coordinate as the corner count.
  EXPECT_EQ(load_error(path),
            path.string() + ":24: '0.000000' is not an integer (the property is uchar)");
}

TEST(ReadPly, TruncatedHeadersAreErrors) {
  const test::TempDir dir;
  // 16 bytes that made assimp's reader spin for ever.
  const auto cut = dir.write("cut.ply", "ply\nformat ascii");
  EXPECT_EQ(load_error(cut), cut.string() +
                                 ":2: expected 'format ascii|binary_little_endian|"
                                 "binary_big_endian 1.0'");
  const auto no_end = dir.write("noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n");
  EXPECT_EQ(load_error(no_end),
            no_end.string() + ":3: file ends in the header: no 'end_header' line");
  const auto magic = dir.write("magic.ply", "plx\nformat ascii 1.0\nend_header\n");
  EXPECT_EQ(load_error(magic),
            magic.string() + ":1: not a PLY file: it does not start with the line 'ply'");
}

TEST(ReadPly, CountsTheFileCannotHoldAreRefusedBeforeAllocating) {
  const test::TempDir dir;
  const auto ascii = dir.write(
      "huge.ply",
      "ply\nformat ascii 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float "
      "y\nproperty float z\nend_header\n0 0 0\n");
  EXPECT_EQ(load_error(ascii),
            ascii.string() +
                ":3: the header announces 1000000000000 'vertex' records of at least 6 bytes "
                "each, but the file has room for at most 1 (6 bytes after the header)");
  std::string binary = binary_box(false);
  binary.resize(binary.size() - 1);  // the last face loses its last index
  const auto cut = dir.write("cut.ply", binary);
  EXPECT_EQ(load_error(cut),
            cut.string() +
                ": record 5 of element 'face': a list of 4 items runs past the end "
                "of the file");
  std::string faces = binary_box(true);
  faces.replace(faces.find("element face 6"), 14, "element face 9");
  const auto many = dir.write("many.ply", faces);
  // A face takes at least its count byte, so 9 faces fit the size; the body runs out at the 7th.
  EXPECT_EQ(load_error(many), many.string() +
                                  ": file ends early in record 6 of element 'face' (the header "
                                  "announces 9)");
}

TEST(ReadPly, BadIndicesAndCoordinatesAreNamed) {
  const test::TempDir dir;
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const auto index = dir.write("index.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  EXPECT_EQ(load_error(index),
            index.string() + ":13: vertex index 3 is out of range (the file has 3 vertices)");
  const auto negative = dir.write("negative.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n");
  EXPECT_THAT(load_error(negative), HasSubstr("vertex index -1 is out of range"));
  const auto nan = dir.write("nan.ply", header + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(load_error(nan),
            nan.string() + ":11: a vertex has a non-finite coordinate (1, nan, 0)");
  const auto word = dir.write("word.ply", header + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(load_error(word), word.string() + ":11: 'zero' is not a number");
  const auto short_file = dir.write("short.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n");
  EXPECT_EQ(load_error(short_file),
            short_file.string() +
                ":13: file ends early in record 0 of element 'face' (the header announces 1)");

  std::string binary = binary_box(false);
  const std::size_t first_index = binary.size() - 6 * 17 + 1;
  const std::uint32_t bad = 8;
  std::memcpy(&binary[first_index], &bad, sizeof bad);  // little endian on this machine
  const auto binary_index = dir.write("index_binary.ply", binary);
  EXPECT_EQ(load_error(binary_index),
            binary_index.string() +
                ": record 0 of element 'face': vertex index 8 is out of range (the file has 8 "
                "vertices)");
}

TEST(ReadPly, HeaderMistakesAreNamedByLine) {
  const test::TempDir dir;
  const auto type = dir.write("type.ply",
                              "ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\n"
                              "end_header\n");
  EXPECT_EQ(load_error(type), type.string() + ":4: unknown property type 'real'");
  const auto no_z = dir.write("noz.ply",
                              "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                              "property float y\nend_header\n0 0\n");
  EXPECT_EQ(load_error(no_z), no_z.string() + ":3: the vertex element has no number property 'z'");
  const auto float_index =
      dir.write("float_index.ply",
                "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                "property float z\nelement face 0\nproperty list uchar float vertex_indices\n"
                "end_header\n");
  EXPECT_EQ(load_error(float_index),
            float_index.string() + ":7: vertex indices must have an integer type, not float");
}

// Random byte changes of a valid file: each must load or be an Error, never crash or hang. The
// reader is linear in the file's size, so 200 files of 300 bytes take milliseconds.
TEST(ReadPly, MutatedFilesLoadOrFailCleanly) {
  const test::TempDir dir;
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const std::vector<std::string> originals = {ascii, binary_box(false)};
  std::mt19937 random(2208);
  constexpr int kMutations = 200;
  int loaded = 0;
  int refused = 0;
  for (int m = 0; m < kMutations; ++m) {
    std::string bytes = originals[static_cast<std::size_t>(m) % originals.size()];
    const int changes = 1 + static_cast<int>(random() % 4);
    for (int c = 0; c < changes; ++c) {
      const std::size_t at = random() % bytes.size();
      switch (random() % 3) {
        case 0:
          bytes[at] = static_cast<char>(random());
          break;
        case 1:
          bytes.erase(at, 1 + random() % 8);
          break;
        default:
          bytes.insert(at, 1, "0123456789 \n-e.x"[random() % 16]);
      }
    }
    const auto path = dir.write("mutant.ply", bytes);
    try {
      (void)load_mesh(path);
      ++loaded;
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr(path.string())) << "mutation " << m;
      ++refused;
    }
  }
  EXPECT_EQ(loaded + refused, kMutations);
  EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace sphys::tools
