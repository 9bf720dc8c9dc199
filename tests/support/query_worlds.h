#pragma once

// Random worlds for the query tests, and the oracle they are checked against: every leaf sphere
// of every body, placed as the world places it, in a plain loop.

#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "sphys/error.h"
#include "sphys/sphere_tree.h"
#include "sphys/world.h"
#include "sphys/world_query.h"

namespace sphys::test {

using QueryRng = std::mt19937;

inline float uniform_in(QueryRng& rng, float low, float high) {
  return std::uniform_real_distribution<float>(low, high)(rng);
}

inline Vec3 uniform_point(QueryRng& rng, float half_side) {
  return {uniform_in(rng, -half_side, half_side), uniform_in(rng, -half_side, half_side),
          uniform_in(rng, -half_side, half_side)};
}

inline Quat uniform_rotation(QueryRng& rng) {
  std::normal_distribution<float> normal;
  return Quat(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
}

// A random tree of `depth` levels whose children stick out of their parents (up to 1.5 parent
// radii from the parent's centre) with 0..branching children each, so only subtree bounds may
// prune. Root radius 0.3 m.
inline std::shared_ptr<const SphereTree> random_query_tree(QueryRng& rng, int branching,
                                                           int depth) {
  std::vector<SphereTreeNode> nodes{{{Vec3::Zero(), 0.3f}, -1}};
  std::size_t level_begin = 0;
  for (int level = 1; level < depth; ++level) {
    const std::size_t level_end = nodes.size();
    for (std::size_t p = level_begin; p < level_end; ++p) {
      const int children = std::uniform_int_distribution<int>(level == 1 ? 1 : 0, branching)(rng);
      for (int c = 0; c < children; ++c) {
        const Sphere& parent = nodes[p].sphere;
        const Vec3 direction = uniform_point(rng, 1.0f).normalized();
        const Vec3 centre = parent.center + direction * uniform_in(rng, 0.0f, 1.5f) * parent.radius;
        nodes.push_back(
            {{centre, parent.radius * uniform_in(rng, 0.3f, 0.7f)}, static_cast<std::int32_t>(p)});
      }
    }
    level_begin = level_end;
  }
  return std::make_shared<const SphereTree>(SphereTree::from_nodes(nodes, branching));
}

// `bodies` bodies with random trees of depth 2 or 3 at random poses in a cube of 2 half_side,
// every third static, no gravity (so that stepping moves nothing).
inline World random_query_world(QueryRng& rng, int bodies, float half_side, int tree_depth = 0) {
  WorldSettings settings;
  settings.gravity = Vec3::Zero();
  settings.collision.tree_depth = tree_depth;
  World world(settings);
  for (int i = 0; i < bodies; ++i) {
    BodyDesc desc;
    desc.tree = random_query_tree(rng, std::uniform_int_distribution<int>(2, 8)(rng),
                                  std::uniform_int_distribution<int>(2, 3)(rng));
    desc.pose.rotation = uniform_rotation(rng);
    desc.pose.translation = uniform_point(rng, half_side);
    desc.is_static = i % 3 == 0;
    world.add_body(desc);
  }
  return world;
}

// A leaf sphere of a body in the world frame, for the oracle.
struct WorldLeaf {
  BodyId body;
  std::uint32_t node = 0;
  Sphere sphere;
};

// Every leaf sphere (at the world's tree_depth, or at `depth` levels when given) of every body
// the filter sees (categories, mask, skip and sleep read by a plain loop), centres placed as the
// world places them.
inline std::vector<WorldLeaf> oracle_leaves(const World& world, const QueryFilter& filter = {},
                                            std::optional<int> levels = std::nullopt) {
  std::vector<WorldLeaf> out;
  const int depth = levels.value_or(world.settings().collision.tree_depth);
  for (std::uint32_t slot = 0; slot < world.body_slots(); ++slot) {
    const BodyId id = world.id_of(slot);
    if (!world.alive(id)) continue;
    const std::uint32_t category = slot < filter.categories.size() ? filter.categories[slot] : 1u;
    if ((category & filter.mask) == 0) continue;
    if (filter.skip_sleeping && world.asleep(id)) continue;
    if (std::find(filter.skip.begin(), filter.skip.end(), id) != filter.skip.end()) continue;
    const SphereTree& full = world.tree(id);
    const SphereTree tree = depth > 0 ? full.truncated(std::min(depth, full.depth())) : full;
    const Transform pose = world.bodies().poses()[slot];
    for (const std::uint32_t node : tree.leaves()) {
      out.push_back(
          {id,
           node,
           {pose.rotation.toRotationMatrix() * tree.sphere(node).center + pose.translation,
            tree.sphere(node).radius}});
    }
  }
  return out;
}

// The message of the sphys::Error that `call` throws, or "no error".
template <class Call>
std::string error_message(const Call& call) {
  try {
    call();
  } catch (const Error& error) {
    return error.what();
  }
  return "no error";
}

}  // namespace sphys::test
