// The narrow phase's decision per pair (collision/pair_kind.h), against its rule worked by hand:
// crowded, then reusable, then paper, then fast by parts, then manifold.

#include "collision/pair_kind.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "collision/collision_detector.h"
#include "collision/crowd.h"

namespace sphys {
namespace {

// A detector that reduces to 4 points, reuses pairs that moved up to 1 cm and reduces by parts
// pairs that can close by more than 5 cm.
DetectorSettings reducing() {
  DetectorSettings settings;
  settings.contact_margin = 0.001f;
  settings.manifold_points = 4;
  settings.reuse_distance = 0.01f;
  settings.fast_pair_reach = 0.05f;
  return settings;
}

// A pair whose last descent looked 3 cm out from body b at (1, 0, 0), now at `relative`, with
// bodies of extents 0.5 m (b) and 0.4 m.
struct Pair {
  PairCache::Record record;
  Transform relative;
  PairFacts facts;

  explicit Pair(const Transform& now, float margin = 0.002f) : relative(now) {
    record.relative = {Quat::Identity(), Vec3(1, 0, 0)};
    record.descent_margin = 0.03f;
    facts = {.record = &record,
             .relative = &relative,
             .margin = margin,
             .extent_b = 0.5f,
             .smaller_extent = 0.4f};
  }
};

Transform moved_by(const Vec3& offset) { return {Quat::Identity(), Vec3(1, 0, 0) + offset}; }

TEST(PairKind, APairThatMovedLessThanTheReuseDistanceIsReused) {
  Pair pair(moved_by(Vec3(0.006f, 0, 0)));
  EXPECT_EQ(pair_kind(pair.facts, reducing()), PairKind::kReused);
}

TEST(PairKind, APairThatMovedFartherThanTheReuseDistanceDescends) {
  Pair pair(moved_by(Vec3(0, 0.012f, 0)));
  EXPECT_EQ(pair_kind(pair.facts, reducing()), PairKind::kManifold);
}

// A turn of 0.01 rad moves b's farthest point (0.5 m out) by 5 mm, within the reuse distance; of
// 0.03 rad by 15 mm, beyond it.
TEST(PairKind, ATurnCountsByHowFarItMovesBodyBsFarthestPoint) {
  const auto turned = [](float angle) {
    return Transform{Quat(Eigen::AngleAxisf(angle, Vec3::UnitY())), Vec3(1, 0, 0)};
  };
  EXPECT_EQ(pair_kind(Pair(turned(0.01f)).facts, reducing()), PairKind::kReused);
  EXPECT_EQ(pair_kind(Pair(turned(0.03f)).facts, reducing()), PairKind::kManifold);
}

// The gap grown by the move must stay within the gap the last descent looked up to (3 cm): a
// pair with a 2.5 cm gap that moved 6 mm reaches 3.1 cm.
TEST(PairKind, APairWhoseGapOutgrewItsLastDescentDescends) {
  Pair pair(moved_by(Vec3(0.006f, 0, 0)), 0.025f);
  EXPECT_EQ(pair_kind(pair.facts, reducing()), PairKind::kManifold);
}

TEST(PairKind, NoPairIsReusedWithoutAReuseDistanceUnderABudgetOrAfterACrowd) {
  const Transform still = moved_by(Vec3::Zero());
  DetectorSettings no_reuse = reducing();
  no_reuse.reuse_distance = 0.0f;
  EXPECT_EQ(pair_kind(Pair(still).facts, no_reuse), PairKind::kManifold);
  DetectorSettings tests_budget = reducing();
  tests_budget.max_sphere_tests = 1000;
  EXPECT_EQ(pair_kind(Pair(still).facts, tests_budget), PairKind::kManifold);
  DetectorSettings time_budget = reducing();
  time_budget.max_microseconds = 100.0;
  EXPECT_EQ(pair_kind(Pair(still).facts, time_budget), PairKind::kManifold);
  Pair after_crowd(still);
  after_crowd.record.descent_margin = -1.0f;  // as a crowd's roots' descent leaves it
  EXPECT_EQ(pair_kind(after_crowd.facts, reducing()), PairKind::kManifold);
}

TEST(PairKind, TwoCrowdedBodiesAreACrowdBeforeAnythingElse) {
  Pair pair(moved_by(Vec3::Zero()), 0.1f);  // reusable were it not crowded, and fast
  pair.facts.margin = 0.002f;
  pair.facts.crowded = true;
  EXPECT_EQ(pair_kind(pair.facts, reducing()), PairKind::kCrowded);
  pair.facts.margin = 0.1f;
  EXPECT_EQ(pair_kind(pair.facts, reducing()), PairKind::kCrowded);
}

// Fast: the reach (gap less the contact margin) over 5 cm and at most the smaller extent (0.4 m).
TEST(PairKind, APairClosingFasterThanTheReachButNotPastTheSmallerBodyIsReducedByParts) {
  const Transform far = moved_by(Vec3(0.5f, 0, 0));
  EXPECT_EQ(pair_kind(Pair(far, 0.001f + 0.04f).facts, reducing()), PairKind::kManifold);
  EXPECT_EQ(pair_kind(Pair(far, 0.001f + 0.06f).facts, reducing()), PairKind::kFastByParts);
  EXPECT_EQ(pair_kind(Pair(far, 0.001f + 0.39f).facts, reducing()), PairKind::kFastByParts);
  EXPECT_EQ(pair_kind(Pair(far, 0.001f + 0.45f).facts, reducing()), PairKind::kManifold);
  Pair plane(far, 0.001f + 0.06f);
  plane.facts.plane = true;  // the plane's contacts share one normal: its manifold serves
  EXPECT_EQ(pair_kind(plane.facts, reducing()), PairKind::kManifold);
}

TEST(PairKind, WithoutReductionAPairThatDescendsIsThePapers) {
  DetectorSettings paper = reducing();
  paper.manifold_points = 0;
  EXPECT_EQ(pair_kind(Pair(moved_by(Vec3(0.5f, 0, 0)), 0.061f).facts, paper), PairKind::kPaper);
  EXPECT_EQ(pair_kind(Pair(moved_by(Vec3::Zero())).facts, paper), PairKind::kReused);
}

// A crowd's root contact reports at most half the smaller root's radius.
TEST(CrowdContactDepth, IsCappedAtHalfTheSmallerRootsRadius) {
  const Sphere small{Vec3::Zero(), 0.2f};
  const Sphere large{Vec3::Zero(), 1.0f};
  EXPECT_EQ(crowd_contact_depth(0.05f, small, large), 0.05f);
  EXPECT_EQ(crowd_contact_depth(0.7f, small, large), 0.1f);
  EXPECT_EQ(crowd_contact_depth(0.7f, large, small), 0.1f);
  EXPECT_EQ(crowd_contact_depth(-0.01f, small, large), -0.01f);
}

}  // namespace
}  // namespace sphys
