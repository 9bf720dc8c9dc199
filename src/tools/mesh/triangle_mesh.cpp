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

}  // namespace sphys::tools
