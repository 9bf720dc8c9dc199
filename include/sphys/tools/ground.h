#pragma once

#include "sphys/sphere_tree.h"
#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// The paper's static plane (§5): a thin box whose top face is the plane y = 0, approximated by
// a sphere-tree "with 5 levels built through an octree subdivision".
struct GroundOptions {
  double size = 16.0;      // side of the square top face, along x and z. unit: m
  double thickness = 0.5;  // unit: m
  int depth = 5;           // levels including the root
};

// The box, top face at y = 0, centred on the y axis.
[[nodiscard]] TriangleMesh make_ground_box(const GroundOptions& options = {});
// Its octree sphere-tree (branching 8). Throws sphys::Error for non-positive or non-finite sizes.
[[nodiscard]] SphereTree build_ground_tree(const GroundOptions& options = {});

}  // namespace sphys::tools
