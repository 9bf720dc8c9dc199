#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sphys::tools {

using Vec3d = Eigen::Vector3d;                  // a point or vector in double
using Mat3d = Eigen::Matrix3d;                  // a 3×3 matrix in double
using Box3d = Eigen::AlignedBox3d;              // an axis-aligned box in double
using Triangle = std::array<std::uint32_t, 3>;  // three indices into TriangleMesh::vertices

// An indexed triangle mesh in double precision, the input of every offline tool. Vertices are
// welded (no two share a position) when the mesh comes from load_mesh(); triangles are
// counter-clockwise seen from outside, so normals point out.
struct TriangleMesh {
  std::vector<Vec3d> vertices;      // in the mesh's units (m once normalised)
  std::vector<Triangle> triangles;  // counter-clockwise seen from outside
  std::string name;  // where it came from (a file path or a model name), for messages

  // The smallest box holding every vertex; empty for no vertices.
  [[nodiscard]] Box3d bounds() const;
  // Corner k (0, 1 or 2) of a triangle.
  [[nodiscard]] Vec3d corner(std::size_t triangle, int k) const {
    return vertices[triangles[triangle][static_cast<std::size_t>(k)]];
  }
  // Area-weighted (unnormalised) normal: (b - a) x (c - a), twice the triangle's area long.
  [[nodiscard]] Vec3d area_normal(std::size_t triangle) const;
};

// Per vertex, the unit normal averaged over its triangles weighted by their areas (smooth
// shading); +y for a vertex no triangle with an area uses.
[[nodiscard]] std::vector<Vec3d> vertex_normals(const TriangleMesh& mesh);

}  // namespace sphys::tools
