#include "bunny_pile.h"

#include "sphys/tools/scenarios.h"
#include "sphys/tools/tree_cache.h"

namespace sphys::examples {

BunnyPile settle_bunny_pile(int stacks, int per_stack, int max_frames) {
  tools::Scene scene = tools::bunny_stacks_scene(stacks, per_stack, 2);
  scene.ground.kind = tools::GroundSpec::Kind::kPlane;
  scene.ground.height = 0.0;
  tools::BuildWorldOptions build;
  build.cache_dir = tools::default_cache_dir();
  BunnyPile pile;
  pile.setup = tools::build_world(scene, build);
  World& world = *pile.setup.world;
  const auto dt = static_cast<float>(scene.time_step);
  while (pile.frames < max_frames) {
    const StepStats& stats = world.step(dt);
    ++pile.frames;
    if (stats.bodies_asleep == pile.setup.bodies.size()) break;
  }
  const SphereTree& tree = *pile.setup.shapes.front().tree;
  for (const std::uint32_t leaf : tree.leaves()) pile.leaves.push_back(tree.sphere(leaf));
  for (const BodyId id : pile.setup.bodies) {
    const Transform pose = world.body(id).pose;
    pile.poses.push_back(pose);
    for (const Sphere& leaf : pile.leaves) {
      pile.bounds.extend(Aabb::around_sphere(pose.apply(leaf.center), leaf.radius));
    }
  }
  return pile;
}

}  // namespace sphys::examples
