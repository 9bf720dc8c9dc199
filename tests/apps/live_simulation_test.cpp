// The viewer's live simulation: bodies dropped and shot in, resets, the detection budget.

#include "viewer/live_simulation.h"

#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/tools/scenarios.h"

namespace sphys::viewer {
namespace {

// Two bunnies stacked on the preset's exact plane, depth-2 trees (built here: no cache).
LiveSimulation two_bunnies() {
  static const tools::BuildWorldOptions build{.tree_depth = 2, .cache_dir = {}, .progress = {}};
  return LiveSimulation(tools::preset_scene("stacks:1x2"), build);
}

float highest(const LiveSimulation& simulation) {
  std::vector<BodyView> bodies;
  simulation.bodies(bodies);
  float top = -1e30f;
  for (const BodyView& body : bodies) top = std::max(top, body.pose.translation.y());
  return top;
}

TEST(LiveSimulation, ADroppedBodyCopiesTheFirstAndFallsFromAboveTheHighest) {
  LiveSimulation simulation = two_bunnies();
  ASSERT_TRUE(simulation.can_add_bodies());
  const float top = highest(simulation);
  std::mt19937 random(7);
  simulation.drop_body(random);
  ASSERT_EQ(simulation.body_count(), 3u);
  std::vector<BodyView> bodies;
  simulation.bodies(bodies);
  const BodyView& dropped = bodies[2];
  EXPECT_EQ(dropped.shape, bodies[0].shape);
  EXPECT_FLOAT_EQ(dropped.pose.translation.y(), top + 3.0f);
  EXPECT_NEAR(dropped.pose.rotation.norm(), 1.0f, 1e-5f);
  // Same mass and inertia as the scene's first body.
  const World& world = simulation.world();
  std::uint32_t first_moving = 0;
  while (world.body(world.id_of(first_moving)).is_static) ++first_moving;  // the ground comes first
  const RigidBody& first = world.body(world.id_of(first_moving));
  const RigidBody& copy = world.body(world.id_of(world.body_slots() - 1));
  EXPECT_FLOAT_EQ(copy.mass(), first.mass());
  EXPECT_TRUE(copy.inertia_body.isApprox(first.inertia_body));
  // It falls: after 0.2 s it has dropped by g t² / 2 (the integrator's known small excess
  // aside), before meeting anything.
  for (int frame = 0; frame < 12; ++frame) simulation.step();
  simulation.bodies(bodies);
  const float fallen = top + 3.0f - bodies[2].pose.translation.y();
  EXPECT_NEAR(fallen, 0.5f * 9.81f * 0.2f * 0.2f, 0.02f);
}

TEST(LiveSimulation, AShotBodyLeavesWithTheGivenVelocity) {
  LiveSimulation simulation = two_bunnies();
  std::mt19937 random(7);
  simulation.shoot_body(Vec3(10.0f, 5.0f, 0.0f), Vec3(-25.0f, 0.0f, 0.0f), random);
  ASSERT_EQ(simulation.body_count(), 3u);
  const RigidBody& shot =
      simulation.world().body(simulation.world().id_of(simulation.world().body_slots() - 1));
  EXPECT_TRUE(shot.linear_velocity.isApprox(Vec3(-25.0f, 0.0f, 0.0f)));
  EXPECT_TRUE(shot.pose.translation.isApprox(Vec3(10.0f, 5.0f, 0.0f)));
}

TEST(LiveSimulation, ResetRemovesAddedBodiesAndKeepsTheBudget) {
  LiveSimulation simulation = two_bunnies();
  std::mt19937 random(7);
  simulation.set_detection_budget(500, 0.0);
  simulation.drop_body(random);
  for (int frame = 0; frame < 5; ++frame) simulation.step();
  EXPECT_EQ(simulation.frame(), 5);
  simulation.reset();
  EXPECT_EQ(simulation.frame(), 0);
  EXPECT_EQ(simulation.body_count(), 2u);
  EXPECT_EQ(simulation.world().settings().collision.max_sphere_tests, 500u);
  std::vector<Aabb> boxes;
  simulation.bounds(boxes);
  EXPECT_EQ(boxes.size(), 2u);  // the two bunnies: the exact plane has no box
  for (const Aabb& box : boxes) EXPECT_FALSE(box.empty());
}

}  // namespace
}  // namespace sphys::viewer
