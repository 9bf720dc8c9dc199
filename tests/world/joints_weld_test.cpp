// A weld makes two boxes one body: welded, they fall, land and bounce as one body of their mass
// and inertia does, each box within 1 cm of where the one body carries it for 2 s.
//
// The one body and the boxes are in two worlds, and each world chooses its collision passes by
// its bodies' bounding radii (WorldSettings::max_collision_passes): the boxes' are smaller, so
// they may step with shorter substeps, and symplectic Euler's path under gravity depends on the
// substep (by g h t / 2: 2.7 cm over 2 s at 1/360 s). Both worlds here step with one collision
// pass a step, so that what differs is the weld alone.

#include <array>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/world.h"
#include "support/joint_scenes.h"

namespace sphys {
namespace {

using test::kDt;
constexpr float kSide = 0.5f;  // a box's side. unit: m
constexpr float kMass = 1.0f;  // a box's. unit: kg
// A box's tree: a sphere of a quarter side in each corner, under one around them all. unit: m
constexpr float kLeafRadius = 0.25f * kSide;

// The corner spheres of a box centred at `centre`, under a parent at node `parent`.
void add_corners(const Vec3& centre, std::int32_t parent, std::vector<SphereTreeNode>& nodes) {
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 offset((corner & 1) ? 1.0f : -1.0f, (corner & 2) ? 1.0f : -1.0f,
                      (corner & 4) ? 1.0f : -1.0f);
    nodes.push_back({{centre + kLeafRadius * offset, kLeafRadius}, parent});
  }
}

// Enough to hold a box's corner spheres from its centre. unit: m
float box_radius() { return kLeafRadius * std::sqrt(3.0f) + kLeafRadius; }

std::shared_ptr<const SphereTree> box_tree() {
  std::vector<SphereTreeNode> nodes{{{Vec3::Zero(), box_radius()}, -1}};
  add_corners(Vec3::Zero(), 0, nodes);
  return std::make_shared<const SphereTree>(SphereTree::from_nodes(nodes, 8));
}

// Both boxes as one tree, side by side along x at ±side/2 from its centre.
std::shared_ptr<const SphereTree> pair_tree() {
  std::vector<SphereTreeNode> nodes{{{Vec3::Zero(), 0.5f * kSide + box_radius()}, -1}};
  const std::array<float, 2> centres{-0.5f * kSide, 0.5f * kSide};
  for (const float x : centres) nodes.push_back({{Vec3(x, 0.0f, 0.0f), box_radius()}, 0});
  for (std::int32_t box = 0; box < 2; ++box)
    add_corners(Vec3(centres[box], 0.0f, 0.0f), 1 + box, nodes);
  return std::make_shared<const SphereTree>(SphereTree::from_nodes(nodes, 8));
}

// The two boxes as one body and as two welded, each from `start` (a pose of the one body, its
// velocities), in worlds made with `settings`.
struct Pair {
  World one;
  World welded;
  BodyId body;
  std::array<BodyId, 2> boxes;
};
constexpr std::array<float, 2> kOffsets{-0.5f * kSide, 0.5f * kSide};  // along the body's x

std::unique_ptr<Pair> make_pair(const WorldSettings& settings, const BodyDesc& start) {
  auto pair = std::make_unique<Pair>(Pair{World(settings), World(settings), {}, {}});
  const float box_inertia = kMass * kSide * kSide / 6.0f;
  // The one body: twice the mass; each box's inertia, and their masses at side/2 from the axes
  // across x.
  BodyDesc whole = start;
  whole.tree = pair_tree();
  whole.mass = 2.0f * kMass;
  const float across = 2.0f * (box_inertia + kMass * 0.25f * kSide * kSide);
  whole.inertia = Vec3(2.0f * box_inertia, across, across).asDiagonal();
  pair->body = pair->one.add_body(whole);
  for (int i = 0; i < 2; ++i) {
    BodyDesc box = start;
    box.tree = box_tree();
    box.mass = kMass;
    box.inertia = Mat3::Identity() * box_inertia;
    const Vec3 arm = start.pose.rotation * Vec3(kOffsets[i], 0.0f, 0.0f);
    box.pose.translation += arm;
    box.linear_velocity += start.angular_velocity.cross(arm);
    pair->boxes[i] = pair->welded.add_body(box);
  }
  pair->welded.add_joint(test::joint_at(pair->welded, JointType::kWeld, pair->boxes[0],
                                        pair->boxes[1], start.pose.translation));
  return pair;
}

// Steps both for `frames` frames; returns how far the welded boxes' centres were at most from
// where the one body carries them (unit: m), and their centres' heights, at most (unit: m).
std::pair<float, float> follow(Pair& pair, int frames) {
  float apart = 0.0f;
  float heights = 0.0f;
  for (int frame = 0; frame < frames; ++frame) {
    pair.one.step(kDt);
    pair.welded.step(kDt);
    const Transform pose = pair.one.body(pair.body).pose;
    for (int i = 0; i < 2; ++i) {
      const Vec3 carried = pose.apply(Vec3(kOffsets[i], 0.0f, 0.0f));
      const Vec3 box = pair.welded.body(pair.boxes[i]).pose.translation;
      apart = std::max(apart, (box - carried).norm());
      heights = std::max(heights, std::abs(box.y() - carried.y()));
    }
  }
  return {apart, heights};
}

// One collision pass a step in both worlds.
WorldSettings same_passes(WorldSettings settings) {
  settings.collision_passes = settings.max_collision_passes = 1;
  return settings;
}

// Thrown tumbling about no principal axis, the welded pair turns as the one body does for 2 s
// (Euler's equations: its mass and inertia, not just its weight).
TEST(JointsWeld, TwoWeldedBoxesTumbleAsOneBody) {
  BodyDesc start;
  start.pose.translation = Vec3(0.0f, 10.0f, 0.0f);
  start.pose.rotation = Quat(Eigen::AngleAxisf(0.3f, Vec3(1.0f, 1.0f, 0.0f).normalized()));
  start.linear_velocity = Vec3(1.0f, 5.0f, 0.0f);
  start.angular_velocity = Vec3(1.0f, 3.0f, 0.5f);
  const auto pair = make_pair(same_passes(WorldSettings{}), start);
  const float apart = follow(*pair, 120).first;
  std::cout << "tumbling welded boxes at most " << 1000.0f * apart << " mm from the one body's\n";
  EXPECT_LT(apart, 0.01f);
}

// Dropped level onto a frictionless floor, the welded pair falls, lands and bounces with the one
// body, each box within 1 cm of where the one body carries it for 2 s (four bounces). The
// restitution pass takes turns with the joints' relax (soft_step_solver.cpp): with the bounce
// given to the box alone it ended 1.46 cm off.
TEST(JointsWeld, TwoWeldedBoxesFallAndBounceAsOneBody) {
  BodyDesc start;
  start.pose.translation = Vec3(0.0f, 1.5f, 0.0f);
  start.restitution = 0.5f;
  start.friction = 0.0f;
  const auto pair = make_pair(same_passes(test::on_plane(0.0f, 0.5f)), start);
  const float apart = follow(*pair, 120).first;
  std::cout << "welded boxes dropped on a frictionless floor: at most " << 1000.0f * apart
            << " mm from the one body's\n";
  EXPECT_LT(pair->one.body(pair->body).pose.translation.y(), 0.3f)
      << "not on the floor again by 2 s";
  EXPECT_LT(apart, 0.01f);
}

// On a floor with friction they bounce as high as the one body, within 1 cm through their first
// bounce (1 s), but part sideways: landing level, on eight corner spheres in one body and on two
// manifolds of four in the boxes, the contacts' sequential solve kicks each sideways its own way
// (the one body at 0.24 m/s, the boxes at 0.22 m/s in another direction), and tilts each its own
// way, so that from the second landing they bounce differently (4.3 cm apart in height by 2 s):
// the contacts' doing, not the weld's, as the frictionless floor above shows.
TEST(JointsWeld, TwoWeldedBoxesBounceAsHighAsOneBodyOnAFloorWithFriction) {
  BodyDesc start;
  start.pose.translation = Vec3(0.0f, 1.5f, 0.0f);
  start.restitution = 0.5f;
  const auto pair = make_pair(same_passes(test::on_plane(0.5f, 0.5f)), start);
  const auto [apart, heights] = follow(*pair, 60);
  std::cout << "welded boxes dropped on a floor with friction: heights at most "
            << 1000.0f * heights << " mm from the one body's (" << 1000.0f * apart
            << " mm apart in all)\n";
  EXPECT_LT(heights, 0.01f);
}

}  // namespace
}  // namespace sphys
