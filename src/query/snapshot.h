#pragma once

// What the queries read: the world's leaf spheres in the world frame, in groups of up to
// kGroupLeaves siblings of one body stored as lanes (x, y, z, radius arrays), and a bounding
// volume hierarchy of boxes over the groups. Made once per WorldQuery::refresh(), so that a query
// neither moves a sphere nor allocates to find its candidates.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <vector>

#include "core/simd.h"
#include "sphys/math.h"
#include "sphys/sphere_tree.h"
#include "sphys/world.h"

namespace sphys::query_detail {

#if defined(__SSE2__)
using Lanes = Sse2Lanes;
#else
using Lanes = PortableLanes<4>;
#endif
inline constexpr std::uint32_t kLaneWidth = Lanes::kWidth;

// Leaves per group: a depth-2 tree of branching 8 is one group. unit: spheres
inline constexpr std::uint32_t kGroupLeaves = 8;

// Far away and of zero radius: what pads a group to whole lanes, never within reach of anything.
// unit: m
inline constexpr float kPaddingCentre = 1e15f;

// Floats whose storage starts on a 32-byte boundary, so that lanes load them aligned (SSE2's and
// AVX2's aligned loads fault otherwise, and a plain vector<float> promises 4 bytes).
template <class T>
struct LaneAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlignment{32};
  LaneAllocator() = default;
  template <class U>
  explicit LaneAllocator(const LaneAllocator<U>& /*other*/) {}
  [[nodiscard]] T* allocate(std::size_t count) {
    return static_cast<T*>(::operator new(count * sizeof(T), kAlignment));
  }
  void deallocate(T* pointer, std::size_t /*count*/) { ::operator delete(pointer, kAlignment); }
  friend bool operator==(const LaneAllocator&, const LaneAllocator&) { return true; }
};
using LaneFloats = std::vector<float, LaneAllocator<float>>;

struct LeafGroup {
  Aabb bounds;              // of the group's spheres
  std::uint32_t body = 0;   // the body's slot
  std::uint32_t first = 0;  // its first sphere in Snapshot's lanes, a multiple of kLaneWidth
  std::uint32_t count = 0;  // spheres, 1..kGroupLeaves
  // Spheres rounded up to whole lanes. unit: spheres
  [[nodiscard]] std::uint32_t padded() const {
    return (count + kLaneWidth - 1) / kLaneWidth * kLaneWidth;
  }
};

// A node of the hierarchy over the groups: an inner node's children are nodes `first` and
// `first + 1`; a leaf holds `count` groups from `first` on.
struct BvhNode {
  Aabb bounds;
  std::uint32_t first = 0;
  std::uint32_t count = 0;  // 0 for an inner node
};

// Deepest a hierarchy over 2^32 groups split at medians can be, with room: the traversal stacks.
inline constexpr int kMaxBvhDepth = 64;

struct Snapshot {
  // The world's leaf spheres in lanes, each group's padded with kPaddingCentre spheres.
  LaneFloats x, y, z, radius;       // unit: m
  std::vector<std::uint32_t> node;  // each sphere's node in its body's tree
  std::vector<LeafGroup> groups;    // in the hierarchy's leaf order
  std::vector<BvhNode> bvh;         // node 0 the root; empty when the world has no body
  // Per body slot, as in the world when the snapshot was made. The trees are shared, so that a
  // snapshot stays whole while the world removes bodies.
  std::vector<Transform> poses;
  std::vector<BodyId> ids;                               // the null id for a free slot
  std::vector<std::shared_ptr<const SphereTree>> trees;  // null for a free slot
  std::vector<std::uint8_t> asleep;
  int tree_depth = 0;  // CollisionSettings::tree_depth: the levels in use, 0 for all

  void read(const World& world);
};

// The first node of a tree that acts as a leaf when `depth` levels are in use (0: all), and the
// end of the nodes in use: node n is a leaf in use when n < end and (n >= leaf_from or it has no
// children).
struct LeafRange {
  std::uint32_t leaf_from = 0;
  std::uint32_t end = 0;
};
[[nodiscard]] LeafRange leaf_range(const SphereTree& tree, int depth);
[[nodiscard]] inline bool acts_as_leaf(const SphereTree& tree, const LeafRange& range,
                                       std::uint32_t node) {
  return node >= range.leaf_from || tree.is_leaf(node);
}

}  // namespace sphys::query_detail
