// Plausible mode checked like physics: scenes whose outcome is known in advance (friction on a
// slope and on the floor, a standing stack, a restitution ladder, a fast impact, sleep).

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/build_tree.h"
#include "sphys/tools/primitives.h"
#include "sphys/world.h"
#include "support/world_scenes.h"

namespace sphys::test {
namespace {

// 1. Coulomb friction on a slope.

TEST(PlausibleFriction, ABoxStaysPutOnASlopeGentlerThanItsFrictionAngle) {
  const float mu = 0.5f;
  const float angle = std::atan(0.8f * mu);  // tan θ = 0.4 < μ
  World world(slope(angle, mu));
  const Vec3 start(0.0f, cube_half_height(), 0.0f);
  const BodyId box = world.add_body(cube(start, mu));
  run(world, 3.0f);
  // Static friction holds: it may settle by a hair, but it does not creep.
  EXPECT_LT((world.body(box).pose.translation - start).norm(), 0.01f * kBoxSide);
  EXPECT_LT(world.body(box).linear_velocity.norm(), 0.01f);
}

// Static friction just above the slope: μ = 0.6 holds a 30° slope (tan 30° = 0.577, 4% less).
// From rest, the box must stay put, not creep down by what each step's gravity adds.
TEST(PlausibleFriction, ABoxOnA30DegreeSlopeWithMu06MovesUnder1MillimetreIn5Seconds) {
  const float mu = 0.6f;
  const float angle = std::numbers::pi_v<float> / 6.0f;
  World world(slope(angle, mu));
  const Vec3 start(0.0f, cube_half_height(), 0.0f);
  const BodyId box = world.add_body(cube(start, mu));
  run(world, 5.0f);
  const Vec3 moved = world.body(box).pose.translation - start;
  // Along the slope only: settling into the slope's slop is not sliding.
  EXPECT_LT(std::hypot(moved.x(), moved.z()), 0.001f);
}

TEST(PlausibleFriction, ABoxSlidesDownASteeperSlopeAtGTimesSinMinusMuCos) {
  const float mu = 0.5f;
  for (const float tangent : {0.7f, 1.0f}) {
    const float angle = std::atan(tangent);
    World world(slope(angle, mu));
    const BodyId box = world.add_body(cube(Vec3(0.0f, cube_half_height(), 0.0f), mu));
    run(world, 0.5f);
    const float v0 = world.body(box).linear_velocity.x();
    const float x0 = world.body(box).pose.translation.x();
    run(world, 1.0f);
    const float v1 = world.body(box).linear_velocity.x();
    const float expected = kGravity * (std::sin(angle) - mu * std::cos(angle));
    EXPECT_NEAR((v1 - v0) / 1.0f, expected, 0.05f * expected) << "tan θ = " << tangent;
    // It slides: it does not tumble or leave the slope.
    EXPECT_GT(world.body(box).pose.translation.x() - x0, 0.0f);
    EXPECT_LT(world.body(box).angular_velocity.norm(), 0.05f) << "tan θ = " << tangent;
    EXPECT_NEAR(world.body(box).pose.translation.y(), cube_half_height(), 0.01f);
  }
}

// 2. Sliding to a stop on the floor.

TEST(PlausibleFriction, ABoxLaunchedAlongTheFloorStopsAfterVSquaredOverTwoMuG) {
  const float mu = 0.5f;
  for (const float speed : {3.0f, 6.0f}) {
    World world(on_plane(mu, 0.0f));
    BodyDesc desc = cube(Vec3(0.0f, cube_half_height(), 0.0f), mu);
    desc.linear_velocity = Vec3(speed, 0.0f, 0.0f);
    const BodyId box = world.add_body(desc);
    run(world, 3.0f);
    const float expected = speed * speed / (2.0f * mu * kGravity);
    EXPECT_NEAR(world.body(box).pose.translation.x(), expected, 0.05f * expected)
        << "v0 = " << speed;
    EXPECT_LT(world.body(box).linear_velocity.norm(), 0.01f);
    EXPECT_NEAR(world.body(box).pose.translation.z(), 0.0f, 0.01f);
  }
}

TEST(PlausibleFriction, APairMaterialReplacesTheMixOfTheBodiesOwn) {
  // A box sliding on a huge static ball (locally flat): with the pair made frictionless it keeps
  // sliding; with the mix of its own μ = 0.5 it stops within v²/(2μg) = 0.92 m.
  for (const bool frictionless : {false, true}) {
    WorldSettings settings;
    World world(settings);
    BodyDesc floor = ball(1000.0f, Vec3(0.0f, -1000.0f, 0.0f), 0.0f);
    floor.is_static = true;
    floor.friction = 0.5f;
    const BodyId ground = world.add_body(floor);
    BodyDesc desc = cube(Vec3(0.0f, cube_half_height(), 0.0f), 0.5f);
    desc.linear_velocity = Vec3(3.0f, 0.0f, 0.0f);
    const BodyId box = world.add_body(desc);
    if (frictionless) world.set_pair_material(ground, box, {0.0f, 0.0f});
    run(world, 1.0f);
    const float speed = world.body(box).linear_velocity.x();
    if (frictionless) {
      EXPECT_GT(speed, 2.9f);
    } else {
      EXPECT_LT(std::abs(speed), 0.01f);
      EXPECT_NEAR(world.body(box).pose.translation.x(), 9.0f / (2.0f * 0.5f * kGravity), 0.05f);
    }
  }
  World world;
  const BodyId a = world.add_body(ball(0.5f, Vec3::Zero(), 0.0f));
  const BodyId b = world.add_body(ball(0.5f, Vec3(2.0f, 0.0f, 0.0f), 0.0f));
  EXPECT_THROW(world.set_pair_material(a, b, {-1.0f, 0.0f}), Error);
  EXPECT_THROW(world.set_pair_material(a, b, {0.5f, 1.5f}), Error);
}

// 2b. Rolling resistance: a torque of at most the arm e times the normal force.

// A solid ball rolling without slipping: the resisting torque e m g slows it at
// a = e g / (R + I / (m R)) = e g / (1.4 R), so it stops after v0² / (2a).
TEST(PlausibleRollingResistance, ARollingBallStopsAfterVSquaredOverTwoA) {
  const float radius = 0.25f;
  for (const float speed : {1.0f, 2.0f}) {
    WorldSettings settings = on_plane(0.5f, 0.0f);
    settings.solver.rolling_resistance = 0.01f;
    World world(settings);
    BodyDesc desc = ball(radius, Vec3(0.0f, radius, 0.0f), 0.0f);
    desc.friction = 0.5f;
    desc.linear_velocity = Vec3(speed, 0.0f, 0.0f);
    desc.angular_velocity = Vec3(0.0f, 0.0f, -speed / radius);  // rolling towards +x
    const BodyId id = world.add_body(desc);
    const float deceleration = settings.solver.rolling_resistance * kGravity / (1.4f * radius);
    run(world, speed / deceleration + 1.0f);
    const float expected = speed * speed / (2.0f * deceleration);
    EXPECT_NEAR(world.body(id).pose.translation.x(), expected, 0.05f * expected)
        << "v0 = " << speed;
    EXPECT_LT(world.body(id).linear_velocity.norm(), 0.01f);
  }
}

// A frictionless box spinning about the vertical on its four lowest spheres: the pair's
// contacts together resist with e m g, so ω falls at e m g / I and it turns ω0² / (2α).
TEST(PlausibleRollingResistance, ASpinningBoxStopsAsItsWholeWeightResists) {
  WorldSettings settings = on_plane(0.0f, 0.0f);
  settings.solver.rolling_resistance = 0.01f;
  World world(settings);
  BodyDesc desc = cube(Vec3(0.0f, cube_half_height(), 0.0f), 0.0f);
  const float spin = 1.0f;  // unit: rad/s
  desc.angular_velocity = Vec3(0.0f, spin, 0.0f);
  const BodyId box = world.add_body(desc);
  const float inertia = desc.inertia(1, 1);
  const float deceleration = settings.solver.rolling_resistance * desc.mass * kGravity / inertia;
  float turned = 0.0f;
  const int steps = static_cast<int>(std::lround((spin / deceleration + 1.0f) / kDt));
  for (int i = 0; i < steps; ++i) {
    ASSERT_FALSE(world.step(kDt).non_finite_body);
    turned += world.body(box).angular_velocity.y() * kDt;
  }
  const float expected = spin * spin / (2.0f * deceleration);
  EXPECT_NEAR(turned, expected, 0.05f * expected);
  EXPECT_LT(world.body(box).angular_velocity.norm(), 0.01f);
  EXPECT_NEAR(world.body(box).pose.translation.x(), 0.0f, 0.01f);
}

// 3. A stack of ten boxes stands, then sleeps.

TEST(PlausibleStack, TenBoxesStandForTenSecondsAndFallAsleep) {
  const WorldSettings settings = on_plane(0.5f, 0.0f);
  World world(settings);
  std::vector<BodyId> boxes;
  std::vector<Vec3> starts;
  for (int i = 0; i < 10; ++i) {
    // Sphere on sphere, touching: the stack as the trees make it.
    starts.emplace_back(0.0f, cube_half_height() * static_cast<float>(2 * i + 1), 0.0f);
    boxes.push_back(world.add_body(cube(starts.back(), 0.5f)));
  }
  // The stack first settles into the slop that resting contacts keep, plus what the velocity
  // passes leave unconverged under a ten-high load (measured: 0.5 to 1.6 mm per contact, the
  // most at the bottom), at each of the contacts below a box; then it must not move: drift is
  // measured from there.
  constexpr float kUnconvergedSink = 0.0015f;  // per contact. unit: m
  run(world, 0.5f);
  std::vector<Vec3> settled;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const Vec3 position = world.body(boxes[i]).pose.translation;
    EXPECT_LT((position - starts[i]).norm(),
              (settings.solver.linear_slop + kUnconvergedSink) * static_cast<float>(i + 1))
        << "box " << i;
    settled.push_back(position);
  }
  float worst_drift = 0.0f;
  int first_all_asleep = -1;
  for (int frame = 30; frame < 600; ++frame) {
    const StepStats& stats = world.step(kDt);
    ASSERT_FALSE(stats.non_finite_body);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      worst_drift =
          std::max(worst_drift, (world.body(boxes[i]).pose.translation - settled[i]).norm());
    }
    if (first_all_asleep < 0 && stats.bodies_asleep == boxes.size()) first_all_asleep = frame;
  }
  EXPECT_LT(worst_drift, 0.01f * kBoxSide);
  ASSERT_GE(first_all_asleep, 0) << "the stack never fell asleep";
  EXPECT_LT(first_all_asleep, 300);
  for (const BodyId box : boxes) EXPECT_TRUE(world.asleep(box));
  EXPECT_EQ(world.stats().bodies_at_rest, 10u);
  EXPECT_EQ(world.stats().jitter, 0.0);
}

// The soft step's contact spring takes as its mass the mass whose weight the contact carries (at
// least the heavier body's), so every contact of a column yields the same g / ω² beyond the slop,
// 0.28 mm at 30 Hz, where a spring of one box's mass lets the contact
// under nine boxes yield nine times that (2.5 mm).
TEST(PlausibleSoftStep, EachContactOfATenBoxColumnYieldsAsUnderOneBox) {
  WorldSettings settings = on_plane(0.5f, 0.0f);
  World world(settings);
  std::vector<BodyId> boxes;
  const float half = cube_half_height();
  for (int i = 0; i < 10; ++i) {
    boxes.push_back(
        world.add_body(cube(Vec3(0.0f, half * static_cast<float>(2 * i + 1), 0.0f), 0.5f)));
  }
  run(world, 3.0f);
  const float substep_rate = static_cast<float>(settings.solver.soft_substeps) / kDt;
  const float omega = 2.0f * std::numbers::pi_v<float> *
                      std::min(settings.solver.contact_hertz, substep_rate / 8.0f);
  const float yield = settings.gravity.norm() / (omega * omega);
  // Rounding of the spring's implicit solve and the slop's edge. unit: m
  constexpr float kTolerance = 0.0002f;
  float below = 0.0f;  // the top of the box below (the plane first)
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const float centre = world.body(boxes[i]).pose.translation.y();
    EXPECT_GT(centre - half, below - settings.solver.linear_slop - yield - kTolerance)
        << "box " << i;
    below = centre + half;
  }
}

// 4. The restitution ladder, and no energy gained.

struct Bounce {
  float rebound_height = 0.0f;      // top of the first rebound above the resting height. unit: m
  double most_energy_gained = 0.0;  // largest rise of KE + PE above its start. unit: J
};

// With `fixed_step`, one step per frame: the energy invariant below holds for a fixed step, and
// the adaptive substeps change the step from frame to frame (then most_energy_gained means
// nothing).
Bounce drop_ball(float restitution, float height, bool fixed_step = true) {
  WorldSettings settings = on_plane(0.5f, restitution);
  if (fixed_step) settings.max_collision_passes = 1;
  // The soft step integrates in its own substeps.
  const double integrator_step = kDt / static_cast<float>(settings.solver.soft_substeps);
  World world(settings);
  const float radius = 0.25f;
  const BodyId id = world.add_body(ball(radius, Vec3(0.0f, radius + height, 0.0f), restitution));
  // The energy the integrator keeps exactly in flight: semi-implicit Euler conserves
  // ½ m v² + m g h − ½ m g v_y dt, not ½ m v² + m g h, which swings by ±½ m g |v| dt (0.5 J here)
  // with the direction of flight. Rebounds are measured against it.
  const auto energy = [&] {
    const RigidBody& body = world.body(id);
    const double above = body.pose.translation.y() - radius;
    return body.kinetic_energy() + body.mass() * kGravity * above -
           0.5 * body.mass() * kGravity * body.linear_velocity.y() * integrator_step;
  };
  const double start = energy();
  Bounce bounce;
  bool hit = false;
  for (int frame = 0; frame < 240; ++frame) {
    world.step(kDt);
    const RigidBody& body = world.body(id);
    bounce.most_energy_gained = std::max(bounce.most_energy_gained, energy() - start);
    if (body.linear_velocity.y() > 0.0f) hit = true;
    // Stop at the first apex after the impact (or when a dead ball has lain still a while).
    if (hit && body.linear_velocity.y() <= 0.0f) break;
    if (hit || frame > 120) {
      bounce.rebound_height = std::max(bounce.rebound_height, body.pose.translation.y() - radius);
    }
  }
  return bounce;
}

TEST(PlausibleRestitution, BallsReboundToEpsilonSquaredTimesTheDropHeight) {
  const float height = 2.0f;
  for (const float restitution : {0.0f, 0.5f, 1.0f}) {
    const Bounce bounce = drop_ball(restitution, height);
    const float expected = restitution * restitution * height;
    // Within 4% of the drop height: the step's 1/60 s samples the apex, and semi-implicit Euler
    // loses ½ g² dt² of energy per step in flight.
    EXPECT_NEAR(bounce.rebound_height, expected, 0.04f * height) << "ε = " << restitution;
    // Never above what it started with, beyond float rounding (≈ 1e-6 · 20 J).
    EXPECT_LE(bounce.most_energy_gained, 1e-4) << "ε = " << restitution;
    // The same with the default adaptive substeps (by the travel rule, three per frame as the
    // ball nears the plane at 6.3 m/s).
    EXPECT_NEAR(drop_ball(restitution, height, false).rebound_height, expected, 0.04f * height)
        << "ε = " << restitution << ", adaptive substeps";
  }
}

TEST(PlausibleRestitution, SlowImpactsUnderTheThresholdDoNotBounce) {
  // Dropped from 2 cm: 0.63 m/s at impact, under the 1 m/s threshold, so even ε = 1 stays put.
  const Bounce bounce = drop_ball(1.0f, 0.02f);
  EXPECT_LT(bounce.rebound_height, 0.002f);
}

// 5. A fast impact: stopped at the surface, not inside or through.

struct Impact {
  float deepest = 0.0f;  // unit: m
  float top_y = 0.0f;    // the falling box's centre at the end. unit: m
  float bottom_y = 0.0f;
  float horizontal_distance = 0.0f;  // between the two centres at the end. unit: m
};

// 30 m/s downwards, half its own size per step, from `gap` above a box resting on the floor.
Impact drop_box_fast(bool speculative, float gap) {
  WorldSettings settings = on_plane(0.5f, 0.0f);
  settings.solver.speculative_contacts = speculative;
  World world(settings);
  const float rest = cube_half_height();
  const BodyId bottom = world.add_body(cube(Vec3(0.0f, rest, 0.0f), 0.5f));
  BodyDesc top = cube(Vec3(0.1f, 3.0f * rest + gap, 0.05f), 0.5f);
  top.linear_velocity = Vec3(0.0f, -30.0f, 0.0f);
  const BodyId falling = world.add_body(top);
  Impact impact;
  for (int frame = 0; frame < 180; ++frame) {
    impact.deepest = std::max(impact.deepest, world.step(kDt).deepest_penetration);
  }
  impact.top_y = world.body(falling).pose.translation.y();
  impact.bottom_y = world.body(bottom).pose.translation.y();
  const Vec3 apart = world.body(falling).pose.translation - world.body(bottom).pose.translation;
  impact.horizontal_distance = Vec3(apart.x(), 0.0f, apart.z()).norm();
  return impact;
}

// Gaps that put the last step before the impact anywhere in the 0.5 m it covers.
constexpr float kGaps[] = {3.0f, 3.1f, 3.2f, 3.3f, 3.4f};

TEST(PlausibleImpact, ABoxAt30MetresPerSecondStopsOnAnotherWithin5PercentOfItsSize) {
  for (const float gap : kGaps) {
    const Impact impact = drop_box_fast(true, gap);
    EXPECT_LT(impact.deepest, 0.05f * kBoxSide) << "gap " << gap;
    // Never through: the falling box ends on the other or knocked beside it, both on the floor.
    if (impact.horizontal_distance < kBoxSide) {
      EXPECT_GT(impact.top_y - impact.bottom_y, 2.0f * cube_half_height() - 0.05f * kBoxSide)
          << "gap " << gap;
    }
    EXPECT_GT(impact.top_y, cube_half_height() - 0.05f * kBoxSide) << "gap " << gap;
    EXPECT_GT(impact.bottom_y, cube_half_height() - 0.05f * kBoxSide) << "gap " << gap;
  }
}

TEST(PlausibleImpact, WithoutSpeculativeContactsTheSameImpactSinksDeep) {
  // The scene is hard: the step alone, without contacts ahead of the impact, lets the box in by
  // more than the bound above for some of the gaps.
  float deepest = 0.0f;
  for (const float gap : kGaps) deepest = std::max(deepest, drop_box_fast(false, gap).deepest);
  EXPECT_GT(deepest, 0.05f * kBoxSide);
}

TEST(PlausibleImpact, ABlowOnASleepingStackMeetsAllOfIt) {
  // The detector skips pairs of sleeping bodies; a body landing on a sleeping stack wakes its top
  // box, which must meet its contact with the box below in the same step, or it is driven into
  // that box unopposed (seen with one step per frame and 20 passes: 19% of a box deep before the
  // world detected again, 1.1% after). The box below, asleep, holds like a static one: the blow
  // ends in the ground, and what it does not move sleeps on.
  World world(on_plane(0.5f, 0.0f));
  const float rest = cube_half_height();
  std::vector<BodyId> stack;
  for (int i = 0; i < 10; ++i) {
    stack.push_back(
        world.add_body(cube(Vec3(0.0f, rest * static_cast<float>(2 * i + 1), 0.0f), 0.5f)));
  }
  run(world, 6.0f);  // the bottom boxes, pressed in, wait 2 s
  for (const BodyId box : stack) ASSERT_TRUE(world.asleep(box));
  const float top = world.body(stack.back()).pose.translation.y();
  BodyDesc falling = cube(Vec3(0.1f, top + 2.0f * rest + 3.2f, 0.05f), 0.5f);
  falling.linear_velocity = Vec3(0.0f, -30.0f, 0.0f);
  world.add_body(falling);
  float deepest = 0.0f;
  bool woke = false;
  for (int frame = 0; frame < 60; ++frame) {
    deepest = std::max(deepest, world.step(kDt).deepest_penetration);
    woke = woke || !world.asleep(stack.back());
  }
  EXPECT_TRUE(woke);
  EXPECT_LT(deepest, 0.05f * kBoxSide);
}

// 6. Sleep and waking.

TEST(PlausibleSleep, ARestingBodySleepsAndAnImpulseOrAnImpactWakesIt) {
  World world(on_plane(0.5f, 0.0f));
  const BodyId box = world.add_body(cube(Vec3(0.0f, cube_half_height(), 0.0f), 0.5f));
  run(world, 1.5f);
  ASSERT_TRUE(world.asleep(box));
  const Vec3 resting = world.body(box).pose.translation;
  run(world, 1.0f);  // asleep: not moved at all
  EXPECT_EQ(world.body(box).pose.translation, resting);

  world.apply_impulse(box, Vec3(2000.0f, 0.0f, 0.0f), world.body(box).pose.translation);
  EXPECT_FALSE(world.asleep(box));
  world.step(kDt);
  EXPECT_GT(world.body(box).pose.translation.x(), resting.x());
  run(world, 3.0f);
  ASSERT_TRUE(world.asleep(box));

  // A ball dropped onto the sleeping box wakes it (their island is disturbed).
  const Vec3 top = world.body(box).pose.translation + Vec3(0.0f, 1.5f, 0.0f);
  const BodyId dropped = world.add_body(ball(0.2f, top, 0.0f));
  bool woke = false;
  for (int frame = 0; frame < 60 && !woke; ++frame) {
    world.step(kDt);
    woke = !world.asleep(box);
  }
  EXPECT_TRUE(woke);
  run(world, 3.0f);
  EXPECT_TRUE(world.asleep(box));
  EXPECT_TRUE(world.asleep(dropped));
}

// A row of boxes on the floor, each within the contact margin of the next (one island): box 0
// slides to and fro beside the row, driven, and never rests. Boxes two places away and more
// sleep; box 1, which touches it, stays awake. Then box 0 is driven into box 1, which wakes the
// sleeping boxes with it.
// Six boxes in a row along x on the floor: 1 cm between box 0 and box 1, 5 mm between the
// others, all within the 2 cm margin.
std::vector<BodyId> add_row(World& world) {
  const float half = cube_half_height();
  std::vector<BodyId> row;
  for (int i = 0; i < 6; ++i) {
    const float x = static_cast<float>(i) * (2.0f * half + 0.005f) + (i > 0 ? 0.005f : 0.0f);
    row.push_back(world.add_body(cube(Vec3(x, half, 0.0f), 0.5f)));
  }
  return row;
}

// A column of `count` boxes on the floor, 1 mm apart.
std::vector<BodyId> add_stack(World& world, int count) {
  const float half = cube_half_height();
  std::vector<BodyId> stack;
  for (int i = 0; i < count; ++i) {
    stack.push_back(world.add_body(
        cube(Vec3(0.0f, half + static_cast<float>(i) * (2.0f * half + 0.001f), 0.0f), 0.5f)));
  }
  return stack;
}

TEST(PlausibleSleep, ARestlessBodyKeepsOnlyItsNeighboursAwake) {
  World world(on_plane(0.5f, 0.0f));
  const std::vector<BodyId> row = add_row(world);
  const auto drive = [&](int frames, const Vec3& velocity) {
    for (int frame = 0; frame < frames; ++frame) {
      if (velocity.isZero()) {
        jiggle(world, row[0], frame);
      } else {
        world.set_velocity(row[0], velocity, Vec3::Zero());
        world.step(kDt);
      }
    }
  };
  drive(180, Vec3::Zero());
  EXPECT_FALSE(world.asleep(row[0]));
  EXPECT_FALSE(world.asleep(row[1]));
  for (std::size_t i = 2; i < row.size(); ++i) EXPECT_TRUE(world.asleep(row[i])) << "box " << i;

  drive(5, Vec3(1.0f, 0.0f, 0.0f));
  for (std::size_t i = 0; i < row.size(); ++i) EXPECT_FALSE(world.asleep(row[i])) << "box " << i;
}

// The same row, box 0 restless beside it and boxes 2 to 5 asleep. Box 1 is nudged along the row's
// faces, moving now, and wakes box 2, which it touches, mid-substep; box 2 does not move, so the
// boxes beyond it sleep on. Box 2 was still while asleep and keeps half the sleep time of it, so it
// sleeps again once it has been still for twice the sleep time (box 0 keeps the row's island
// restless) less the half it kept: 0.75 s, not 1 s. Woken mid-substep, it gets that substep's
// gravity, so that the impulse that held it up when it fell asleep does not lift it.
TEST(PlausibleSleep, WokenBodiesThatStayStillSleepAgainSooner) {
  World world(on_plane(0.5f, 0.0f));
  const std::vector<BodyId> row = add_row(world);
  int frame = 0;
  const auto step = [&] { jiggle(world, row[0], frame++); };
  while (frame < 180) step();
  for (std::size_t i = 2; i < row.size(); ++i) ASSERT_TRUE(world.asleep(row[i])) << "box " << i;
  const Vec3 resting = world.body(row[2]).pose.translation;

  world.set_velocity(row[1], Vec3(0.0f, 0.0f, 0.1f), Vec3::Zero());
  const int nudged = frame;
  step();
  ASSERT_FALSE(world.asleep(row[2]));
  float fastest = 0.0f;
  while (!world.asleep(row[2]) && frame < nudged + 120) {
    fastest = std::max(fastest, world.body(row[2]).linear_velocity.norm());
    for (std::size_t i = 3; i < row.size(); ++i) EXPECT_TRUE(world.asleep(row[i])) << "box " << i;
    step();
  }
  const float seconds = static_cast<float>(frame - nudged) * kDt;
  const float time = SleepSettings{}.time;
  EXPECT_GE(seconds, 1.5f * time - 2.0f * kDt);
  EXPECT_LE(seconds, 1.5f * time + 2.0f * kDt);
  EXPECT_LT(fastest, SleepSettings{}.speed);
  // The soft step's contact springs give a little as the box wakes (0.16 mm).
  const float moved = 5e-4f;
  EXPECT_LT((world.body(row[2]).pose.translation - resting).norm(), moved);
}

// A stack asleep keeps its contacts' impulses: woken, it starts from them (every contact warm
// started in the first step) and does not sag (beyond what the soft step's springs give).
TEST(PlausibleSleep, AWokenStackStartsFromItsRestingImpulses) {
  World world(on_plane(0.5f, 0.0f));
  const std::vector<BodyId> stack = add_stack(world, 4);
  run(world, 4.0f);
  for (const BodyId box : stack) ASSERT_TRUE(world.asleep(box));
  const float bottom = world.body(stack[0]).pose.translation.y();
  const float top = world.body(stack[3]).pose.translation.y();

  for (const BodyId box : stack) world.set_velocity(box, Vec3::Zero(), Vec3::Zero());  // wakes it
  for (const BodyId box : stack) ASSERT_FALSE(world.asleep(box));
  const StepStats& first = world.step(kDt);
  EXPECT_GT(first.contacts_solved, 0u);
  EXPECT_EQ(first.warm_started, first.contacts_solved);
  float lowest_top = top;
  for (int frame = 0; frame < 30; ++frame) {
    world.step(kDt);
    lowest_top = std::min(lowest_top, world.body(stack[3]).pose.translation.y());
  }
  // Sequential impulses keep the stack where it slept (started cold, its top sank 1.2 mm); the
  // soft step's contact springs let it settle 0.5 mm whatever it starts from (0.75 mm cold).
  const float sag = 0.001f;
  EXPECT_GT(lowest_top, top - sag);
  EXPECT_NEAR(world.body(stack[0]).pose.translation.y(), bottom, sag);
}

TEST(PlausibleSleep, SleepingCanBeTurnedOff) {
  WorldSettings settings = on_plane(0.5f, 0.0f);
  settings.sleep.enabled = false;
  World world(settings);
  const BodyId box = world.add_body(cube(Vec3(0.0f, cube_half_height(), 0.0f), 0.5f));
  run(world, 3.0f);
  EXPECT_FALSE(world.asleep(box));
  EXPECT_EQ(world.stats().bodies_at_rest, 1u);
}

TEST(PlausibleSettings, ImpossibleSolverSettingsAreRefused) {
  const auto refused = [](auto change) {
    WorldSettings settings;
    change(settings);
    EXPECT_THROW(World{settings}, Error);
  };
  refused([](WorldSettings& s) { s.collision_passes = 0; });
  refused([](WorldSettings& s) { s.collision_passes = 65; });
  refused([](WorldSettings& s) { s.max_collision_passes = 0; });
  refused([](WorldSettings& s) { s.max_collision_passes = 65; });
  refused([](WorldSettings& s) { s.collision_pass_travel = 0.0f; });
  refused(
      [](WorldSettings& s) { s.collision_pass_travel = std::numeric_limits<float>::infinity(); });
  refused([](WorldSettings& s) { s.solver.soft_substeps = 0; });
  refused([](WorldSettings& s) { s.solver.contact_hertz = 0.0f; });
  refused([](WorldSettings& s) { s.solver.rolling_resistance = std::nanf(""); });
  refused([](WorldSettings& s) { s.solver.manifold_points = 0; });
  refused([](WorldSettings& s) { s.solver.manifold_points = 9; });
  refused([](WorldSettings& s) { s.solver.linear_slop = -0.1f; });
  refused([](WorldSettings& s) { s.solver.max_correction_speed = -1.0f; });
  refused([](WorldSettings& s) { s.solver.contact_margin = std::nanf(""); });
  refused([](WorldSettings& s) { s.sleep.time = -1.0f; });
  refused([](WorldSettings& s) { s.ground_friction = -0.5f; });
}

}  // namespace
}  // namespace sphys::test
