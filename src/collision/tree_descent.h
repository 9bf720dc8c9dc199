#pragma once

// Narrow phase: the simultaneous descent of two sphere-trees (paper §3.2), exact or time-critical.

#include <cstdint>
#include <vector>

#include "collision/child_test.h"
#include "sphys/math.h"
#include "sphys/sphere_tree.h"

namespace sphys {

// One overlapping pair of spheres, as node indices of the two trees.
struct NodePair {
  std::uint32_t node_a = 0;
  std::uint32_t node_b = 0;

  friend bool operator==(const NodePair&, const NodePair&) = default;
  friend auto operator<=>(const NodePair&, const NodePair&) = default;
};

struct DescentSettings {
  // Levels of each tree used, the root included; 0 (or more than the tree has) uses them all.
  // The nodes of the last used level act as leaves (a depth-3 tree used as depth 2).
  int depth_a = 0;
  int depth_b = 0;

  // Spheres this close count as overlapping: a gap of up to `margin` between two leaf spheres
  // still returns the pair (speculative contacts; see CollisionSettings). unit: m
  float margin = 0.0f;

  // Time-critical mode (paper §3.2; Hubbard 1995; Dingliana & O'Sullivan 2000): once a budget is
  // spent the descent stops, and each pair still waiting is resolved at the level it reached: it
  // is returned if the nodes' own spheres overlap. 0 turns a budget off; with both off the descent
  // is exact.
  // Sphere tests before stopping. One expansion may overrun it by up to the branching factor, and
  // resolving the waiting pairs costs one more test each. unit: sphere tests
  std::uint64_t max_sphere_tests = 0;
  // Wall-clock time before stopping, measured from the start of the call. unit: µs
  double max_microseconds = 0.0;
  // Sphere tests between two readings of the clock, so that the clock stays cheap. unit: sphere
  // tests
  std::uint32_t clock_check_interval = 256;
};

// Figures of one descend() call.
struct DescentStats {
  std::uint64_t sphere_tests = 0;     // overlap tests of two spheres (subtree bounds or leaves)
  std::uint32_t leaf_pairs = 0;       // overlapping pairs of leaves returned
  std::uint32_t cut_short_pairs = 0;  // pairs still waiting when a budget ran out
  std::uint32_t internal_pairs = 0;   // cut-short pairs returned (their own spheres overlap)
};

// The descent's reusable working memory: its stack and the world-frame centres of the nodes it
// visits. After the first calls have grown it to the trees' sizes, descend() allocates nothing.
// One per thread; not shared.
class TreeDescent {
 public:
  // The children of a node are placed and tested in `lanes` (kAuto: the widest the processor
  // has); every lane set returns the same pairs in the same order.
  explicit TreeDescent(SolverLanes lanes = SolverLanes::kAuto)
      : test_children_(child_test_kernel(lanes)) {}

  // Appends to `pairs` every pair of leaves of tree a at pose_a and tree b at pose_b whose spheres
  // overlap (closed test: touching counts) or are apart by at most DescentSettings::margin, and
  // with a budget, the cut-short pairs described in
  // DescentSettings. Poses move the centres (rotation, then translation); radii are unchanged.
  // Order: deterministic for given inputs, not sorted.
  DescentStats descend(const SphereTree& tree_a, const Transform& pose_a, const SphereTree& tree_b,
                       const Transform& pose_b, const DescentSettings& settings,
                       std::vector<NodePair>& pairs);

  // World-frame spheres of the nodes of the pairs the last descend() returned (for contacts,
  // paper eq. 1-3); valid until the next call. Other nodes may hold stale centres.
  [[nodiscard]] Sphere world_sphere_a(const SphereTree& tree_a, std::uint32_t node) const {
    return {world_a_.center(node), tree_a.sphere(node).radius};
  }
  [[nodiscard]] Sphere world_sphere_b(const SphereTree& tree_b, std::uint32_t node) const {
    return {world_b_.center(node), tree_b.sphere(node).radius};
  }

 private:
  // World centres of one tree's nodes as columns, written as the descent expands their parents:
  // a node far from the other body costs nothing. Each column has kChildLanes more floats than
  // the tree has nodes, for the kernel's stores.
  struct WorldCenters {
    std::vector<float> x, y, z;
    [[nodiscard]] Vec3 center(std::uint32_t node) const { return {x[node], y[node], z[node]}; }
    void set(std::uint32_t node, const Vec3& c) {
      x[node] = c.x();
      y[node] = c.y();
      z[node] = c.z();
    }
  };

  std::vector<NodePair> stack_;
  WorldCenters world_a_;
  WorldCenters world_b_;
  ChildTestKernel test_children_;
};

}  // namespace sphys
