#include "collision/cell_sweep_and_prune.h"

#include <cstdint>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "collision/broad_phase_scene.h"
#include "sphys/error.h"

namespace sphys {
namespace {

using test::box_at;
using test::pairs_of;
using test::SceneSettings;

std::uint64_t run_scene(float cell_size, std::uint32_t seed, const SceneSettings& settings) {
  CellSweepAndPrune sap(cell_size);
  return test::run_scene(sap, seed, settings);
}

TEST(CellSweepAndPrune, RejectsBadCellSizesAndBoxes) {
  EXPECT_THROW(CellSweepAndPrune(-1.0f), Error);
  EXPECT_THROW(CellSweepAndPrune(std::numeric_limits<float>::infinity()), Error);
  EXPECT_THROW(CellSweepAndPrune(std::numeric_limits<float>::quiet_NaN()), Error);
  CellSweepAndPrune sap;
  EXPECT_THROW(sap.add(Aabb{}, ProxyKind::kDynamic), Error);
  EXPECT_THROW(sap.add(Aabb{Vec3(0, 0, 0), Vec3(1, std::numeric_limits<float>::quiet_NaN(), 1)},
                       ProxyKind::kDynamic),
               Error);
  EXPECT_EQ(sap.size(), 0u);
}

// The cell size chosen at the first update with boxes: six times the median largest extent.
TEST(CellSweepAndPrune, ChoosesTheCellFromTheMedianBox) {
  CellSweepAndPrune sap;
  sap.update();
  EXPECT_EQ(sap.cell_size(), 0.0f);
  sap.add(box_at(0, 0, 0, 0.5f), ProxyKind::kDynamic);    // extent 1
  sap.add(box_at(5, 0, 0, 1.0f), ProxyKind::kDynamic);    // extent 2
  sap.add(box_at(50, 0, 0, 40.0f), ProxyKind::kDynamic);  // extent 80
  sap.update();
  EXPECT_EQ(sap.cell_size(), 12.0f);
}

// Two boxes that overlap in the four cells around the origin are one pair, listed until they
// part in every cell.
TEST(CellSweepAndPrune, APairSharingSeveralCellsIsListedOnce) {
  CellSweepAndPrune sap(2.0f);
  const ProxyId a = sap.add(Aabb{Vec3(-1, 0.5f, -1), Vec3(1, 1.5f, 1)}, ProxyKind::kDynamic);
  const ProxyId b =
      sap.add(Aabb{Vec3(-0.5f, 0.5f, -0.5f), Vec3(0.5f, 1, 0.5f)}, ProxyKind::kDynamic);
  sap.update();
  EXPECT_EQ(sap.cell_count(), 4u);
  EXPECT_EQ(pairs_of(sap), (std::vector<ProxyPair>{{a, b}}));
  // b moves into one of the cells only: still one pair.
  sap.set_box(b, Aabb{Vec3(0.25f, 0.5f, 0.25f), Vec3(0.75f, 1, 0.75f)});
  sap.update();
  EXPECT_EQ(pairs_of(sap), (std::vector<ProxyPair>{{a, b}}));
  sap.set_box(b, Aabb{Vec3(1.5f, 0.5f, 0.25f), Vec3(1.75f, 1, 0.75f)});
  sap.update();
  EXPECT_TRUE(sap.pairs().empty());
  EXPECT_EQ(sap.cell_count(), 4u);
  sap.remove(a);  // three cells empty: listed for reuse, not counted
  sap.update();
  EXPECT_EQ(sap.cell_count(), 1u);
}

// Cells are counted while boxes reach them: an emptied cell is not, nor is a cell one box leaves
// while another enters it in the same update counted as emptied.
TEST(CellSweepAndPrune, CountsTheCellsBoxesReach) {
  CellSweepAndPrune sap(2.0f);
  const ProxyId p = sap.add(box_at(1, 1, 1), ProxyKind::kDynamic);
  const ProxyId x = sap.add(box_at(11, 1, 1), ProxyKind::kDynamic);
  sap.update();
  EXPECT_EQ(sap.cell_count(), 2u);
  sap.set_box(p, box_at(5, 1, 1));  // leaves its cell for a new one
  sap.update();
  EXPECT_EQ(sap.cell_count(), 2u);
  sap.remove(x);
  sap.add(box_at(11, 1, 1), ProxyKind::kDynamic);  // into the cell x leaves
  sap.update();
  EXPECT_EQ(sap.cell_count(), 2u);
  sap.set_box(p, box_at(1, 1, 1));  // back into the emptied cell
  sap.update();
  EXPECT_EQ(sap.cell_count(), 2u);
}

// A box reaching more than kMaxCellsPerBox cells is tested against all the others, statics
// excepted, and turns back into a celled box when it shrinks.
TEST(CellSweepAndPrune, WideBoxesPairWithEveryOverlappingBox) {
  CellSweepAndPrune sap(1.0f);
  const ProxyId ground = sap.add(Aabb{Vec3(-50, -1, -50), Vec3(50, 0, 50)}, ProxyKind::kStatic);
  const ProxyId wall = sap.add(Aabb{Vec3(-50, 0, 0), Vec3(50, 10, 0.1f)}, ProxyKind::kStatic);
  const ProxyId body = sap.add(box_at(3, 0.25f, 0), ProxyKind::kDynamic);
  const ProxyId far = sap.add(box_at(3, 20, 3), ProxyKind::kDynamic);
  sap.update();
  EXPECT_EQ(pairs_of(sap), (std::vector<ProxyPair>{{ground, body}, {wall, body}}));
  sap.set_box(far, Aabb{Vec3(-10, -10, -10), Vec3(10, 30, 10)});  // now wide, over everything
  sap.update();
  EXPECT_EQ(pairs_of(sap),
            (std::vector<ProxyPair>{
                {ground, body}, {ground, far}, {wall, body}, {wall, far}, {body, far}}));
  sap.set_box(far, box_at(3, 0.5f, 0.5f));  // small again, beside the body
  sap.update();
  EXPECT_EQ(pairs_of(sap),
            (std::vector<ProxyPair>{
                {ground, body}, {ground, far}, {wall, body}, {wall, far}, {body, far}}));
  sap.remove(ground);
  sap.update();
  EXPECT_EQ(pairs_of(sap), (std::vector<ProxyPair>{{wall, body}, {wall, far}, {body, far}}));
}

// Random scenes against brute force, after every update: the cell size chosen, cells about the
// size of a box (most boxes in several cells, some wide) and cells holding many boxes.
TEST(CellSweepAndPrune, MatchesBruteForceUnderSmallMotions) {
  for (const float cell : {0.0f, 1.0f, 6.0f}) {
    for (const std::uint32_t seed : {1u, 2u}) {
      EXPECT_NE(run_scene(cell, seed, SceneSettings{}), 0u) << "cell " << cell;
    }
  }
}

TEST(CellSweepAndPrune, MatchesBruteForceUnderLargeMotions) {
  SceneSettings settings;
  settings.small_step = 3.0f;
  settings.jump_chance = 0.2;
  for (const float cell : {0.0f, 1.0f}) {
    EXPECT_NE(run_scene(cell, 4, settings), 0u) << "cell " << cell;
  }
}

TEST(CellSweepAndPrune, MatchesBruteForceWithoutLattice) {
  SceneSettings settings;
  settings.lattice = 1e-6f;
  settings.proxies = 250;
  settings.steps = 150;
  EXPECT_NE(run_scene(0.0f, 6, settings), 0u);
}

TEST(CellSweepAndPrune, MatchesBruteForceInACrowd) {
  SceneSettings settings;
  settings.region = 4.0f;
  settings.proxies = 100;
  settings.steps = 100;
  settings.churn_chance = 0.05;
  EXPECT_NE(run_scene(0.5f, 7, settings), 0u);
}

// A wide region with small cells: boxes leave cells behind, which are freed and reused.
TEST(CellSweepAndPrune, MatchesBruteForceWhileCellsEmptyAndRefill) {
  SceneSettings settings;
  settings.region = 60.0f;
  settings.small_step = 2.0f;
  settings.jump_chance = 0.1;
  settings.steps = 200;
  EXPECT_NE(run_scene(1.5f, 10, settings), 0u);
}

TEST(CellSweepAndPrune, SameCallsGiveSamePairs) {
  SceneSettings settings;
  settings.steps = 100;
  const std::uint64_t first = run_scene(1.0f, 8, settings);
  EXPECT_NE(first, 0u);
  EXPECT_EQ(run_scene(1.0f, 8, settings), first);
}

}  // namespace
}  // namespace sphys
