#pragma once

// A tree over one Sweep & Prune's boxes for the crowd rule (collision/crowd.h, Crowd::list;
// docs/collision.md, "Crowds"): boxes piled on each other overlap by the square of their number,
// and the rule needs each box's overlaps counted and each crowded box's nearest few, never the
// overlaps themselves. The tree answers both without listing them.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "collision/broad_phase.h"

namespace sphys {

// A box as six floats, min x y z then max x y z (unit: m).
using BoxBounds = std::array<float, 6>;

// The squared distance of two boxes' centres (unit: m²), `a` the box of the lower id: the crowd
// rule's measure of nearness, computed so that every caller gets the same bits.
inline float centre_distance2(const BoxBounds& a, const BoxBounds& b) {
  float distance2 = 0.0f;
  for (int k = 0; k < 3; ++k) {
    const float d = 0.5f * (a[k] + a[k + 3] - b[k] - b[k + 3]);
    distance2 += d * d;
  }
  return distance2;
}

// Whether two boxes overlap, as Aabb::overlaps says: closed intervals, so boxes that touch do.
inline bool boxes_overlap(const BoxBounds& p, const BoxBounds& q) {
  return p[0] <= q[3] && q[0] <= p[3] && p[1] <= q[4] && q[1] <= p[4] && p[2] <= q[5] &&
         q[2] <= p[5];
}

// A crowded box's partner, ordered by distance (centre_distance2; unit: m²), then id.
struct CrowdPartner {
  float distance2 = 0.0f;
  ProxyId other = 0;
  friend auto operator<=>(const CrowdPartner&, const CrowdPartner&) = default;
};

// A kd-tree over boxes, split at the median of their centres (ties by id), built afresh for each
// listing: O(n log n). Each node knows the bounds that all its boxes reach and those they all
// share, so that a box covering all of a node's boxes counts them at once: a crowd at one point
// counts every box's overlaps in O(n log n), not O(n²). Static boxes never overlap each other
// here, as in the broad phases. Deterministic: answers depend on the boxes alone.
class CrowdTree {
 public:
  // Starts a tree afresh; add() the boxes (each id once), then build().
  void clear();
  void add(ProxyId id, const BoxBounds& box, bool is_static);
  void build();

  // The boxes of the tree that overlap box `id`'s (which must be in the tree), itself left out.
  [[nodiscard]] std::uint32_t count_overlaps(ProxyId id) const;
  // Hands `found` the id of every box of the tree that overlaps box `id`'s, itself left out.
  template <class Found>
  void for_each_overlap(ProxyId id, const Found& found) const;

  // Marks the boxes that nearest() chooses among: those with marked[id] != 0.
  void mark(const std::vector<std::uint8_t>& marked);
  // The `count` nearest marked boxes that overlap box `id`'s (by CrowdPartner's order, itself
  // left out), into `nearest` (replaced; in no particular order).
  void nearest(ProxyId id, std::size_t count, std::vector<CrowdPartner>& nearest) const;

 private:
  static constexpr ProxyId kNone = ~ProxyId{0};

  // Lengths in m.
  struct Item {
    BoxBounds box{};
    std::array<float, 3> centre{};
    std::array<float, 3> largest{};  // the largest coordinate's magnitude, per axis
    ProxyId id = 0;
    bool is_static = false;
    bool marked = false;
  };
  // Lengths in m.
  struct Node {
    BoxBounds reach{};   // min of the mins, max of the maxes: what some box of it reaches
    BoxBounds shared{};  // max of the mins, min of the maxes: what every box of it reaches
    std::array<float, 3> centre_min{};
    std::array<float, 3> centre_max{};
    std::array<float, 3> largest{};  // the largest coordinate's magnitude, per axis
    std::uint32_t begin = 0;         // items_[begin, end)
    std::uint32_t end = 0;
    std::uint32_t children = 0;     // the first of two, in nodes_; 0 for a leaf
    std::uint32_t dynamic = 0;      // dynamic boxes among them
    ProxyId lowest_marked = kNone;  // the lowest marked id among them
  };

  void build_node(std::uint32_t index, std::uint32_t begin, std::uint32_t end);
  void bound_node(Node& node) const;
  [[nodiscard]] const Item& item(ProxyId id) const { return items_[slot_of_[id]]; }
  // The boxes of a subtree that overlap `box`, counting static ones only if `with_static`.
  [[nodiscard]] std::uint32_t count_in(const Node& node, const BoxBounds& box,
                                       bool with_static) const;
  template <class Found>
  void overlaps_in(const Node& node, const Item& query, const Found& found) const;
  // A lower bound of centre_distance2 from `query` to every box of the node, whatever the
  // rounding. unit: m²
  [[nodiscard]] float distance2_bound(const Node& node, const Item& query) const;
  void nearest_in(const Node& node, const CrowdPartner& bound, const Item& query, std::size_t count,
                  std::vector<CrowdPartner>& heap) const;

  std::vector<Item> items_;
  std::vector<std::uint32_t> slot_of_;  // per id: its place in items_
  std::vector<Node> nodes_;             // nodes_[0] the root; children after their parent
};

template <class Found>
void CrowdTree::for_each_overlap(ProxyId id, const Found& found) const {
  if (!nodes_.empty()) overlaps_in(nodes_[0], item(id), found);
}

template <class Found>
void CrowdTree::overlaps_in(const Node& node, const Item& query, const Found& found) const {
  if (!boxes_overlap(node.reach, query.box)) return;
  if (query.is_static && node.dynamic == 0) return;
  if (node.children != 0) {
    overlaps_in(nodes_[node.children], query, found);
    overlaps_in(nodes_[node.children + 1], query, found);
    return;
  }
  for (std::uint32_t i = node.begin; i < node.end; ++i) {
    const Item& other = items_[i];
    if (other.id == query.id || (query.is_static && other.is_static)) continue;
    if (boxes_overlap(other.box, query.box)) found(other.id);
  }
}

}  // namespace sphys
