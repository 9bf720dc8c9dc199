#pragma once

// A pile of bunnies at rest: the `stacks:SxN` preset (depth-2 trees) over the exact plane y = 0,
// stepped in sphys until every bunny sleeps, then frozen. What the planning example plans around
// and the queries' benchmark asks about.

#include <vector>

#include "sphys/math.h"
#include "sphys/sphere_tree.h"
#include "sphys/tools/build_world.h"

namespace sphys::examples {

struct BunnyPile {
  tools::SimulationSetup setup;  // the world, at rest
  std::vector<Transform> poses;  // per bunny, setup.bodies' order
  std::vector<Sphere> leaves;    // a bunny's leaf spheres, body frame. unit: m
  Aabb bounds;                   // of every bunny's leaf spheres
  int frames = 0;                // steps taken to rest

  // A bunny's mesh, body frame.
  [[nodiscard]] const tools::TriangleMesh& mesh() const { return *setup.shapes.front().body_mesh; }
};

// S stacks of N bunnies, stepped until all sleep or `max_frames` have passed (0: as placed).
[[nodiscard]] BunnyPile settle_bunny_pile(int stacks, int per_stack, int max_frames);

}  // namespace sphys::examples
