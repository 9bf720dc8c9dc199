// The plausible mode's acceptance scene: four stacks of fifty bunnies (sphere-trees of depth 3)
// fall onto the exact plane. The top bunnies meet the piles at about 30 m/s, half their size per
// step. Every bunny must come to rest within the 880 frames, no bunny may sink into another or
// into the ground by more than 5% of its size at any time, the resting pile by no more than 1 mm
// per metre of bunny, the whole pile must end asleep, and none may end below the plane. The same
// for the heaps of 1,000 and 10,000 bunnies (stacks of ten, depth 2).

#include <algorithm>
#include <cstdint>

#include <gtest/gtest.h>

#include "sphys/tools/build_world.h"
#include "sphys/tools/overlap.h"
#include "sphys/tools/scenarios.h"
#include "sphys/world.h"
#include "support/sanitized_run.h"
#include "support/temp_file.h"

namespace sphys::tools {
namespace {

constexpr double kBunnySize = 1.0;  // the preset's bunny: longest bounding-box side. unit: m

TEST(BunnyPile, FourStacksOfFiftyComeToRestWithoutSinkingIn) {
  Scene scene = bunny_stacks_scene(4, 50, 3);
  ASSERT_EQ(scene.response, ResponseMode::kPlausible);
  scene.ground.kind = GroundSpec::Kind::kPlane;
  // Under the sanitizers the fall and the impacts only: that run looks for memory errors, and
  // the release run checks the whole scene.
  const int frames = test::sanitized_run() ? 120 : scene.frames;
  BuildWorldOptions options;
  options.plausibility_figures = true;  // penetration and rest, checked below
  const SimulationSetup setup = build_world(scene, options);
  World& world = *setup.world;
  ASSERT_EQ(setup.bodies.size(), 200u);

  float deepest = 0.0f;
  int at_rest_from = -1;  // the frame from which every bunny stayed at rest
  for (int frame = 1; frame <= frames; ++frame) {
    const StepStats& stats = world.step(static_cast<float>(scene.time_step));
    ASSERT_FALSE(stats.non_finite_body) << "frame " << frame;
    deepest = std::max(deepest, stats.deepest_penetration);
    if (stats.bodies_at_rest < stats.movable_bodies) {
      at_rest_from = -1;
    } else if (at_rest_from < 0) {
      at_rest_from = frame;
    }
  }
  EXPECT_LT(deepest, 0.05 * kBunnySize);
  for (const BodyId body : setup.bodies) {
    EXPECT_GT(world.body(body).pose.translation.y(), 0.0f) << "body " << body.index;
  }
  if (test::sanitized_run()) return;

  ASSERT_GT(at_rest_from, 0) << "some bunny still moved in the last frame";
  EXPECT_EQ(world.stats().bodies_at_rest, 200u);
  EXPECT_EQ(world.stats().bodies_asleep, 200u);
  // Counted afresh over every pair, the sleeping ones included, which the world no longer
  // tests against each other.
  const Overlap resting = deepest_overlap(setup, 0.0f);
  EXPECT_LT(resting.depth, 0.001 * kBunnySize)
      << "bodies " << resting.body_a << " and " << resting.body_b;
}

// The heaps: S stacks of ten bunnies of depth 2 fall onto the plane and must all be asleep by
// frame 880, none ever deeper than 5% of a bunny in another, resting less than 1 mm deep, none
// below the plane.
void expect_heap_comes_to_rest(int stacks) {
  Scene scene = bunny_stacks_scene(stacks, 10, 2);
  scene.ground.kind = GroundSpec::Kind::kPlane;
  const test::TempDir cache;
  BuildWorldOptions options;
  options.cache_dir = cache.path();
  options.plausibility_figures = true;
  options.threads = 2;
  const SimulationSetup setup = build_world(scene, options);
  World& world = *setup.world;
  float deepest = 0.0f;
  for (int frame = 1; frame <= 880; ++frame) {
    const StepStats& stats = world.step(static_cast<float>(scene.time_step));
    ASSERT_FALSE(stats.non_finite_body) << "frame " << frame;
    deepest = std::max(deepest, stats.deepest_penetration);
  }
  EXPECT_LT(deepest, 0.05 * kBunnySize);
  EXPECT_EQ(world.stats().bodies_asleep, setup.bodies.size());
  for (const BodyId body : setup.bodies) {
    ASSERT_GT(world.body(body).pose.translation.y(), 0.0f) << "body " << body.index;
  }
  const Overlap resting = deepest_overlap(setup, 0.0f);
  EXPECT_LT(resting.depth, 0.001 * kBunnySize)
      << "bodies " << resting.body_a << " and " << resting.body_b;
}

TEST(BunnyHeaps, AThousandBunniesAreAllAsleepByFrame880LessThanAMillimetreDeep) {
  expect_heap_comes_to_rest(100);
}

TEST(BunnyHeaps, TenThousandBunniesAreAllAsleepByFrame880LessThanAMillimetreDeep) {
  expect_heap_comes_to_rest(1000);
}

}  // namespace
}  // namespace sphys::tools
