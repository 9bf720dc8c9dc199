// The soft step's solver on its own, against impulses worked out by hand: a head-on pair of
// equal balls (momentum kept, the pair leaving at ε times its approach), a ball at rest on the
// plane (each substep's impulse its weight's, no motion), and a ball sliding on the plane
// (friction at the manifold's centre decelerating it by μ g and spinning it up as a rigid ball).

#include "dynamics/soft_step_solver.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/body_store.h"
#include "sphys/contact.h"
#include "sphys/material.h"
#include "sphys/parallel.h"
#include "sphys/solver_settings.h"

namespace sphys {
namespace {

constexpr float kRadius = 0.5f;        // unit: m
constexpr float kMass = 2.0f;          // unit: kg
constexpr float kStep = 1.0f / 60.0f;  // unit: s
constexpr std::uint32_t kSubsteps = 4;

// A solid ball of kMass and kRadius at `position`, moving at `velocity`.
RigidBody ball(const Vec3& position, const Vec3& velocity) {
  RigidBody body;
  body.pose.translation = position;
  body.linear_velocity = velocity;
  body.inverse_mass = 1.0f / kMass;
  const float inertia = 0.4f * kMass * kRadius * kRadius;
  body.inertia_body = inertia * Mat3::Identity();
  body.inverse_inertia_body = (1.0f / inertia) * Mat3::Identity();
  return body;
}

// The solver's settings for a hand-worked case: no rolling resistance.
SolverSettings plain_settings() {
  SolverSettings settings;
  settings.rolling_resistance = 0.0f;
  return settings;
}

struct Solved {
  BodyStore bodies;
  std::vector<ContactMemory> memory;
};

// One step of the solver over `contacts`, every contact of `material`.
Solved solve(BodyStore bodies, const std::vector<Contact>& contacts, const PairMaterial& material,
             const Vec3& gravity) {
  Solved solved{std::move(bodies), std::vector<ContactMemory>(contacts.size())};
  SoftStepSolver solver;
  const std::vector<PairMaterial> materials(contacts.size(), material);
  const Parallel one;
  (void)solver.solve(solved.bodies, contacts, solved.memory, materials,
                     SoftStepContext(plain_settings(), gravity, kStep, kSubsteps, one));
  return solved;
}

// Two balls touching at the origin approach at 2 m/s: the relax passes stop the approach (the
// pair's effective mass m/2 takes m/2 · 2 m/s), and restitution sends them apart at ε · 2 m/s,
// m/2 · 2ε N·s kept; momentum is zero throughout.
TEST(SoftStepSolver, AHeadOnPairKeepsMomentumAndLeavesAtEpsilonTimesItsApproach) {
  for (const float restitution : {0.0f, 0.5f, 1.0f}) {
    SCOPED_TRACE(restitution);
    BodyStore bodies;
    bodies.add(ball(Vec3(-kRadius, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)), kRadius);
    bodies.add(ball(Vec3(kRadius, 0.0f, 0.0f), Vec3(-1.0f, 0.0f, 0.0f)), kRadius);
    const std::vector<Contact> contacts = {{.body_a = 0, .body_b = 1, .normal = Vec3::UnitX()}};
    const Solved solved = solve(std::move(bodies), contacts,
                                {.friction = 0.0f, .restitution = restitution}, Vec3::Zero());
    const Vec3 va = solved.bodies.linear_velocities()[0];
    const Vec3 vb = solved.bodies.linear_velocities()[1];
    EXPECT_NEAR((va + vb).norm(), 0.0f, 1e-6f);
    EXPECT_NEAR(vb.x() - va.x(), 2.0f * restitution, 1e-5f);
    EXPECT_NEAR(va.y(), 0.0f, 1e-6f);
    EXPECT_NEAR(solved.bodies.angular_velocities()[0].norm(), 0.0f, 1e-6f);
    // The restitution impulse, the last the contact took (the approach was stopped in an
    // earlier substep and its impulse released in the next).
    EXPECT_NEAR(solved.memory[0].normal_impulse, 0.5f * kMass * 2.0f * restitution, 1e-5f);
  }
}

// A ball resting on the plane (touching, no overlap): each substep's normal impulse carries its
// weight for the substep, m g h, and it does not move.
TEST(SoftStepSolver, ABallAtRestOnThePlaneTakesItsWeightEachSubstepAndStays) {
  BodyStore bodies;
  bodies.add(ball(Vec3(0.0f, kRadius, 0.0f), Vec3::Zero()), kRadius);
  const std::vector<Contact> contacts = {
      {.body_a = kGroundPlaneBody, .body_b = 0, .point = Vec3::Zero(), .normal = Vec3::UnitY()}};
  const float gravity = 9.81f;
  BodyStore state = std::move(bodies);
  std::vector<ContactMemory> memory(1);
  SoftStepSolver solver;
  const std::vector<PairMaterial> materials(1, PairMaterial{});
  const Parallel one;
  for (int step = 0; step < 10; ++step) {
    (void)solver.solve(
        state, contacts, memory, materials,
        SoftStepContext(plain_settings(), Vec3(0.0f, -gravity, 0.0f), kStep, kSubsteps, one));
    SCOPED_TRACE(step);
    EXPECT_NEAR(state.linear_velocities()[0].norm(), 0.0f, 1e-5f);
    EXPECT_NEAR(state.poses()[0].translation.y(), kRadius, 1e-6f);
    EXPECT_NEAR(memory[0].normal_impulse, kMass * gravity * kStep / kSubsteps, 1e-5f);
  }
}

// A ball sliding on the plane at 2 m/s without spin: friction at the contact, μ m g, takes
// μ g h off its speed each substep and adds μ m g r h / I to its spin, for the step
// Δv = −μ g dt and Δω = −5 μ g dt / (2 r) about z; it does not rise or turn about the normal.
TEST(SoftStepSolver, FrictionAtTheCentreSlowsASlidingBallByMuGAndSpinsItUp) {
  const float mu = 0.3f;
  const float gravity = 9.81f;
  BodyStore bodies;
  bodies.add(ball(Vec3(0.0f, kRadius, 0.0f), Vec3(2.0f, 0.0f, 0.0f)), kRadius);
  const std::vector<Contact> contacts = {
      {.body_a = kGroundPlaneBody, .body_b = 0, .point = Vec3::Zero(), .normal = Vec3::UnitY()}};
  const Solved solved = solve(std::move(bodies), contacts, {.friction = mu, .restitution = 0.0f},
                              Vec3(0.0f, -gravity, 0.0f));
  const Vec3 v = solved.bodies.linear_velocities()[0];
  const Vec3 w = solved.bodies.angular_velocities()[0];
  // The contact's anchor on the ball turns with it and rises by r (1 − cos θ), a few µm in the
  // step, a gap the ball may close (the solver keeps its anchors fixed on the bodies, as Box2D
  // does): its normal impulse, and so friction's bound, come out a fraction of a per cent short,
  // and it sinks at a fraction of a mm/s.
  const float slowing = mu * gravity * kStep;
  EXPECT_NEAR(v.x(), 2.0f - slowing, 0.01f * slowing);
  EXPECT_NEAR(v.y(), 0.0f, 1e-3f);
  EXPECT_NEAR(v.z(), 0.0f, 1e-6f);
  EXPECT_NEAR(w.z(), -2.5f * slowing / kRadius, 0.01f * 2.5f * slowing / kRadius);
  EXPECT_NEAR(w.x(), 0.0f, 1e-6f);
  EXPECT_NEAR(w.y(), 0.0f, 1e-6f);
  // The friction kept is the Coulomb bound of the last substep, against the motion.
  const float bound = mu * kMass * gravity * kStep / kSubsteps;
  EXPECT_NEAR(solved.memory[0].friction_impulse.x(), -bound, 0.01f * bound);
  EXPECT_NEAR(solved.memory[0].friction_impulse.z(), 0.0f, 1e-6f);
}

}  // namespace
}  // namespace sphys
