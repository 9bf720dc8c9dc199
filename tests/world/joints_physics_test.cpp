// Joints against analytic ground truth: a pendulum's period and energy, a hanging chain's gaps,
// limits that hold a motor, a motor's speed and stall, and a weld that makes two boxes one body.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/world.h"
#include "support/joint_scenes.h"

namespace sphys {
namespace {

using test::ball_body;
using test::joint_at;
using test::rod_body;

using test::kDt;
constexpr double kGravity = 9.81;
constexpr double kPi = std::numbers::pi;

WorldSettings no_sleep() {
  WorldSettings settings;
  settings.sleep.enabled = false;
  return settings;
}

// A bob of `radius` hinged to the world at the origin, hanging `length` below it, turned `angle`
// (unit: rad) from the vertical about z.
struct Pendulum {
  BodyId bob;
  JointId hinge;
};
Pendulum pendulum(World& world, float length, float radius, float angle) {
  const Vec3 position(length * std::sin(angle), -length * std::cos(angle), 0.0f);
  const BodyId bob = world.add_body(ball_body(radius, 1.0f, position));
  const JointId hinge =
      world.add_joint(joint_at(world, JointType::kHinge, BodyId{}, bob, Vec3::Zero()));
  return {bob, hinge};
}

// 1. A 1 m pendulum swinging 0.05 rad: its period is 2π √(L/g) within 1%.
TEST(JointsPhysics, APendulumSwingsWithThePeriodOfTheSmallAngleFormula) {
  World world(no_sleep());
  const float length = 1.0f;
  const Pendulum p = pendulum(world, length, 0.02f, 0.05f);
  // Times at which the bob crosses the vertical moving towards −x, interpolated in the step.
  std::vector<double> crossings;
  float x = world.body(p.bob).pose.translation.x();
  for (int step = 1; step <= 60 * 12; ++step) {
    world.step(kDt);
    const float next = world.body(p.bob).pose.translation.x();
    if (x > 0.0f && next <= 0.0f) {
      crossings.push_back(kDt * (static_cast<double>(step - 1) + x / (x - next)));
    }
    x = next;
  }
  ASSERT_GE(crossings.size(), 5u);
  const double period = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  const double expected = 2.0 * kPi * std::sqrt(length / kGravity);
  std::cout << "pendulum period " << period << " s, expected " << expected << " s, error "
            << 100.0 * (period / expected - 1.0) << "%\n";
  EXPECT_NEAR(period / expected, 1.0, 0.01);
}

// 2. A frictionless hinge keeps a 1 rad swing's energy within 2% for 10 s at 60 Hz, with the
// default settings: 6 solver substeps, and 2 to 4 collision passes a step as the 5 cm bob speeds
// up and slows down (substep_change.h: without the velocities' shift at each change of substep
// it lost 3.7%).
TEST(JointsPhysics, AFrictionlessHingeKeepsItsEnergy) {
  World world(no_sleep());
  const float length = 1.0f;
  const float angle = 1.0f;
  const Pendulum p = pendulum(world, length, 0.05f, angle);
  // Energy above the bob's lowest point: m g L (1 − cos θ0) at the start.
  const auto energy = [&] {
    const RigidBody bob = world.body(p.bob);
    return bob.kinetic_energy() +
           (1.0 / bob.inverse_mass) * kGravity * (bob.pose.translation.y() + length);
  };
  const double start = energy();
  EXPECT_NEAR(start, kGravity * length * (1.0 - std::cos(angle)), 1e-3);
  double worst = 0.0;
  for (int step = 0; step < 600; ++step) {
    world.step(kDt);
    worst = std::max(worst, std::abs(energy() / start - 1.0));
  }
  std::cout << "hinge energy drift at most " << 100.0 * worst << "% over 10 s\n";
  EXPECT_LT(worst, 0.02);
}

// 3. A chain of 50 links hanging from the world: at rest no joint opens by 1% of a link.
TEST(JointsPhysics, AHangingChainOfFiftyLinksHoldsItsJoints) {
  World world(no_sleep());
  const float link = 0.2f;
  const test::Chain chain =
      test::hang_chain(world, 50, link, Vec3(0.0f, 12.0f, 0.0f), -Vec3::UnitY());
  float worst = 0.0f;
  for (int step = 0; step < 180; ++step) {
    world.step(kDt);
    if (step >= 60) worst = std::max(worst, test::largest_gap(world, chain.joints));
  }
  std::cout << "chain at rest: largest gap " << 1000.0f * worst << " mm, " << 100.0f * worst / link
            << "% of a link\n";
  EXPECT_LT(worst, 0.01f * link);
}

// ... and with a ball 100 times a link's mass at its end, swinging down from horizontal, none
// opens by 5% of a link (Box2D v3's mass-ratio chain).
TEST(JointsPhysics, AChainHoldsABallAHundredTimesHeavierThanALink) {
  World world(no_sleep());
  const float link = 0.2f;
  const test::Chain chain =
      test::hang_chain(world, 50, link, Vec3(0.0f, 12.0f, 0.0f), Vec3::UnitX(), 100.0f);
  float worst = 0.0f;
  for (int step = 0; step < 300; ++step) {
    world.step(kDt);
    worst = std::max(worst, test::largest_gap(world, chain.joints));
  }
  std::cout << "chain with a 100:1 ball, swinging: largest gap " << 1000.0f * worst << " mm, "
            << 100.0f * worst / link << "% of a link\n";
  EXPECT_LT(worst, 0.05f * link);
}

// An arm of 1 kg and 1 m along x, hinged to the world at its end about z.
struct Arm {
  BodyId body;
  JointId hinge;
};
Arm arm(World& world) {
  const BodyId body = world.add_body(rod_body(1.0f, 0.05f, 1.0f, Vec3(0.5f, 0.0f, 0.0f)));
  return {body, world.add_joint(joint_at(world, JointType::kHinge, BodyId{}, body, Vec3::Zero()))};
}

// 4. A hinge's motor drives it into its upper limit: the limit holds within 1°.
TEST(JointsPhysics, AHingeLimitHoldsItsMotorWithinADegree) {
  World world(no_sleep());
  const Arm a = arm(world);
  world.set_joint_limit(a.hinge, {.enabled = true, .lower = -0.5f, .upper = 0.5f});
  world.set_joint_motor(a.hinge, {.enabled = true, .speed = 2.0f, .max_effort = 20.0f});
  float worst = 0.0f;
  for (int step = 0; step < 180; ++step) {
    world.step(kDt);
    if (step >= 60) worst = std::max(worst, std::abs(world.joint_state(a.hinge).position - 0.5f));
  }
  std::cout << "hinge against its limit: at most " << worst * 180.0 / kPi << " deg off\n";
  EXPECT_LT(worst, static_cast<float>(kPi / 180.0));
}

// ... and a slider's within 1 mm.
TEST(JointsPhysics, ASliderLimitHoldsItsMotorWithinAMillimetre) {
  World world(no_sleep());
  const BodyId box = world.add_body(ball_body(0.1f, 1.0f, Vec3::Zero()));
  JointDesc desc = joint_at(world, JointType::kSlider, BodyId{}, box, Vec3::Zero(), Vec3::UnitX());
  desc.limit = {.enabled = true, .lower = -0.3f, .upper = 0.3f};
  desc.motor = {.enabled = true, .speed = 1.0f, .max_effort = 20.0f};
  const JointId slider = world.add_joint(desc);
  float worst = 0.0f;
  for (int step = 0; step < 180; ++step) {
    world.step(kDt);
    if (step >= 60) worst = std::max(worst, std::abs(world.joint_state(slider).position - 0.3f));
  }
  std::cout << "slider against its limit: at most " << 1000.0f * worst << " mm off\n";
  EXPECT_LT(worst, 0.001f);
  // Gravity across the axis is held by the slider's rows: the box stays on it.
  EXPECT_LT(world.joint_state(slider).gap, 0.001f);
}

// 5. A motor with the torque to spare turns the arm (against gravity's m g L/2 at most) at its
// target speed within 1%.
TEST(JointsPhysics, AMotorReachesItsTargetSpeedUnderItsTorqueLimit) {
  World world(no_sleep());
  const Arm a = arm(world);
  const float most_load = static_cast<float>(kGravity) * 0.5f;  // m g L/2. unit: N·m
  world.set_joint_motor(a.hinge, {.enabled = true, .speed = 1.0f, .max_effort = 2.0f * most_load});
  float worst = 0.0f;
  for (int step = 0; step < 240; ++step) {
    world.step(kDt);
    if (step >= 30) worst = std::max(worst, std::abs(world.joint_state(a.hinge).speed - 1.0f));
  }
  std::cout << "motor speed at most " << 100.0f * worst << "% off its target\n";
  EXPECT_LT(worst, 0.01f);
}

// ... and stalls against its lower limit when gravity needs more torque than it has.
TEST(JointsPhysics, AMotorStallsWhenTheLoadNeedsMoreTorque) {
  World world(no_sleep());
  const Arm a = arm(world);
  const float load = static_cast<float>(kGravity) * 0.5f;  // m g L/2 with the arm level
  world.set_joint_limit(a.hinge, {.enabled = true, .lower = 0.0f, .upper = 1.0f});
  world.set_joint_motor(a.hinge, {.enabled = true, .speed = 1.0f, .max_effort = 0.5f * load});
  float fastest = 0.0f;
  for (int step = 0; step < 180; ++step) {
    world.step(kDt);
    if (step >= 60) fastest = std::max(fastest, std::abs(world.joint_state(a.hinge).speed));
  }
  std::cout << "stalled motor: speed at most " << fastest << " rad/s\n";
  EXPECT_LT(fastest, 1e-3f);
  EXPECT_NEAR(world.joint_state(a.hinge).position, 0.0f, 0.01f);
  // The motor gave all it has: its torque about z is the most it may apply, and the limit the
  // rest of the load.
  EXPECT_NEAR(world.joint_state(a.hinge).torque.z(), load, 0.02f * load);
}

// 6. A ball on a distance spring of 2 Hz to the world, undamped, in zero gravity: the spring's
// stiffness is the ball's mass times (2π 2 Hz)², so it swings with a period of 0.5 s.
TEST(JointsPhysics, ADistanceSpringSwingsAtItsFrequency) {
  WorldSettings settings = no_sleep();
  settings.gravity = Vec3::Zero();
  World world(settings);
  const BodyId ball = world.add_body(ball_body(0.05f, 1.0f, Vec3(1.1f, 0.0f, 0.0f)));
  JointDesc spring;
  spring.type = JointType::kDistance;
  spring.body_b = ball;
  spring.length = 1.0f;
  spring.spring = {.enabled = true, .hertz = 2.0f, .damping_ratio = 0.0f};
  const JointId joint = world.add_joint(spring);
  // Times at which the length passes its rest length growing, interpolated in the step.
  std::vector<double> crossings;
  float stretch = 0.1f;  // as placed
  for (int step = 1; step <= 60 * 3; ++step) {
    world.step(kDt);
    const float next = world.joint_state(joint).position - 1.0f;
    if (stretch < 0.0f && next >= 0.0f) {
      crossings.push_back(kDt * (static_cast<double>(step - 1) + stretch / (stretch - next)));
    }
    stretch = next;
  }
  ASSERT_GE(crossings.size(), 4u);
  const double period = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  std::cout << "distance spring period " << period << " s, expected 0.5 s\n";
  EXPECT_NEAR(period, 0.5, 0.01);
}

// 7. A rod hanging from a ball joint with a swing cone of 0.3 rad, struck sideways hard: its
// axis never leaves the cone by more than a degree.
TEST(JointsPhysics, ABallJointsConeHoldsTheSwing) {
  World world(no_sleep());
  BodyDesc desc = rod_body(1.0f, 0.05f, 1.0f, Vec3(0.0f, -0.5f, 0.0f));
  desc.pose.rotation = Quat::FromTwoVectors(Vec3::UnitX(), -Vec3::UnitY());
  desc.linear_velocity = Vec3(3.0f, 0.0f, 1.0f);
  const BodyId rod = world.add_body(desc);
  JointDesc ball = joint_at(world, JointType::kBall, BodyId{}, rod, Vec3::Zero(), -Vec3::UnitY());
  ball.cone = {.enabled = true, .angle = 0.3f};
  world.add_joint(ball);
  float widest = 0.0f;
  for (int step = 0; step < 180; ++step) {
    world.step(kDt);
    const Vec3 axis = world.body(rod).pose.rotation * Vec3::UnitX();
    widest = std::max(widest, std::acos(std::clamp(axis.dot(-Vec3::UnitY()), -1.0f, 1.0f)));
  }
  std::cout << "ball joint's swing at most " << widest << " rad in a cone of 0.3 rad\n";
  EXPECT_GT(widest, 0.25f) << "the blow did not reach the cone";
  EXPECT_LT(widest, 0.3f + static_cast<float>(kPi / 180.0));
}

}  // namespace
}  // namespace sphys
