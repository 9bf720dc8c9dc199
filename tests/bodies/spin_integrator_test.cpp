// The spin integrator gives the same bits in every lane set this processor has (plain doubles,
// SSE2, AVX2), for bodies at rest, tumbling, turning too far for the midpoint rule and in batches
// the lanes do not fill; and a torque-free asymmetric body keeps its angular momentum and kinetic
// energy, as Euler's equations do.

#include "bodies/spin_integrator.h"

#include <bit>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/rigid_body.h"

namespace sphys {
namespace {

struct Body {
  Transform pose;
  Vec3 linear_velocity;
  Vec3 angular_velocity;
  Mat3 inertia;
  Mat3 inverse_inertia;
};

// An inertia with distinct principal moments along random axes.
Mat3 random_inertia(std::mt19937& random) {
  std::uniform_real_distribution<float> moment(0.05f, 3.0f);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const Mat3 axes =
      Quat(unit(random), unit(random), unit(random), unit(random)).normalized().toRotationMatrix();
  const Vec3 moments(moment(random), moment(random), moment(random));
  return axes * moments.asDiagonal() * axes.transpose();
}

// `count` bodies whose spins run from nearly still to several times too fast for one step of
// `dt` (unit: s).
std::vector<Body> random_bodies(std::size_t count, float dt, std::uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_real_distribution<float> exponent(-4.0f, 2.0f);
  std::vector<Body> bodies(count);
  for (Body& body : bodies) {
    body.pose.translation = Vec3(unit(random), unit(random), unit(random));
    body.pose.rotation = Quat(unit(random), unit(random), unit(random), unit(random)).normalized();
    body.linear_velocity = 5.0f * Vec3(unit(random), unit(random), unit(random));
    const float turn = std::pow(10.0f, exponent(random));  // h |ω|. unit: rad
    body.angular_velocity =
        Vec3(unit(random), unit(random), unit(random)).normalized() * (turn / dt);
    body.inertia = random_inertia(random);
    body.inverse_inertia = body.inertia.inverse();
  }
  return bodies;
}

void integrate(std::vector<Body>& bodies, float dt, SpinKernel kernel) {
  std::vector<SpinningBody> spinning;
  for (Body& body : bodies) {
    spinning.push_back({&body.pose, &body.linear_velocity, &body.angular_velocity, &body.inertia,
                        &body.inverse_inertia});
  }
  integrate_positions_keeping_spin(spinning, dt, kernel);
}

std::vector<std::uint32_t> bits_of(const std::vector<Body>& bodies) {
  std::vector<std::uint32_t> out;
  for (const Body& body : bodies) {
    for (const float x : {body.pose.translation.x(), body.pose.translation.y(),
                          body.pose.translation.z(), body.pose.rotation.x(), body.pose.rotation.y(),
                          body.pose.rotation.z(), body.pose.rotation.w(), body.angular_velocity.x(),
                          body.angular_velocity.y(), body.angular_velocity.z()}) {
      out.push_back(std::bit_cast<std::uint32_t>(x));
    }
  }
  return out;
}

TEST(SpinIntegrator, EveryLaneSetGivesTheSameBits) {
  constexpr float kDt = 1.0f / 360.0f;
  // 4 × 50 + 3: the last batch leaves a lane empty.
  const std::vector<Body> start = random_bodies(203, kDt, 7);
  std::vector<Body> portable = start;
  for (int step = 0; step < 20; ++step)
    integrate(portable, kDt, spin_kernel(SolverLanes::kPortable));
  for (const SolverLanes lanes : {SolverLanes::kSse2, SolverLanes::kAvx2}) {
    SpinKernel kernel = nullptr;
    try {
      kernel = spin_kernel(lanes);
    } catch (const Error& error) {
      // Only AVX2 may be missing, and then the message says so.
      EXPECT_EQ(lanes, SolverLanes::kAvx2) << error.what();
      EXPECT_NE(std::string(error.what()).find("avx2"), std::string::npos) << error.what();
      continue;
    }
    std::vector<Body> run = start;
    for (int step = 0; step < 20; ++step) integrate(run, kDt, kernel);
    EXPECT_EQ(bits_of(run), bits_of(portable)) << "lanes " << static_cast<int>(lanes);
  }
  // The bodies moved: the comparison is not of untouched copies.
  EXPECT_NE(bits_of(portable), bits_of(start));
}

TEST(SpinIntegrator, TorqueFreeBodyKeepsItsMomentumAndEnergy) {
  constexpr float kDt = 1.0f / 360.0f;
  Body body;
  body.pose.rotation = Quat(Eigen::AngleAxisf(0.3f, Vec3(1.0f, 2.0f, 0.5f).normalized()));
  body.linear_velocity = Vec3::Zero();
  // Spun mostly about the intermediate axis, the unstable one: it tumbles.
  body.inertia = Vec3(1.0f, 2.0f, 3.0f).asDiagonal();
  body.inverse_inertia = body.inertia.inverse();
  body.angular_velocity = body.pose.rotation * Vec3(0.05f, 3.0f, 0.05f);
  const auto momentum = [](const Body& b) {
    const Mat3 r = b.pose.rotation.toRotationMatrix();
    return Vec3(r * (b.inertia * (r.transpose() * b.angular_velocity)));
  };
  const Vec3 momentum_start = momentum(body);
  const double energy_start = kinetic_energy(body.pose.rotation, body.linear_velocity,
                                             body.angular_velocity, 1.0f, body.inertia);
  std::vector<Body> one = {body};
  const Vec3 body_axis_start = one[0].pose.rotation * Vec3::UnitY();
  float least_alignment = 1.0f;
  for (int step = 0; step < 3600; ++step) {  // 10 s
    integrate(one, kDt, spin_kernel(SolverLanes::kAuto));
    least_alignment =
        std::min(least_alignment, (one[0].pose.rotation * Vec3::UnitY()).dot(body_axis_start));
  }
  const double energy_end = kinetic_energy(one[0].pose.rotation, one[0].linear_velocity,
                                           one[0].angular_velocity, 1.0f, one[0].inertia);
  EXPECT_LT((momentum(one[0]) - momentum_start).norm(), 1e-4f * momentum_start.norm());
  EXPECT_NEAR(energy_end, energy_start, 1e-4 * energy_start);
  // It did tumble: the spin axis turned over at some time.
  EXPECT_LT(least_alignment, 0.0f);
}

}  // namespace
}  // namespace sphys
