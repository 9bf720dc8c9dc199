#include "bunny_pile.h"

#include "sphys/error.h"
#include "sphys/tools/scenarios.h"
#include "sphys/tools/scene_file.h"
#include "sphys/tools/text_file.h"
#include "sphys/tools/tree_cache.h"

namespace sphys::examples {
namespace {

// The poses, the leaf spheres at `levels_used` and their bounds, from the pile's world.
void read_poses(BunnyPile& pile, int levels_used) {
  const World& world = *pile.setup.world;
  const SphereTree tree = pile.setup.shapes.front().tree->truncated(levels_used);
  for (const std::uint32_t leaf : tree.leaves()) pile.leaves.push_back(tree.sphere(leaf));
  for (const BodyId id : pile.setup.bodies) {
    const Transform pose = world.body(id).pose;
    pile.poses.push_back(pose);
    for (const Sphere& leaf : pile.leaves) {
      pile.bounds.extend(Aabb::around_sphere(pose.apply(leaf.center), leaf.radius));
    }
  }
}

}  // namespace

BunnyPile settle_bunny_pile(int stacks, int per_stack, int max_frames) {
  constexpr int kTreeDepth = 2;  // unit: levels
  BunnyPile pile;
  pile.scene = tools::bunny_stacks_scene(stacks, per_stack, kTreeDepth);
  pile.scene.ground.kind = tools::GroundSpec::Kind::kPlane;
  pile.scene.ground.height = 0.0;
  tools::BuildWorldOptions build;
  build.cache_dir = tools::default_cache_dir();
  pile.setup = tools::build_world(pile.scene, build);
  World& world = *pile.setup.world;
  const auto dt = static_cast<float>(pile.scene.time_step);
  while (pile.frames < max_frames) {
    const StepStats& stats = world.step(dt);
    ++pile.frames;
    if (stats.bodies_asleep == pile.setup.bodies.size()) break;
  }
  read_poses(pile, kTreeDepth);
  for (std::size_t i = 0; i < pile.poses.size(); ++i) {
    tools::BodySpec& body = pile.scene.bodies[i];
    body.position = pile.poses[i].translation;
    body.orientation = pile.poses[i].rotation;
    body.linear_velocity = Vec3::Zero();
    body.angular_velocity = Vec3::Zero();
  }
  return pile;
}

std::filesystem::path kept_bunny_pile() { return SPHYS_KEPT_BUNNY_PILE; }

void write_bunny_pile(const BunnyPile& pile, const std::filesystem::path& path) {
  tools::write_text_file(path, tools::scene_to_json(pile.scene) + "\n");
}

BunnyPile read_bunny_pile(const std::filesystem::path& path, int tree_depth, int levels_used) {
  if (levels_used < 1 || levels_used > tree_depth) {
    throw Error("bunny pile: the world uses " + std::to_string(levels_used) + " of " +
                std::to_string(tree_depth) + " levels; give 1 to " + std::to_string(tree_depth));
  }
  BunnyPile pile;
  pile.scene = tools::read_scene_file(path);
  tools::BuildWorldOptions build;
  build.cache_dir = tools::default_cache_dir();
  build.tree_depth = tree_depth;
  pile.setup = tools::build_world(pile.scene, build);
  // The same bodies in a world that uses `levels_used` of their trees' levels, static: nothing
  // steps a kept pile.
  WorldSettings settings = pile.setup.world->settings();
  settings.collision.tree_depth = levels_used;
  auto world = std::make_unique<World>(settings);
  for (BodyId& id : pile.setup.bodies) {
    BodyDesc desc;
    desc.tree = pile.setup.world->shared_tree(id);
    desc.pose = pile.setup.world->body(id).pose;
    desc.is_static = true;
    id = world->add_body(desc);
  }
  pile.setup.world = std::move(world);
  read_poses(pile, levels_used);
  return pile;
}

}  // namespace sphys::examples
