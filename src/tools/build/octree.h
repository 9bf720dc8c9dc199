#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "ball.h"
#include "sphys/tools/mesh_query.h"

namespace sphys::tools::build {

// A node of a tree under construction: its ball and its parent (-1 for the root), breadth-first.
struct BallNode {
  Ball ball;
  std::int32_t parent = -1;
};

// Hubbard-style octree (Hubbard 1996; the toolkit's "octree" method): the root cell is the
// mesh's bounding cube, each cell splits into its 8 octants, and a child exists for every octant
// that meets the solid (its surface or its inside). A cell's ball is the smallest ball around
// the solid's part of the cell (the surface clipped to the cell, plus the cell corners inside the
// solid), not the cell's circumscribed ball, so balls hug the surface. `depth` counts levels
// including the root.
[[nodiscard]] std::vector<BallNode> build_octree(const MeshQuery& query, int depth,
                                                 const std::function<void(double)>& progress);

}  // namespace sphys::tools::build
