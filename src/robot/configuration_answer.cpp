// One configuration's answer: sphere after sphere of the links near any group is tested against
// its link's groups only (kLaneWidth leaves at a time), or through the hierarchy for a link near
// too many, stopping at the first sphere that touches; then, if asked, the pairs of spheres of
// links that may collide. A check deeper than the world's trees descends below the groups' leaves.

#include <algorithm>
#include <array>
#include <cmath>

#include "query/bvh_walk.h"
#include "query/group_tests.h"
#include "robot/configuration_layout.h"
#include "robot/configuration_scratch.h"

namespace sphys {
namespace {

using query_detail::kGroupLeaves;
using query_detail::LeafGroup;
using query_detail::Snapshot;

// What touches_below's stack holds at most: a group's leaves, then (branching - 1) more nodes for
// each level below them (SphereTree's branching is 8 at most).
constexpr std::size_t kGroupLeavesAndLevelsBelow = kGroupLeaves + 7 * kMostTreeDepth;

// The squared distance from a point to a box. unit: m²
float squared_distance(const Aabb& box, float x, float y, float z) {
  const float dx = std::max({box.min.x() - x, x - box.max.x(), 0.0f});
  const float dy = std::max({box.min.y() - y, y - box.max.y(), 0.0f});
  const float dz = std::max({box.min.z() - z, z - box.max.z(), 0.0f});
  return dx * dx + dy * dy + dz * dz;
}

// Calls visit(group index) for every group whose box, and every box above it in the hierarchy,
// the sphere reaches; visit returns false to stop.
template <class Visit>
void walk_near(const Snapshot& snapshot, float x, float y, float z, float radius,
               const Visit& visit) {
  const float radius_squared = radius * radius;
  const auto reached = [&](const Aabb& box) {
    return squared_distance(box, x, y, z) <= radius_squared;
  };
  query_detail::walk_boxes(snapshot, reached, [&](const LeafGroup& group) {
    return !reached(group.bounds) ||
           visit(static_cast<std::uint32_t>(&group - snapshot.groups.data()));
  });
}

}  // namespace

std::int32_t ConfigurationChecker::sphere_touches(const float* s, std::size_t link,
                                                  const Scratch& scratch) const {
  const std::int32_t count = scratch.candidate_count[link];
  if (count == Scratch::kTooMany) return touched_body(s[0], s[1], s[2], s[3]);
  return touched_body(s[0], s[1], s[2], s[3],
                      std::span(scratch.candidates.data() + link * Scratch::kMostCandidates,
                                static_cast<std::size_t>(count)));
}

std::int32_t ConfigurationChecker::self_collision(const float* spheres, std::int32_t& other) const {
  for (const auto& [i, j] : self_pairs_) {
    const float* a = spheres + i * kFloatsPerSphere;
    const float* b = spheres + j * kFloatsPerSphere;
    const float dx = a[0] - b[0];
    const float dy = a[1] - b[1];
    const float dz = a[2] - b[2];
    const float reach = a[3] + b[3];
    if (dx * dx + dy * dy + dz * dz <= reach * reach) {
      other = j;
      return i;
    }
  }
  return -1;
}

bool ConfigurationChecker::group_touches(std::uint32_t group, const Vec3& centre,
                                         float radius) const {
  const Snapshot& snapshot = query_->snapshot();
  return query_detail::group_touches_sphere(snapshot, snapshot.groups[group], centre, radius) &&
         (deeper_depth_ == 0 || touches_below(group, centre, radius));
}

bool ConfigurationChecker::touches_below(std::uint32_t group_index, const Vec3& centre,
                                         float radius) const {
  const Snapshot& snapshot = query_->snapshot();
  const LeafGroup& group = snapshot.groups[group_index];
  const SphereTree& tree = *snapshot.trees[group.body];
  const Transform& pose = snapshot.poses[group.body];
  const Mat3& rotation = rotations_[group.body];
  // Nodes from here on answer as spheres: the level asked, or a tree's last.
  const std::uint32_t answer_from = tree.level_begin(tree.last_level(deeper_depth_));
  // Depth first; each node pops once and pushes at most a branching's children, so the stack
  // holds at most the group's leaves and (branching - 1) more per level below them.
  std::array<std::uint32_t, kGroupLeavesAndLevelsBelow> stack;
  int top = 0;
  for (std::uint32_t i = group.first; i < group.first + group.count; ++i) {
    stack[top++] = snapshot.node[i];
  }
  while (top > 0) {
    const std::uint32_t n = stack[--top];
    const Vec3 at = rotation * tree.sphere(n).center + pose.translation;
    const float distance_squared = (at - centre).squaredNorm();
    if (n >= answer_from || tree.is_leaf(n)) {
      const float reach = tree.sphere(n).radius + radius;
      if (distance_squared <= reach * reach) return true;
      continue;
    }
    // With the bounds' relative margin against the rounding of the placed centre.
    const float reach = (tree.subtree_radius(n) + radius) * (1.0f + 1e-5f);
    if (distance_squared > reach * reach) continue;
    for (std::uint32_t c = tree.first_child(n); c < tree.first_child(n) + tree.child_count(n);
         ++c) {
      stack[top++] = c;
    }
  }
  return false;
}

std::int32_t ConfigurationChecker::touched_body(float x, float y, float z, float radius) const {
  const Snapshot& snapshot = query_->snapshot();
  const Vec3 centre(x, y, z);
  std::int32_t body = -1;
  walk_near(snapshot, x, y, z, radius, [&](std::uint32_t g) {
    if (group_seen_[g] != 0 && group_touches(g, centre, radius)) {
      body = static_cast<std::int32_t>(snapshot.groups[g].body);
      return false;
    }
    return true;
  });
  return body;
}

std::int32_t ConfigurationChecker::touched_body(float x, float y, float z, float radius,
                                                std::span<const std::uint32_t> candidates) const {
  const Snapshot& snapshot = query_->snapshot();
  const Vec3 centre(x, y, z);
  const float radius_squared = radius * radius;
  for (const std::uint32_t g : candidates) {
    const LeafGroup& group = snapshot.groups[g];
    if (squared_distance(group.bounds, x, y, z) <= radius_squared &&
        group_touches(g, centre, radius)) {
      return static_cast<std::int32_t>(group.body);
    }
  }
  return -1;
}

ConfigurationResult ConfigurationChecker::answer(const float* spheres, const Scratch& scratch,
                                                 bool every_sphere_given) const {
  ConfigurationResult result;
  const auto collide = [&](std::size_t sphere, std::int32_t body, std::int32_t other) {
    result.free = false;
    result.sphere = static_cast<std::int32_t>(sphere);
    result.body = body;
    result.other_sphere = other;
    return result;
  };
  for (const SphereRun& run : runs_) {
    const bool near_link = scratch.candidate_count[run.link] != 0;
    if (!near_link && !every_sphere_given) continue;  // not given
    for (std::size_t i = run.first; i < run.end; ++i) {
      const float* s = spheres + i * kFloatsPerSphere;
      // A sum of the four is finite only when each is: a NaN or infinite sphere is never free.
      if (!std::isfinite(s[0] + s[1] + s[2] + s[3]) || s[3] < 0.0f) return collide(i, -1, -1);
      if (!near_link) continue;
      const std::int32_t body = sphere_touches(s, run.link, scratch);
      if (body >= 0) return collide(i, body, -1);
    }
  }
  std::int32_t other = -1;
  const std::int32_t sphere = self_collision(spheres, other);
  if (sphere >= 0) return collide(static_cast<std::size_t>(sphere), -1, other);
  return result;
}

}  // namespace sphys
