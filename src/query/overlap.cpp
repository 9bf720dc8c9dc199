// Overlap queries: the bodies with a leaf sphere touching a sphere, a box or another tree's
// leaves. The hierarchy gives the groups near the shape; a body found once is not tested again.

#include <algorithm>
#include <string>

#include "query/body_filter.h"
#include "query/bvh_walk.h"
#include "query/checked_input.h"
#include "query/group_tests.h"
#include "query/snapshot.h"
#include "sphys/error.h"
#include "sphys/world_query.h"

namespace sphys {
namespace {

using query_detail::BodyFilter;
using query_detail::LeafGroup;
using query_detail::Snapshot;

// The bodies of the groups within `bounds` that `touches` accepts, as ids by increasing slot.
template <class Touches>
std::vector<BodyId> bodies_touching(const Snapshot& snapshot, const BodyFilter& filter,
                                    const Aabb& bounds, const Touches& touches) {
  std::vector<std::uint32_t> found;
  query_detail::walk_boxes(
      snapshot, [&](const Aabb& box) { return box.overlaps(bounds); },
      [&](const LeafGroup& group) {
        if (group.bounds.overlaps(bounds) && filter.sees(group.body) &&
            std::ranges::find(found, group.body) == found.end() && touches(group)) {
          found.push_back(group.body);
        }
        return true;
      });
  std::ranges::sort(found);
  std::vector<BodyId> out;
  out.reserve(found.size());
  for (const std::uint32_t slot : found) out.push_back(snapshot.ids[slot]);
  return out;
}

}  // namespace

std::vector<BodyId> WorldQuery::overlap_sphere(const Vec3& center, float radius,
                                               const QueryFilter& filter) const {
  query_detail::check_finite(center, "center");
  query_detail::check_size(radius, "radius");
  const BodyFilter seen(*snapshot_, filter);
  return bodies_touching(
      *snapshot_, seen, Aabb::around_sphere(center, radius), [&](const LeafGroup& group) {
        return query_detail::group_touches_sphere(*snapshot_, group, center, radius);
      });
}

std::vector<BodyId> WorldQuery::overlap_aabb(const Aabb& box, const QueryFilter& filter) const {
  query_detail::check_finite(box.min, "box.min");
  query_detail::check_finite(box.max, "box.max");
  query_detail::check_size(Vec3(box.max - box.min), "box.max - box.min");
  const BodyFilter seen(*snapshot_, filter);
  return bodies_touching(*snapshot_, seen, box, [&](const LeafGroup& group) {
    return query_detail::group_touches_aabb(*snapshot_, group, box);
  });
}

std::vector<BodyId> WorldQuery::overlap_box(const OrientedBox& box,
                                            const QueryFilter& filter) const {
  query_detail::check_pose(box.pose, "box.pose");
  query_detail::check_size(box.half_extents, "box.half_extents");
  const BodyFilter seen(*snapshot_, filter);
  const Mat3 rotation = box.pose.rotation.normalized().toRotationMatrix();
  // The world box around the turned box: each world axis gets |R| times the half extents.
  const Vec3 reach = rotation.cwiseAbs() * box.half_extents;
  const Aabb bounds{box.pose.translation - reach, box.pose.translation + reach};
  return bodies_touching(*snapshot_, seen, bounds, [&](const LeafGroup& group) {
    return query_detail::group_touches_oriented_box(*snapshot_, group, rotation,
                                                    box.pose.translation, box.half_extents);
  });
}

std::vector<BodyId> WorldQuery::overlap_tree(const SphereTree& tree, const Transform& pose,
                                             const QueryFilter& filter) const {
  query_detail::check_pose(pose, "pose");
  if (tree.empty()) throw Error("tree: empty");
  const BodyFilter seen(*snapshot_, filter);
  // The tree's leaves in the world frame, each with its box.
  const query_detail::LeafRange range = query_detail::leaf_range(tree, snapshot_->tree_depth);
  const Mat3 rotation = pose.rotation.normalized().toRotationMatrix();
  std::vector<Sphere> leaves;
  std::vector<Aabb> boxes;
  Aabb bounds;
  for (std::uint32_t n = 0; n < range.end; ++n) {
    if (!query_detail::acts_as_leaf(tree, range, n)) continue;
    const Sphere leaf{rotation * tree.sphere(n).center + pose.translation, tree.sphere(n).radius};
    leaves.push_back(leaf);
    boxes.push_back(Aabb::around_sphere(leaf.center, leaf.radius));
    bounds.extend(boxes.back());
  }
  return bodies_touching(*snapshot_, seen, bounds, [&](const LeafGroup& group) {
    for (std::size_t i = 0; i < leaves.size(); ++i) {
      if (boxes[i].overlaps(group.bounds) &&
          query_detail::group_touches_sphere(*snapshot_, group, leaves[i].center,
                                             leaves[i].radius)) {
        return true;
      }
    }
    return false;
  });
}

std::vector<BodyId> WorldQuery::overlap_body(BodyId body, const Transform& pose,
                                             QueryFilter filter) const {
  const std::uint32_t slot = query_detail::checked_slot(*snapshot_, body, "body");
  filter.skip.push_back(body);
  return overlap_tree(*snapshot_->trees[slot], pose, filter);
}

}  // namespace sphys
