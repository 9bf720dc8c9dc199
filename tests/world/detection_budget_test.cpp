#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/world.h"
#include "support/cube_tree.h"

namespace sphys {
namespace {

// Two 1 m cubes overlapping by half their width: many node pairs to descend.
World overlapping_cubes(const WorldSettings& settings) {
  World world(settings);
  const auto tree = test::octree_cube_tree();
  for (const float x : {0.0f, 0.5f}) {
    BodyDesc desc;
    desc.tree = tree;
    desc.pose.translation = Vec3(x, 0.0f, 0.0f);
    desc.inertia = Mat3::Identity() / 6.0f;
    world.add_body(desc);
  }
  return world;
}

WorldSettings weightless_paper() {
  WorldSettings settings;
  settings.response = ResponseMode::kPaper;
  settings.gravity = Vec3::Zero();
  return settings;
}

TEST(DetectionBudget, SetBetweenStepsActsAsTheSameBudgetGivenAtConstruction) {
  World exact = overlapping_cubes(weightless_paper());
  const StepStats exact_step = exact.step(0.01f);
  ASSERT_EQ(exact_step.pairs_cut_short, 0u);
  ASSERT_GT(exact_step.sphere_tests, 40u);
  const std::uint64_t budget = exact_step.sphere_tests / 4;

  WorldSettings budgeted = weightless_paper();
  budgeted.collision.max_sphere_tests = budget;
  World built_with = overlapping_cubes(budgeted);
  World set_later = overlapping_cubes(weightless_paper());
  set_later.set_detection_budget(budget, 0.0);
  EXPECT_EQ(set_later.settings().collision.max_sphere_tests, budget);

  const StepStats a = built_with.step(0.01f);
  const StepStats b = set_later.step(0.01f);
  EXPECT_GT(a.pairs_cut_short, 0u);
  EXPECT_LT(a.sphere_tests, exact_step.sphere_tests);
  EXPECT_GT(a.contacts, 0u);  // a cut-short descent still reports the overlap it reached
  EXPECT_EQ(b.sphere_tests, a.sphere_tests);
  EXPECT_EQ(b.pairs_cut_short, a.pairs_cut_short);
  EXPECT_EQ(b.contacts, a.contacts);
}

TEST(DetectionBudget, ZeroTurnsTheBudgetOffAgain) {
  World world = overlapping_cubes(weightless_paper());
  world.set_detection_budget(10, 0.0);
  world.set_detection_budget(0, 0.0);
  EXPECT_EQ(world.step(0.01f).pairs_cut_short, 0u);
}

TEST(DetectionBudget, ATimeThatIsNegativeOrNotFiniteIsRefused) {
  World world = overlapping_cubes(weightless_paper());
  EXPECT_THROW(world.set_detection_budget(0, -1.0), Error);
  EXPECT_THROW(world.set_detection_budget(0, std::numeric_limits<double>::quiet_NaN()), Error);
  EXPECT_THROW(world.set_detection_budget(0, std::numeric_limits<double>::infinity()), Error);
  EXPECT_EQ(world.settings().collision.max_microseconds, 0.0);  // left as it was
  WorldSettings settings;
  settings.collision.max_microseconds = -5.0;
  EXPECT_THROW(World{settings}, Error);
}

}  // namespace
}  // namespace sphys
