#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "sphys/math.h"

namespace sphys {

// A ball: one node of a sphere-tree, or a bound.
struct Sphere {
  Vec3 center = Vec3::Zero();  // unit: m, in the body frame
  float radius = 0.0f;         // unit: m
};

// The nodes' spheres as columns of floats by node index, for the narrow phase's vector tests: each
// column holds SphereTree::size() values, then kSphereColumnPadding zeros, so that a load of that
// many from any node stays in bounds. unit: m, in the body frame
struct SphereColumns {
  const float* x;               // centres' x
  const float* y;               // centres' y
  const float* z;               // centres' z
  const float* radius;          // the nodes' own radii
  const float* subtree_radius;  // SphereTree::subtree_radius
};
// Zeros after each column of SphereColumns: one vector of the widest lanes. unit: floats
inline constexpr std::size_t kSphereColumnPadding = 8;

// A node as a builder or a file reader hands it over: its sphere and its parent's index
// (-1 for the root), in breadth-first order.
struct SphereTreeNode {
  Sphere sphere;             // the node's sphere. unit: m
  std::int32_t parent = -1;  // index of the parent node among those handed over; -1: the root
};

// A hierarchy of spheres bounding one body, read every step by the narrow phase.
//
// Nodes are stored breadth-first in flat arrays: node 0 is the root, the children of a node are a
// contiguous range, and level k (the root is level 0) is a contiguous range too. Depth is the
// number of levels including the root: the paper's "depth 2" is a root and up to B leaves,
// "depth 3" a root, up to B children and up to B² grandchildren. Trees need not be complete: a
// node above the last level may have no children (it is then a leaf). A node's index is stable
// and serves as the feature id of contacts made with it.
class SphereTree {
 public:
  SphereTree() = default;

  // Validates and packs nodes given in breadth-first order (every parent before its children,
  // the children of one parent adjacent, parents in non-decreasing order). Throws sphys::Error
  // for an empty list, a bad parent index, a non-finite centre, a non-positive or non-finite
  // radius, more than `branching` children, or branching outside 2..8.
  [[nodiscard]] static SphereTree from_nodes(std::span<const SphereTreeNode> nodes, int branching);

  // Number of nodes, every level.
  [[nodiscard]] std::size_t size() const { return spheres_.size(); }
  // True only for a default-constructed tree: from_nodes makes none without a root.
  [[nodiscard]] bool empty() const { return spheres_.empty(); }
  // The most children a node may have, 2..8 (the paper's B).
  [[nodiscard]] int branching() const { return branching_; }
  // Number of levels including the root.
  [[nodiscard]] int depth() const { return static_cast<int>(level_begin_.size()) - 1; }

  // A node's sphere, in the body frame. unit: m
  [[nodiscard]] const Sphere& sphere(std::uint32_t node) const { return spheres_[node]; }
  // Node 0's sphere, which bounds the body. unit: m
  [[nodiscard]] const Sphere& root() const { return spheres_.front(); }
  // Every node's sphere, by node index (breadth-first). unit: m
  [[nodiscard]] std::span<const Sphere> spheres() const { return spheres_; }
  // The index of a node's parent; -1 for the root.
  [[nodiscard]] std::int32_t parent(std::uint32_t node) const { return parent_[node]; }
  // The index of a node's first child; its children are the child_count(node) nodes from there.
  // 0 for a leaf.
  [[nodiscard]] std::uint32_t first_child(std::uint32_t node) const { return first_child_[node]; }
  // How many children a node has, 0..branching().
  [[nodiscard]] std::uint32_t child_count(std::uint32_t node) const { return child_count_[node]; }
  // Bit i set where the node's child i has no children of its own.
  [[nodiscard]] std::uint32_t childless_children(std::uint32_t node) const {
    return childless_children_[node];
  }
  // True for a node without children (on the last level or above it).
  [[nodiscard]] bool is_leaf(std::uint32_t node) const { return child_count_[node] == 0; }
  // Radius about the node's centre of a sphere holding the node's sphere and every sphere below
  // it. Builders do not nest children inside parents (each level is fitted to the surface on its
  // own), so culling a subtree must use this bound, not the node's own radius. unit: m
  [[nodiscard]] float subtree_radius(std::uint32_t node) const { return subtree_radius_[node]; }
  // The spheres as columns (SphereColumns); valid while the tree lives unchanged.
  [[nodiscard]] SphereColumns columns() const {
    return {center_x_.data(), center_y_.data(), center_z_.data(), radius_.data(),
            subtree_radius_.data()};
  }
  // The level a node is on, 0 for the root.
  [[nodiscard]] int level(std::uint32_t node) const;

  // The deepest level a descent uses when it stops after `tree_depth` levels (0, or more than
  // the tree has: every level): its nodes act as leaves.
  [[nodiscard]] int last_level(int tree_depth) const {
    return tree_depth <= 0 || tree_depth > depth() ? depth() - 1 : tree_depth - 1;
  }
  // Nodes of level k (0 = root) as the index range [begin, end).
  [[nodiscard]] std::uint32_t level_begin(int level) const { return level_begin_[level]; }
  // One past the last node of level k.
  [[nodiscard]] std::uint32_t level_end(int level) const { return level_begin_[level + 1]; }
  // The spheres of level k's nodes, in index order. unit: m
  [[nodiscard]] std::span<const Sphere> level_spheres(int level) const {
    return std::span(spheres_).subspan(level_begin(level), level_end(level) - level_begin(level));
  }
  // Nodes that have no children, in index order.
  [[nodiscard]] std::vector<std::uint32_t> leaves() const;

  // The same tree cut to its first `depth` levels (the nodes of the last kept level become
  // leaves). Throws sphys::Error unless 1 <= depth.
  [[nodiscard]] SphereTree truncated(int depth) const;

  // The same branching, parents and spheres (centres and radii compared exactly).
  friend bool operator==(const SphereTree& a, const SphereTree& b);

 private:
  std::vector<Sphere> spheres_;
  std::vector<std::int32_t> parent_;
  std::vector<std::uint32_t> first_child_;
  std::vector<std::uint8_t> child_count_;
  std::vector<std::uint8_t> childless_children_;
  std::vector<float> subtree_radius_;  // padded as the columns
  std::vector<float> center_x_;        // the columns, padded (SphereColumns)
  std::vector<float> center_y_;
  std::vector<float> center_z_;
  std::vector<float> radius_;
  std::vector<std::uint32_t> level_begin_;  // depth() + 1 entries
  int branching_ = 8;
};

}  // namespace sphys
