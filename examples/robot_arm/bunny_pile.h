#pragma once

// A pile of bunnies at rest: the `stacks:SxN` preset (depth-2 trees) over the exact plane y = 0,
// stepped in sphys until every bunny sleeps, then frozen. What the planning example plans around
// and the queries' benchmark asks about. A settled pile is kept as a scene file (the bunnies where
// they rest, still), so that those two see the same pile whatever the solver does today.

#include <filesystem>
#include <vector>

#include "sphys/math.h"
#include "sphys/sphere_tree.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/scene.h"

namespace sphys::examples {

struct BunnyPile {
  tools::Scene scene;            // the bunnies where they rest, still
  tools::SimulationSetup setup;  // the world, at rest
  std::vector<Transform> poses;  // per bunny, setup.bodies' order
  std::vector<Sphere> leaves;    // a bunny's leaf spheres at the levels the world uses, body frame
  Aabb bounds;                   // of every bunny's leaf spheres
  int frames = 0;                // steps taken to rest

  // A bunny's mesh, body frame.
  [[nodiscard]] const tools::TriangleMesh& mesh() const { return *setup.shapes.front().body_mesh; }
};

// S stacks of N bunnies, stepped until all sleep or `max_frames` have passed (0: as placed).
[[nodiscard]] BunnyPile settle_bunny_pile(int stacks, int per_stack, int max_frames);

// The pile kept with the sources (examples/robot_arm/bunny-pile-100.json): 10 stacks of 10
// settled by write_bunny_pile.
[[nodiscard]] std::filesystem::path kept_bunny_pile();

// The pile's scene, written whole or not at all.
void write_bunny_pile(const BunnyPile& pile, const std::filesystem::path& path);

// A pile write_bunny_pile wrote, its bunnies' trees built to `tree_depth` levels of which the
// world uses `levels_used` (CollisionSettings::tree_depth): queries may look deeper than the
// world does. Throws sphys::Error naming the file.
[[nodiscard]] BunnyPile read_bunny_pile(const std::filesystem::path& path, int tree_depth,
                                        int levels_used);

}  // namespace sphys::examples
