#pragma once

#include <cstddef>

#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// Simplifies the mesh to at most target_triangles by edge collapse (meshoptimizer's
// quadric-error simplifier), keeping open borders in place. A watertight input stays watertight:
// if the simplifier cannot keep it so, this throws sphys::Error rather than return a broken
// mesh. A target at or above the current count returns the mesh unchanged.
[[nodiscard]] TriangleMesh decimate(const TriangleMesh& mesh, std::size_t target_triangles);

}  // namespace sphys::tools
