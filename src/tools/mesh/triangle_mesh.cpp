#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

Box3d TriangleMesh::bounds() const {
  Box3d box;  // Eigen's default box is empty
  for (const Vec3d& v : vertices) box.extend(v);
  return box;
}

Vec3d TriangleMesh::area_normal(std::size_t triangle) const {
  const Vec3d a = corner(triangle, 0);
  return (corner(triangle, 1) - a).cross(corner(triangle, 2) - a);
}

std::vector<Vec3d> vertex_normals(const TriangleMesh& mesh) {
  std::vector<Vec3d> normals(mesh.vertices.size(), Vec3d::Zero());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Vec3d normal = mesh.area_normal(t);
    for (const std::uint32_t v : mesh.triangles[t]) normals[v] += normal;
  }
  for (Vec3d& normal : normals) {
    normal = normal.norm() > 0.0 ? normal.normalized() : Vec3d::UnitY();
  }
  return normals;
}

}  // namespace sphys::tools
