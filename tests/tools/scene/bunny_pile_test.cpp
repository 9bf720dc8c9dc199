// The plausible mode's acceptance scene: four stacks of fifty bunnies (sphere-trees of depth 3)
// fall onto the exact plane. The top bunnies meet the piles at about 30 m/s, half their size per
// step. Every bunny must come to rest within the 880 frames, no bunny may sink into another or
// into the ground by more than 5% of its size at any time, the resting pile by no more than 1 mm
// per metre of bunny, the whole pile must end asleep, and none may end below the plane. The same
// for the heaps of 1,000 and 10,000 bunnies (stacks of ten, depth 2), and a hundred bunnies shot
// into a resting heap at 50 m/s.

#include <algorithm>
#include <cstdint>
#include <random>

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

// A hundred bunnies (depth 2) dropped as a 5 × 5 × 4 block come to rest as a heap; then a hundred
// more, one above the other over the heap, are shot down into it at 50 m/s (0.83 m a frame). None
// may sink into another or the plane by more than 5% of a bunny at any pass, so none passes
// through: a collision pass carries a bunny at most 0.3 of its bounding radius (about 0.26 m),
// less than twice the reach of two of its smallest leaf spheres beyond 5% of overlap (about
// 2 × (0.26 - 0.05) m), so a bunny crossing another is seen more than 5% inside it by some pass.
// None ends below the plane. With one pass a frame (`max_collision_passes` 1) the shots sank 38%
// deep.
TEST(BunnyHeaps, AHundredBunniesShotAt50MetresPerSecondIntoARestingHeapPassThroughNothing) {
  Scene scene;
  scene.ground.kind = GroundSpec::Kind::kPlane;
  for (int i = 0; i < 100; ++i) {
    BodySpec body;
    body.mesh = "bunny";
    body.size = kBunnySize;
    body.tree.depth = 2;
    body.position =
        Vec3(1.05f * static_cast<float>(i % 5), 0.8f + 1.05f * static_cast<float>(i / 25),
             1.05f * static_cast<float>((i / 5) % 5));
    scene.bodies.push_back(body);
  }
  const test::TempDir cache;
  BuildWorldOptions options;
  options.cache_dir = cache.path();
  options.plausibility_figures = true;
  const SimulationSetup setup = build_world(scene, options);
  World& world = *setup.world;
  // Under the sanitizers a few frames of each phase: that run looks for memory errors.
  const int settle_frames = test::sanitized_run() ? 20 : 880;
  const int shot_frames = test::sanitized_run() ? 20 : 240;
  const float dt = static_cast<float>(scene.time_step);
  for (int frame = 0; frame < settle_frames && world.stats().bodies_asleep < 100; ++frame) {
    ASSERT_FALSE(world.step(dt).non_finite_body) << "frame " << frame;
  }
  if (!test::sanitized_run()) {
    ASSERT_EQ(world.stats().bodies_asleep, 100u);
  }

  Aabb heap;
  for (const BodyId body : setup.bodies) heap.extend(world.body(body).pose.translation);
  const RigidBody bunny = world.body(setup.bodies[0]);
  std::mt19937 random(49);
  std::uniform_real_distribution<float> x(heap.min.x(), heap.max.x());
  std::uniform_real_distribution<float> z(heap.min.z(), heap.max.z());
  std::vector<BodyId> shots;
  for (int k = 0; k < 100; ++k) {
    BodyDesc shot;
    shot.tree = world.shared_tree(setup.bodies[0]);
    shot.pose.translation =
        Vec3(x(random), heap.max.y() + 2.0f + 1.5f * static_cast<float>(k), z(random));
    shot.linear_velocity = Vec3(0.0f, -50.0f, 0.0f);
    shot.mass = 1.0f / bunny.inverse_mass;
    shot.inertia = bunny.inertia_body;
    shots.push_back(world.add_body(shot));
  }
  float deepest = 0.0f;
  for (int frame = 0; frame < shot_frames; ++frame) {
    const StepStats& stats = world.step(dt);
    ASSERT_FALSE(stats.non_finite_body) << "frame " << frame;
    deepest = std::max(deepest, stats.deepest_penetration);
  }
  EXPECT_LT(deepest, 0.05 * kBunnySize);
  for (const BodyId body : setup.bodies) {
    EXPECT_GT(world.body(body).pose.translation.y(), 0.0f) << "body " << body.index;
  }
  for (const BodyId body : shots) {
    EXPECT_GT(world.body(body).pose.translation.y(), 0.0f) << "body " << body.index;
  }
}

}  // namespace
}  // namespace sphys::tools
