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

// The slope of angle θ as tilted gravity (down the slope is +x), the bunny placed in `pose`.
SimulationSetup on_slope(float angle, float friction, const Transform& pose,
                         const test::TempDir& cache) {
  Scene scene = one_bunny(friction);
  scene.gravity = 9.81f * Vec3(std::sin(angle), -std::cos(angle), 0.0f);
  scene.bodies[0].position = pose.translation;
  scene.bodies[0].orientation = pose.rotation;
  return build(scene, cache);
}

// A pose in which the bunny stands on a 30° slope with its centre of mass inside its support:
// dropped on the flat plane turned a quarter about x, it lands on its feet with its longest
// stance (from 0.14 m behind its centre of mass to 0.29 m ahead, the centre 0.39 m up) along x,
// then turned a quarter about the vertical so that the stance runs down the slope; the line of
// gravity meets the slope 0.22 m ahead. Held there by friction of μ = 3 for a second, it is at
// rest on the slope. (Standing as it lands from the flat plane without the quarter turn about x,
// its stance reaches 0.27 m ahead, on a rounded sphere that rolls: it tips over whatever μ is.)
Transform slope_resting_pose(float angle, const test::TempDir& cache) {
  Scene flat = one_bunny(0.6f);
  flat.bodies[0].orientation =
      Quat(Eigen::AngleAxisf(std::numbers::pi_v<float> / 2.0f, Vec3::UnitX())) *
      flat.bodies[0].orientation;
  flat.bodies[0].position.y() += 0.3f;
  const SimulationSetup landed = build(flat, cache);
  for (int frame = 0; frame < 300; ++frame) landed.world->step(kDt);
  EXPECT_TRUE(landed.world->asleep(landed.bodies[0]));
  Transform pose = landed.world->body(landed.bodies[0]).pose;
  pose.rotation =
      Quat(Eigen::AngleAxisf(std::numbers::pi_v<float> / 2.0f, Vec3::UnitY())) * pose.rotation;
  // Tilted a third of the way at a time, so that it shifts onto its downhill foot gently.
  for (int third = 1; third <= 3; ++third) {
    const SimulationSetup held =
        on_slope(angle * static_cast<float>(third) / 3.0f, 3.0f, pose, cache);
    for (int frame = 0; frame < 60; ++frame) held.world->step(kDt);
    EXPECT_LT(held.world->body(held.bodies[0]).linear_velocity.norm(), 1e-3f) << third;
    pose = held.world->body(held.bodies[0]).pose;
  }
  return pose;
}

TEST(BunnyOnASlope, AtRestOnThirtyDegreesWithMu06ItMovesUnderAMillimetreInFiveSecondsAndSleeps) {
  const test::TempDir cache;
  const float angle = std::numbers::pi_v<float> / 6.0f;
  const Transform pose = slope_resting_pose(angle, cache);
  const SimulationSetup setup = on_slope(angle, 0.6f, pose, cache);
  float worst = 0.0f;  // along the slope, from where it was placed
  for (int frame = 0; frame < 300; ++frame) {
    ASSERT_FALSE(setup.world->step(kDt).non_finite_body);
    const Vec3 moved = setup.world->body(setup.bodies[0]).pose.translation - pose.translation;
    worst = std::max(worst, std::hypot(moved.x(), moved.z()));
  }
  EXPECT_LT(worst, 0.001f);
  EXPECT_TRUE(setup.world->asleep(setup.bodies[0]));
}

TEST(BunnyOnASlope, OnThirtyDegreesWithMu03ItSlidesAtGTimesSinMinusMuCos) {
  const test::TempDir cache;
  const float angle = std::numbers::pi_v<float> / 6.0f;
  const Transform pose = slope_resting_pose(angle, cache);
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

// A bunny of 100 tonnes in its flat resting pose, raised by `lift` (unit: m) above where it rests
// on the plane: over a light body lying there.
SimulationSetup heavy_bunny_above(float lift, const test::TempDir& cache) {
  const Transform rest = flat_resting_pose(cache);
  Scene scene = one_bunny(0.5f);
  scene.bodies[0].position = rest.translation + Vec3(0.0f, lift, 0.0f);
  scene.bodies[0].orientation = rest.rotation;
  scene.bodies[0].mass = 100.0 * 1000.0;
  return build(scene, cache);
}

// A bunny of 100 times the mass of the box it rests on, the box on the plane. (Not a bunny on a
// bunny: one bunny does not rest on another's rounded back; at equal masses the upper one slid off
// at each of the eight yaws tried.)
TEST(BunnyMassRatio, ABunnyAHundredTimesHeavierRestsOnALightBoxWithoutSinkingIn) {
  const test::TempDir cache;
  const float box_half = test::cube_half_height();
  const SimulationSetup setup = heavy_bunny_above(2.0f * box_half + 0.005f, cache);
  const Vec3 start = setup.world->body(setup.bodies[0]).pose.translation;
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
  const Vec3 moved = world.body(bunny).pose.translation - start;
  EXPECT_LT(std::hypot(moved.x(), moved.z()), 0.05f);
  EXPECT_GT(moved.y(), -0.015f);
  EXPECT_TRUE(world.asleep(box));
  EXPECT_TRUE(world.asleep(bunny));
}

// A bunny of 100 times the mass of a 2 × 0.4 × 2 m slab lying on the plane, dropped 0.3 m onto
// it: once settled it stays where it settled, and both sleep.
TEST(BunnyMassRatio, ABunnyAHundredTimesHeavierDroppedOnALightSlabStaysWhereItSettled) {
  const test::TempDir cache;
  tools::BuildOptions octree;
  octree.method = tools::BuildMethod::Octree;
  octree.depth = 3;
  const auto slab_tree = std::make_shared<const SphereTree>(
      tools::build_sphere_tree(tools::make_box(tools::Vec3d(2.0, 0.4, 2.0)), octree));
  float slab_half = 0.0f;  // how far its spheres reach below and above its centre. unit: m
  for (std::uint32_t node = 0; node < slab_tree->size(); ++node) {
    if (!slab_tree->is_leaf(node)) continue;
    const Sphere& sphere = slab_tree->sphere(node);
    slab_half = std::max(slab_half, sphere.radius - sphere.center.y());
  }
  const SimulationSetup setup = heavy_bunny_above(2.0f * slab_half + 0.3f, cache);
  World& world = *setup.world;
  BodyDesc slab;
  slab.tree = slab_tree;
  slab.pose.translation = Vec3(0.0f, slab_half, 0.0f);
  slab.mass = 1000.0f;
  slab.inertia = Vec3(0.4f * 0.4f + 4.0f, 8.0f, 4.0f + 0.4f * 0.4f).asDiagonal();
  slab.inertia *= slab.mass / 12.0f;  // a box's m (b² + c²) / 12 about each axis
  slab.friction = 0.5f;
  slab.restitution = 0.0f;
  const BodyId slab_id = world.add_body(slab);
  const BodyId bunny = setup.bodies[0];
  // Falling 0.3 m takes 0.25 s; landing on its rounded underside on the slab's bumps, it rocks
  // (up to 2 rad/s, its centre of mass swinging 4 cm) and has settled by 1 s. From then on it
  // stays where it settled.
  Vec3 settled = Vec3::Zero();
  float drift = 0.0f;
  for (int frame = 1; frame <= 600; ++frame) {
    ASSERT_FALSE(world.step(kDt).non_finite_body);
    const Vec3 at = world.body(bunny).pose.translation;
    if (frame == 60) settled = at;
    if (frame > 60) drift = std::max(drift, (at - settled).norm());
  }
  EXPECT_LT(drift, 0.01f);
  EXPECT_GT(world.body(bunny).pose.translation.y(), slab_half) << "it sank through the slab";
  EXPECT_TRUE(world.asleep(slab_id));
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
