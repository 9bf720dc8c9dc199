#include "collision/sweep_and_prune.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <new>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "collision/broad_phase_scene.h"
#include "sphys/error.h"

// Counts every allocation in this test program, so that a test can check that the broad phase
// allocates nothing in steady state (docs/collision.md). Kept out of line: GCC 12 warns of a
// new/free mismatch when it inlines these into the standard allocator.
namespace {
std::atomic<std::uint64_t> allocation_count{0};
}  // namespace

[[gnu::noinline]] void* operator new(std::size_t size) {
  allocation_count.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept { std::free(p); }
[[gnu::noinline]] void* operator new(std::size_t size, std::align_val_t align) {
  allocation_count.fetch_add(1, std::memory_order_relaxed);
  const auto a = static_cast<std::size_t>(align);
  if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}

namespace sphys {
namespace {

using test::box_at;
using test::pairs_of;
using test::SceneSettings;

std::uint64_t run_scene(std::uint32_t seed, const SceneSettings& settings) {
  SweepAndPrune sap;
  return test::run_scene(sap, seed, settings);
}

TEST(SweepAndPrune, EmptyHasNoPairs) {
  SweepAndPrune sap;
  sap.update();
  EXPECT_TRUE(sap.pairs().empty());
  EXPECT_EQ(sap.size(), 0u);
}

TEST(SweepAndPrune, PairsAppearAtTheNextUpdate) {
  SweepAndPrune sap;
  const ProxyId a = sap.add(box_at(0, 0, 0), ProxyKind::kDynamic);
  const ProxyId b = sap.add(box_at(0.5f, 0, 0), ProxyKind::kDynamic);
  EXPECT_TRUE(sap.pairs().empty());
  EXPECT_EQ(sap.size(), 2u);
  sap.update();
  EXPECT_EQ(pairs_of(sap), (std::vector<ProxyPair>{{a, b}}));
}

TEST(SweepAndPrune, TouchingBoxesOverlapOnFacesEdgesAndCorners) {
  // Small boxes around a unit box, each touching it and no other (exact binary fractions).
  SweepAndPrune sap;
  const ProxyId center = sap.add(box_at(0, 0, 0), ProxyKind::kDynamic);
  const ProxyId face = sap.add(box_at(0.75f, 0, 0, 0.25f), ProxyKind::kDynamic);
  const ProxyId edge = sap.add(box_at(0, -0.75f, 0.75f, 0.25f), ProxyKind::kDynamic);
  const ProxyId corner = sap.add(box_at(-0.75f, -0.75f, -0.75f, 0.25f), ProxyKind::kDynamic);
  const ProxyId apart = sap.add(box_at(0, 0, -0.751f, 0.25f), ProxyKind::kDynamic);
  sap.update();
  EXPECT_EQ(pairs_of(sap),
            (std::vector<ProxyPair>{{center, face}, {center, edge}, {center, corner}}));

  // Touching reached by motion, from both sides: the endpoints become equal during the sort.
  sap.set_box(apart, box_at(0, 0, -0.75f, 0.25f));
  sap.set_box(face, box_at(1.25f, 0, 0, 0.25f));
  sap.update();
  EXPECT_EQ(pairs_of(sap),
            (std::vector<ProxyPair>{{center, edge}, {center, corner}, {center, apart}}));
  sap.set_box(face, box_at(0.75f, 0, 0, 0.25f));
  sap.update();
  EXPECT_EQ(pairs_of(sap), (std::vector<ProxyPair>{
                               {center, face}, {center, edge}, {center, corner}, {center, apart}}));
}

TEST(SweepAndPrune, NegativeZeroTouchesPositiveZero) {
  SweepAndPrune sap;
  const ProxyId a = sap.add(Aabb{Vec3(-3, -1, -1), Vec3(-2, 1, 1)}, ProxyKind::kDynamic);
  const ProxyId b = sap.add(Aabb{Vec3(0.0f, -1, -1), Vec3(1, 1, 1)}, ProxyKind::kDynamic);
  sap.update();
  EXPECT_TRUE(sap.pairs().empty());
  // Reached by the sort: -0 and +0 are equal coordinates.
  sap.set_box(a, Aabb{Vec3(-1, -1, -1), Vec3(-0.0f, 1, 1)});
  sap.update();
  EXPECT_EQ(pairs_of(sap), (std::vector<ProxyPair>{{a, b}}));
}

TEST(SweepAndPrune, NestedAndIdenticalBoxesOverlap) {
  SweepAndPrune sap;
  const ProxyId outer = sap.add(box_at(0, 0, 0, 2), ProxyKind::kDynamic);
  const ProxyId inner = sap.add(box_at(0.5f, 0, 0, 0.25f), ProxyKind::kDynamic);
  const ProxyId same1 = sap.add(box_at(5, 5, 5), ProxyKind::kDynamic);
  const ProxyId same2 = sap.add(box_at(5, 5, 5), ProxyKind::kDynamic);
  sap.update();
  EXPECT_EQ(pairs_of(sap), (std::vector<ProxyPair>{{outer, inner}, {same1, same2}}));

  // The inner box leaves through the outer one's side, then comes back.
  sap.set_box(inner, box_at(3, 0, 0, 0.25f));
  sap.update();
  EXPECT_EQ(pairs_of(sap), (std::vector<ProxyPair>{{same1, same2}}));
  sap.set_box(inner, box_at(0, 0, 0, 0.25f));
  sap.update();
  EXPECT_EQ(pairs_of(sap), (std::vector<ProxyPair>{{outer, inner}, {same1, same2}}));
}

TEST(SweepAndPrune, StaticPairsNeverPair) {
  SweepAndPrune sap;
  const ProxyId ground = sap.add(Aabb{Vec3(-10, -1, -10), Vec3(10, 0, 10)}, ProxyKind::kStatic);
  const ProxyId wall = sap.add(Aabb{Vec3(9, -1, -10), Vec3(10, 5, 10)}, ProxyKind::kStatic);
  const ProxyId body = sap.add(box_at(5, 2, 0), ProxyKind::kDynamic);
  sap.update();
  EXPECT_TRUE(sap.pairs().empty());

  sap.set_box(body, box_at(9, 0.5f, 0));
  sap.update();
  EXPECT_EQ(pairs_of(sap), (std::vector<ProxyPair>{{ground, body}, {wall, body}}));

  // A static box moved onto another static box still does not pair with it.
  sap.set_box(wall, Aabb{Vec3(0, -1, -10), Vec3(1, 5, 10)});
  sap.update();
  EXPECT_EQ(pairs_of(sap), (std::vector<ProxyPair>{{ground, body}}));
}

TEST(SweepAndPrune, RemoveThenAddAgainRecyclesTheId) {
  SweepAndPrune sap;
  const ProxyId a = sap.add(box_at(0, 0, 0), ProxyKind::kDynamic);
  const ProxyId b = sap.add(box_at(0.5f, 0, 0), ProxyKind::kDynamic);
  const ProxyId c = sap.add(box_at(1, 0, 0), ProxyKind::kDynamic);
  sap.update();
  EXPECT_EQ(pairs_of(sap), (std::vector<ProxyPair>{{a, b}, {a, c}, {b, c}}));

  sap.remove(b);
  EXPECT_EQ(sap.size(), 2u);
  sap.update();
  EXPECT_EQ(pairs_of(sap), (std::vector<ProxyPair>{{a, c}}));

  const ProxyId again = sap.add(box_at(0.5f, 0, 0), ProxyKind::kStatic);
  EXPECT_EQ(again, b);
  sap.update();
  EXPECT_EQ(pairs_of(sap), (std::vector<ProxyPair>{{a, b}, {a, c}, {b, c}}));
}

TEST(SweepAndPrune, RemoveBeforeTheFirstUpdate) {
  SweepAndPrune sap;
  const ProxyId a = sap.add(box_at(0, 0, 0), ProxyKind::kDynamic);
  const ProxyId b = sap.add(box_at(0, 0, 0), ProxyKind::kDynamic);
  sap.remove(a);
  sap.update();
  EXPECT_TRUE(sap.pairs().empty());
  EXPECT_EQ(sap.size(), 1u);
  EXPECT_EQ(sap.box(b).min, Vec3(-0.5f, -0.5f, -0.5f));
}

TEST(SweepAndPrune, RejectsBadBoxes) {
  SweepAndPrune sap;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_THROW(sap.add(Aabb{}, ProxyKind::kDynamic), Error);  // empty
  EXPECT_THROW(sap.add(Aabb{Vec3(0, 0, 0), Vec3(1, nan, 1)}, ProxyKind::kDynamic), Error);
  EXPECT_THROW(sap.add(Aabb{Vec3(-inf, 0, 0), Vec3(1, 1, 1)}, ProxyKind::kStatic), Error);
  EXPECT_THROW(sap.add(Aabb{Vec3(0, 0, 2), Vec3(1, 1, 1)}, ProxyKind::kDynamic), Error);
  EXPECT_EQ(sap.size(), 0u);
  // A point is a box.
  EXPECT_NO_THROW(sap.add(Aabb{Vec3(1, 1, 1), Vec3(1, 1, 1)}, ProxyKind::kDynamic));
}

TEST(SweepAndPrune, CountsSwapsOnlyForMotion) {
  SweepAndPrune sap;
  const ProxyId a = sap.add(box_at(0, 0, 0), ProxyKind::kDynamic);
  sap.add(box_at(2, 0, 0), ProxyKind::kDynamic);
  sap.update();
  sap.update();
  EXPECT_EQ(sap.swaps_last_update(), 0u);
  // a's min and max both pass the other box's min and max on x: 4 swaps.
  sap.set_box(a, box_at(4, 0, 0));
  sap.update();
  EXPECT_EQ(sap.swaps_last_update(), 4u);
  EXPECT_TRUE(sap.pairs().empty());
}

TEST(SweepAndPrune, MatchesBruteForceUnderSmallMotions) {
  for (const std::uint32_t seed : {1u, 2u, 3u}) {
    EXPECT_NE(run_scene(seed, SceneSettings{}), 0u);
  }
}

TEST(SweepAndPrune, MatchesBruteForceUnderLargeMotions) {
  SceneSettings settings;
  settings.small_step = 3.0f;
  settings.jump_chance = 0.2;
  for (const std::uint32_t seed : {4u, 5u}) EXPECT_NE(run_scene(seed, settings), 0u);
}

TEST(SweepAndPrune, MatchesBruteForceWithoutLattice) {
  SceneSettings settings;
  settings.lattice = 1e-6f;  // ties are rare
  settings.proxies = 250;
  settings.steps = 150;
  EXPECT_NE(run_scene(6, settings), 0u);
}

TEST(SweepAndPrune, MatchesBruteForceInACrowd) {
  SceneSettings settings;
  settings.region = 4.0f;  // nearly every box overlaps every other
  settings.proxies = 100;
  settings.steps = 100;
  settings.churn_chance = 0.05;
  EXPECT_NE(run_scene(7, settings), 0u);
}

TEST(SweepAndPrune, SameCallsGiveSamePairs) {
  SceneSettings settings;
  settings.steps = 100;
  const std::uint64_t first = run_scene(8, settings);
  EXPECT_NE(first, 0u);
  EXPECT_EQ(run_scene(8, settings), first);
}

// Boxes swing between two configurations; once every buffer has reached its size, an update
// allocates nothing (DESIGN: no allocation in steady state).
TEST(SweepAndPrune, SteadyStateAllocatesNothing) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  SweepAndPrune sap;
  std::vector<Vec3> centers;
  std::vector<Vec3> swing;
  for (int i = 0; i < 500; ++i) {
    centers.emplace_back(unit(rng) * 10, unit(rng) * 10, unit(rng) * 10);
    swing.emplace_back(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f);
    sap.add(box_at(centers.back().x(), centers.back().y(), centers.back().z()),
            i % 10 == 0 ? ProxyKind::kStatic : ProxyKind::kDynamic);
  }
  const auto step = [&](int k) {
    const float phase = k % 2 == 0 ? 1.0f : -1.0f;
    for (ProxyId id = 0; id < centers.size(); ++id) {
      const Vec3 c = centers[id] + phase * swing[id];
      sap.set_box(id, box_at(c.x(), c.y(), c.z()));
    }
    sap.update();
  };
  for (int k = 0; k < 4; ++k) step(k);
  const std::uint64_t before = allocation_count.load();
  std::uint64_t swaps = 0;
  for (int k = 4; k < 20; ++k) {
    step(k);
    swaps += sap.swaps_last_update();
  }
  EXPECT_EQ(allocation_count.load(), before);
  EXPECT_GT(swaps, 0u);
  EXPECT_FALSE(sap.pairs().empty());
}

}  // namespace
}  // namespace sphys
