// Joints through the world's public face: ids and their staleness, bad input named by joint and
// field, removal with a body, contacts between joined bodies, sleeping and waking together, and
// the force a joint reports.

#include <iostream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/world.h"
#include "support/joint_scenes.h"

namespace sphys {
namespace {

using test::ball_body;
using test::joint_at;
using ::testing::HasSubstr;

using test::kDt;

// The message of the sphys::Error that `call` throws; fails the test if it throws none.
template <class Call>
std::string error_of(const Call& call) {
  try {
    call();
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "no sphys::Error";
  return {};
}

TEST(JointsApi, IdsCountFromOneAndGoStaleWithTheirJoint) {
  World world;
  const BodyId bob = world.add_body(ball_body(0.1f, 1.0f, Vec3(0.0f, -1.0f, 0.0f)));
  const JointId first = world.add_joint(joint_at(world, JointType::kBall, {}, bob, Vec3::Zero()));
  EXPECT_EQ(first, (JointId{0, 1}));
  EXPECT_TRUE(world.joint_alive(first));
  EXPECT_EQ(world.joint(first).type, JointType::kBall);
  world.remove_joint(first);
  EXPECT_FALSE(world.joint_alive(first));
  EXPECT_THAT(error_of([&] { (void)world.joint_state(first); }), HasSubstr("no joint with id 0.1"));
  const JointId second = world.add_joint(joint_at(world, JointType::kHinge, {}, bob, Vec3::Zero()));
  EXPECT_EQ(second, (JointId{0, 2}));  // the slot again, a new generation
  EXPECT_FALSE(world.joint_alive(first));
  EXPECT_FALSE(world.joint_alive(JointId{}));
  EXPECT_THAT(error_of([&] { world.remove_joint(JointId{}); }), HasSubstr("null joint id"));
}

TEST(JointsApi, BadInputNamesTheJointAndTheField) {
  World world;
  const BodyId a = world.add_body(ball_body(0.1f, 1.0f, Vec3::Zero()));
  const BodyId b = world.add_body(ball_body(0.1f, 1.0f, Vec3(1.0f, 0.0f, 0.0f)));
  const BodyId gone = world.add_body(ball_body(0.1f, 1.0f, Vec3(3.0f, 0.0f, 0.0f)));
  world.remove_body(gone);
  JointDesc good;
  good.type = JointType::kHinge;
  good.body_a = a;
  good.body_b = b;
  const auto fails = [&](const auto& change) {
    JointDesc desc = good;
    change(desc);
    return error_of([&] { (void)world.add_joint(desc); });
  };
  EXPECT_THAT(fails([&](JointDesc& d) {
                d.body_b = BodyId{99, 1};
              }),
              HasSubstr("add_joint (hinge): body_b: no body with id 99.1"));
  EXPECT_THAT(fails([&](JointDesc& d) { d.body_a = gone; }),
              HasSubstr("add_joint (hinge): body_a: no body with id 2.1"));
  EXPECT_THAT(fails([&](JointDesc& d) { d.body_b = a; }), HasSubstr("body_b: the same body"));
  EXPECT_THAT(fails([&](JointDesc& d) { d.body_a = d.body_b = BodyId{}; }),
              HasSubstr("the same world"));
  EXPECT_THAT(fails([&](JointDesc& d) { d.axis_b = Vec3::Zero(); }),
              HasSubstr("axis_b must not be zero"));
  EXPECT_THAT(fails([&](JointDesc& d) { d.anchor_a.y() = std::nanf(""); }),
              HasSubstr("anchor_a must be finite"));
  EXPECT_THAT(
      fails([&](JointDesc& d) { d.limit = {.enabled = true, .lower = 1.0f, .upper = 0.0f}; }),
      HasSubstr("limit.lower must not be above limit.upper"));
  EXPECT_THAT(fails([&](JointDesc& d) { d.motor.max_effort = -1.0f; }),
              HasSubstr("motor.max_effort must not be negative"));
  EXPECT_THAT(fails([&](JointDesc& d) { d.friction = -0.5f; }),
              HasSubstr("add_joint (hinge): friction must not be negative, got -0.5"));
  EXPECT_THAT(fails([&](JointDesc& d) {
                d.type = JointType::kBall;
                d.friction = std::nanf("");
              }),
              HasSubstr("add_joint (ball): friction must be finite"));
  EXPECT_THAT(fails([&](JointDesc& d) { d.spring.hertz = -2.0f; }),
              HasSubstr("spring.hertz must not be negative"));
  EXPECT_THAT(fails([&](JointDesc& d) { d.spring.damping_ratio = std::nanf(""); }),
              HasSubstr("spring.damping_ratio must be finite"));
  EXPECT_THAT(fails([&](JointDesc& d) {
                d.type = JointType::kBall;
                d.cone.angle = 4.0f;
              }),
              HasSubstr("add_joint (ball): cone.angle must be at most"));
  EXPECT_THAT(fails([&](JointDesc& d) {
                d.type = JointType::kDistance;
                d.length = 0.0f;
              }),
              HasSubstr("add_joint (distance): length must be positive"));
  // The setters name the joint by its id.
  const JointId hinge = world.add_joint(good);
  EXPECT_THAT(error_of([&] { world.set_joint_motor(hinge, {.max_effort = -1.0f}); }),
              HasSubstr("joint 0.1 (hinge): motor.max_effort must not be negative"));
  EXPECT_THAT(error_of([&] {
                world.set_joint_limit(hinge, {.enabled = true, .lower = 2.0f, .upper = 1.0f});
              }),
              HasSubstr("joint 0.1 (hinge): limit.lower"));
  EXPECT_THAT(error_of([&] { world.set_joint_spring(hinge, {.hertz = -1.0f}); }),
              HasSubstr("joint 0.1 (hinge): spring.hertz"));
  // Nothing was added by the calls that failed.
  EXPECT_EQ(hinge, (JointId{0, 1}));
  WorldSettings paper;
  paper.response = ResponseMode::kPaper;
  World paper_world(paper);
  const BodyId c = paper_world.add_body(ball_body(0.1f, 1.0f, Vec3::Zero()));
  EXPECT_THAT(
      error_of([&] {
        (void)paper_world.add_joint(joint_at(paper_world, JointType::kBall, {}, c, Vec3::Zero()));
      }),
      HasSubstr("plausible mode only"));
}

TEST(JointsApi, RemovingABodyRemovesItsJointsAndSaysWhich) {
  World world;
  const test::Chain chain = test::hang_chain(world, 3, 0.5f, Vec3::Zero(), -Vec3::UnitY());
  world.remove_body(chain.links[1]);
  const std::span<const JointId> removed = world.joints_removed();
  ASSERT_EQ(removed.size(), 2u);
  EXPECT_EQ(removed[0], chain.joints[1]);
  EXPECT_EQ(removed[1], chain.joints[2]);
  EXPECT_TRUE(world.joint_alive(chain.joints[0]));
  EXPECT_FALSE(world.joint_alive(chain.joints[1]));
  EXPECT_FALSE(world.joint_alive(chain.joints[2]));
  world.remove_body(chain.links[2]);  // no joint left on it
  EXPECT_TRUE(world.joints_removed().empty());
  world.step(kDt);  // the world steps on with the joint left
  EXPECT_LT(world.joint_state(chain.joints[0]).gap, 0.01f);
}

// Two overlapping balls held by a ball joint: no contacts between them by default, contacts
// with collide_connected.
TEST(JointsApi, JoinedBodiesCollideOnlyWhenAsked) {
  for (const bool collide : {false, true}) {
    WorldSettings settings;
    settings.gravity = Vec3::Zero();
    World world(settings);
    const BodyId a = world.add_body(ball_body(0.1f, 1.0f, Vec3::Zero()));
    const BodyId b = world.add_body(ball_body(0.1f, 1.0f, Vec3(0.15f, 0.0f, 0.0f)));
    JointDesc desc = joint_at(world, JointType::kBall, a, b, Vec3(0.075f, 0.0f, 0.0f));
    desc.collide_connected = collide;
    world.add_joint(desc);
    world.step(kDt);
    EXPECT_EQ(world.contacts().empty(), !collide) << "collide_connected " << collide;
  }
}

// Two balls on the floor joined by a slack rope fall asleep together, and one set moving wakes
// both: the one left still sleeps only once the other, rolling within the rope, is still too.
TEST(JointsApi, JoinedBodiesSleepAndWakeTogether) {
  World world(test::on_plane(0.5f, 0.0f));
  const BodyId a = world.add_body(ball_body(0.1f, 1.0f, Vec3(0.0f, 0.1f, 0.0f)));
  const BodyId b = world.add_body(ball_body(0.1f, 1.0f, Vec3(0.5f, 0.1f, 0.0f)));
  JointDesc rope;
  rope.type = JointType::kDistance;
  rope.body_a = a;
  rope.body_b = b;
  rope.length = 1.0f;
  rope.spring = {.enabled = true, .hertz = 0.0f};
  rope.limit = {.enabled = true, .lower = 0.0f, .upper = 1.0f};
  const JointId joint = world.add_joint(rope);
  world.set_velocity(b, Vec3(0.0f, 0.0f, 1.0f), Vec3::Zero());
  int asleep_at = -1;
  for (int step = 0; step < 600 && asleep_at < 0; ++step) {
    world.step(kDt);
    ASSERT_EQ(world.asleep(a), world.asleep(b)) << "step " << step;
    if (world.asleep(a)) asleep_at = step;
  }
  ASSERT_GE(asleep_at, 0) << "never slept";
  std::cout << "joined balls asleep at step " << asleep_at << "\n";
  // a alone was still from the start, and would have slept after settings.sleep.time (0.5 s).
  EXPECT_GT(asleep_at, 45);
  const float length = world.joint_state(joint).position;
  EXPECT_GT(length, 0.55f);  // b rolled away within the rope
  EXPECT_LT(length, 1.0f);
  world.set_velocity(a, Vec3(0.5f, 0.0f, 0.0f), Vec3::Zero());
  world.step(kDt);
  EXPECT_FALSE(world.asleep(b));
}

// A bob hanging still from a static body: the joint holds its weight, m g up on the bob.
TEST(JointsApi, AJointToAStaticBodyHoldsTheWeightItReports) {
  World world;
  BodyDesc beam = ball_body(0.1f, 1.0f, Vec3(0.0f, 2.0f, 0.0f));
  beam.is_static = true;
  const BodyId anchor = world.add_body(beam);
  const BodyId bob = world.add_body(ball_body(0.05f, 2.0f, Vec3(0.0f, 1.0f, 0.0f)));
  const JointId joint =
      world.add_joint(joint_at(world, JointType::kBall, anchor, bob, Vec3(0.0f, 2.0f, 0.0f)));
  for (int step = 0; step < 60; ++step) world.step(kDt);
  const JointState state = world.joint_state(joint);
  EXPECT_NEAR(state.force.y(), 2.0f * 9.81f, 0.01f * 2.0f * 9.81f);
  EXPECT_LT(state.gap, 1e-4f);
  EXPECT_NEAR(world.body(bob).pose.translation.y(), 1.0f, 1e-3f);
}

}  // namespace
}  // namespace sphys
