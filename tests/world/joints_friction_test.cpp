// Joint friction (JointDesc::friction) against Newton: a wheel on a frictionless axle keeps
// turning, on an axle with friction T it slows at T / I and stops at I ω₀ / T, and then stays
// stopped; a ball joint slows the same whichever way the body turns; a slider's friction F slows
// a sliding body at F / m.

#include <cmath>
#include <iostream>
#include <string>

#include <gtest/gtest.h>

#include "sphys/world.h"
#include "support/joint_scenes.h"

namespace sphys {
namespace {

using test::ball_body;
using test::kDt;

// No gravity and no sleep: only the joint's friction acts on the body.
WorldSettings weightless() {
  WorldSettings settings;
  settings.gravity = Vec3::Zero();
  settings.sleep.enabled = false;
  return settings;
}

constexpr float kRadius = 0.5f;
constexpr float kMass = 2.0f;
// A solid ball's moment of inertia, 2/5 m r². unit: kg·m²
constexpr float kInertia = 0.4f * kMass * kRadius * kRadius;

// A ball of kMass turning at `spin` (unit: rad/s, world frame) on a joint of `type` to the world
// at its centre, with `friction` (unit: N·m). Returns its angular speed after each of `steps`.
std::vector<float> spin_down(JointType type, const Vec3& spin, float friction, int steps) {
  World world(weightless());
  BodyDesc desc = ball_body(kRadius, kMass, Vec3::Zero());
  desc.angular_velocity = spin;
  const BodyId ball = world.add_body(desc);
  JointDesc joint = test::joint_at(world, type, BodyId{}, ball, Vec3::Zero(), spin.normalized());
  joint.friction = friction;
  (void)world.add_joint(joint);
  std::vector<float> speeds;
  for (int step = 0; step < steps; ++step) {
    world.step(kDt);
    speeds.push_back(world.body(ball).angular_velocity.norm());
  }
  return speeds;
}

// The angular speed ω₀ − (T / I) t, and 0 once it has stopped. unit: rad/s
float slowed(float start, float friction, float seconds) {
  return std::max(0.0f, start - friction / kInertia * seconds);
}

TEST(JointFriction, AHingesFrictionSlowsAWheelAtTOverIAndHoldsItStopped) {
  const float spin = 4.0f;
  const float friction = 0.5f;  // stops in I ω₀ / T = 0.2 · 4 / 0.5 = 1.6 s
  const std::vector<float> free = spin_down(JointType::kHinge, spin * Vec3::UnitZ(), 0.0f, 120);
  EXPECT_NEAR(free.back(), spin, 1e-4f) << "no friction: it keeps turning";
  const std::vector<float> speeds =
      spin_down(JointType::kHinge, spin * Vec3::UnitZ(), friction, 180);
  float worst = 0.0f;
  for (std::size_t k = 0; k < speeds.size(); ++k) {
    const float expected = slowed(spin, friction, kDt * static_cast<float>(k + 1));
    worst = std::max(worst, std::abs(speeds[k] - expected));
  }
  std::cout << "hinge friction: angular speed off T / I's by at most " << worst << " rad/s; at 3 s "
            << speeds.back() << " rad/s\n";
  EXPECT_LT(worst, 1e-3f * spin);
  EXPECT_LT(speeds.back(), 1e-5f);
}

TEST(JointFriction, ABallJointsFrictionIsTheSameAboutEveryAxis) {
  const float spin = 3.0f;
  const float friction = 0.3f;  // stops in 0.2 · 3 / 0.3 = 2 s
  for (const Vec3& axis : {Vec3(Vec3::UnitX()), Vec3(1.0f, 1.0f, 0.0f).normalized(),
                           Vec3(1.0f, -2.0f, 3.0f).normalized()}) {
    const std::vector<float> speeds = spin_down(JointType::kBall, spin * axis, friction, 150);
    float worst = 0.0f;
    for (std::size_t k = 0; k < speeds.size(); ++k) {
      worst = std::max(
          worst, std::abs(speeds[k] - slowed(spin, friction, kDt * static_cast<float>(k + 1))));
    }
    std::cout << "ball friction about (" << axis.transpose() << "): off by at most " << worst
              << " rad/s; at 2.5 s " << speeds.back() << " rad/s\n";
    EXPECT_LT(worst, 1e-3f * spin);
    EXPECT_LT(speeds.back(), 1e-5f);
  }
}

TEST(JointFriction, ASlidersFrictionSlowsASlidingBodyAtFOverM) {
  World world(weightless());
  const float speed = 2.0f;
  const float friction = 4.0f;  // N: slows at F / m = 2 m/s², stops in 1 s
  BodyDesc desc = ball_body(kRadius, kMass, Vec3::Zero());
  desc.linear_velocity = speed * Vec3::UnitX();
  const BodyId body = world.add_body(desc);
  JointDesc slider =
      test::joint_at(world, JointType::kSlider, BodyId{}, body, Vec3::Zero(), Vec3::UnitX());
  slider.friction = friction;
  (void)world.add_joint(slider);
  float worst = 0.0f;
  for (int step = 1; step <= 90; ++step) {
    world.step(kDt);
    const float expected =
        std::max(0.0f, speed - friction / kMass * kDt * static_cast<float>(step));
    worst = std::max(worst, std::abs(world.body(body).linear_velocity.x() - expected));
  }
  std::cout << "slider friction: speed off F / m's by at most " << worst << " m/s\n";
  EXPECT_LT(worst, 1e-3f * speed);
  EXPECT_LT(world.body(body).linear_velocity.norm(), 1e-5f);
}

}  // namespace
}  // namespace sphys
