// Bodies spawned on top of each other, as a game might spawn them (docs/collision.md, "Crowds"):
// icospheres of radius 5 cm with their default sphere-tree, all at one point 1 m above the ground
// plane, in the plausible response with default settings. The step's work stays bounded (each
// crowded body is paired with its nearest only), and the crowd parts: within 5 s of simulated
// time no two balls overlap by 1 mm or more, none goes faster than 20 m/s on the way, and none
// ends below the ground.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/tools/build_tree.h"
#include "sphys/tools/primitives.h"
#include "sphys/world.h"

namespace sphys::crowd_spawn_test {
namespace {

constexpr float kRadius = 0.05f;  // unit: m
constexpr float kDt = 1.0f / 60.0f;

std::shared_ptr<const SphereTree> ball_tree() {
  static const auto tree = std::make_shared<const SphereTree>(
      tools::build_sphere_tree(tools::make_icosphere(kRadius, 2), tools::BuildOptions{}));
  return tree;
}

World crowd(int bodies) {
  WorldSettings settings;
  settings.collision.ground_plane_height = 0.0f;
  World world(settings);
  BodyDesc desc;
  desc.tree = ball_tree();
  desc.pose.translation = Vec3(0.0f, 1.0f, 0.0f);
  desc.mass = 1000.0f * 4.0f / 3.0f * 3.14159265f * kRadius * kRadius * kRadius;
  desc.inertia = Mat3::Identity() * (0.4f * desc.mass * kRadius * kRadius);
  for (int i = 0; i < bodies; ++i) (void)world.add_body(desc);
  return world;
}

// The deepest overlap of two balls, 2r minus their centres' distance, over every pair: it bounds
// the overlap of their meshes. unit: m
float deepest_ball_overlap(const World& world) {
  const std::span<const Transform> poses = world.bodies().poses();
  float deepest = -1.0f;
  for (std::size_t a = 0; a < poses.size(); ++a) {
    for (std::size_t b = a + 1; b < poses.size(); ++b) {
      const float distance = (poses[a].translation - poses[b].translation).norm();
      deepest = std::max(deepest, 2.0f * kRadius - distance);
    }
  }
  return deepest;
}

float fastest_point(const World& world) {
  const BodyStore& store = world.bodies();
  float fastest = 0.0f;
  for (std::uint32_t i = 0; i < store.slots(); ++i) {
    fastest = std::max(fastest, store.linear_velocities()[i].norm() +
                                    kRadius * store.angular_velocities()[i].norm());
  }
  return fastest;
}

// Every pair overlaps. In each cell of the broad phase that the point touches (four: it is on the
// corner of two cells along x and two along z), each crowded ball lists its 16 nearest at most,
// and each such pair makes one contact, from the trees' roots.
void expect_bounded_first_step(World& world, std::uint32_t bodies) {
  const StepStats& first = world.step(kDt);
  EXPECT_EQ(first.crowded_bodies, bodies);
  EXPECT_GT(first.pairs_deferred, 0u);
  EXPECT_LE(first.candidate_pairs, 4u * 16u * bodies);
  EXPECT_EQ(first.contacts, first.candidate_pairs);
  EXPECT_FALSE(world.stopped());
}

TEST(CrowdSpawn, AThousandBallsAtOnePointPartWithin5sNeverFasterThan20mPerS) {
  World world = crowd(1000);
  expect_bounded_first_step(world, 1000);  // 499,500 overlapping pairs
  float fastest = fastest_point(world);
  for (int step = 1; step < 300; ++step) {  // 5 s
    world.step(kDt);
    fastest = std::max(fastest, fastest_point(world));
  }
  EXPECT_FALSE(world.stopped());
  EXPECT_LT(fastest, 20.0f);
  EXPECT_LT(deepest_ball_overlap(world), 0.001f);
  EXPECT_EQ(world.stats().pairs_deferred, 0u);
  for (const Transform& pose : world.bodies().poses()) {
    EXPECT_GT(pose.translation.y(), 0.0f);
  }
}

// 4,000 at one point: 7,998,000 overlapping pairs, of which the first step lists a bounded few.
TEST(CrowdSpawn, FourThousandBallsAtOnePointMakeABoundedFirstStep) {
  World world = crowd(4000);
  expect_bounded_first_step(world, 4000);
}

// 20,000 at one point: 199,990,000 overlapping pairs, cut before any is listed.
TEST(CrowdSpawn, TwentyThousandBallsAtOnePointMakeABoundedFirstStep) {
  World world = crowd(20000);
  expect_bounded_first_step(world, 20000);
}

}  // namespace
}  // namespace sphys::crowd_spawn_test
