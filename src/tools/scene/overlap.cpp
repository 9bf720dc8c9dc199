#include "sphys/tools/overlap.h"

#include <algorithm>
#include <vector>

namespace sphys::tools {
namespace {

struct Placed {
  std::uint32_t body = 0;
  Sphere bound;                // around every leaf, world frame
  std::vector<Sphere> leaves;  // world frame
};

Placed place(std::uint32_t body, const SphereTree& tree, const Transform& pose) {
  Placed placed;
  placed.body = body;
  for (std::uint32_t node = 0; node < tree.size(); ++node) {
    if (tree.is_leaf(node)) {
      placed.leaves.push_back({pose.apply(tree.sphere(node).center), tree.sphere(node).radius});
    }
  }
  // Centred on the root's centre, but reaching every leaf: a tree's parent spheres cover the
  // surface, not always their children's whole spheres.
  placed.bound.center = pose.apply(tree.sphere(0).center);
  for (const Sphere& leaf : placed.leaves) {
    placed.bound.radius =
        std::max(placed.bound.radius, (leaf.center - placed.bound.center).norm() + leaf.radius);
  }
  return placed;
}

void deepest_between(const Placed& a, const Placed& b, Overlap& deepest) {
  if ((a.bound.center - b.bound.center).norm() >= a.bound.radius + b.bound.radius) return;
  for (const Sphere& x : a.leaves) {
    for (const Sphere& y : b.leaves) {
      const float depth = x.radius + y.radius - (x.center - y.center).norm();
      if (depth > deepest.depth) deepest = {depth, a.body, b.body};
    }
  }
}

}  // namespace

Overlap deepest_overlap(const SimulationSetup& setup, std::optional<float> plane_height) {
  std::vector<Placed> bodies;
  bodies.reserve(setup.bodies.size());
  for (std::uint32_t i = 0; i < setup.bodies.size(); ++i) {
    const SphereTree& tree = *setup.shapes[setup.body_shape[i]].tree;
    bodies.push_back(place(i, tree, setup.world->body(setup.bodies[i]).pose));
  }
  Overlap deepest;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    for (std::size_t j = i + 1; j < bodies.size(); ++j)
      deepest_between(bodies[i], bodies[j], deepest);
  }
  if (setup.ground && setup.ground_tree) {
    const Placed ground =
        place(Overlap::kGround, *setup.ground_tree, setup.world->body(*setup.ground).pose);
    for (const Placed& body : bodies) deepest_between(ground, body, deepest);
  }
  if (plane_height) {
    for (const Placed& body : bodies) {
      for (const Sphere& leaf : body.leaves) {
        const float depth = leaf.radius - (leaf.center.y() - *plane_height);
        if (depth > deepest.depth) deepest = {depth, Overlap::kGround, body.body};
      }
    }
  }
  return deepest;
}

}  // namespace sphys::tools
