// The groups near each link's box, collected for kLinksPerWalk links at a time, their boxes in
// lanes: by one walk of the snapshot's hierarchy, or, with every link inside the reach's box, by a
// scan of the groups that meet it.

#include <algorithm>
#include <array>
#include <bit>

#include "robot/configuration_scratch.h"

namespace sphys {
namespace {

using query_detail::kLaneWidth;
using query_detail::Lanes;
using query_detail::Snapshot;

}  // namespace

void ConfigurationChecker::collect_candidates(Scratch& scratch) const {
  for (std::size_t first = 0; first < link_count_; first += kLinksPerWalk) {
    collect_candidates(first, std::min(link_count_, first + kLinksPerWalk), scratch);
  }
}

void ConfigurationChecker::collect_candidates(std::size_t first, std::size_t end,
                                              Scratch& scratch) const {
  const Snapshot& snapshot = query_->snapshot();
  // The links' boxes in lanes, link first + k in lane k; a link without spheres meets nothing
  // (its lanes, and those past the last link, are never among the links a test asks about).
  const float* low_x = scratch.row(0) + first;
  const float* low_y = scratch.row(1) + first;
  const float* low_z = scratch.row(2) + first;
  const float* high_x = scratch.row(3) + first;
  const float* high_y = scratch.row(4) + first;
  const float* high_z = scratch.row(5) + first;
  const std::size_t registers = (end - first + kLaneWidth - 1) / kLaneWidth;
  std::uint32_t walking = 0;  // bit k: link first + k is still collecting
  for (std::size_t k = 0; k < end - first; ++k) {
    scratch.candidate_count[first + k] = 0;
    if (scratch.spheres[first + k] != 0) walking |= 1u << k;
  }
  if (walking == 0 || snapshot.bvh.empty()) return;
  // Bit k: link first + k, among `among`, has a box that meets this one (touching counts).
  const auto reached = [&](const Aabb& box, std::uint32_t among) {
    std::uint32_t out = 0;
    for (std::size_t r = 0; r < registers; ++r) {
      const std::size_t lane = r * kLaneWidth;
      if (((among >> lane) & ((1u << kLaneWidth) - 1)) == 0) continue;
      const auto meets = [&](const float* lows, const float* highs, float box_low, float box_high) {
        return (Lanes::load(&lows[lane]) <= Lanes::splat(box_high)) &
               (Lanes::splat(box_low) <= Lanes::load(&highs[lane]));
      };
      out |= bits(meets(low_x, high_x, box.min.x(), box.max.x()) &
                  meets(low_y, high_y, box.min.y(), box.max.y()) &
                  meets(low_z, high_z, box.min.z(), box.max.z()))
             << lane;
    }
    return out & among;
  };
  // Groups a link's box meets, in the order a walk of the hierarchy meets them (a group's box
  // lies inside every box above it, so a walk reaches exactly the groups whose boxes meet the
  // link's): each appended to the candidates of the links in `hit`.
  const auto take = [&](std::uint32_t g, std::uint32_t hit) {
    for (; hit != 0; hit &= hit - 1) {
      const auto k = static_cast<std::size_t>(std::countr_zero(hit));
      std::int32_t& count = scratch.candidate_count[first + k];
      if (count == static_cast<std::int32_t>(Scratch::kMostCandidates)) {
        // Near too many: this link's spheres walk the hierarchy one by one.
        count = Scratch::kTooMany;
        walking &= ~(1u << k);
        continue;
      }
      scratch.candidates[(first + k) * Scratch::kMostCandidates + count++] = g;
    }
  };
  // Every link inside the reach's box: the groups that meet that box, scanned in order.
  if (reach_box_) {
    std::uint32_t inside = 0;
    for (std::size_t r = 0; r < registers; ++r) {
      const std::size_t lane = r * kLaneWidth;
      const auto within = [&](const float* lows, const float* highs, float box_low,
                              float box_high) {
        return (Lanes::splat(box_low) <= Lanes::load(&lows[lane])) &
               (Lanes::load(&highs[lane]) <= Lanes::splat(box_high));
      };
      const Aabb& box = *reach_box_;
      inside |= bits(within(low_x, high_x, box.min.x(), box.max.x()) &
                     within(low_y, high_y, box.min.y(), box.max.y()) &
                     within(low_z, high_z, box.min.z(), box.max.z()))
                << lane;
    }
    if ((inside & walking) == walking) {
      for (const std::uint32_t g : reachable_groups_) {
        if (walking == 0) return;
        const Aabb& bounds = snapshot.groups[g].bounds;
        // Most groups miss the box around every link: one test spares each link's.
        if (scratch.around_known && !scratch.around.overlaps(bounds)) continue;
        take(g, reached(bounds, walking));
      }
      return;
    }
  }
  // One walk for every link, depth first and left first as each link's own walk would go, so
  // that each link's groups come in the same order: a node is entered by the links that reach
  // it and every box above it.
  struct Entry {
    std::uint32_t node;
    std::uint32_t links;
  };
  std::array<Entry, query_detail::kMaxBvhDepth> stack;
  int top = 0;
  const std::uint32_t at_root = reached(snapshot.bvh[0].bounds, walking);
  if (at_root != 0) stack[top++] = {0, at_root};
  while (top > 0) {
    const Entry entry = stack[--top];
    const std::uint32_t links = entry.links & walking;
    if (links == 0) continue;
    const query_detail::BvhNode& node = snapshot.bvh[entry.node];
    if (node.count == 0) {
      const std::uint32_t right = reached(snapshot.bvh[node.first + 1].bounds, links);
      const std::uint32_t left = reached(snapshot.bvh[node.first].bounds, links);
      if (right != 0) stack[top++] = {node.first + 1, right};
      if (left != 0) stack[top++] = {node.first, left};
      continue;
    }
    for (std::uint32_t g = node.first; g < node.first + node.count; ++g) {
      if (group_seen_[g] != 0) take(g, reached(snapshot.groups[g].bounds, links & walking));
    }
  }
}

}  // namespace sphys
