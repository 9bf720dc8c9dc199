#include "sphys/tools/overlap.h"

#include <cmath>
#include <memory>
#include <numbers>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/world.h"

namespace sphys::tools {
namespace {

// A root of radius 2 with two leaves of radius 0.5 at x = ±1, in the body frame.
std::shared_ptr<const SphereTree> dumbbell() {
  const SphereTreeNode nodes[] = {{{Vec3::Zero(), 2.0f}, -1},
                                  {{Vec3(-1.0f, 0.0f, 0.0f), 0.5f}, 0},
                                  {{Vec3(1.0f, 0.0f, 0.0f), 0.5f}, 0}};
  return std::make_shared<const SphereTree>(SphereTree::from_nodes(std::span(nodes), 8));
}

// Scene bodies of one shape at the given poses, in a world without gravity or ground.
SimulationSetup setup_of(std::shared_ptr<const SphereTree> tree,
                         const std::vector<Transform>& poses) {
  SimulationSetup setup;
  setup.world = std::make_unique<World>();
  BodyShape shape;
  shape.tree = tree;
  setup.shapes.push_back(shape);
  for (const Transform& pose : poses) {
    BodyDesc desc;
    desc.tree = tree;
    desc.pose = pose;
    setup.bodies.push_back(setup.world->add_body(desc));
    setup.body_shape.push_back(0);
  }
  return setup;
}

Transform at(const Vec3& position, const Quat& rotation = Quat::Identity()) {
  return {rotation, position};
}

TEST(DeepestOverlap, TheDeepestLeafPairOfTwoBodies) {
  // Leaves at x = 1 and x = 2.8 - 1 = 1.8: 0.5 + 0.5 - 0.8 = 0.2 deep; the roots overlap too, but
  // only leaves count.
  const SimulationSetup setup =
      setup_of(dumbbell(), {at(Vec3::Zero()), at(Vec3(2.8f, 0.0f, 0.0f))});
  const Overlap overlap = deepest_overlap(setup, std::nullopt);
  EXPECT_NEAR(overlap.depth, 0.2f, 1e-5f);
  EXPECT_EQ(overlap.body_a, 0u);
  EXPECT_EQ(overlap.body_b, 1u);
}

TEST(DeepestOverlap, PosesTurnTheLeaves) {
  // The second body turned a quarter about z: its leaves at y = ±1 above x = 1.5, so the nearest
  // leaf pair is (1, 0, 0) with (1.5, -1, 0): 1 - √1.25 = -0.118, no overlap. Unturned, its
  // leaf at x = 0.5 would sit 0.5 from the first body's, 0.5 deep.
  const Quat quarter(Eigen::AngleAxisf(std::numbers::pi_v<float> / 2.0f, Vec3::UnitZ()));
  const SimulationSetup turned =
      setup_of(dumbbell(), {at(Vec3::Zero()), at(Vec3(1.5f, 0.0f, 0.0f), quarter)});
  EXPECT_EQ(deepest_overlap(turned, std::nullopt).depth, 0.0f);
  const SimulationSetup straight =
      setup_of(dumbbell(), {at(Vec3::Zero()), at(Vec3(1.5f, 0.0f, 0.0f))});
  EXPECT_NEAR(deepest_overlap(straight, std::nullopt).depth, 0.5f, 1e-5f);
}

TEST(DeepestOverlap, ThePlaneCountsWhenGiven) {
  // Leaves 0.5 across at y = 0.3: 0.2 below the plane y = 0, 0.7 below y = 0.5; apart from each
  // other.
  const SimulationSetup setup =
      setup_of(dumbbell(), {at(Vec3(0.0f, 0.3f, 0.0f)), at(Vec3(10.0f, 0.3f, 0.0f))});
  EXPECT_EQ(deepest_overlap(setup, std::nullopt).depth, 0.0f);
  const Overlap on_plane = deepest_overlap(setup, 0.0f);
  EXPECT_NEAR(on_plane.depth, 0.2f, 1e-6f);
  EXPECT_EQ(on_plane.body_a, Overlap::kGround);
  EXPECT_NEAR(deepest_overlap(setup, 0.5f).depth, 0.7f, 1e-6f);
}

TEST(DeepestOverlap, TheOctreeGroundsTreeCounts) {
  SimulationSetup setup = setup_of(dumbbell(), {at(Vec3(0.0f, 0.9f, 0.0f))});
  // A static one-sphere "ground" of radius 1 at the origin: the leaves at (±1, 0.9, 0) lie
  // √1.81 = 1.345 from it, 0.155 deep.
  const SphereTreeNode root{{Vec3::Zero(), 1.0f}, -1};
  setup.ground_tree =
      std::make_shared<const SphereTree>(SphereTree::from_nodes(std::span(&root, 1), 8));
  BodyDesc ground;
  ground.tree = setup.ground_tree;
  ground.is_static = true;
  setup.ground = setup.world->add_body(ground);
  const Overlap overlap = deepest_overlap(setup, std::nullopt);
  EXPECT_NEAR(overlap.depth, 1.5f - std::sqrt(1.81f), 1e-5f);
  EXPECT_EQ(overlap.body_a, Overlap::kGround);
  EXPECT_EQ(overlap.body_b, 0u);
}

TEST(DeepestOverlap, NothingOverlapsInAnEmptyOrSparseScene) {
  EXPECT_EQ(deepest_overlap(setup_of(dumbbell(), {}), 0.0f).depth, 0.0f);
  const SimulationSetup apart =
      setup_of(dumbbell(), {at(Vec3(0.0f, 1.0f, 0.0f)), at(Vec3(3.0f, 1.0f, 0.0f))});
  EXPECT_EQ(deepest_overlap(apart, 0.0f).depth, 0.0f);  // leaves exactly touch: 0 deep
}

}  // namespace
}  // namespace sphys::tools
