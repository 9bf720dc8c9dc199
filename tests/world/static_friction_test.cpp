// Static friction that holds: scenes where bodies must stand still under a tangential load
// smaller than the friction bound, and slide by Coulomb's law once it is larger. A pyramid of
// boxes, a heavy box dropped on a light one, and a box pushed along the floor.

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/world.h"
#include "support/world_scenes.h"

namespace sphys::test {
namespace {

// The farthest a body got from where it was at `settle` (the frame by which it had settled) until
// the end, and whether all slept at the end.
struct Standing {
  float worst_drift = 0.0f;  // unit: m
  bool all_asleep = false;
};

Standing watch_stand(World& world, const std::vector<BodyId>& bodies, int settle, int frames) {
  Standing result;
  std::vector<Vec3> settled;
  for (int frame = 0; frame < frames; ++frame) {
    EXPECT_FALSE(world.step(kDt).non_finite_body);
    if (frame + 1 == settle) {
      for (const BodyId b : bodies) settled.push_back(world.body(b).pose.translation);
    }
    if (frame + 1 <= settle) continue;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const float moved = (world.body(bodies[i]).pose.translation - settled[i]).norm();
      result.worst_drift = std::max(result.worst_drift, moved);
    }
  }
  result.all_asleep =
      std::all_of(bodies.begin(), bodies.end(), [&](BodyId b) { return world.asleep(b); });
  return result;
}

// The floor, solved on `threads` threads (the results are the same bit for bit).
WorldSettings floor_on(std::uint32_t threads) {
  WorldSettings settings = on_plane(0.5f, 0.0f);
  settings.threads = threads;
  return settings;
}

// 1. A 2-D pyramid of 55 one-metre boxes: a base of 10, 12 mm apart, each row above resting on
// two boxes of the row below. It stands where it settled in its first second, and sleeps. (In
// that second each row sinks about a centimetre as its bumps nestle between those below.)
class StaticFrictionOnThreads : public ::testing::TestWithParam<std::uint32_t> {};

TEST_P(StaticFrictionOnThreads, APyramidOfFiftyFiveBoxesStandsWhereItSettledAndSleeps) {
  World world(floor_on(GetParam()));
  const float half = cube_half_height();
  const float pitch = 2.0f * half + 0.012f;
  std::vector<BodyId> boxes;
  for (int row = 0; row < 10; ++row) {
    for (int k = 0; k < 10 - row; ++k) {
      const float x = (static_cast<float>(k) + 0.5f * static_cast<float>(row)) * pitch;
      const float y = half + static_cast<float>(row) * 2.0f * half;
      boxes.push_back(world.add_body(cube(Vec3(x, y, 0.0f), 0.5f)));
    }
  }
  ASSERT_EQ(boxes.size(), 55u);
  const Standing pyramid = watch_stand(world, boxes, 60, 600);
  EXPECT_LT(pyramid.worst_drift, 0.01f);
  EXPECT_TRUE(pyramid.all_asleep);
}

// 2. A box 100 times heavier dropped 0.3 m onto a light one lying on the plane: it lands, stays
// where it landed and both sleep.
TEST_P(StaticFrictionOnThreads, ABoxAHundredTimesHeavierDroppedOnALightOneStaysWhereItLanded) {
  World world(floor_on(GetParam()));
  const float half = cube_half_height();
  const BodyId light = world.add_body(cube(Vec3(0.0f, half, 0.0f), 0.5f, 1000.0f));
  const BodyId heavy = world.add_body(cube(Vec3(0.0f, 3.0f * half + 0.3f, 0.0f), 0.5f, 100000.0f));
  // Falling 0.3 m takes 0.25 s: landed by 0.5 s.
  const Standing pair = watch_stand(world, {light, heavy}, 30, 600);
  EXPECT_LT(pair.worst_drift, 0.01f);
  EXPECT_TRUE(pair.all_asleep);
  const Vec3 apart = world.body(heavy).pose.translation - world.body(light).pose.translation;
  EXPECT_GT(apart.y(), 2.0f * half - 0.01f) << "the heavy box sank into the light one";
}

INSTANTIATE_TEST_SUITE_P(OneAndTwo, StaticFrictionOnThreads, ::testing::Values(1u, 2u));

// 3. A box pushed along the floor by a horizontal force through its centre. Below μ m g static
// friction holds it; above, it slides with a = (F − μ m g) / m. And a row of boxes side by side,
// 2 mm apart, pushed along the row through the first: the push passes from box to box, so once
// the first has closed the gaps the row holds below n μ m g and slides above it as one,
// a = (F − n μ m g) / (n m). Both figures are the last box's over the push's second half (by
// then a row held under its bound has stopped, after the knock of closing its gaps).
float pushed_travel(int boxes, float share_of_bound, float seconds, float* speed_gain) {
  const float mu = 0.5f;
  World world(on_plane(mu, 0.0f));
  const float pitch = 2.0f * cube_half_height() + 0.002f;
  std::vector<BodyId> row;
  for (int k = 0; k < boxes; ++k) {
    row.push_back(
        world.add_body(cube(Vec3(pitch * static_cast<float>(k), cube_half_height(), 0.0f), mu)));
  }
  run(world, 0.5f);  // settled on the plane
  const BodyId first = row.front();
  const BodyId last = row.back();
  const float bound = mu * static_cast<float>(boxes) * world.body(first).mass() * kGravity;
  const Vec3 force(share_of_bound * bound, 0.0f, 0.0f);
  const int frames = static_cast<int>(std::lround(seconds / kDt));
  float start = 0.0f;
  float v0 = 0.0f;
  for (int frame = 0; frame < frames; ++frame) {
    world.apply_force(first, force, world.body(first).pose.translation);
    EXPECT_FALSE(world.step(kDt).non_finite_body);
    if (frame + 1 == frames / 2) {
      start = world.body(last).pose.translation.x();
      v0 = world.body(last).linear_velocity.x();
    }
  }
  if (speed_gain != nullptr) *speed_gain = world.body(last).linear_velocity.x() - v0;
  return world.body(last).pose.translation.x() - start;
}

// A row of `boxes` pushed at 1.1 times its bound for 2 s slides, its last box gaining over the
// second second what Coulomb's law gives the row: (1.1 − 1) μ g · 1 s.
void expect_slides_at_coulombs_rate(int boxes) {
  const float mu = 0.5f;
  const float share = 1.1f;
  const float seconds = 2.0f;
  float gain = 0.0f;
  EXPECT_GT(pushed_travel(boxes, share, seconds, &gain), 0.0f);
  const float expected = (share - 1.0f) * mu * kGravity * (0.5f * seconds);
  EXPECT_NEAR(gain, expected, 0.05f * expected);
}

TEST(StaticFriction, ABoxPushedJustUnderMuMgDoesNotMove) {
  EXPECT_LT(std::abs(pushed_travel(1, 0.95f, 5.0f, nullptr)), 0.001f);
}

TEST(StaticFriction, ABoxPushedJustOverMuMgAcceleratesAtTheForceLessFrictionOverItsMass) {
  expect_slides_at_coulombs_rate(1);
}

TEST(StaticFriction, ARowOfThreeBoxesPushedJustUnderTheirBoundDoesNotMove) {
  EXPECT_LT(std::abs(pushed_travel(3, 0.95f, 5.0f, nullptr)), 0.001f);
}

// The last box, pushed by the others, gains what the whole row gains.
TEST(StaticFriction, ARowOfThreeBoxesPushedJustOverTheirBoundSlidesAsOne) {
  expect_slides_at_coulombs_rate(3);
}

// 4. A box on the floor twisted about the vertical by a torque. Its manifold's friction resists
// the twist the way its points do: up to μ times each point's share of the weight times its
// distance from their centre (μ m g r̄, r̄ the points' mean distance). Below that it stays; above,
// it turns with α = (τ − μ m g r̄ − e m g) / I, where rolling resistance's arm e resists the
// spinning too.
struct Twist {
  float turned = 0.0f;           // about the vertical over the push. unit: rad
  float spin_gain = 0.0f;        // over the push's second half. unit: rad/s
  float friction_torque = 0.0f;  // μ m g r̄. unit: N m
  float rolling_torque = 0.0f;   // e m g. unit: N m
};

Twist twist_box(float share_of_bound, float seconds) {
  const float mu = 0.5f;
  World world(on_plane(mu, 0.0f));
  const BodyId box = world.add_body(cube(Vec3(0.0f, cube_half_height(), 0.0f), mu));
  run(world, 0.5f);  // settled on the plane
  // The manifold's points, and their mean distance from their centre.
  Vec3 centre = Vec3::Zero();
  const auto contacts = world.contacts();
  for (const Contact& c : contacts) centre += c.point;
  centre /= static_cast<float>(contacts.size());
  float lever = 0.0f;
  for (const Contact& c : contacts) {
    const Vec3 r = c.point - centre;
    lever += std::hypot(r.x(), r.z());
  }
  lever /= static_cast<float>(contacts.size());
  Twist twist;
  twist.friction_torque = mu * world.body(box).mass() * kGravity * lever;
  twist.rolling_torque =
      world.settings().solver.rolling_resistance * world.body(box).mass() * kGravity;
  const Vec3 torque(0.0f, share_of_bound * twist.friction_torque, 0.0f);
  const Quat start = world.body(box).pose.rotation;
  const int frames = static_cast<int>(std::lround(seconds / kDt));
  float spin0 = 0.0f;
  for (int frame = 0; frame < frames; ++frame) {
    world.apply_torque(box, torque);
    EXPECT_FALSE(world.step(kDt).non_finite_body);
    if (frame + 1 == frames / 2) spin0 = world.body(box).angular_velocity.y();
  }
  twist.spin_gain = world.body(box).angular_velocity.y() - spin0;
  twist.turned = world.body(box).pose.rotation.angularDistance(start);
  EXPECT_EQ(contacts.size(), 4u);
  return twist;
}

TEST(StaticFriction, ABoxTwistedJustUnderItsFrictionTorqueDoesNotTurn) {
  const Twist twist = twist_box(0.95f, 5.0f);
  // A millimetre at the box's corner, 0.7 m out.
  EXPECT_LT(twist.turned, 0.001f / 0.7f);
}

TEST(StaticFriction,
     ABoxTwistedJustOverItsFrictionTorqueTurnsAtTheTorqueLessFrictionOverItsInertia) {
  const float share = 1.2f;
  const float seconds = 2.0f;
  const Twist twist = twist_box(share, seconds);
  const float inertia = 1000.0f * kBoxSide * kBoxSide / 6.0f;
  const float excess = (share - 1.0f) * twist.friction_torque - twist.rolling_torque;
  const float expected = excess / inertia * (0.5f * seconds);
  EXPECT_NEAR(twist.spin_gain, expected, 0.05f * expected);
}

}  // namespace
}  // namespace sphys::test
