#include "query/snapshot.h"

#include <algorithm>
#include <numeric>

namespace sphys::query_detail {
namespace {

// Groups per leaf of the hierarchy: two keep a leaf's boxes tight and the tree shallow.
constexpr std::uint32_t kGroupsPerBvhLeaf = 2;

// Fills bvh[index] as the node over groups[order[begin..end)], halving at the median of the
// groups' centres along the widest axis of those centres. An inner node's two children are
// appended side by side before either is filled.
void build_node(std::vector<BvhNode>& bvh, const std::vector<LeafGroup>& groups,
                std::vector<std::uint32_t>& order, std::uint32_t index, std::uint32_t begin,
                std::uint32_t end) {
  Aabb bounds;
  Aabb centres;
  for (std::uint32_t i = begin; i < end; ++i) {
    bounds.extend(groups[order[i]].bounds);
    centres.extend(groups[order[i]].bounds.center());
  }
  bvh[index].bounds = bounds;
  if (end - begin <= kGroupsPerBvhLeaf) {
    bvh[index].first = begin;
    bvh[index].count = end - begin;
    return;
  }
  int axis = 0;
  centres.size().maxCoeff(&axis);
  const std::uint32_t middle = begin + (end - begin) / 2;
  std::nth_element(order.begin() + begin, order.begin() + middle, order.begin() + end,
                   [&](std::uint32_t a, std::uint32_t b) {
                     return groups[a].bounds.center()[axis] < groups[b].bounds.center()[axis];
                   });
  const auto left = static_cast<std::uint32_t>(bvh.size());
  bvh.resize(bvh.size() + 2);
  bvh[index].first = left;
  bvh[index].count = 0;
  build_node(bvh, groups, order, left, begin, middle);
  build_node(bvh, groups, order, left + 1, middle, end);
}

}  // namespace

LeafRange leaf_range(const SphereTree& tree, int depth) {
  const int last = tree.last_level(depth);
  return {tree.level_begin(last), tree.level_end(last)};
}

void Snapshot::read(const World& world) {
  // One state of the world, read whole: a step or change on another thread throws meanwhile.
  const World::Reading reading(world);
  tree_depth = world.settings().collision.tree_depth;
  const BodyStore& store = world.bodies();
  const std::uint32_t slots = store.slots();
  poses.assign(store.poses().begin(), store.poses().end());
  ids.assign(slots, BodyId{});
  trees.assign(slots, nullptr);
  asleep.assign(slots, 0);
  x.clear();
  y.clear();
  z.clear();
  radius.clear();
  node.clear();
  std::vector<LeafGroup> made;
  for (std::uint32_t slot = 0; slot < slots; ++slot) {
    if (!store.alive(slot)) continue;
    ids[slot] = store.id_of(slot);
    trees[slot] = world.shared_tree(ids[slot]);
    const SphereTree& tree = *trees[slot];
    asleep[slot] = store.asleep(slot) ? 1 : 0;
    const Transform& pose = poses[slot];
    const Mat3 rotation = pose.rotation.toRotationMatrix();
    const LeafRange range = leaf_range(tree, tree_depth);
    LeafGroup group;
    const auto close_group = [&] {
      if (group.count == 0) return;
      for (std::uint32_t pad = group.count; pad < group.padded(); ++pad) {
        x.push_back(kPaddingCentre);
        y.push_back(kPaddingCentre);
        z.push_back(kPaddingCentre);
        radius.push_back(0.0f);
        node.push_back(0);
      }
      made.push_back(group);
      group = LeafGroup{};
    };
    // Breadth-first order keeps siblings adjacent, so consecutive leaves make compact groups.
    for (std::uint32_t n = 0; n < range.end; ++n) {
      if (!acts_as_leaf(tree, range, n)) continue;
      if (group.count == 0) {
        group.body = slot;
        group.first = static_cast<std::uint32_t>(x.size());
      }
      const Sphere& sphere = tree.sphere(n);
      const Vec3 centre = rotation * sphere.center + pose.translation;
      x.push_back(centre.x());
      y.push_back(centre.y());
      z.push_back(centre.z());
      radius.push_back(sphere.radius);
      node.push_back(n);
      group.bounds.extend(Aabb::around_sphere(centre, sphere.radius));
      if (++group.count == kGroupLeaves) close_group();
    }
    close_group();
  }

  bvh.clear();
  groups.clear();
  if (made.empty()) return;
  std::vector<std::uint32_t> order(made.size());
  std::iota(order.begin(), order.end(), 0u);
  bvh.reserve(2 * made.size());
  bvh.resize(1);
  build_node(bvh, made, order, 0, 0, static_cast<std::uint32_t>(made.size()));
  groups.reserve(made.size());
  for (const std::uint32_t i : order) groups.push_back(made[i]);
}

}  // namespace sphys::query_detail
