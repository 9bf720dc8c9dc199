#pragma once

// Sphere-trees for tests: a bumpy cube and a ball.

#include <memory>
#include <span>

#include "sphys/sphere_tree.h"
#include "sphys/tools/build_tree.h"
#include "sphys/tools/primitives.h"

namespace sphys::test {

// The octree sphere-tree (depth 3) of a cube of side 1 m, as the tools build it: 64 leaves whose
// spheres stick out of the faces, so the body is a slightly rounded, bumpy box. Built once.
inline std::shared_ptr<const SphereTree> octree_cube_tree() {
  static const auto tree = [] {
    tools::BuildOptions options;
    options.method = tools::BuildMethod::Octree;
    options.depth = 3;
    return std::make_shared<const SphereTree>(
        tools::build_sphere_tree(tools::make_box(tools::Vec3d::Constant(1.0)), options));
  }();
  return tree;
}

// A tree of one sphere of this radius (unit: m) about the body's origin: a ball.
inline std::shared_ptr<const SphereTree> one_sphere_tree(float radius) {
  const SphereTreeNode root{{Vec3::Zero(), radius}, -1};
  return std::make_shared<const SphereTree>(SphereTree::from_nodes(std::span(&root, 1), 8));
}

}  // namespace sphys::test
