// A ragdoll of 11 bunnies (pelvis, torso, head, upper and lower arms and legs) on ball joints at
// the spine, neck, shoulders and hips and hinges at the elbows and knees, with swing cones, twist
// and hinge limits and joint friction, dropped lying onto a heap of 50 bunnies: it comes to rest
// and falls asleep with the heap, every joint within its limits and no joint open by more than
// 2 cm at any frame. Without friction it never sleeps: a limb hanging at its cone's rim keeps
// turning about it (docs/joints.md).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "sphys/tools/build_world.h"
#include "sphys/tools/scene.h"
#include "sphys/world.h"
#include "support/joint_scenes.h"
#include "support/sanitized_run.h"

namespace sphys {
namespace {

using test::joint_at;

constexpr int kHeapBunnies = 50;
constexpr float kHeapBunnySize = 0.5f;  // unit: m
// The joints' friction: a few times less than the torque of a lower leg's weight about its knee
// (about 5 kg at 0.15 m), so that it damps the limbs' swinging without holding them up.
// unit: N·m
constexpr float kJointFriction = 2.0f;
// How far beyond a limit (unit: rad) a resting joint may be: the limits are soft while they
// push back (docs/joints.md, "Softness").
constexpr float kLimitSlack = 0.035f;  // 2°
constexpr float kMostGap = 0.02f;      // unit: m

// A part of the ragdoll, standing: its size (longest side, unit: m) and centre (unit: m).
struct Part {
  float size;
  Vec3 centre;
};
enum PartIndex {
  kPelvis,
  kTorso,
  kHead,
  kArmL,
  kForearmL,
  kArmR,
  kForearmR,
  kThighL,
  kShinL,
  kThighR,
  kShinR,
  kParts
};
const Part kRagdoll[kParts] = {
    {0.3f, {0.0f, 1.0f, 0.0f}},    {0.4f, {0.0f, 1.35f, 0.0f}},   {0.25f, {0.0f, 1.75f, 0.0f}},
    {0.25f, {-0.36f, 1.3f, 0.0f}}, {0.25f, {-0.36f, 1.0f, 0.0f}}, {0.25f, {0.36f, 1.3f, 0.0f}},
    {0.25f, {0.36f, 1.0f, 0.0f}},  {0.3f, {-0.16f, 0.65f, 0.0f}}, {0.3f, {-0.16f, 0.3f, 0.0f}},
    {0.3f, {0.16f, 0.65f, 0.0f}},  {0.3f, {0.16f, 0.3f, 0.0f}}};

// A joint of the ragdoll, standing: its parts, point and axis (a ball's twist axis, a hinge's
// axis), and its limits.
struct RagdollJoint {
  JointType type;
  PartIndex a;
  PartIndex b;
  Vec3 point;
  Vec3 axis;
  float cone;          // ball: the swing cone's half-angle. unit: rad
  float lower, upper;  // ball: twist; hinge: angle. unit: rad
};
const RagdollJoint kJoints[] = {
    {JointType::kBall, kPelvis, kTorso, {0.0f, 1.15f, 0.0f}, Vec3::UnitY(), 0.4f, -0.4f, 0.4f},
    {JointType::kBall, kTorso, kHead, {0.0f, 1.6f, 0.0f}, Vec3::UnitY(), 0.5f, -0.5f, 0.5f},
    {JointType::kBall, kTorso, kArmL, {-0.36f, 1.45f, 0.0f}, -Vec3::UnitY(), 1.5f, -0.5f, 0.5f},
    {JointType::kHinge, kArmL, kForearmL, {-0.36f, 1.15f, 0.0f}, Vec3::UnitX(), 0, 0.0f, 2.4f},
    {JointType::kBall, kTorso, kArmR, {0.36f, 1.45f, 0.0f}, -Vec3::UnitY(), 1.5f, -0.5f, 0.5f},
    {JointType::kHinge, kArmR, kForearmR, {0.36f, 1.15f, 0.0f}, Vec3::UnitX(), 0, 0.0f, 2.4f},
    {JointType::kBall, kPelvis, kThighL, {-0.16f, 0.85f, 0.0f}, -Vec3::UnitY(), 1.0f, -0.3f, 0.3f},
    {JointType::kHinge, kThighL, kShinL, {-0.16f, 0.475f, 0.0f}, Vec3::UnitX(), 0, -2.4f, 0.0f},
    {JointType::kBall, kPelvis, kThighR, {0.16f, 0.85f, 0.0f}, -Vec3::UnitY(), 1.0f, -0.3f, 0.3f},
    {JointType::kHinge, kThighR, kShinR, {0.16f, 0.475f, 0.0f}, Vec3::UnitX(), 0, -2.4f, 0.0f}};

// The heap: 50 bunnies in two layers of 5 × 5, turned at random about y, dropped from just above
// one another; then the ragdoll, lying face down (turned −90° about x) 2.5 m up over the heap.
tools::Scene ragdoll_scene(const Quat& lying, const Vec3& lifted) {
  tools::Scene scene;
  scene.name = "ragdoll";
  scene.ground.kind = tools::GroundSpec::Kind::kPlane;
  std::mt19937 random(65);
  std::uniform_real_distribution<float> yaw(0.0f, 2.0f * std::numbers::pi_v<float>);
  for (int k = 0; k < kHeapBunnies; ++k) {
    tools::BodySpec bunny;
    bunny.size = kHeapBunnySize;
    bunny.tree.depth = 2;
    const int layer = k / 25;
    bunny.position =
        Vec3(0.6f * static_cast<float>(k % 5 - 2), 0.35f + 0.6f * static_cast<float>(layer),
             0.6f * static_cast<float>((k / 5) % 5 - 2));
    bunny.orientation = Quat(Eigen::AngleAxisf(yaw(random), Vec3::UnitY()));
    scene.bodies.push_back(bunny);
  }
  for (const Part& part : kRagdoll) {
    tools::BodySpec bunny;
    bunny.size = part.size;
    bunny.tree.depth = 2;
    bunny.position = lying * part.centre + lifted;
    bunny.orientation = lying;
    scene.bodies.push_back(bunny);
  }
  return scene;
}

// How far the joint is beyond its limits now (unit: rad; 0 within them): a hinge's angle, a
// ball's twist and its swing (the angle between the bodies' axes).
float beyond_limits(const World& world, JointId id, const RagdollJoint& spec) {
  const JointDesc desc = world.joint(id);
  const float position = world.joint_state(id).position;
  float beyond = std::max({0.0f, desc.limit.lower - position, position - desc.limit.upper});
  if (spec.type == JointType::kBall) {
    const Vec3 axis_a = world.body(desc.body_a).pose.rotation * desc.axis_a;
    const Vec3 axis_b = world.body(desc.body_b).pose.rotation * desc.axis_b;
    const float swing = std::atan2(axis_a.cross(axis_b).norm(), axis_a.dot(axis_b));
    beyond = std::max(beyond, swing - desc.cone.angle);
  }
  return beyond;
}

TEST(JointsRagdoll, ARagdollDroppedOnAHeapOfBunniesComesToRestAsleepWithinItsLimits) {
  const Quat lying(Eigen::AngleAxisf(-0.5f * std::numbers::pi_v<float>, Vec3::UnitX()));
  const Vec3 lifted(0.0f, 2.5f, 1.0f);
  const tools::Scene scene = ragdoll_scene(lying, lifted);
  const tools::SimulationSetup setup = tools::build_world(scene);
  World& world = *setup.world;
  const auto part = [&](PartIndex index) { return setup.bodies[kHeapBunnies + index]; };
  std::vector<JointId> joints;
  for (const RagdollJoint& spec : kJoints) {
    JointDesc desc = joint_at(world, spec.type, part(spec.a), part(spec.b),
                              lying * spec.point + lifted, lying * spec.axis);
    desc.limit = {.enabled = true, .lower = spec.lower, .upper = spec.upper};
    desc.cone = {.enabled = spec.type == JointType::kBall, .angle = spec.cone};
    desc.friction = kJointFriction;
    joints.push_back(world.add_joint(desc));
  }

  // Under the sanitizers the fall and the landing only; the release run checks the whole.
  const int frames = test::sanitized_run() ? 90 : 60 * 20;
  const auto dt = static_cast<float>(scene.time_step);
  float largest_gap = 0.0f;
  int asleep_at = -1;  // the first frame at which every body was asleep
  for (int frame = 1; frame <= frames && asleep_at < 0; ++frame) {
    const StepStats& stats = world.step(dt);
    ASSERT_FALSE(stats.non_finite_body) << "frame " << frame;
    largest_gap = std::max(largest_gap, test::largest_gap(world, joints));
    if (stats.bodies_asleep == stats.movable_bodies) asleep_at = frame;
  }
  float most_beyond = 0.0f;
  for (std::size_t k = 0; k < joints.size(); ++k) {
    most_beyond = std::max(most_beyond, beyond_limits(world, joints[k], kJoints[k]));
  }
  const float trunk = std::min(world.body(part(kPelvis)).pose.translation.y(),
                               world.body(part(kTorso)).pose.translation.y());
  std::cout << "ragdoll: every body asleep at frame " << asleep_at << "; largest joint gap "
            << largest_gap << " m; at rest at most " << most_beyond
            << " rad beyond a limit; pelvis and torso centres at " << trunk << " m or higher\n";
  EXPECT_LT(largest_gap, kMostGap);
  if (test::sanitized_run()) return;
  EXPECT_GT(asleep_at, 0) << "still awake after " << frames << " frames";
  EXPECT_LT(most_beyond, kLimitSlack);
  // Its trunk lies on the heap, not beside it on the ground, where the pelvis's and the torso's
  // centres would be within half their size of the ground (0.2 m at most), below the middle of
  // the heap's first layer; a limb may hang down the heap's side.
  EXPECT_GT(trunk, 0.5f * kHeapBunnySize);
}

}  // namespace
}  // namespace sphys
