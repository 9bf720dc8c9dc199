#include "collision/contact_reduction.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/contact.h"
#include "sphys/error.h"
#include "support/vec_near.h"

namespace sphys {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

// leaf_a is the contact's index in its run, so that an output contact names the input it came from.
Contact contact_at(const Vec3& point, float depth, std::uint32_t leaf,
                   const Vec3& normal = Vec3::UnitY(), std::uint32_t body_a = 1,
                   std::uint32_t body_b = 2) {
  Contact c;
  c.body_a = body_a;
  c.body_b = body_b;
  c.point = point;
  c.normal = normal;
  c.depth = depth;
  c.leaf_a = leaf;
  c.leaf_b = 1000 + leaf;
  return c;
}

// 5 × 5 contacts one metre apart on the plane y = 0; contact i*5 + j lies at (i, 0, j), so the
// corners are 0, 4, 20 and 24 and the centre is 12.
std::vector<Contact> grid_5x5(float depth, std::uint32_t body_a = 1, std::uint32_t body_b = 2) {
  std::vector<Contact> grid;
  for (std::uint32_t i = 0; i < 5; ++i) {
    for (std::uint32_t j = 0; j < 5; ++j) {
      grid.push_back(contact_at(Vec3(static_cast<float>(i), 0, static_cast<float>(j)), depth,
                                i * 5 + j, Vec3::UnitY(), body_a, body_b));
    }
  }
  return grid;
}

// Each run of one body pair's contacts reduced in turn, as the detector does pair by pair; `kept`
// stands for the pairs' records: a pair's manifold from the last reduction.
std::vector<Contact> reduce_runs(ContactReducer& reducer, std::span<const Contact> contacts,
                                 std::uint32_t max_points, std::span<const Contact> kept = {}) {
  std::vector<Contact> reduced;
  std::vector<Contact> kept_of_pair;
  for (std::size_t begin = 0; begin < contacts.size();) {
    std::size_t end = begin + 1;
    const auto same_pair = [&](const Contact& c) {
      return c.body_a == contacts[begin].body_a && c.body_b == contacts[begin].body_b;
    };
    while (end < contacts.size() && same_pair(contacts[end])) ++end;
    kept_of_pair.clear();
    std::copy_if(kept.begin(), kept.end(), std::back_inserter(kept_of_pair), same_pair);
    reducer.reduce(contacts.subspan(begin, end - begin), max_points, kept_of_pair, reduced);
    begin = end;
  }
  return reduced;
}

std::vector<Contact> reduce(std::span<const Contact> contacts, std::uint32_t max_points) {
  ContactReducer reducer;
  return reduce_runs(reducer, contacts, max_points);
}

std::vector<std::uint32_t> leaves_of(std::span<const Contact> contacts) {
  std::vector<std::uint32_t> leaves;
  for (const Contact& c : contacts) leaves.push_back(c.leaf_a);
  return leaves;
}

bool identical(const Contact& a, const Contact& b) {
  return a.body_a == b.body_a && a.body_b == b.body_b && a.point == b.point &&
         a.normal == b.normal && a.depth == b.depth && a.leaf_a == b.leaf_a && a.leaf_b == b.leaf_b;
}

void expect_identical(std::span<const Contact> actual, std::span<const Contact> expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    EXPECT_TRUE(identical(actual[i], expected[i])) << "contact " << i;
  }
}

std::string error_message(std::uint32_t max_points) {
  const std::vector<Contact> grid = grid_5x5(0.01f);
  try {
    reduce(grid, max_points);
  } catch (const Error& error) {
    return error.what();
  }
  return "no error";
}

TEST(ContactReducer, RunsWithinTheLimitAreCopiedUnchanged) {
  const std::vector<Contact> run = {
      contact_at(Vec3(0, 0, 0), 0.01f, 0, Vec3(0.6f, 0.8f, 0)),
      contact_at(Vec3(0, 0, 0), 0.03f, 1),  // coincident, yet kept: the run is small enough
      contact_at(Vec3(1, 2, 3), -0.02f, 2, Vec3(0, 0, 1)),
      contact_at(Vec3(4, 0, 1), 0.0f, 3, Vec3(0, -1, 0)),
  };
  expect_identical(reduce(run, 4), run);
  expect_identical(reduce(run, 8), run);
  expect_identical(reduce(std::span(run).first(1), 1), std::span(run).first(1));
}

TEST(ContactReducer, AppendsWithoutTouchingWhatIsAlreadyThere) {
  const std::vector<Contact> grid = grid_5x5(0.01f);
  const Contact earlier = contact_at(Vec3(9, 9, 9), 0.5f, 77, Vec3::UnitX(), 5, 6);
  std::vector<Contact> reduced = {earlier};
  ContactReducer reducer;
  reducer.reduce(grid, 4, {}, reduced);
  ASSERT_EQ(reduced.size(), 5u);
  EXPECT_TRUE(identical(reduced[0], earlier));
}

TEST(ContactReducer, RunsOfDifferentBodyPairsStayApartAndInOrder) {
  std::vector<Contact> contacts = grid_5x5(0.01f, 1, 2);
  contacts.push_back(contact_at(Vec3(0, 0, 0), 0.02f, 100, Vec3::UnitY(), 1, 3));
  contacts.push_back(contact_at(Vec3(1, 0, 0), 0.02f, 101, Vec3::UnitY(), 1, 3));
  // The pair (1, 2) again, after another pair: a run of its own, not merged with the first.
  for (const Contact& c : grid_5x5(0.01f, 1, 2)) {
    contacts.push_back(c);
    contacts.back().leaf_a += 200;
  }
  // Same body_b, other body_a: another pair.
  for (const Contact& c : grid_5x5(0.01f, 4, 2)) {
    contacts.push_back(c);
    contacts.back().leaf_a += 300;
  }

  const std::vector<Contact> reduced = reduce(contacts, 4);
  EXPECT_THAT(leaves_of(reduced),
              ElementsAre(0, 24, 4, 20, 100, 101, 200, 224, 204, 220, 300, 324, 304, 320));
  for (std::size_t i = 0; i < reduced.size(); ++i) {
    const std::uint32_t run = reduced[i].leaf_a / 100;
    EXPECT_EQ(reduced[i].body_a, run == 3 ? 4u : 1u) << "contact " << i;
    EXPECT_EQ(reduced[i].body_b, run == 1 ? 3u : 2u) << "contact " << i;
  }
}

TEST(ContactReducer, AGridOnAPlaneReducesToItsFourCorners) {
  // Equal depths: the first contact counts as the deepest.
  EXPECT_THAT(leaves_of(reduce(grid_5x5(0.01f), 4)), ElementsAre(0, 24, 4, 20));

  std::vector<Contact> grid = grid_5x5(0.01f);
  grid[20].depth = 0.05f;
  const std::vector<Contact> reduced = reduce(grid, 4);
  // Deepest first, then the farthest corner, then the earlier of the two equal triangles.
  EXPECT_THAT(leaves_of(reduced), ElementsAre(20, 4, 0, 24));
  for (const Contact& c : reduced) {
    EXPECT_TRUE(identical(c, grid[c.leaf_a])) << "corner " << c.leaf_a;
  }
}

TEST(ContactReducer, TheFourthPointIsTheOneAddingTheMostArea) {
  const std::vector<Contact> run = {
      contact_at(Vec3(0, 0, 0), 0.05f, 0),   // deepest
      contact_at(Vec3(10, 0, 0), 0.01f, 1),  // farthest from it
      contact_at(Vec3(5, 0, 8), 0.01f, 2),   // largest triangle with those two
      contact_at(Vec3(5, 0, -1), 0.01f, 3),  // the farthest from those three, but adds 5 m²
      contact_at(Vec3(2, 0, -3), 0.01f, 4),  // nearer to them, and adds 15 m²
      contact_at(Vec3(6, 0, 4), 0.01f, 5),   // inside the triangle: adds nothing
  };
  EXPECT_THAT(leaves_of(reduce(run, 4)), ElementsAre(0, 1, 2, 4));
  // From the 5th point on, spread decides: 5 is 4.1 m from the nearest chosen point, 3 only 3.6.
  EXPECT_THAT(leaves_of(reduce(run, 5)), ElementsAre(0, 1, 2, 4, 5));
}

TEST(ContactReducer, TheDeepestContactIsKeptEvenInsideTheManifold) {
  std::vector<Contact> grid = grid_5x5(0.01f);
  grid[12].depth = 0.05f;  // the centre
  const std::vector<Contact> reduced = reduce(grid, 4);
  ASSERT_EQ(reduced.size(), 4u);
  EXPECT_EQ(reduced[0].leaf_a, 12u);
  EXPECT_FLOAT_EQ(reduced[0].depth, 0.05f);
  // The next is the farthest from the centre: the first corner, by the tie rule.
  EXPECT_EQ(reduced[1].leaf_a, 0u);
}

TEST(ContactReducer, EachDepthIsTheLargestOfItsCluster) {
  const std::vector<Contact> run = {
      contact_at(Vec3(0, 0, 0), 0.5f, 0),   // deepest: chosen first
      contact_at(Vec3(10, 0, 0), 0.1f, 1),  // farthest: chosen second
      contact_at(Vec3(1, 0, 0), 0.3f, 2),   // joins 0
      contact_at(Vec3(9, 0, 0), 0.4f, 3),   // joins 1, deeper than it
  };
  const std::vector<Contact> reduced = reduce(run, 2);
  EXPECT_THAT(leaves_of(reduced), ElementsAre(0, 1));
  ASSERT_EQ(reduced.size(), 2u);
  EXPECT_FLOAT_EQ(reduced[0].depth, 0.5f);
  EXPECT_FLOAT_EQ(reduced[1].depth, 0.4f);
  // The point stays the chosen contact's, whatever the cluster's deepest point.
  EXPECT_EQ(reduced[1].point, Vec3(10, 0, 0));
}

TEST(ContactReducer, TheNormalIsTheDepthWeightedMeanOfItsCluster) {
  const float s = std::sin(std::numbers::pi_v<float> / 6);
  const float c = std::cos(std::numbers::pi_v<float> / 6);
  const std::vector<Contact> run = {
      contact_at(Vec3(0, 0, 0), 0.3f, 0, Vec3(s, c, 0)),
      contact_at(Vec3(0.1f, 0, 0), 0.1f, 1, Vec3(-s, c, 0)),
      contact_at(Vec3(5, 0, 0), 0.05f, 2),
      contact_at(Vec3(5.1f, 0, 0), 0.2f, 3),
  };
  const std::vector<Contact> reduced = reduce(run, 2);
  EXPECT_THAT(leaves_of(reduced), ElementsAre(0, 3));
  ASSERT_EQ(reduced.size(), 2u);
  // 0.3 (s, c) + 0.1 (-s, c) = (0.1, 0.4 c) = (0.1, 0.34641), of length sqrt(0.13). The small
  // weight floor for touching contacts moves this by about 1e-4, well inside the tolerance.
  expect_vec_near(reduced[0].normal, Vec3(0.27735f, 0.96077f, 0), 1e-3f);
  EXPECT_NEAR(reduced[0].normal.norm(), 1.0f, 1e-6f);
  expect_vec_near(reduced[1].normal, Vec3::UnitY(), 1e-6f);
}

TEST(ContactReducer, NormalsThatCancelFallBackToTheChosenContactsNormal) {
  const std::vector<Contact> run = {
      contact_at(Vec3(0, 0, 0), 0.2f, 0, Vec3::UnitX()),
      contact_at(Vec3(0.1f, 0, 0), 0.2f, 1, -Vec3::UnitX()),
      contact_at(Vec3(5, 0, 0), 0.1f, 2),
  };
  const std::vector<Contact> reduced = reduce(run, 2);
  EXPECT_THAT(leaves_of(reduced), ElementsAre(0, 2));
  ASSERT_EQ(reduced.size(), 2u);
  EXPECT_EQ(reduced[0].normal, Vec3::UnitX());
}

// A 5 × 5 grid whose corner 0 is the deepest contact, by a tenth of a millimetre, just reduced
// (so its manifold is the four corners).
struct CornerFirst {
  std::vector<Contact> grid = grid_5x5(0.005f);
  ContactReducer reducer;
  std::vector<Contact> first;

  CornerFirst() {
    grid[0].depth = 0.0101f;
    first = reduce_runs(reducer, grid, 4);
  }

  std::vector<Contact> reduce_again(std::span<const Contact> contacts) {
    return reduce_runs(reducer, contacts, 4, first);
  }
};

// A resting pair whose corner and centre contacts take turns at being the deepest by a tenth of
// a millimetre (rounding): the corner was chosen first, so the manifold stays the four corners.
TEST(ContactReducer, AKeptContactStaysFirstWhileNearlyTheDeepest) {
  CornerFirst pair;
  ASSERT_THAT(leaves_of(pair.first), ElementsAre(0, 24, 4, 20));

  std::vector<Contact>& grid = pair.grid;
  grid[12].depth = 0.0102f;
  const std::vector<Contact> next = pair.reduce_again(grid);
  EXPECT_THAT(leaves_of(next), ElementsAre(0, 24, 4, 20));
  // The centre joins the first corner's cluster, whose depth is its deepest: nothing is lost.
  EXPECT_FLOAT_EQ(next[0].depth, 0.0102f);
  // Without the memory the centre would come first.
  EXPECT_EQ(reduce(grid, 4)[0].leaf_a, 12u);
}

TEST(ContactReducer, AContactDeeperByMoreThanThePersistentDepthTakesOver) {
  CornerFirst pair;
  ASSERT_EQ(pair.first[0].leaf_a, 0u);

  std::vector<Contact>& grid = pair.grid;
  grid[12].depth = grid[0].depth + 2.0f * ContactReducer::kPersistentDepth;
  EXPECT_EQ(pair.reduce_again(grid)[0].leaf_a, 12u);
}

TEST(ContactReducer, AKeptContactKeepsItsPlaceAgainstASlightlyBetterNewOne) {
  std::vector<Contact> run = {
      contact_at(Vec3(0, 0, 0), 0.02f, 0),  // deepest
      contact_at(Vec3(1, 0, 0), 0.01f, 1),  // the farthest from it, at first
      contact_at(Vec3(0, 0, 0.95f), 0.01f, 2),
  };
  ContactReducer reducer;
  const std::vector<Contact> first = reduce_runs(reducer, run, 2);
  ASSERT_THAT(leaves_of(first), ElementsAre(0, 1));

  // 2 is now farther, but its squared distance (1.1025 m²) is less than kPersistentScoreBonus
  // times 1's (1 m²).
  run[2].point = Vec3(0, 0, 1.05f);
  EXPECT_THAT(leaves_of(reduce_runs(reducer, run, 2, first)), ElementsAre(0, 1));
  EXPECT_THAT(leaves_of(reduce(run, 2)), ElementsAre(0, 2));

  // Well beyond the bonus, the better one wins.
  run[2].point = Vec3(0, 0, 1.5f);
  EXPECT_THAT(leaves_of(reduce_runs(reducer, run, 2, first)), ElementsAre(0, 2));
}

TEST(ContactReducer, ReductionIsDeterministic) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
  std::uniform_real_distribution<float> depth(-0.01f, 0.05f);
  std::vector<Contact> contacts;
  for (std::uint32_t i = 0; i < 90; ++i) {
    const Vec3 normal = Vec3(0.2f * coordinate(rng), 1, 0.2f * coordinate(rng)).normalized();
    const Vec3 point(coordinate(rng), 0.1f * coordinate(rng), coordinate(rng));
    contacts.push_back(contact_at(point, depth(rng), i, normal, 1, 2 + i / 30));
  }
  ContactReducer reducer;
  const std::vector<Contact> first = reduce_runs(reducer, contacts, 5);
  // With the scratch left by the first call.
  const std::vector<Contact> again = reduce_runs(reducer, contacts, 5);
  ASSERT_EQ(first.size(), 15u);
  expect_identical(again, first);
  expect_identical(reduce(contacts, 5), first);
}

TEST(ContactReducer, OnePointKeepsTheDeepestWithTheWholeRunsNormalAndDepth) {
  const std::vector<Contact> run = {
      contact_at(Vec3(0, 0, 0), 0.2f, 0), contact_at(Vec3(1, 0, 0), 0.6f, 1, Vec3(0.6f, 0.8f, 0)),
      contact_at(Vec3(2, 0, 0), -0.05f, 2, Vec3::UnitZ()),  // speculative: the floor weight only
      contact_at(Vec3(0, 0, 1), 0.0f, 3),                   // touching: the floor weight only
  };
  const std::vector<Contact> reduced = reduce(run, 1);
  ASSERT_EQ(reduced.size(), 1u);
  EXPECT_EQ(reduced[0].leaf_a, 1u);
  EXPECT_EQ(reduced[0].leaf_b, 1001u);
  EXPECT_EQ(reduced[0].point, Vec3(1, 0, 0));
  EXPECT_FLOAT_EQ(reduced[0].depth, 0.6f);
  // 0.2 (0, 1, 0) + 0.6 (0.6, 0.8, 0) = (0.36, 0.68, 0), of length sqrt(0.592).
  expect_vec_near(reduced[0].normal, Vec3(0.46788f, 0.88378f, 0), 1e-3f);
}

TEST(ContactReducer, ByPartsEachPairOfPartsIsReducedOnItsOwnInOrderOfFirstAppearance) {
  // Three pairs of parts, interleaved: 7 (contacts 0, 2, 5, 6), 3 (1, 4) and 9 (3).
  const std::vector<Contact> run = {
      contact_at(Vec3(0, 0, 0), 0.01f, 0),  contact_at(Vec3(5, 0, 0), -0.04f, 1, Vec3::UnitX()),
      contact_at(Vec3(1, 0, 0), 0.03f, 2),  contact_at(Vec3(9, 0, 0), -0.02f, 3, Vec3::UnitZ()),
      contact_at(Vec3(6, 0, 0), -0.01f, 4), contact_at(Vec3(2, 0, 0), 0.02f, 5),
      contact_at(Vec3(4, 0, 0), 0.0f, 6),
  };
  const std::vector<std::uint64_t> parts = {7, 3, 7, 9, 3, 7, 7};
  ContactReducer reducer;
  std::vector<Contact> reduced;
  reducer.reduce_by_parts(run, parts, {}, reduced);
  static_assert(ContactReducer::kPointsPerPart == 2);
  // Part pair 7: the deepest (2) and the farthest from it (6), each with its cluster's largest
  // depth (0 joins 2's cluster; 5, at 2 m, is nearer 2 than 6); part pair 3 has two contacts and
  // 9 one, each copied as it is.
  ASSERT_EQ(reduced.size(), 5u);
  EXPECT_THAT(leaves_of(reduced), ElementsAre(2u, 6u, 1u, 4u, 3u));
  EXPECT_FLOAT_EQ(reduced[0].depth, 0.03f);
  EXPECT_EQ(reduced[0].point, Vec3(1, 0, 0));
  EXPECT_FLOAT_EQ(reduced[1].depth, 0.0f);
  EXPECT_EQ(reduced[1].point, Vec3(4, 0, 0));
  expect_identical(std::span(reduced).subspan(2, 2), std::vector<Contact>{run[1], run[4]});
  expect_identical(std::span(reduced).subspan(4), std::span(run).subspan(3, 1));
}

TEST(ContactReducer, ByPartsAKeptContactStaysFirstInItsPairOfParts) {
  const std::vector<Contact> run = {contact_at(Vec3(0, 0, 0), 0.0200f, 0),
                                    contact_at(Vec3(0.1f, 0, 0), 0.0205f, 1),
                                    contact_at(Vec3(3, 0, 0), 0.0f, 2)};
  const std::vector<std::uint64_t> parts = {1, 1, 1};
  ContactReducer reducer;
  std::vector<Contact> reduced;
  reducer.reduce_by_parts(run, parts, std::span(run).first(1), reduced);
  ASSERT_EQ(reduced.size(), 2u);
  EXPECT_EQ(reduced[0].leaf_a, 0u);
  EXPECT_FLOAT_EQ(reduced[0].depth, 0.0205f);
  EXPECT_EQ(reduced[1].leaf_a, 2u);
}

double min_pairwise_distance(std::span<const Vec3> points) {
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t j = i + 1; j < points.size(); ++j) {
      nearest = std::min(nearest, static_cast<double>((points[i] - points[j]).norm()));
    }
  }
  return nearest;
}

TEST(ContactReducer, EightOfARingOfSixteenAreSpreadAsWellAsPossible) {
  std::vector<Contact> ring;
  for (std::uint32_t i = 0; i < 16; ++i) {
    const float angle = 2 * std::numbers::pi_v<float> * static_cast<float>(i) / 16;
    // Depths vary so that the deepest is not the first; the spread must not depend on that.
    const float depth = i == 5 ? 0.02f : 0.01f;
    ring.push_back(contact_at(Vec3(std::cos(angle), 0, std::sin(angle)), depth, i));
  }
  const std::vector<Contact> reduced = reduce(ring, 8);
  ASSERT_EQ(reduced.size(), 8u);
  EXPECT_EQ(reduced[0].leaf_a, 5u);
  std::vector<Vec3> chosen;
  for (const Contact& c : reduced) chosen.push_back(c.point);

  // Brute force over all 12870 ways to pick 8 of the 16.
  double best = 0;
  for (std::uint32_t mask = 0; mask < (1u << 16); ++mask) {
    if (std::popcount(mask) != 8) continue;
    std::vector<Vec3> subset;
    for (std::uint32_t i = 0; i < 16; ++i) {
      if ((mask >> i & 1u) != 0) subset.push_back(ring[i].point);
    }
    best = std::max(best, min_pairwise_distance(subset));
  }
  EXPECT_GE(min_pairwise_distance(chosen), 0.999 * best);
}

TEST(ContactReducer, GroundPlaneRunsAreReducedLikeOthers) {
  // The bottom of a box resting on the plane y = 0: a 3 × 3 layer of spheres, one sunk deeper.
  std::vector<Contact> run;
  for (std::uint32_t i = 0; i < 3; ++i) {
    for (std::uint32_t j = 0; j < 3; ++j) {
      const std::uint32_t index = i * 3 + j;
      const float sink = index == 8 ? 0.004f : 0.001f;
      const Sphere sphere{
          Vec3(0.1f * static_cast<float>(i), 0.05f - sink, 0.1f * static_cast<float>(j)), 0.05f};
      Contact c;
      c.body_a = kGroundPlaneBody;
      c.body_b = 3;
      c.leaf_a = index;
      c.leaf_b = 40 + index;
      sphere_plane_contact(0.0f, sphere, c);
      run.push_back(c);
    }
  }
  const std::vector<Contact> reduced = reduce(run, 4);
  EXPECT_THAT(leaves_of(reduced), ElementsAre(8, 0, 2, 6));
  for (const Contact& c : reduced) {
    EXPECT_EQ(c.body_a, kGroundPlaneBody);
    EXPECT_EQ(c.body_b, 3u);
    EXPECT_EQ(c.leaf_b, 40 + c.leaf_a);
    EXPECT_EQ(c.point, run[c.leaf_a].point);
    expect_vec_near(c.normal, Vec3::UnitY(), 1e-6f);
  }
  EXPECT_NEAR(reduced[0].depth, 0.004f, 1e-6f);
}

TEST(ContactReducer, MaxPointsOutsideOneToEightIsRefused) {
  EXPECT_THAT(error_message(0), HasSubstr("1..8"));
  EXPECT_THAT(error_message(9), HasSubstr("1..8"));
  EXPECT_THAT(error_message(9), HasSubstr("got 9"));
  // Refused even when there is nothing to reduce: the parameter is wrong regardless.
  ContactReducer reducer;
  std::vector<Contact> reduced;
  EXPECT_THROW(reducer.reduce({}, 0, {}, reduced), Error);
  EXPECT_NO_THROW(reducer.reduce({}, kMaxManifoldPoints, {}, reduced));
  EXPECT_TRUE(reduced.empty());
}

TEST(ContactReducer, ARunOfCoincidentContactsBecomesOne) {
  std::vector<Contact> run;
  for (std::uint32_t i = 0; i < 6; ++i) {
    run.push_back(contact_at(Vec3(1, 2, 3), 0.01f * static_cast<float>(i % 4), i));
  }
  const std::vector<Contact> reduced = reduce(run, 4);
  ASSERT_EQ(reduced.size(), 1u);
  EXPECT_EQ(reduced[0].leaf_a, 3u);  // the deepest, depth 0.03
  EXPECT_FLOAT_EQ(reduced[0].depth, 0.03f);
}

TEST(ContactReducer, ContactsStackedAlongTheNormalCountAsCoincident) {
  std::vector<Contact> run;
  for (std::uint32_t i = 0; i < 5; ++i) {
    run.push_back(contact_at(Vec3(0, 0.01f * static_cast<float>(i), 0), 0.01f, i));
  }
  run.push_back(contact_at(Vec3(1, 0, 0), 0.01f, 5));
  EXPECT_THAT(leaves_of(reduce(run, 4)), ElementsAre(0, 5));
}

TEST(ContactReducer, CollinearContactsAreSpreadAlongTheirLine) {
  // No triangle has area: after the two ends, the farthest-point rule takes over.
  std::vector<Contact> line;
  for (std::uint32_t i = 0; i < 9; ++i) {
    line.push_back(contact_at(Vec3(static_cast<float>(i), 0, 0), 0.01f, i));
  }
  EXPECT_THAT(leaves_of(reduce(line, 4)), ElementsAre(0, 8, 4, 2));
}

TEST(ContactReducer, SpeculativeContactsTakePart) {
  // Nothing overlaps: the least separated contact counts as the deepest.
  std::vector<Contact> grid = grid_5x5(-0.01f);
  grid[24].depth = -0.001f;
  std::vector<Contact> reduced = reduce(grid, 4);
  EXPECT_THAT(leaves_of(reduced), ElementsAre(24, 0, 4, 20));
  EXPECT_FLOAT_EQ(reduced[0].depth, -0.001f);
  EXPECT_FLOAT_EQ(reduced[1].depth, -0.01f);

  // A speculative contact far from an overlapping patch widens the manifold.
  grid = grid_5x5(0.02f);
  grid[12].depth = 0.03f;
  grid.push_back(contact_at(Vec3(10, 0, 2), -0.005f, 25));
  reduced = reduce(grid, 4);
  ASSERT_EQ(reduced.size(), 4u);
  EXPECT_EQ(reduced[0].leaf_a, 12u);
  EXPECT_EQ(reduced[1].leaf_a, 25u);
  EXPECT_FLOAT_EQ(reduced[1].depth, -0.005f);
}

// --- Brute-force properties over random runs -------------------------------------------------

struct Point2 {
  double x = 0;
  double y = 0;
};

double cross(const Point2& o, const Point2& a, const Point2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Andrew's monotone chain, then the shoelace formula.
double convex_hull_area(std::vector<Point2> points) {
  std::sort(points.begin(), points.end(), [](const Point2& a, const Point2& b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
  });
  if (points.size() < 3) return 0;
  std::vector<Point2> hull(2 * points.size());
  std::size_t k = 0;
  for (const Point2& p : points) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  double twice_area = 0;
  for (std::size_t i = 0; i + 1 < k; ++i) {
    twice_area += hull[i].x * hull[i + 1].y - hull[i + 1].x * hull[i].y;
  }
  return 0.5 * std::abs(twice_area);
}

TEST(ContactReducer, ConvexHullAreaOfTheOracleIsRight) {
  const std::vector<Point2> square_with_inside = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 1}, {1, 0}};
  EXPECT_DOUBLE_EQ(convex_hull_area(square_with_inside), 4.0);
  EXPECT_DOUBLE_EQ(convex_hull_area({{0, 0}, {1, 1}, {2, 2}}), 0.0);
}

struct RandomRun {
  std::vector<Contact> contacts;
  Vec3 normal;
  Vec3 u;  // u, v, normal: an orthonormal frame
  Vec3 v;
};

RandomRun random_run(std::mt19937& rng) {
  std::uniform_int_distribution<std::uint32_t> count(5, 12);
  std::normal_distribution<float> gaussian;
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_real_distribution<float> extent(0.05f, 1.0f);
  std::uniform_real_distribution<float> depth(-0.02f, 0.05f);
  std::bernoulli_distribution duplicate(0.15);

  RandomRun run;
  run.normal = Vec3(gaussian(rng), gaussian(rng), gaussian(rng)).normalized();
  run.u = run.normal.unitOrthogonal();
  run.v = run.normal.cross(run.u);
  const Vec3 centre(unit(rng), unit(rng), unit(rng));
  const float extent_u = extent(rng);
  const float extent_v = extent(rng);
  const std::uint32_t n = count(rng);
  for (std::uint32_t i = 0; i < n; ++i) {
    Vec3 point = centre + extent_u * unit(rng) * run.u + extent_v * unit(rng) * run.v +
                 0.05f * unit(rng) * run.normal;
    if (i > 0 && duplicate(rng)) point = run.contacts[i / 2].point;
    run.contacts.push_back(contact_at(point, depth(rng), i, run.normal, 1, 2));
  }
  return run;
}

Point2 projected(const RandomRun& run, const Vec3& point) {
  return {static_cast<double>(run.u.dot(point)), static_cast<double>(run.v.dot(point))};
}

double projected_distance_squared(const RandomRun& run, const Vec3& p, const Vec3& q) {
  const Point2 a = projected(run, p);
  const Point2 b = projected(run, q);
  return (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y);
}

std::size_t distinct_points(std::span<const Contact> contacts) {
  std::vector<Vec3> seen;
  for (const Contact& c : contacts) {
    if (std::find(seen.begin(), seen.end(), c.point) == seen.end()) seen.push_back(c.point);
  }
  return seen.size();
}

double best_four_point_area(const RandomRun& run) {
  const std::vector<Contact>& c = run.contacts;
  double best = 0;
  for (std::size_t a = 0; a < c.size(); ++a) {
    for (std::size_t b = a + 1; b < c.size(); ++b) {
      for (std::size_t d = b + 1; d < c.size(); ++d) {
        for (std::size_t e = d + 1; e < c.size(); ++e) {
          best = std::max(
              best, convex_hull_area({projected(run, c[a].point), projected(run, c[b].point),
                                      projected(run, c[d].point), projected(run, c[e].point)}));
        }
      }
    }
  }
  return best;
}

// Checks one reduction against brute force; returns the indices of the run's contacts chosen.
std::vector<std::uint32_t> check_reduction(const RandomRun& run, std::uint32_t max_points,
                                           std::span<const Contact> reduced) {
  const std::vector<Contact>& input = run.contacts;
  if (input.size() <= max_points) {
    expect_identical(reduced, input);
    return {};
  }
  EXPECT_EQ(reduced.size(), std::min<std::size_t>(max_points, distinct_points(input)));
  std::vector<std::uint32_t> chosen;
  for (const Contact& c : reduced) {
    // leaf_a is the index in the run; the other ids and the point must match that contact.
    EXPECT_LT(c.leaf_a, input.size());
    if (c.leaf_a >= input.size()) return {};
    const Contact& original = input[c.leaf_a];
    EXPECT_EQ(c.leaf_b, original.leaf_b);
    EXPECT_EQ(c.body_a, original.body_a);
    EXPECT_EQ(c.body_b, original.body_b);
    EXPECT_EQ(c.point, original.point);
    EXPECT_GE(c.depth, original.depth);
    EXPECT_NEAR(c.normal.dot(run.normal), 1.0f, 1e-5f);
    EXPECT_EQ(std::count(chosen.begin(), chosen.end(), c.leaf_a), 0) << "chosen twice";
    chosen.push_back(c.leaf_a);
  }
  const auto deepest = std::max_element(input.begin(), input.end(), [](auto& a, auto& b) {
    return a.depth < b.depth;  // max_element keeps the first of equals
  });
  EXPECT_EQ(chosen.front(), static_cast<std::uint32_t>(deepest - input.begin()));

  // The depth of each output is the largest of the contacts nearest to it.
  std::vector<float> cluster_depth(chosen.size(), -std::numeric_limits<float>::infinity());
  for (const Contact& c : input) {
    std::size_t nearest = 0;
    for (std::size_t k = 1; k < chosen.size(); ++k) {
      if (projected_distance_squared(run, c.point, input[chosen[k]].point) <
          projected_distance_squared(run, c.point, input[chosen[nearest]].point)) {
        nearest = k;
      }
    }
    cluster_depth[nearest] = std::max(cluster_depth[nearest], c.depth);
  }
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    EXPECT_EQ(reduced[k].depth, cluster_depth[k]) << "cluster " << k;
  }
  return chosen;
}

TEST(ContactReducer, RandomRunsKeepTheirOwnContactsAndCoverMostOfTheBestArea) {
  std::mt19937 rng(20240611);
  double worst_ratio = std::numeric_limits<double>::infinity();
  double ratio_sum = 0;
  int ratio_count = 0;
  for (int r = 0; r < 200; ++r) {
    const RandomRun run = random_run(rng);
    for (std::uint32_t max_points = 1; max_points <= kMaxManifoldPoints; ++max_points) {
      SCOPED_TRACE(::testing::Message() << "run " << r << ", max_points " << max_points);
      const std::vector<Contact> reduced = reduce(run.contacts, max_points);
      const std::vector<std::uint32_t> chosen = check_reduction(run, max_points, reduced);
      if (max_points != 4 || chosen.size() != 4) continue;
      std::vector<Point2> manifold;
      for (const std::uint32_t i : chosen)
        manifold.push_back(projected(run, run.contacts[i].point));
      const double ratio = convex_hull_area(manifold) / best_four_point_area(run);
      worst_ratio = std::min(worst_ratio, ratio);
      ratio_sum += ratio;
      ++ratio_count;
    }
  }
  // Deepest first sometimes forces an inner point into the manifold, and the greedy choice after
  // it is not the best 4-subset: measured over 250 000 such runs (other seeds), the worst ratio
  // was 0.41 and the mean 0.93 (this seed: 0.59 and 0.93). Choosing the 4th point by spread
  // instead of by area added brings this seed's mean down to 0.86.
  ASSERT_GT(ratio_count, 150);
  EXPECT_GE(worst_ratio, 0.4);
  EXPECT_GE(ratio_sum / ratio_count, 0.9);
}

}  // namespace
}  // namespace sphys
