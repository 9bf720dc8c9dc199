#pragma once

// Walks of the snapshot's hierarchy: every group whose box a test accepts, or the groups along a
// ray nearest first.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "query/snapshot.h"

namespace sphys::query_detail {

// Calls visit(group) for every group in a leaf whose box, and every box above it, `accepts`.
// visit returns false to stop the walk.
template <class Accepts, class Visit>
void walk_boxes(const Snapshot& snapshot, const Accepts& accepts, const Visit& visit) {
  if (snapshot.bvh.empty()) return;
  std::array<std::uint32_t, kMaxBvhDepth> stack;
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& node = snapshot.bvh[stack[--top]];
    if (!accepts(node.bounds)) continue;
    if (node.count == 0) {
      stack[top++] = node.first + 1;
      stack[top++] = node.first;
      continue;
    }
    for (std::uint32_t g = node.first; g < node.first + node.count; ++g) {
      if (!visit(snapshot.groups[g])) return;
    }
  }
}

// Where a ray (origin, 1 / direction per axis) enters a box, if it does before `limit`: the
// slab test, with the entry clamped to 0 for a ray starting inside. unit: m
[[nodiscard]] inline bool ray_enters(const Aabb& box, const Vec3& origin,
                                     const Vec3& inverse_direction, float limit, float& entry) {
  const Vec3 t0 = (box.min - origin).cwiseProduct(inverse_direction);
  const Vec3 t1 = (box.max - origin).cwiseProduct(inverse_direction);
  const float near = std::max(t0.cwiseMin(t1).maxCoeff(), 0.0f);
  const float far = std::min(t0.cwiseMax(t1).minCoeff(), limit);
  entry = near;
  return near <= far;
}

// Calls visit(group) for the groups whose boxes the ray enters within `limit`, nearer boxes
// first; visit may lower `limit` (the nearest hit so far), which prunes what lies beyond.
template <class Visit>
void walk_ray(const Snapshot& snapshot, const Vec3& origin, const Vec3& direction, float& limit,
              const Visit& visit) {
  if (snapshot.bvh.empty()) return;
  // 1 / direction, with a huge finite stand-in where a component is zero: an infinite one would
  // make 0 · ∞ = NaN for an origin exactly on a box's face, where the stand-in gives 0 (the ray
  // is then taken as inside that slab, which keeps the box: never a missed hit).
  const Vec3 inverse = direction.unaryExpr([](float d) {
    constexpr float kHuge = 1e30f;
    return std::abs(d) > 1.0f / kHuge ? 1.0f / d : kHuge;
  });
  struct Entry {
    std::uint32_t node;
    float entry;
  };
  std::array<Entry, kMaxBvhDepth> stack;
  int top = 0;
  float root_entry = 0.0f;
  if (!ray_enters(snapshot.bvh[0].bounds, origin, inverse, limit, root_entry)) return;
  stack[top++] = {0, root_entry};
  while (top > 0) {
    const Entry item = stack[--top];
    if (item.entry > limit) continue;
    const BvhNode& node = snapshot.bvh[item.node];
    if (node.count > 0) {
      for (std::uint32_t g = node.first; g < node.first + node.count; ++g) {
        visit(snapshot.groups[g]);
      }
      continue;
    }
    float entry_a = 0.0f;
    float entry_b = 0.0f;
    const bool a = ray_enters(snapshot.bvh[node.first].bounds, origin, inverse, limit, entry_a);
    const bool b = ray_enters(snapshot.bvh[node.first + 1].bounds, origin, inverse, limit, entry_b);
    // The nearer child goes on top, so it is walked first.
    if (a && b) {
      const bool a_first = entry_a <= entry_b;
      stack[top++] = a_first ? Entry{node.first + 1, entry_b} : Entry{node.first, entry_a};
      stack[top++] = a_first ? Entry{node.first, entry_a} : Entry{node.first + 1, entry_b};
    } else if (a) {
      stack[top++] = {node.first, entry_a};
    } else if (b) {
      stack[top++] = {node.first + 1, entry_b};
    }
  }
}

}  // namespace sphys::query_detail
