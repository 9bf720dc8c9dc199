#include "collision/crowd_tree.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace sphys {
namespace {

// Boxes per leaf: a leaf's boxes are tested one by one.
constexpr std::uint32_t kLeafItems = 8;

// How far a centre computed one way may lie from the same centre computed another, relative to
// the largest coordinate involved (a few roundings of 2^-24 each, with room to spare).
// unit: dimensionless
constexpr float kCentreSlack = 1e-5f;

}  // namespace

void CrowdTree::clear() {
  items_.clear();
  nodes_.clear();
}

void CrowdTree::add(ProxyId id, const BoxBounds& box, bool is_static) {
  Item item;
  item.box = box;
  for (int k = 0; k < 3; ++k) {
    item.centre[k] = 0.5f * (box[k] + box[k + 3]);
    item.largest[k] = std::max(std::abs(box[k]), std::abs(box[k + 3]));
  }
  item.id = id;
  item.is_static = is_static;
  items_.push_back(item);
}

void CrowdTree::build() {
  nodes_.clear();
  if (items_.empty()) return;
  nodes_.emplace_back();
  build_node(0, 0, static_cast<std::uint32_t>(items_.size()));
  ProxyId ids = 0;
  for (const Item& item : items_) ids = std::max(ids, item.id + 1);
  slot_of_.assign(ids, 0);
  for (std::uint32_t slot = 0; slot < items_.size(); ++slot) slot_of_[items_[slot].id] = slot;
}

// Bounds nodes_[index] over items_[begin, end) and, past a leaf's size, splits it at the median
// of the centres along their widest axis.
void CrowdTree::build_node(std::uint32_t index, std::uint32_t begin, std::uint32_t end) {
  Node node;
  node.begin = begin;
  node.end = end;
  bound_node(node);
  const std::uint32_t middle = begin + (end - begin) / 2;
  if (end - begin > kLeafItems) {
    int axis = 0;
    for (int k = 1; k < 3; ++k) {
      if (node.centre_max[k] - node.centre_min[k] > node.centre_max[axis] - node.centre_min[axis]) {
        axis = k;
      }
    }
    // Ties by id: boxes at one point split by id, which nearest() then prunes by.
    std::nth_element(items_.begin() + begin, items_.begin() + middle, items_.begin() + end,
                     [axis](const Item& a, const Item& b) {
                       return std::tie(a.centre[axis], a.id) < std::tie(b.centre[axis], b.id);
                     });
    node.children = static_cast<std::uint32_t>(nodes_.size());
    nodes_.resize(nodes_.size() + 2);
  }
  nodes_[index] = node;
  if (node.children == 0) return;
  build_node(node.children, begin, middle);
  build_node(node.children + 1, middle, end);
}

void CrowdTree::bound_node(Node& node) const {
  const Item& first = items_[node.begin];
  node.reach = first.box;
  node.shared = first.box;
  node.centre_min = first.centre;
  node.centre_max = first.centre;
  node.largest = first.largest;
  node.dynamic = 0;
  for (std::uint32_t i = node.begin; i < node.end; ++i) {
    const Item& item = items_[i];
    for (int k = 0; k < 3; ++k) {
      node.reach[k] = std::min(node.reach[k], item.box[k]);
      node.reach[k + 3] = std::max(node.reach[k + 3], item.box[k + 3]);
      node.shared[k] = std::max(node.shared[k], item.box[k]);
      node.shared[k + 3] = std::min(node.shared[k + 3], item.box[k + 3]);
      node.centre_min[k] = std::min(node.centre_min[k], item.centre[k]);
      node.centre_max[k] = std::max(node.centre_max[k], item.centre[k]);
      node.largest[k] = std::max(node.largest[k], item.largest[k]);
    }
    node.dynamic += item.is_static ? 0 : 1;
  }
}

std::uint32_t CrowdTree::count_overlaps(ProxyId id) const {
  const Item& query = item(id);
  const std::uint32_t count = count_in(nodes_[0], query.box, !query.is_static);
  return query.is_static ? count : count - 1;  // a dynamic box counted itself
}

std::uint32_t CrowdTree::count_in(const Node& node, const BoxBounds& box, bool with_static) const {
  const std::uint32_t boxes = with_static ? node.end - node.begin : node.dynamic;
  if (boxes == 0 || !boxes_overlap(node.reach, box)) return 0;
  // Every box of the node starts before `box` ends and ends after it starts, on every axis.
  if (boxes_overlap(node.shared, box)) return boxes;
  if (node.children != 0) {
    return count_in(nodes_[node.children], box, with_static) +
           count_in(nodes_[node.children + 1], box, with_static);
  }
  std::uint32_t count = 0;
  for (std::uint32_t i = node.begin; i < node.end; ++i) {
    const Item& other = items_[i];
    if ((with_static || !other.is_static) && boxes_overlap(other.box, box)) ++count;
  }
  return count;
}

void CrowdTree::mark(const std::vector<std::uint8_t>& marked) {
  for (Item& item : items_) item.marked = item.id < marked.size() && marked[item.id] != 0;
  // Children come after their parent: from the last node back, each finds its children done.
  for (std::size_t index = nodes_.size(); index-- > 0;) {
    Node& node = nodes_[index];
    node.lowest_marked = kNone;
    if (node.children != 0) {
      node.lowest_marked =
          std::min(nodes_[node.children].lowest_marked, nodes_[node.children + 1].lowest_marked);
      continue;
    }
    for (std::uint32_t i = node.begin; i < node.end; ++i) {
      if (items_[i].marked) node.lowest_marked = std::min(node.lowest_marked, items_[i].id);
    }
  }
}

float CrowdTree::distance2_bound(const Node& node, const Item& query) const {
  float bound = 0.0f;
  for (int k = 0; k < 3; ++k) {
    const float c = query.centre[k];
    const float largest = std::max(node.largest[k], query.largest[k]);
    const float gap = std::max({node.centre_min[k] - c, c - node.centre_max[k], 0.0f});
    const float sure_gap = std::max(0.0f, gap - kCentreSlack * largest);
    bound += sure_gap * sure_gap;
  }
  return bound * (1.0f - kCentreSlack);
}

void CrowdTree::nearest(ProxyId id, std::size_t count, std::vector<CrowdPartner>& nearest) const {
  nearest.clear();
  if (nodes_.empty() || count == 0) return;
  const Item& query = item(id);
  const Node& root = nodes_[0];
  nearest_in(root, {distance2_bound(root, query), root.lowest_marked}, query, count, nearest);
}

// A bounded max-heap of the nearest so far; a subtree is skipped when none of its boxes can come
// before the farthest kept, by distance or, at equal distance, by id: when `bound` (no box of
// the node nearer, none of a lower id) does not come before it.
void CrowdTree::nearest_in(const Node& node, const CrowdPartner& bound, const Item& query,
                           std::size_t count, std::vector<CrowdPartner>& heap) const {
  if (node.lowest_marked == kNone || !boxes_overlap(node.reach, query.box)) return;
  if (heap.size() == count && !(bound < heap.front())) return;
  if (node.children != 0) {
    const Node& first = nodes_[node.children];
    const Node& second = nodes_[node.children + 1];
    const CrowdPartner first_bound{distance2_bound(first, query), first.lowest_marked};
    const CrowdPartner second_bound{distance2_bound(second, query), second.lowest_marked};
    if (second_bound < first_bound) {
      nearest_in(second, second_bound, query, count, heap);
      nearest_in(first, first_bound, query, count, heap);
    } else {
      nearest_in(first, first_bound, query, count, heap);
      nearest_in(second, second_bound, query, count, heap);
    }
    return;
  }
  for (std::uint32_t i = node.begin; i < node.end; ++i) {
    const Item& other = items_[i];
    if (!other.marked || other.id == query.id || !boxes_overlap(other.box, query.box)) continue;
    const bool query_lower = query.id < other.id;
    const CrowdPartner partner{
        centre_distance2(query_lower ? query.box : other.box, query_lower ? other.box : query.box),
        other.id};
    if (heap.size() < count) {
      heap.push_back(partner);
      std::push_heap(heap.begin(), heap.end());
    } else if (partner < heap.front()) {
      std::pop_heap(heap.begin(), heap.end());
      heap.back() = partner;
      std::push_heap(heap.begin(), heap.end());
    }
  }
}

}  // namespace sphys
