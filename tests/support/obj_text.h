#pragma once

// A mesh as Wavefront OBJ text, for tests that write mesh files of made-up shapes.

#include <string>

#include "sphys/tools/triangle_mesh.h"

namespace sphys::test {

// The mesh's vertices and faces, moved by `offset`.
inline std::string obj_text(const tools::TriangleMesh& mesh,
                            const tools::Vec3d& offset = tools::Vec3d::Zero()) {
  std::string text;
  for (const tools::Vec3d& v : mesh.vertices) {
    const tools::Vec3d p = v + offset;
    text += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " +
            std::to_string(p.z()) + "\n";
  }
  for (const tools::Triangle& t : mesh.triangles) {
    text += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " +
            std::to_string(t[2] + 1) + "\n";
  }
  return text;
}

}  // namespace sphys::test
