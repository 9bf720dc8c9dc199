#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/build_tree.h"
#include "sphys/tools/mass_properties.h"
#include "sphys/tools/primitives.h"
#include "sphys/world.h"
#include "support/cube_tree.h"
#include "support/float_limits.h"
#include "support/world_scenes.h"

namespace sphys {
namespace {

using test::kFloatEpsilon;
constexpr double kPi = std::numbers::pi;

using test::one_sphere_tree;

// A homogeneous solid ball as one sphere: m = ρ 4/3 π r³, I = 2/5 m r² about every axis.
BodyDesc solid_ball(float radius, float density, const Vec3& position) {
  BodyDesc desc;
  desc.tree = one_sphere_tree(radius);
  desc.pose.translation = position;
  const double r = radius;
  const double mass = density * 4.0 / 3.0 * kPi * r * r * r;
  desc.mass = static_cast<float>(mass);
  desc.inertia = Mat3::Identity() * static_cast<float>(0.4 * mass * r * r);
  return desc;
}

// These checks are of the paper's response (eq. 4); plausible mode has its own tests.
WorldSettings paper_settings() {
  WorldSettings settings;
  settings.response = ResponseMode::kPaper;
  settings.plausibility_figures = true;
  return settings;
}

WorldSettings zero_gravity() {
  WorldSettings settings = paper_settings();
  settings.gravity = Vec3::Zero();
  return settings;
}

double kinetic_energy(const World& world) {
  double energy = 0.0;
  for (std::uint32_t i = 0; i < world.body_slots(); ++i)
    energy += world.body(world.id_of(i)).kinetic_energy();
  return energy;
}

// 1. Free fall: the semi-implicit Euler closed form, and its known distance from g t²/2.

TEST(WorldPhysics, FreeFallFollowsTheSemiImplicitEulerClosedForm) {
  // v_n = −g dt n and y_n = y0 − g dt² n(n + 1)/2: each step adds g dt to the speed, then moves by
  // the new speed. After t = n dt the body has fallen g t²/2 + g dt t/2: the integrator's error,
  // 0.0818 m after 1 s at 60 Hz.
  World world(paper_settings());  // gravity −9.81 m/s² along y, no ground
  const float y0 = 10.0f;
  const BodyId ball = world.add_body(solid_ball(0.5f, 1000.0f, Vec3(0.0f, y0, 0.0f)));
  const float dt = 1.0f / 60.0f;
  const int steps = 60;
  for (int n = 0; n < steps; ++n) {
    const StepStats& stats = world.step(dt);
    ASSERT_EQ(stats.contacts, 0u);
  }
  // The reference takes the float g and dt as given, in double: only the world's rounding is
  // left. Each step rounds g dt and v + g dt (|v| <= 9.81 m/s): under ε · 9.81 m/s a step, so
  // |Δv| <= 60 · ε · 9.81 = 7.0e-5 m/s. Each position update rounds v dt and y + v dt (|y| <= 10 m)
  // and inherits dt |Δv|: |Δy| <= 60 · ε · 10 + 60 · dt · 7.0e-5 = 1.4e-4 m. Both are far below the
  // integrator's 0.08 m, which the test must see.
  const double g = 9.81f;
  const double step = dt;
  const double t = steps * step;
  const double velocity_tolerance = steps * kFloatEpsilon * g;
  const double position_tolerance = steps * kFloatEpsilon * y0 + t * velocity_tolerance;
  const RigidBody& body = world.body(ball);
  const double y = body.pose.translation.y();
  const double closed_form = y0 - g * step * step * steps * (steps + 1) / 2.0;
  EXPECT_NEAR(y, closed_form, position_tolerance);
  EXPECT_NEAR((y0 - y) - g * t * t / 2.0, g * step * t / 2.0, position_tolerance);
  EXPECT_NEAR(body.linear_velocity.y(), -g * t, velocity_tolerance);
  EXPECT_EQ(body.pose.translation.x(), 0.0f);
  EXPECT_EQ(body.pose.translation.z(), 0.0f);
  EXPECT_EQ(body.angular_velocity, Vec3::Zero());
  EXPECT_EQ(body.pose.rotation.coeffs(), Quat::Identity().coeffs());
}

// 2. A ball dropped on the exact ground plane rebounds to ε² h.

struct Rebound {
  double height = 0.0;            // highest lowest point after the first bounce. unit: m
  float pre_impact_speed = 0.0f;  // speed the impulse met. unit: m/s
  float rebound_speed = 0.0f;     // speed right after it. unit: m/s
  std::uint32_t impulses = 0;     // up to the peak
};

Rebound drop_ball(float restitution, float ground_restitution, float drop, float dt) {
  WorldSettings settings = paper_settings();
  settings.collision.ground_plane_height = 0.0f;
  settings.ground_restitution = ground_restitution;
  World world(settings);
  const float radius = 0.5f;
  BodyDesc desc = solid_ball(radius, 1000.0f, Vec3(0.0f, radius + drop, 0.0f));
  desc.restitution = restitution;
  const BodyId ball = world.add_body(desc);
  Rebound rebound;
  bool bounced = false;
  float peak = -std::numeric_limits<float>::infinity();
  for (int step = 0; step < 100000; ++step) {
    // The world adds g dt before the response; the same float sum gives the speed it met.
    const float pre_impact = world.body(ball).linear_velocity.y() + settings.gravity.y() * dt;
    rebound.impulses += world.step(dt).impulses;
    const RigidBody& body = world.body(ball);
    EXPECT_EQ(body.angular_velocity, Vec3::Zero());  // r ∥ n for a ball on a plane
    if (!bounced && rebound.impulses > 0) {
      bounced = true;
      rebound.pre_impact_speed = -pre_impact;
      rebound.rebound_speed = body.linear_velocity.y();
    }
    if (!bounced) continue;
    peak = std::max(peak, body.pose.translation.y());
    if (body.linear_velocity.y() <= 0.0f) break;
  }
  rebound.height = static_cast<double>(peak) - radius;
  return rebound;
}

TEST(WorldPhysics, BallRebound) {
  // From rest at height h the ball meets the plane at V = √(2 g h) and leaves at ε V, so rises
  // ε² h (ε = max of the ball's and the ground's restitution). With steps of dt the world
  // deviates in three ways, each bounded by a multiple of V dt:
  //  - the impulse comes in the first step after the plane is crossed, when the speed is V plus
  //    between ½ and 1½ g dt: the rebound height grows by up to 1½ ε² V dt;
  //  - the ball is then up to V dt into the plane (its depth p), and rises from there: − p;
  //  - the rise itself, semi-implicit, overshoots v'²/(2g) by ε V dt/2.
  // So |rebound − ε² h| <= (1 + 1½ ε² + ½ ε) V dt; the tolerance takes (1 + 2 ε² + ε) V dt.
  // For h = 1 m, dt = 1 ms, V dt = 4.4 mm: 7 mm for ε = 0.3 (ε² h = 0.09 m), 14 mm for ε = 0.8
  // (0.64 m). A response with min mixing, or (1 + ε) wrong, misses by tenths of a metre.
  const float drop = 1.0f;
  const float dt = 1e-3f;
  const double impact_speed = std::sqrt(2.0 * 9.81 * drop);
  struct Case {
    float restitution;
    float ground_restitution;
    float expected;  // the mixed ε
  };
  for (const Case& c : {Case{0.3f, 0.3f, 0.3f}, Case{0.5f, 0.5f, 0.5f}, Case{0.8f, 0.8f, 0.8f},
                        Case{0.8f, 0.3f, 0.8f}, Case{0.5f, 0.0f, 0.5f}, Case{0.3f, 0.8f, 0.8f}}) {
    SCOPED_TRACE(testing::Message()
                 << "ball " << c.restitution << ", ground " << c.ground_restitution);
    const Rebound rebound = drop_ball(c.restitution, c.ground_restitution, drop, dt);
    const double epsilon = c.expected;
    const double tolerance = (1.0 + 2.0 * epsilon * epsilon + epsilon) * impact_speed * dt;
    EXPECT_NEAR(rebound.height, epsilon * epsilon * drop, tolerance);
    // One impulse reverses the speed it meets, scaled by ε, to within the roundings of eq. 4:
    // about five operations on values up to (1 + ε) times the speed.
    EXPECT_NEAR(rebound.rebound_speed, epsilon * rebound.pre_impact_speed,
                8.0 * kFloatEpsilon * (1.0 + epsilon) * rebound.pre_impact_speed);
    // The speed met is V plus ½ to 1½ g dt (see above); 2 g dt leaves room for rounding.
    EXPECT_NEAR(rebound.pre_impact_speed, impact_speed, 2.0 * 9.81 * dt);
    EXPECT_EQ(rebound.impulses, 1u);
  }
}

// 3. Head-on collisions against the 1-D formulas.

struct HeadOnResult {
  float velocity_a = 0.0f;
  float velocity_b = 0.0f;
  std::uint32_t impulses = 0;
  double energy_before = 0.0;
  double energy_after = 0.0;
};

// Ball a at x = −1 m moving at u_a, ball b at x = +1 m moving at u_b, radius 0.5 m, no gravity;
// stepped until well after they part.
HeadOnResult head_on(float mass_a, float mass_b, float restitution, float u_a, float u_b) {
  World world(zero_gravity());
  BodyDesc a = test::ball_body(0.5f, mass_a, Vec3(-1.0f, 0.0f, 0.0f));
  BodyDesc b = test::ball_body(0.5f, mass_b, Vec3(1.0f, 0.0f, 0.0f));
  a.linear_velocity = Vec3(u_a, 0.0f, 0.0f);
  b.linear_velocity = Vec3(u_b, 0.0f, 0.0f);
  a.restitution = restitution;
  b.restitution = restitution;
  const BodyId ia = world.add_body(a);
  const BodyId ib = world.add_body(b);
  HeadOnResult result;
  result.energy_before = kinetic_energy(world);
  for (int step = 0; step < 120; ++step) result.impulses += world.step(1.0f / 60.0f).impulses;
  result.energy_after = kinetic_energy(world);
  for (const BodyId id : {ia, ib}) {
    // The contact lies on the line of centres, n = ±x exactly: nothing leaves the axis.
    EXPECT_EQ(world.body(id).linear_velocity.y(), 0.0f);
    EXPECT_EQ(world.body(id).linear_velocity.z(), 0.0f);
    EXPECT_EQ(world.body(id).angular_velocity, Vec3::Zero());
  }
  result.velocity_a = world.body(ia).linear_velocity.x();
  result.velocity_b = world.body(ib).linear_velocity.x();
  return result;
}

TEST(WorldPhysics, HeadOnCollisionsFollowTheOneDimensionalFormulas) {
  // v_a' = (m_a u_a + m_b u_b − m_b ε (u_a − u_b)) / (m_a + m_b),
  // v_b' = (m_a u_a + m_b u_b + m_a ε (u_a − u_b)) / (m_a + m_b);
  // the kinetic energy lost is (1 − ε²) ½ μ (u_a − u_b)², μ = m_a m_b / (m_a + m_b).
  // Tolerance: eq. 4 passes the relative speed through about eight float operations, so each
  // velocity is within 8 ε |u_a − u_b| (1e-6 relative); the energy within the same relative
  // error of the energies times two (squares). Equal masses and ε = 1 exchange the velocities.
  struct Case {
    float mass_a, mass_b, restitution, u_a, u_b;
  };
  for (const Case& c : {Case{2.5f, 2.5f, 1.0f, 2.0f, -1.0f}, Case{1.0f, 3.0f, 1.0f, 2.0f, -1.0f},
                        Case{1.0f, 3.0f, 0.5f, 2.0f, -1.0f}, Case{7.0f, 0.4f, 0.5f, 0.5f, -3.0f},
                        Case{1.0f, 3.0f, 0.0f, 2.0f, 0.5f}}) {
    SCOPED_TRACE(testing::Message()
                 << "masses " << c.mass_a << ", " << c.mass_b << ", ε " << c.restitution);
    const HeadOnResult result = head_on(c.mass_a, c.mass_b, c.restitution, c.u_a, c.u_b);
    const double ma = c.mass_a;
    const double mb = c.mass_b;
    const double e = c.restitution;
    const double relative = c.u_a - c.u_b;
    const double momentum = ma * c.u_a + mb * c.u_b;
    const double expected_a = (momentum - mb * e * relative) / (ma + mb);
    const double expected_b = (momentum + ma * e * relative) / (ma + mb);
    const double tolerance = 8.0 * kFloatEpsilon * relative;
    EXPECT_EQ(result.impulses, 1u);
    EXPECT_NEAR(result.velocity_a, expected_a, tolerance);
    EXPECT_NEAR(result.velocity_b, expected_b, tolerance);
    const double reduced_mass = ma * mb / (ma + mb);
    const double loss = (1.0 - e * e) * 0.5 * reduced_mass * relative * relative;
    EXPECT_NEAR(result.energy_before - result.energy_after, loss,
                16.0 * kFloatEpsilon * result.energy_before);
  }
  const HeadOnResult equal = head_on(2.5f, 2.5f, 1.0f, 2.0f, -1.0f);
  EXPECT_NEAR(equal.velocity_a, -1.0f, 8.0f * kFloatEpsilon * 3.0f);
  EXPECT_NEAR(equal.velocity_b, 2.0f, 8.0f * kFloatEpsilon * 3.0f);
  EXPECT_NEAR(equal.energy_after, equal.energy_before, 16.0 * kFloatEpsilon * equal.energy_before);
}

// 4. Momentum of free bodies through many collisions.

std::shared_ptr<const SphereTree> box_octree(const tools::Vec3d& size) {
  tools::BuildOptions options;
  options.method = tools::BuildMethod::Octree;
  options.depth = 3;
  return std::make_shared<const SphereTree>(
      tools::build_sphere_tree(tools::make_box(size), options));
}

struct Momenta {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  // about the origin
  double linear_scale = 0.0;                          // Σ m |v|. unit: kg·m/s
  double angular_scale = 0.0;                         // Σ |x| m |v| + |I ω|. unit: kg·m²/s
};

// In double, the mass taken as the exact reciprocal of the stored inverse mass: the sums add
// no rounding of their own worth counting.
Momenta momenta(const World& world) {
  Momenta sum;
  for (std::uint32_t i = 0; i < world.body_slots(); ++i) {
    const RigidBody& body = world.body(world.id_of(i));
    if (body.is_static) continue;
    const double mass = 1.0 / static_cast<double>(body.inverse_mass);
    const Eigen::Vector3d momentum = mass * body.linear_velocity.cast<double>();
    const Eigen::Vector3d position = body.pose.translation.cast<double>();
    const Eigen::Matrix3d rotation = body.pose.rotation.toRotationMatrix().cast<double>();
    const Eigen::Vector3d spin = rotation * body.inertia_body.cast<double>() *
                                 rotation.transpose() * body.angular_velocity.cast<double>();
    sum.linear += momentum;
    sum.angular += position.cross(momentum) + spin;
    sum.linear_scale += momentum.norm();
    sum.angular_scale += position.norm() * momentum.norm() + spin.norm();
  }
  return sum;
}

TEST(WorldPhysics, FreeBodiesConserveMomentumThroughCollisions) {
  const std::vector<tools::Vec3d> sizes{{0.6, 0.3, 0.4}, {0.8, 0.4, 0.4}, {0.5, 0.5, 0.5}};
  std::vector<std::shared_ptr<const SphereTree>> trees;
  std::vector<tools::MassProperties> unit_density;
  for (const tools::Vec3d& size : sizes) {
    trees.push_back(box_octree(size));
    tools::MassPropertiesOptions options;
    options.density = 1.0;
    unit_density.push_back(tools::compute_mass_properties(tools::make_box(size), options));
  }
  std::mt19937 rng(2008);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  const auto unit = [&] { return uniform(rng); };
  // Drawn one after another (the order of a call's arguments is unspecified): the same scene on
  // every compiler.
  const auto unit_vector = [&] {
    const float x = unit();
    const float y = unit();
    const float z = unit();
    return Vec3(x, y, z);
  };
  const auto rotation = [&] {
    const float w = unit();
    const Vec3 v = unit_vector();
    return Quat(w, v.x(), v.y(), v.z()).normalized();
  };
  World world(zero_gravity());
  const auto add_box = [&](std::size_t kind, const Vec3& position, const Vec3& velocity,
                           float restitution) {
    const float density = 300.0f + 850.0f * (unit() + 1.0f);  // unit: kg/m³
    BodyDesc desc;
    desc.tree = trees[kind];
    desc.pose.translation = position;
    desc.pose.rotation = rotation();
    desc.linear_velocity = velocity;
    desc.angular_velocity = 2.0f * unit_vector();
    desc.mass = static_cast<float>(density * unit_density[kind].mass);
    desc.inertia = (density * unit_density[kind].inertia).cast<float>();
    desc.restitution = restitution;
    world.add_body(desc);
  };
  // A heap: 27 boxes on a 3 × 3 × 3 grid of 0.8 m pitch, off the origin, thrown together with
  // little restitution: many simultaneous contacts for the first 80 steps or so.
  const Vec3 heap_centre(0.7f, 0.4f, -0.3f);
  for (int i = 0; i < 27; ++i) {
    const int column = i % 3 - 1;
    const int row = (i / 3) % 3 - 1;
    const int layer = i / 9 - 1;
    const Vec3 cell(static_cast<float>(column), static_cast<float>(row), static_cast<float>(layer));
    const Vec3 position = heap_centre + 0.8f * cell + 0.05f * unit_vector();
    const Vec3 velocity = -2.0f * (position - heap_centre) + 0.5f * unit_vector();
    const float restitution = 0.1f * (1.0f + unit());
    add_box(static_cast<std::size_t>(i) % sizes.size(), position, velocity, restitution);
  }
  // Eight pairs 8 m above it in lanes 2 m apart, each meeting off-centre at its own time, 0.5 s
  // to 4.7 s, so that collisions go on through the run.
  for (int k = 0; k < 8; ++k) {
    const Vec3 meeting = heap_centre + Vec3(0.0f, 8.0f, 2.0f * static_cast<float>(k) - 7.0f);
    const float gap = 0.6f + 2.0f * (0.5f + 0.6f * static_cast<float>(k));  // closing at 2 m/s
    const float offset_y = 0.15f * unit();
    const Vec3 offset(0.5f * gap, offset_y, 0.15f * unit());
    const float restitution_first = 0.5f + 0.5f * unit();
    const float restitution_second = 0.5f + 0.5f * unit();
    add_box(static_cast<std::size_t>(k) % sizes.size(), meeting - offset, Vec3::UnitX(),
            restitution_first);
    add_box(static_cast<std::size_t>(k + 1) % sizes.size(), meeting + offset, -Vec3::UnitX(),
            restitution_second);
  }

  const Momenta before = momenta(world);
  std::uint64_t impulses = 0;
  int steps_with_impulses = 0;
  int last_step_with_impulses = 0;
  const int steps = 400;
  double worst_linear = 0.0;
  double worst_angular = 0.0;
  for (int step = 0; step < steps; ++step) {
    const StepStats& stats = world.step(1.0f / 60.0f);
    ASSERT_FALSE(stats.non_finite_body.has_value());
    impulses += stats.impulses;
    if (stats.impulses > 0) {
      ++steps_with_impulses;
      last_step_with_impulses = step;
    }
    const Momenta now = momenta(world);
    worst_linear = std::max(worst_linear, (now.linear - before.linear).norm());
    worst_angular = std::max(worst_angular, (now.angular - before.angular).norm());
  }
  EXPECT_GT(impulses, 300u);
  EXPECT_GT(steps_with_impulses, 40);
  EXPECT_GT(last_step_with_impulses, 250);
  // Linear: each impulse adds one vector J to one body and takes it from the other; what is
  // left is the rounding of J/m and of v + Δv, at most ε of a body's momentum each and of either
  // sign, so the sum walks like √N ε of the momentum scale Σ m |v| (N impulses): 2.6e-6 here.
  // Moving bodies by v dt changes no linear momentum.
  const double impulse_count = static_cast<double>(impulses);
  EXPECT_LT(worst_linear, std::sqrt(impulse_count) * kFloatEpsilon * before.linear_scale);
  // Angular (about the origin): the impulses conserve it the same way (+J and −J act at one
  // point); in addition every step rounds x + v dt, which moves x × m v, and round-trips I ω
  // through I and I⁻¹, whose rounding repeats every step and can add up linearly (see the
  // spinning box below): at most ε of Σ (|x| m |v| + |I ω|) per step, 4.8e-5 after 400 steps.
  EXPECT_LT(worst_angular, steps * kFloatEpsilon * before.angular_scale);
}

// 5. A torque-free asymmetric body keeps its angular momentum.

TEST(WorldPhysics, SpinningAsymmetricBoxKeepsItsAngularMomentum) {
  // The box 1 × 2 × 3 m at 1000 kg/m³: m = 6000 kg, I = m/12 (b² + c², a² + c², a² + b²)
  // = (6500, 5000, 2500) kg·m², which the mesh integrals must reproduce.
  tools::MassPropertiesOptions options;
  options.density = 1000.0;
  const tools::MassProperties box =
      tools::compute_mass_properties(tools::make_box({1.0, 2.0, 3.0}), options);
  EXPECT_NEAR(box.mass, 6000.0, 1e-9 * 6000.0);
  EXPECT_LT(
      (box.inertia - tools::Vec3d(6500.0, 5000.0, 2500.0).asDiagonal().toDenseMatrix()).norm(),
      1e-9 * 6500.0);

  World world(zero_gravity());
  BodyDesc desc;
  desc.tree = one_sphere_tree(static_cast<float>(std::sqrt(0.25 + 1.0 + 2.25)));
  desc.mass = static_cast<float>(box.mass);
  desc.inertia = box.inertia.cast<float>();
  desc.pose.rotation = Quat(Eigen::AngleAxisf(0.6f, Vec3(1.0f, -1.0f, 2.0f).normalized()));
  desc.angular_velocity = Vec3(0.4f, 1.0f, 0.3f);  // off every principal axis: it tumbles
  const BodyId id = world.add_body(desc);
  const auto momentum = [&] {
    const RigidBody& body = world.body(id);
    const Eigen::Matrix3d rotation = body.pose.rotation.toRotationMatrix().cast<double>();
    return Eigen::Vector3d(rotation * body.inertia_body.cast<double>() * rotation.transpose() *
                           body.angular_velocity.cast<double>());
  };
  const Eigen::Vector3d momentum_before = momentum();
  const double energy_before = world.body(id).kinetic_energy();
  double worst_momentum = 0.0;
  double worst_energy = 0.0;
  const int steps = 600;
  for (int step = 0; step < steps; ++step) {
    world.step(1.0f / 60.0f);
    worst_momentum = std::max(worst_momentum, (momentum() - momentum_before).norm());
    worst_energy =
        std::max(worst_energy, std::abs(world.body(id).kinetic_energy() - energy_before));
  }
  // Momentum: the exact scheme keeps L; in float each step round-trips it through ω, with the
  // rotation matrix of a unit quaternion that is unit only to rounding. That error does not
  // average out (measured: |L| grows by about 0.7 ε a step), so the tolerance counts 4 ε a step:
  // 2.9e-4 after 600 steps. Keeping ω instead of L would move L by tens of per cent.
  const double momentum_tolerance = steps * 4.0 * kFloatEpsilon;
  EXPECT_LT(worst_momentum, momentum_tolerance * momentum_before.norm());
  // Energy: E = ½ L·ω. The implicit midpoint turn has no secular drift; its error stays of order
  // (|ω| dt)² = 3.5e-4 (measured in double: 4e-6). Rounding adds twice the momentum's relative
  // drift. An explicit turn (ω of the step's start) gains energy every step, 1.9e-2 here.
  const double turn = desc.angular_velocity.norm() / 60.0;
  EXPECT_LT(worst_energy, (2.0 * momentum_tolerance + turn * turn) * energy_before);
}

// 6. Input checks and the stopped world.

TEST(World, AddBodyRejectsBadInput) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  World world(paper_settings());
  const BodyDesc good = solid_ball(0.5f, 1000.0f, Vec3(0.0f, 1.0f, 0.0f));
  const auto rejects = [&](const BodyDesc& desc) {
    EXPECT_THROW((void)world.add_body(desc), Error);
  };
  BodyDesc bad = good;
  bad.tree = nullptr;
  rejects(bad);
  bad = good;
  bad.pose.translation.x() = nan;
  rejects(bad);
  bad = good;
  bad.pose.translation.z() = inf;
  rejects(bad);
  bad = good;
  bad.pose.rotation = Quat(2.0f, 0.0f, 0.0f, 0.0f);
  rejects(bad);
  bad = good;
  bad.pose.rotation = Quat(1.01f, 0.0f, 0.0f, 0.0f);  // 1 % off: more than rounding
  rejects(bad);
  bad = good;
  bad.pose.rotation = Quat(nan, 0.0f, 0.0f, 0.0f);
  rejects(bad);
  bad = good;
  bad.linear_velocity.y() = nan;
  rejects(bad);
  bad = good;
  bad.angular_velocity.x() = inf;
  rejects(bad);
  for (const float mass : {0.0f, -1.0f, nan, inf}) {
    bad = good;
    bad.mass = mass;
    rejects(bad);
  }
  bad = good;
  bad.inertia(0, 1) = 0.5f;  // not symmetric
  rejects(bad);
  bad = good;
  bad.inertia = Vec3(1.0f, 1.0f, -1.0f).asDiagonal();
  rejects(bad);
  bad = good;
  bad.inertia = Vec3(1.0f, 1.0f, 0.0f).asDiagonal();
  rejects(bad);
  bad = good;
  // Symmetric with a positive diagonal yet eigenvalues 3, −1 and 1.
  bad.inertia << 1.0f, 2.0f, 0.0f, 2.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f;
  rejects(bad);
  bad = good;
  bad.inertia(2, 2) = nan;
  rejects(bad);
  for (const float restitution : {-0.1f, 1.1f, nan}) {
    bad = good;
    bad.restitution = restitution;
    rejects(bad);
  }
  for (const float friction : {-0.1f, nan, inf}) {
    bad = good;
    bad.friction = friction;
    rejects(bad);
  }
  EXPECT_EQ(world.body_slots(), 0u);  // nothing half-added

  // What is fine: a static body's mass is ignored; a rotation a rounding away from unit length is
  // normalised.
  BodyDesc fine = good;
  fine.is_static = true;
  fine.mass = 0.0f;
  const BodyId fixed = world.add_body(fine);
  EXPECT_TRUE(world.body(fixed).is_static);
  fine = good;
  fine.pose.rotation = Quat(1.0f + 1e-4f, 0.0f, 0.0f, 0.0f);
  const BodyId moving = world.add_body(fine);
  EXPECT_NEAR(world.body(moving).pose.rotation.norm(), 1.0f, 2.0f * kFloatEpsilon);
}

TEST(World, SettingsAreChecked) {
  WorldSettings settings = paper_settings();
  settings.gravity.y() = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(World{settings}, Error);
  settings = WorldSettings{};
  settings.ground_restitution = 1.5f;
  EXPECT_THROW(World{settings}, Error);
  settings = WorldSettings{};
  settings.paper_passes = 0;
  EXPECT_THROW(World{settings}, Error);
}

TEST(World, StepRejectsATimeStepThatIsNotPositiveAndFinite) {
  World world(paper_settings());
  const BodyId ball = world.add_body(solid_ball(0.5f, 1000.0f, Vec3(0.0f, 1.0f, 0.0f)));
  for (const float dt : {0.0f, -0.01f, std::numeric_limits<float>::quiet_NaN(),
                         std::numeric_limits<float>::infinity()}) {
    EXPECT_THROW(world.step(dt), Error) << dt;
  }
  EXPECT_EQ(world.body(ball).pose.translation, Vec3(0.0f, 1.0f, 0.0f));
  EXPECT_EQ(world.body(ball).linear_velocity, Vec3::Zero());
  EXPECT_FALSE(world.stopped());
}

TEST(World, ContactsAreFoundAtThePosesTheStepStartsFrom) {
  // The step detects at the current poses and moves afterwards: a ball 1 mm above the ground,
  // falling at 1 m/s, gets no impulse in the step that carries it 16 mm into the ground, and
  // bounces in the next one.
  WorldSettings settings = paper_settings();
  settings.gravity = Vec3::Zero();
  settings.collision.ground_plane_height = 0.0f;
  settings.ground_restitution = 1.0f;
  World world(settings);
  BodyDesc desc = solid_ball(0.5f, 1000.0f, Vec3(0.0f, 0.501f, 0.0f));
  desc.linear_velocity = Vec3(0.0f, -1.0f, 0.0f);
  const BodyId ball = world.add_body(desc);
  EXPECT_EQ(world.step(1.0f / 60.0f).impulses, 0u);
  EXPECT_LT(world.body(ball).pose.translation.y(), 0.5f);
  EXPECT_EQ(world.step(1.0f / 60.0f).impulses, 1u);
  EXPECT_FLOAT_EQ(world.body(ball).linear_velocity.y(), 1.0f);
  EXPECT_GT(world.stats().deepest_penetration, 0.015f);
}

TEST(World, MorePassesCarryAnImpulseThroughARow) {
  // Three equal touching balls, ε = 1, the first moving at 1 m/s into the others. Whatever order
  // the detector lists the two contacts in, passes repeated until none approaches hand the
  // velocity on to the last ball: (0, 0, 1) m/s, as in Newton's cradle, in two impulses.
  WorldSettings settings = zero_gravity();
  settings.paper_passes = 4;
  World world(settings);
  std::vector<BodyId> balls;
  for (int i = 0; i < 3; ++i) {
    BodyDesc desc = test::ball_body(0.5f, 2.0f, Vec3(static_cast<float>(i), 0.0f, 0.0f));
    desc.restitution = 1.0f;
    if (i == 0) desc.linear_velocity = Vec3(1.0f, 0.0f, 0.0f);
    balls.push_back(world.add_body(desc));
  }
  const StepStats& stats = world.step(1.0f / 60.0f);
  EXPECT_EQ(stats.contacts, 2u);
  EXPECT_EQ(stats.impulses, 2u);
  EXPECT_GE(stats.response_passes, 2u);
  EXPECT_LE(stats.response_passes, 3u);
  // Two impulses of about eight float operations each on speeds of 1 m/s.
  const float tolerance = 16.0f * kFloatEpsilon;
  EXPECT_NEAR(world.body(balls[0]).linear_velocity.x(), 0.0f, tolerance);
  EXPECT_NEAR(world.body(balls[1]).linear_velocity.x(), 0.0f, tolerance);
  EXPECT_NEAR(world.body(balls[2]).linear_velocity.x(), 1.0f, tolerance);
}

TEST(World, StaticBodyIsUnmovedByGravityAndImpacts) {
  WorldSettings settings = paper_settings();
  settings.collision.ground_plane_height = 0.0f;
  World world(settings);
  BodyDesc slab = solid_ball(1.0f, 1000.0f, Vec3(0.0f, 0.5f, 0.0f));  // sunk into the ground
  slab.is_static = true;
  slab.pose.rotation = Quat(Eigen::AngleAxisf(0.3f, Vec3::UnitZ()));
  const BodyId fixed = world.add_body(slab);
  BodyDesc falling = solid_ball(0.25f, 1000.0f, Vec3(0.1f, 2.5f, 0.0f));
  falling.restitution = 0.5f;
  const BodyId ball = world.add_body(falling);
  std::uint32_t impulses = 0;
  for (int step = 0; step < 120; ++step) impulses += world.step(1.0f / 60.0f).impulses;
  EXPECT_GT(impulses, 0u);  // the ball did hit it
  EXPECT_GT(world.body(ball).linear_velocity.norm(), 0.0f);
  const RigidBody& body = world.body(fixed);
  EXPECT_EQ(body.pose.translation, slab.pose.translation);
  EXPECT_EQ(body.pose.rotation.coeffs(), slab.pose.rotation.normalized().coeffs());
  EXPECT_EQ(body.linear_velocity, Vec3::Zero());
  EXPECT_EQ(body.angular_velocity, Vec3::Zero());
}

TEST(World, GravityThatWouldOverflowIsRefusedBeforeAnyStep) {
  // g dt = 1e38 · 100 would overflow float in the first step; the world refuses it at once.
  // (NonFiniteBodyStopsTheWorldAndLaterStepsDoNothing overflows a body through its velocity.)
  WorldSettings settings = paper_settings();
  settings.gravity = Vec3(0.0f, -1e38f, 0.0f);
  try {
    World world(settings);
    ADD_FAILURE() << "accepted";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), ::testing::StartsWith("gravity must be between -1000 and 1000"));
  }
}

TEST(World, NonFiniteBodyStopsTheWorldAndLaterStepsDoNothing) {
  World world(zero_gravity());
  BodyDesc first = solid_ball(0.5f, 1000.0f, Vec3(0.0f, 0.0f, 0.0f));
  first.linear_velocity = Vec3(1.0f, 0.0f, 0.0f);
  const BodyId steady = world.add_body(first);
  BodyDesc fixed = solid_ball(0.5f, 1000.0f, Vec3(0.0f, -10.0f, 0.0f));
  fixed.is_static = true;
  world.add_body(fixed);
  const BodyId runaway = world.add_body(solid_ball(0.5f, 1000.0f, Vec3(0.0f, 10.0f, 0.0f)));
  world.step(1.0f);
  EXPECT_FALSE(world.stats().non_finite_body.has_value());
  // A finite speed that carries the body past the largest float within one step.
  world.set_velocity(runaway, Vec3(3e38f, 0.0f, 0.0f), Vec3::Zero());
  const StepStats& stats = world.step(10.0f);
  ASSERT_TRUE(stats.non_finite_body.has_value());
  EXPECT_EQ(*stats.non_finite_body, runaway.index);
  EXPECT_TRUE(world.stopped());
  EXPECT_EQ(world.body(steady).pose.translation, Vec3(11.0f, 0.0f, 0.0f));

  for (int step = 0; step < 3; ++step) {
    const StepStats& later = world.step(1.0f);
    ASSERT_TRUE(later.non_finite_body.has_value());
    EXPECT_EQ(*later.non_finite_body, runaway.index);
  }
  EXPECT_EQ(world.body(steady).pose.translation, Vec3(11.0f, 0.0f, 0.0f));
  EXPECT_EQ(world.body(steady).linear_velocity, Vec3(1.0f, 0.0f, 0.0f));
}

}  // namespace
}  // namespace sphys
