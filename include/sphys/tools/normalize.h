#pragma once

#include "sphys/tools/mass_properties.h"
#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// A mesh brought to a size and to its centre of mass (normalize), with the map that did it.
struct NormalizedMesh {
  TriangleMesh mesh;                  // scaled and moved
  double scale = 1.0;                 // applied first, about the original origin
  Vec3d translation = Vec3d::Zero();  // applied after scaling: x' = scale * x + translation
};

// Scales the mesh uniformly so that the longest side of its bounding box is target_size and moves
// it so that its centre of mass (by compute_mass_properties) is at the origin. Throws
// sphys::Error for a non-positive or non-finite target size or a mesh with a flat bounding box.
[[nodiscard]] NormalizedMesh normalize(const TriangleMesh& mesh, double target_size,
                                       const MassPropertiesOptions& options = {});

}  // namespace sphys::tools
