#include "sphys/sphere_tree.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "sphys/error.h"

namespace sphys {
namespace {

Error node_error(std::size_t node, const std::string& problem) {
  return Error("sphere-tree node " + std::to_string(node) + ": " + problem);
}

}  // namespace

SphereTree SphereTree::from_nodes(std::span<const SphereTreeNode> nodes, int branching) {
  if (branching < 2 || branching > 8) {
    throw Error("sphere-tree branching factor " + std::to_string(branching) + " is outside 2..8");
  }
  if (nodes.empty()) throw Error("a sphere-tree needs at least a root sphere");

  SphereTree tree;
  tree.branching_ = branching;
  const std::size_t n = nodes.size();
  tree.spheres_.reserve(n);
  tree.parent_.reserve(n);
  tree.first_child_.assign(n, 0);
  tree.child_count_.assign(n, 0);
  std::vector<int> level(n, 0);

  for (std::size_t i = 0; i < n; ++i) {
    const SphereTreeNode& node = nodes[i];
    if (!node.sphere.center.allFinite()) throw node_error(i, "centre is not finite");
    if (!(node.sphere.radius > 0.0f) || !std::isfinite(node.sphere.radius)) {
      throw node_error(i, "radius must be positive and finite");
    }
    if (i == 0) {
      if (node.parent != -1) throw node_error(0, "the root must have no parent");
    } else {
      const std::int32_t p = node.parent;
      if (p < 0 || static_cast<std::size_t>(p) >= i) {
        throw node_error(i, "parent " + std::to_string(p) + " does not come before it");
      }
      if (p < nodes[i - 1].parent) throw node_error(i, "nodes are not in breadth-first order");
      const auto parent = static_cast<std::size_t>(p);
      // Parents in non-decreasing order make each parent's children adjacent.
      if (tree.child_count_[parent] == 0) tree.first_child_[parent] = static_cast<std::uint32_t>(i);
      if (tree.child_count_[parent] == branching) {
        throw node_error(parent, "has more than " + std::to_string(branching) + " children");
      }
      ++tree.child_count_[parent];
      level[i] = level[parent] + 1;
    }
    tree.spheres_.push_back(node.sphere);
    tree.parent_.push_back(node.parent);
  }

  // Children come after their parents, so one backward pass sees every child before its parent.
  tree.subtree_radius_.resize(n);
  for (std::size_t i = n; i-- > 0;) {
    float bound = tree.spheres_[i].radius;
    for (std::uint32_t c = tree.first_child_[i]; c < tree.first_child_[i] + tree.child_count_[i];
         ++c) {
      bound = std::max(bound, (tree.spheres_[c].center - tree.spheres_[i].center).norm() +
                                  tree.subtree_radius_[c]);
    }
    tree.subtree_radius_[i] = bound;
  }

  tree.childless_children_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::uint32_t k = 0; k < tree.child_count_[i]; ++k) {
      if (tree.child_count_[tree.first_child_[i] + k] == 0) {
        tree.childless_children_[i] |= static_cast<std::uint8_t>(1u << k);
      }
    }
  }
  tree.subtree_radius_.resize(n + kSphereColumnPadding, 0.0f);
  for (std::vector<float>* column :
       {&tree.center_x_, &tree.center_y_, &tree.center_z_, &tree.radius_}) {
    column->assign(n + kSphereColumnPadding, 0.0f);
  }
  for (std::size_t i = 0; i < n; ++i) {
    tree.center_x_[i] = tree.spheres_[i].center.x();
    tree.center_y_[i] = tree.spheres_[i].center.y();
    tree.center_z_[i] = tree.spheres_[i].center.z();
    tree.radius_[i] = tree.spheres_[i].radius;
  }

  const int depth = level.back() + 1;
  tree.level_begin_.assign(static_cast<std::size_t>(depth) + 1, static_cast<std::uint32_t>(n));
  for (std::size_t i = n; i-- > 0;) tree.level_begin_[level[i]] = static_cast<std::uint32_t>(i);
  return tree;
}

int SphereTree::level(std::uint32_t node) const {
  const auto it = std::upper_bound(level_begin_.begin(), level_begin_.end(), node);
  return static_cast<int>(it - level_begin_.begin()) - 1;
}

std::vector<std::uint32_t> SphereTree::leaves() const {
  std::vector<std::uint32_t> out;
  for (std::uint32_t i = 0; i < size(); ++i) {
    if (is_leaf(i)) out.push_back(i);
  }
  return out;
}

SphereTree SphereTree::truncated(int new_depth) const {
  if (new_depth < 1) throw Error("a sphere-tree depth must be at least 1 (the root)");
  if (new_depth >= depth()) return *this;
  const std::uint32_t kept = level_end(new_depth - 1);
  std::vector<SphereTreeNode> nodes(kept);
  for (std::uint32_t i = 0; i < kept; ++i) nodes[i] = {spheres_[i], parent_[i]};
  return from_nodes(nodes, branching_);
}

bool operator==(const SphereTree& a, const SphereTree& b) {
  if (a.branching_ != b.branching_ || a.parent_ != b.parent_) return false;
  return std::equal(a.spheres_.begin(), a.spheres_.end(), b.spheres_.begin(), b.spheres_.end(),
                    [](const Sphere& s, const Sphere& t) {
                      return s.center == t.center && s.radius == t.radius;
                    });
}

}  // namespace sphys
