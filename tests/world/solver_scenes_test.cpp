// The soft step checked on scenes whose outcome is known in advance: a ball's bounces, a column
// of boxes, a heavy box on a light one, a woken stack, and a body tumbling freely.

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/world.h"
#include "support/world_scenes.h"

namespace sphys::test {
namespace {

// 1. Restitution: a ball dropped from h₀ rebounds to ε² h₀, then to ε⁴ h₀.

struct Rebounds {
  float first = 0.0f;          // the bottom's height at the first apex after an impact. unit: m
  float second = 0.0f;         // at the second. unit: m
  float after_landing = 0.0f;  // the highest the bottom rose after it first met the plane. unit: m
};

Rebounds drop_ball_twice(float restitution, float height) {
  World world(on_plane(0.5f, restitution));
  const float radius = 0.25f;
  const BodyId id = world.add_body(ball(radius, Vec3(0.0f, radius + height, 0.0f), restitution));
  Rebounds rebounds;
  bool landed = false;
  int apexes = 0;
  float rising_top = 0.0f;
  float last_speed = 0.0f;
  for (int frame = 0; frame < 600 && apexes < 2; ++frame) {
    EXPECT_FALSE(world.step(kDt).non_finite_body);
    const RigidBody& body = world.body(id);
    const float bottom = body.pose.translation.y() - radius;
    const float speed = body.linear_velocity.y();
    landed = landed || speed > 0.0f || bottom < 0.01f;
    if (landed) rebounds.after_landing = std::max(rebounds.after_landing, bottom);
    if (speed > 0.0f) rising_top = std::max(rising_top, bottom);
    // The apex lies between the last frame that rose and this one: the higher of the two.
    if (last_speed > 0.0f && speed <= 0.0f) {
      const float apex = std::max(rising_top, bottom);
      (apexes == 0 ? rebounds.first : rebounds.second) = apex;
      ++apexes;
      rising_top = 0.0f;
    }
    last_speed = speed;
  }
  return rebounds;
}

TEST(SoftStepRestitution, ABallReboundsToEpsilonSquaredThenEpsilonToTheFourthTimesTheDrop) {
  const float height = 2.0f;
  for (const float restitution : {0.5f, 0.9f}) {
    const Rebounds rebounds = drop_ball_twice(restitution, height);
    const float first = restitution * restitution * height;
    const float second = first * restitution * restitution;
    EXPECT_NEAR(rebounds.first, first, 0.05f * first) << "ε = " << restitution;
    EXPECT_NEAR(rebounds.second, second, 0.05f * second) << "ε = " << restitution;
  }
}

TEST(SoftStepRestitution, ABallWithNoRestitutionStaysDown) {
  const Rebounds rebounds = drop_ball_twice(0.0f, 2.0f);
  // Within the slop and the spring's give of the plane.
  EXPECT_LT(rebounds.after_landing, 0.002f);
}

// 2. Columns of one-metre boxes, touching sphere on sphere, stand for 10 s and sleep.

struct ColumnRun {
  float worst_drift = 0.0f;             // horizontal, any box, from where it was placed. unit: m
  float worst_sink_per_contact = 0.0f;  // a box's fall over the contacts below it. unit: m
  bool all_asleep = false;
};

ColumnRun stand_column(int count) {
  World world(on_plane(0.5f, 0.0f));
  const float half = cube_half_height();
  std::vector<BodyId> boxes;
  std::vector<Vec3> starts;
  for (int i = 0; i < count; ++i) {
    starts.emplace_back(0.0f, half * static_cast<float>(2 * i + 1), 0.0f);
    boxes.push_back(world.add_body(cube(starts.back(), 0.5f)));
  }
  ColumnRun result;
  for (int frame = 0; frame < 600; ++frame) {
    EXPECT_FALSE(world.step(kDt).non_finite_body);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      const Vec3 moved = world.body(boxes[i]).pose.translation - starts[i];
      result.worst_drift = std::max(result.worst_drift, std::hypot(moved.x(), moved.z()));
      result.worst_sink_per_contact =
          std::max(result.worst_sink_per_contact, -moved.y() / static_cast<float>(i + 1));
    }
  }
  result.all_asleep =
      std::all_of(boxes.begin(), boxes.end(), [&](BodyId box) { return world.asleep(box); });
  return result;
}

void expect_column_stands(int count) {
  const ColumnRun column = stand_column(count);
  EXPECT_LT(column.worst_drift, 0.01f);
  // Each contact gives no more than the slop and the spring's yield under its load.
  EXPECT_LT(column.worst_sink_per_contact, 0.001f);
  EXPECT_TRUE(column.all_asleep);
}

TEST(SoftStepColumns, TenBoxesStandForTenSecondsAndSleep) { expect_column_stands(10); }

TEST(SoftStepColumns, TwentyBoxesStandForTenSecondsAndSleep) { expect_column_stands(20); }

// 3. A box 100 times heavier resting on a light one on the plane.

TEST(SoftStepMassRatio, ABoxAHundredTimesHeavierRestsOnALightOneWithoutSinkingIn) {
  World world(on_plane(0.5f, 0.0f));
  const float half = cube_half_height();
  const BodyId light = world.add_body(cube(Vec3(0.0f, half, 0.0f), 0.5f, 1000.0f));
  const BodyId heavy = world.add_body(cube(Vec3(0.0f, 3.0f * half, 0.0f), 0.5f, 100000.0f));
  float deepest = 0.0f;  // the heavy box into the light one, or either into the plane
  for (int frame = 0; frame < 180; ++frame) {
    const StepStats& stats = world.step(kDt);
    ASSERT_FALSE(stats.non_finite_body);
    deepest = std::max(deepest, stats.deepest_penetration);
  }
  EXPECT_LT(deepest, 0.01f);
  const Vec3 apart = world.body(heavy).pose.translation - world.body(light).pose.translation;
  EXPECT_LT(std::hypot(apart.x(), apart.z()), 0.01f) << "the heavy box slid";
  EXPECT_GT(apart.y(), 2.0f * half - 0.01f);
  EXPECT_TRUE(world.asleep(light));
  EXPECT_TRUE(world.asleep(heavy));
}

// 4. A sleeping stack, woken from below, is not thrown up.

// A stack of six boxes 1 mm apart, the bottom one kept awake by a restless box beside it, the
// five above asleep. The bottom box is nudged sideways and wakes the box on it, which wakes the
// next in turn: their resting impulses must hold them where they slept, not lift them.
TEST(SoftStepWaking, ASleepingStackWokenByANudgeRisesUnderOneCentimetrePerSecond) {
  World world(on_plane(0.5f, 0.0f));
  const float half = cube_half_height();
  std::vector<BodyId> stack;
  for (int i = 0; i < 6; ++i) {
    stack.push_back(world.add_body(
        cube(Vec3(0.0f, half + static_cast<float>(i) * (2.0f * half + 0.001f), 0.0f), 0.5f)));
  }
  const BodyId beside = world.add_body(cube(Vec3(2.0f * half + 0.01f, half, 0.0f), 0.5f));
  int frame = 0;
  while (frame < 240) jiggle(world, beside, frame++);
  for (std::size_t i = 1; i < stack.size(); ++i) ASSERT_TRUE(world.asleep(stack[i])) << i;
  world.set_velocity(stack[0], Vec3(0.0f, 0.0f, 0.1f), Vec3::Zero());
  float rising = 0.0f;
  for (int i = 0; i < 10; ++i) {
    world.step(kDt);
    for (const BodyId box : stack) rising = std::max(rising, world.body(box).linear_velocity.y());
  }
  EXPECT_FALSE(world.asleep(stack[1]));
  EXPECT_LT(rising, 0.01f);
}

// 5. A body with three different principal moments tumbling freely keeps its angular momentum
// and its kinetic energy.

TEST(SoftStepFreeTumbling, AnAsymmetricBodyKeepsItsAngularMomentumAndEnergyForTenSeconds) {
  WorldSettings settings;
  settings.gravity = Vec3::Zero();
  World world(settings);
  BodyDesc desc = ball(0.5f, Vec3::Zero(), 0.0f);
  desc.inertia = Vec3(1.0f, 2.0f, 3.0f).asDiagonal();  // unit: kg m²
  // Mostly about the middle axis, the unstable one: the body tumbles, flipping over and back.
  desc.angular_velocity = Vec3(0.2f, 3.0f, 0.1f);
  const BodyId id = world.add_body(desc);
  const auto momentum = [&] {
    const RigidBody& body = world.body(id);
    const Eigen::Matrix3d turn = body.pose.rotation.toRotationMatrix().cast<double>();
    const Eigen::Vector3d omega = body.angular_velocity.cast<double>();
    return (turn * desc.inertia.cast<double>() * turn.transpose() * omega).norm();
  };
  const double momentum0 = momentum();
  const double energy0 = world.body(id).kinetic_energy();
  double worst_momentum = 0.0;
  double worst_energy = 0.0;
  for (int frame = 0; frame < 600; ++frame) {
    ASSERT_FALSE(world.step(kDt).non_finite_body);
    worst_momentum = std::max(worst_momentum, std::abs(momentum() / momentum0 - 1.0));
    worst_energy =
        std::max(worst_energy, std::abs(world.body(id).kinetic_energy() / energy0 - 1.0));
  }
  EXPECT_LT(worst_momentum, 1e-4);
  EXPECT_LT(worst_energy, 1e-4);
}

}  // namespace
}  // namespace sphys::test
