#pragma once

// The descent's inner loop in lanes: one node's children placed in the world and tested against
// one node of the other tree, eight at a time (tree_descent.cpp). Plain arrays and no Eigen: the
// AVX2 kernel's file must share no inline function with the rest of the library
// (child_test_lanes_avx2.cpp).

#include <cstdint>

#include "sphys/solver_settings.h"

namespace sphys {

// The most children a node has (SphereTree's branching), all tested in one call. unit: children
inline constexpr int kChildLanes = 8;

// One tree at its pose for a descent, as the kernel reads it.
struct PosedColumns {
  // The tree's columns (SphereColumns: each padded by kChildLanes floats), in its body's frame.
  // unit: m
  const float* x;
  const float* y;
  const float* z;
  const float* radius;
  const float* subtree_radius;
  // The body's pose: rotation (column-major) and translation. unit: m
  float rotation[9];
  float translation[3];
  // The nodes' world centres, written for the children tested (each padded by kChildLanes
  // floats). unit: m
  float* world_x;
  float* world_y;
  float* world_z;
};

// The node of the other tree that a node's children are tested against.
struct OtherNode {
  float center[3];  // its world centre. unit: m
  float radius;     // its own radius. unit: m
  float bound;      // its own radius where it acts as a leaf, else its subtree radius. unit: m
  float margin;     // DescentSettings::margin. unit: m
  float slack;      // the bounds' relative slack. unit: dimensionless
};

// Bit i for child i (lanes past the last child hold nothing): its distance to the other node's
// centre is within each reach, squared.
struct ChildHits {
  std::uint32_t leaf_pair;      // own radii + margin: a leaf pair
  std::uint32_t leaf_bound;     // (own radius + other bound + margin) × slack
  std::uint32_t subtree_bound;  // (subtree radius + other bound + margin) × slack
};

// The children from node `first` on of `tree` (kChildLanes of them, those past the node's last
// child ignored by the caller), placed and tested against `other`.
using ChildTestKernel = ChildHits (*)(const PosedColumns& tree, std::uint32_t first,
                                      const OtherNode& other);

// The kernel in `lanes` (a lane set the processor has; kAuto: the widest). Every lane set gives
// the same bits.
[[nodiscard]] ChildTestKernel child_test_kernel(SolverLanes lanes);
// The AVX2 kernel, or null where this build has none (child_test_lanes_avx2.cpp).
[[nodiscard]] ChildTestKernel avx2_child_test_kernel();

}  // namespace sphys
