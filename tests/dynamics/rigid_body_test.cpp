#include "sphys/rigid_body.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "support/float_limits.h"

namespace sphys {
namespace {

// One float rounding is at most half of this relative to the result; tolerances below count
// roundings and use a whole epsilon per rounding, a margin of 2.
using test::kFloatEpsilon;

// The solid box 1 × 2 × 3 m of density 1000 kg/m³: m = 6000 kg and I = m/12 (b² + c², a² + c²,
// a² + b²) = (6500, 5000, 2500) kg·m². Three different moments: no axis is free to spin stably
// about except the principal ones.
RigidBody asymmetric_box() {
  RigidBody body;
  body.inverse_mass = 1.0f / 6000.0f;
  body.inertia_body = Vec3(6500.0f, 5000.0f, 2500.0f).asDiagonal();
  body.inverse_inertia_body = body.inertia_body.inverse();
  return body;
}

// World angular momentum R I Rᵀ ω, in double so that the check adds no rounding of its own.
Eigen::Vector3d angular_momentum(const RigidBody& body) {
  const Eigen::Matrix3d rotation = body.pose.rotation.toRotationMatrix().cast<double>();
  return rotation * body.inertia_body.cast<double>() * rotation.transpose() *
         body.angular_velocity.cast<double>();
}

TEST(RigidBody, OneStepIsSemiImplicit) {
  // From rest, one step gives v = g dt and then x = v dt = g dt², not the explicit Euler 0 nor
  // the exact ½ g dt²: the position uses the velocity of the end of the step.
  RigidBody body = asymmetric_box();
  body.pose.translation = Vec3(1.0f, 2.0f, 3.0f);
  const float dt = 0.125f;  // powers of two: every value below is exact in float
  // The world's first half, v += g dt with g = 8 m/s² down.
  body.linear_velocity = Vec3(0.0f, -8.0f, 0.0f) * dt;
  integrate_position(body, dt);
  EXPECT_EQ(body.pose.translation, Vec3(1.0f, 1.875f, 3.0f));
  EXPECT_EQ(body.linear_velocity, Vec3(0.0f, -1.0f, 0.0f));
}

TEST(RigidBody, StaticBodiesAreLeftAlone) {
  RigidBody body;
  body.is_static = true;
  body.pose.translation = Vec3(1.0f, 2.0f, 3.0f);
  body.pose.rotation = Quat(Eigen::AngleAxisf(0.5f, Vec3::UnitX()));
  // A static body never has velocities; if one did, the integrator still must not move it.
  body.linear_velocity = Vec3(1.0f, 0.0f, 0.0f);
  body.angular_velocity = Vec3(0.0f, 1.0f, 0.0f);
  const RigidBody before = body;
  integrate_position(body, 0.1f);
  EXPECT_EQ(body.pose.translation, before.pose.translation);
  EXPECT_EQ(body.pose.rotation.coeffs(), before.pose.rotation.coeffs());
  EXPECT_EQ(body.linear_velocity, before.linear_velocity);
  EXPECT_EQ(body.angular_velocity, before.angular_velocity);
  EXPECT_EQ(body.kinetic_energy(), 0.0);
}

TEST(RigidBody, SpinAboutAPrincipalAxisTurnsByTheDiscreteAngle) {
  // q ← normalise((1 + ½ dt (0, ω)) q) is exactly a turn by 2 atan(|ω| dt / 2) about ω, so after
  // n steps the angle is 2 n atan(|ω| dt / 2); here 600 · 2 atan(0.05) = 59.950 rad instead of
  // |ω| t = 60 rad (0.050 rad short). About a principal axis I ω stays along the axis, so ω (at
  // the start and the middle of every step alike) stays constant and the closed form holds.
  RigidBody body = asymmetric_box();
  const float omega = 6.0f;  // unit: rad/s
  body.angular_velocity = Vec3(0.0f, 0.0f, omega);
  const float dt = 1.0f / 60.0f;
  const int steps = 600;
  for (int n = 0; n < steps; ++n) integrate_position(body, dt);

  const double angle = 2.0 * steps * std::atan(0.5 * omega * static_cast<double>(dt));
  const Quat expected(
      Eigen::AngleAxisf(static_cast<float>(std::fmod(angle, 2 * std::numbers::pi)), Vec3::UnitZ()));
  // Each step rounds the quaternion product and the normalisation, a few ε of angle each; 600
  // steps at 4 ε each bound the drift at 2.9e-4 rad, well under the 0.05 rad by which the
  // exact |ω| t differs.
  const float tolerance = steps * 4.0f * kFloatEpsilon;
  EXPECT_LT(body.pose.rotation.angularDistance(expected), tolerance);
  EXPECT_NEAR(body.pose.rotation.norm(), 1.0f, 4.0f * kFloatEpsilon);
  EXPECT_NEAR(body.angular_velocity.z(), omega, 16.0f * kFloatEpsilon * omega);
  EXPECT_EQ(body.angular_velocity.x(), 0.0f);
  EXPECT_EQ(body.angular_velocity.y(), 0.0f);
  EXPECT_EQ(body.pose.translation, Vec3::Zero());
}

TEST(RigidBody, TurningKeepsTheWorldAngularMomentum) {
  // Off a principal axis the world inertia turns with the body: a torque-free step must keep
  // L = I_world ω and change ω instead. One step rounds the rotation matrices and the products
  // I (Rᵀ ω) and I⁻¹ (Rᵀ L): about 20 roundings of quantities up to cond(I) = 2.6 times |L|, so
  // 64 ε |L| bounds it. Keeping ω fixed instead would change L by 1.2 % here.
  RigidBody body = asymmetric_box();
  body.pose.rotation = Quat(Eigen::AngleAxisf(0.7f, Vec3(1.0f, 2.0f, -1.0f).normalized()));
  body.angular_velocity = Vec3(0.8f, -1.5f, 2.0f);
  const Eigen::Vector3d momentum_before = angular_momentum(body);
  integrate_position(body, 1.0f / 60.0f);
  const Eigen::Vector3d momentum_after = angular_momentum(body);
  EXPECT_LT((momentum_after - momentum_before).norm(),
            64.0 * kFloatEpsilon * momentum_before.norm());
  EXPECT_GT((body.angular_velocity - Vec3(0.8f, -1.5f, 2.0f)).norm(), 1e-3f);
  EXPECT_NEAR(body.pose.rotation.norm(), 1.0f, 4.0f * kFloatEpsilon);
}

TEST(RigidBody, TumblingBodyKeepsItsEnergy) {
  // ω = (1.2, 3, 0.9) rad/s off every principal axis, 600 steps of 1/60 s. The turn with ω of
  // the middle of the step has no secular energy error: it stays of order (|ω| dt)² = 3.1e-3,
  // and rounding adds a drift of at most 4 ε a step in L, twice that in E (E = ½ L·ω). A turn
  // with ω of the start of the step gains energy every step: 25 % here.
  RigidBody body = asymmetric_box();
  body.pose.rotation = Quat(Eigen::AngleAxisf(0.6f, Vec3(1.0f, -1.0f, 2.0f).normalized()));
  body.angular_velocity = Vec3(1.2f, 3.0f, 0.9f);
  const double energy_before = body.kinetic_energy();
  const float dt = 1.0f / 60.0f;
  const int steps = 600;
  double worst_energy = 0.0;
  for (int n = 0; n < steps; ++n) {
    integrate_position(body, dt);
    worst_energy = std::max(worst_energy, std::abs(body.kinetic_energy() - energy_before));
  }
  const double turn = body.angular_velocity.norm() * dt;
  const double tolerance = 2.0 * steps * 4.0 * kFloatEpsilon + turn * turn;
  EXPECT_LT(worst_energy, tolerance * energy_before);
}

TEST(RigidBody, QuaternionStaysUnitUnderFastSpin) {
  // 50 rad/s at 1/60 s turns 0.83 rad a step: without renormalisation |q| would grow by
  // √(1 + (|ω| dt / 2)²) = 1.08 per step.
  RigidBody body = asymmetric_box();
  body.angular_velocity = Vec3(30.0f, -20.0f, 35.0f);
  for (int n = 0; n < 1000; ++n) {
    integrate_position(body, 1.0f / 60.0f);
    ASSERT_NEAR(body.pose.rotation.norm(), 1.0f, 4.0f * kFloatEpsilon) << "step " << n;
  }
}

TEST(RigidBody, InverseInertiaWorldIsTheBodyTensorTurned) {
  // A quarter turn about z takes body x to world y: the world tensor swaps the x and y moments.
  RigidBody body = asymmetric_box();
  body.pose.rotation = Quat(Eigen::AngleAxisf(std::numbers::pi_v<float> / 2, Vec3::UnitZ()));
  const Mat3 expected = Vec3(1.0f / 5000.0f, 1.0f / 6500.0f, 1.0f / 2500.0f).asDiagonal();
  EXPECT_LT((body.inverse_inertia_world() - expected).cwiseAbs().maxCoeff(),
            4.0f * kFloatEpsilon / 2500.0f);
}

TEST(RigidBody, KineticEnergyAddsTranslationAndRotation) {
  // ½ · 6000 · (3² + 4²) + ½ (6500 · 1² + 2500 · 2²) = 75000 + 8250 J, with ω given in the world
  // frame of a body turned a quarter about y (body x is world −z, body z is world x).
  RigidBody body = asymmetric_box();
  body.pose.rotation = Quat(Eigen::AngleAxisf(std::numbers::pi_v<float> / 2, Vec3::UnitY()));
  body.linear_velocity = Vec3(3.0f, 0.0f, 4.0f);
  body.angular_velocity = Vec3(2.0f, 0.0f, -1.0f);  // body axes: (1, 0, 2)
  EXPECT_NEAR(body.kinetic_energy(), 83250.0, 8.0 * kFloatEpsilon * 83250.0);
}

TEST(RigidBody, VelocityAtAddsTheSpinAboutTheCentreOfMass) {
  RigidBody body = asymmetric_box();
  body.pose.translation = Vec3(1.0f, 1.0f, 1.0f);
  body.linear_velocity = Vec3(0.5f, 0.0f, 0.0f);
  body.angular_velocity = Vec3(0.0f, 0.0f, 2.0f);
  // ω × r = (0, 0, 2) × (0, 1, 0) = (−2, 0, 0).
  EXPECT_EQ(body.velocity_at(Vec3(1.0f, 2.0f, 1.0f)), Vec3(-1.5f, 0.0f, 0.0f));
}

}  // namespace
}  // namespace sphys
