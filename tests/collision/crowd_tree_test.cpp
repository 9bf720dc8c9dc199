// The crowd rule's tree (collision/crowd_tree.h): each box's overlaps counted and listed, and a
// box's nearest marked partners, checked against every pair of boxes tested by hand, on boxes
// that touch, coincide or are static, and on a crowd at one point.
#include "collision/crowd_tree.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace sphys::test {
namespace {

struct TreeBox {
  BoxBounds bounds{};
  bool is_static = false;
  bool marked = false;
};

// Overlap as the broad phases see it: closed intervals, never two static boxes.
bool pair_overlaps(const TreeBox& a, const TreeBox& b) {
  return !(a.is_static && b.is_static) && boxes_overlap(a.bounds, b.bounds);
}

std::vector<ProxyId> brute_overlaps(const std::vector<TreeBox>& boxes, ProxyId id) {
  std::vector<ProxyId> found;
  for (ProxyId other = 0; other < boxes.size(); ++other) {
    if (other != id && pair_overlaps(boxes[id], boxes[other])) found.push_back(other);
  }
  return found;
}

// Every marked partner overlapping `id`, sorted by (distance, id), the first `count` of them.
std::vector<CrowdPartner> brute_nearest(const std::vector<TreeBox>& boxes, ProxyId id,
                                        std::size_t count) {
  std::vector<CrowdPartner> partners;
  for (const ProxyId other : brute_overlaps(boxes, id)) {
    if (!boxes[other].marked) continue;
    const ProxyId low = std::min(id, other);
    const ProxyId high = std::max(id, other);
    partners.push_back({centre_distance2(boxes[low].bounds, boxes[high].bounds), other});
  }
  std::sort(partners.begin(), partners.end());
  partners.resize(std::min(count, partners.size()));
  return partners;
}

CrowdTree tree_of(const std::vector<TreeBox>& boxes) {
  CrowdTree tree;
  tree.clear();
  for (ProxyId id = 0; id < boxes.size(); ++id) tree.add(id, boxes[id].bounds, boxes[id].is_static);
  tree.build();
  std::vector<std::uint8_t> marked;
  for (const TreeBox& box : boxes) marked.push_back(box.marked ? 1 : 0);
  tree.mark(marked);
  return tree;
}

void expect_matches_brute_force(const std::vector<TreeBox>& boxes, std::size_t count) {
  const CrowdTree tree = tree_of(boxes);
  std::vector<CrowdPartner> nearest;
  for (ProxyId id = 0; id < boxes.size(); ++id) {
    const std::vector<ProxyId> expected = brute_overlaps(boxes, id);
    EXPECT_EQ(tree.count_overlaps(id), expected.size()) << "box " << id;
    std::vector<ProxyId> listed;
    tree.for_each_overlap(id, [&](ProxyId other) { listed.push_back(other); });
    std::sort(listed.begin(), listed.end());
    EXPECT_EQ(listed, expected) << "box " << id;
    tree.nearest(id, count, nearest);
    std::sort(nearest.begin(), nearest.end());
    EXPECT_EQ(nearest, brute_nearest(boxes, id, count)) << "box " << id;
  }
}

// Boxes on a coarse lattice (so that many touch, and some coincide), of sizes from a tenth to
// twice the lattice, a tenth of them static, a third marked.
std::vector<TreeBox> lattice_boxes(std::uint32_t seed, int count, float region) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const auto snap = [](float x) { return std::round(x * 4.0f) / 4.0f; };
  std::vector<TreeBox> boxes(static_cast<std::size_t>(count));
  for (TreeBox& box : boxes) {
    for (int k = 0; k < 3; ++k) {
      const float centre = snap(unit(rng) * region);
      const float half = snap(0.1f + unit(rng));
      box.bounds[k] = centre - half;
      box.bounds[k + 3] = centre + half;
    }
    box.is_static = unit(rng) < 0.1f;
    box.marked = !box.is_static && unit(rng) < 0.35f;
  }
  return boxes;
}

TEST(CrowdTree, CountsListsAndFindsTheNearestAsEveryPairTestedByHand) {
  for (const std::uint32_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    expect_matches_brute_force(lattice_boxes(seed, 400, 6.0f), 16);
  }
}

TEST(CrowdTree, ADenseHeapMatchesEveryPairTestedByHand) {
  expect_matches_brute_force(lattice_boxes(4, 300, 1.5f), 4);
}

// Boxes at one point: every box overlaps every other, all at distance 0, so each box's nearest
// are the lowest ids but its own; a static box over all of them overlaps every dynamic one.
TEST(CrowdTree, BoxesAtOnePointPickTheLowestIds) {
  constexpr ProxyId kBoxes = 2000;
  std::vector<TreeBox> boxes(kBoxes, TreeBox{{-0.1f, 0.9f, -0.1f, 0.1f, 1.1f, 0.1f}, false, true});
  boxes.push_back({{-5.0f, -1.0f, -5.0f, 5.0f, 0.95f, 5.0f}, true, false});
  const CrowdTree tree = tree_of(boxes);
  std::vector<CrowdPartner> nearest;
  for (const ProxyId id : {ProxyId{0}, ProxyId{3}, ProxyId{16}, ProxyId{1999}}) {
    EXPECT_EQ(tree.count_overlaps(id), kBoxes);  // the others and the static box
    tree.nearest(id, 16, nearest);
    std::sort(nearest.begin(), nearest.end());
    std::vector<CrowdPartner> expected;
    for (ProxyId other = 0; expected.size() < 16; ++other) {
      if (other != id) expected.push_back({0.0f, other});
    }
    EXPECT_EQ(nearest, expected) << "box " << id;
  }
  EXPECT_EQ(tree.count_overlaps(kBoxes), kBoxes);
  std::uint32_t listed = 0;
  tree.for_each_overlap(kBoxes, [&](ProxyId) { ++listed; });
  EXPECT_EQ(listed, kBoxes);
}

}  // namespace
}  // namespace sphys::test
