#include "dynamics/paper_response.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <span>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "support/float_limits.h"
#include "support/vec_near.h"

namespace sphys {
namespace {

using test::kFloatEpsilon;

// The values checked below come from about ten float operations each on speeds up to 4 m/s; with
// a whole ε per operation (twice the worst rounding) and another factor 1.6 they are within
// 16 ε · 4 m/s = 7.6e-6 m/s of the hand computation. A wrong lever arm or inertia moves them by
// 0.1 or more.
constexpr float kHandTolerance = 16.0f * kFloatEpsilon * 4.0f;

// A solid box of full sides 2 × 0.5 × 1 m and mass 12 kg: I = m/12 (b² + c², a² + c², a² + b²)
// = (1.25, 5, 4.25) kg·m².
RigidBody flat_box(const Vec3& position, const Quat& rotation = Quat::Identity()) {
  RigidBody body;
  body.pose.translation = position;
  body.pose.rotation = rotation;
  body.inverse_mass = 1.0f / 12.0f;
  body.inertia_body = Vec3(1.25f, 5.0f, 4.25f).asDiagonal();
  body.inverse_inertia_body = body.inertia_body.inverse();
  return body;
}

RigidBody ball(const Vec3& position, float mass, float restitution) {
  RigidBody body;
  body.pose.translation = position;
  body.inverse_mass = 1.0f / mass;
  body.inertia_body = Mat3::Identity() * (0.4f * mass * 0.25f);  // radius 0.5 m
  body.inverse_inertia_body = body.inertia_body.inverse();
  body.restitution = restitution;
  return body;
}

// The paper's response to the bodies, put in a body store in their order, with the velocities
// it leaves copied back.
PaperResponseStats respond(std::span<RigidBody> bodies, std::span<const Contact> contacts,
                           float ground_restitution, std::uint32_t max_passes) {
  BodyStore store;
  for (const RigidBody& body : bodies) store.add(body, 0.0f);
  const PaperResponseStats stats =
      apply_paper_response(store, contacts, ground_restitution, max_passes);
  for (std::uint32_t i = 0; i < bodies.size(); ++i) {
    bodies[i].linear_velocity = store.linear_velocities()[i];
    bodies[i].angular_velocity = store.angular_velocities()[i];
  }
  return stats;
}

// One Gauss–Seidel pass, the paper's response; returns the impulses applied.
std::uint32_t one_pass(std::span<RigidBody> bodies, std::span<const Contact> contacts,
                       float ground_restitution) {
  const PaperResponseStats stats = respond(bodies, contacts, ground_restitution, 1);
  EXPECT_EQ(stats.passes, 1u);
  return stats.impulses;
}

Contact ground_contact(std::uint32_t body, const Vec3& point) {
  Contact contact;
  contact.body_a = kGroundPlaneBody;
  contact.body_b = body;
  contact.point = point;
  contact.normal = Vec3::UnitY();
  return contact;
}

Contact body_contact(std::uint32_t a, std::uint32_t b, const Vec3& point, const Vec3& normal) {
  Contact contact;
  contact.body_a = a;
  contact.body_b = b;
  contact.point = point;
  contact.normal = normal;
  return contact;
}

// The box falls at 2 m/s onto the ground on its bottom edge at body x = +1 m, r = (1, −0.25, 0):
//   r × n = (0, 0, 1), I⁻¹ (r × n) = (0, 0, 4/17), n · ((I⁻¹ (r × n)) × r) = 4/17,
//   denominator = 1/12 + 4/17 = 65/204, j = (1 + 0.5) · 2 / (65/204) = 612/65 N·s,
//   Δv = j/m n = (0, 51/65, 0) m/s, Δω = j I⁻¹ (r × n) = (0, 0, 144/65) rad/s.
// The contact point then leaves at −2 + 51/65 + 144/65 = +1 m/s = −ε v_c.
TEST(PaperResponse, OffCentreContactOnABoxMatchesTheHandComputedImpulse) {
  std::vector<RigidBody> bodies{flat_box(Vec3(3.0f, 0.25f, -1.0f))};
  bodies[0].linear_velocity = Vec3(0.5f, -2.0f, 0.0f);  // the sliding part takes no impulse
  bodies[0].restitution = 0.2f;                         // the ground's 0.5 is larger and wins
  const std::array contacts{ground_contact(0, Vec3(4.0f, 0.0f, -1.0f))};
  EXPECT_EQ(one_pass(bodies, contacts, 0.5f), 1u);
  expect_vec_near(bodies[0].linear_velocity, Vec3(0.5f, -2.0f + 51.0f / 65.0f, 0.0f),
                  kHandTolerance);
  expect_vec_near(bodies[0].angular_velocity, Vec3(0.0f, 0.0f, 144.0f / 65.0f), kHandTolerance);
  EXPECT_NEAR(bodies[0].velocity_at(contacts[0].point).y(), 1.0f, kHandTolerance);
  EXPECT_EQ(bodies[0].pose.translation, Vec3(3.0f, 0.25f, -1.0f));  // response moves nothing
}

TEST(PaperResponse, TurnedBoxUsesItsWorldInertia) {
  // The same box and contact turned a quarter about y (body z is world x): the impulse is the
  // same, the spin is the body's (0, 0, 144/65) turned, (144/65, 0, 0). Using the body-frame
  // inverse inertia unturned would give 1/1.25 instead of 1/4.25 about world x.
  const Quat quarter(Eigen::AngleAxisf(std::numbers::pi_v<float> / 2, Vec3::UnitY()));
  std::vector<RigidBody> bodies{flat_box(Vec3(3.0f, 0.25f, -1.0f), quarter)};
  bodies[0].linear_velocity = Vec3(0.0f, -2.0f, 0.0f);
  const Vec3 point = bodies[0].pose.apply(Vec3(1.0f, -0.25f, 0.0f));
  const std::array contacts{ground_contact(0, point)};
  EXPECT_EQ(one_pass(bodies, contacts, 0.5f), 1u);
  expect_vec_near(bodies[0].linear_velocity, Vec3(0.0f, -2.0f + 51.0f / 65.0f, 0.0f),
                  kHandTolerance);
  expect_vec_near(bodies[0].angular_velocity, Vec3(144.0f / 65.0f, 0.0f, 0.0f), kHandTolerance);
}

TEST(PaperResponse, CentralContactBetweenTwoBodiesFollowsTheOneDimensionalFormula) {
  // Masses 1 and 3 kg, ε = max(0.5, 0.25) = 0.5, approaching at 4 m/s along x:
  //   j = (1 + 0.5) · 4 / (1 + 1/3) = 4.5 N·s, a: 3 − 4.5 = −1.5 m/s, b: −1 + 1.5 = 0.5 m/s.
  // The contact point is on the line of centres: no spin.
  std::vector<RigidBody> bodies{ball(Vec3(0.0f, 0.0f, 0.0f), 1.0f, 0.5f),
                                ball(Vec3(0.9f, 0.0f, 0.0f), 3.0f, 0.25f)};
  bodies[0].linear_velocity = Vec3(3.0f, 0.0f, 0.0f);
  bodies[1].linear_velocity = Vec3(-1.0f, 0.0f, 0.0f);
  const std::array contacts{body_contact(0, 1, Vec3(0.45f, 0.0f, 0.0f), Vec3::UnitX())};
  EXPECT_EQ(one_pass(bodies, contacts, 0.0f), 1u);
  expect_vec_near(bodies[0].linear_velocity, Vec3(-1.5f, 0.0f, 0.0f), kHandTolerance);
  expect_vec_near(bodies[1].linear_velocity, Vec3(0.5f, 0.0f, 0.0f), kHandTolerance);
  EXPECT_EQ(bodies[0].angular_velocity, Vec3::Zero());
  EXPECT_EQ(bodies[1].angular_velocity, Vec3::Zero());
}

TEST(PaperResponse, SeparatingAndRestingContactsGetNoImpulse) {
  std::vector<RigidBody> bodies{ball(Vec3(0.0f, 0.5f, 0.0f), 2.0f, 1.0f),
                                ball(Vec3(0.9f, 0.5f, 0.0f), 2.0f, 1.0f)};
  bodies[0].linear_velocity = Vec3(-1.0f, 0.3f, 0.0f);  // leaving the ground and body 1
  bodies[1].linear_velocity = Vec3(0.0f, 0.0f, 2.0f);   // sliding past body 0: v_c = 0
  const std::vector<RigidBody> before = bodies;
  const std::array contacts{
      ground_contact(0, Vec3(0.0f, 0.0f, 0.0f)),
      body_contact(0, 1, Vec3(0.45f, 0.5f, 0.0f), Vec3::UnitX()),
      ground_contact(1, Vec3(0.9f, 0.0f, 0.0f)),  // resting on the ground: v_c = 0
  };
  EXPECT_EQ(one_pass(bodies, contacts, 1.0f), 0u);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    EXPECT_EQ(bodies[i].linear_velocity, before[i].linear_velocity);
    EXPECT_EQ(bodies[i].angular_velocity, before[i].angular_velocity);
  }
}

TEST(PaperResponse, StaticBodiesAreUnmovedOnEitherSideOfAContact) {
  // A static body has infinite mass: the moving one bounces off as off the ground, v' = −ε v.
  const auto static_box = [](const Vec3& position) {
    RigidBody body = flat_box(position);
    body.is_static = true;
    body.inverse_mass = 0.0f;
    body.inverse_inertia_body = Mat3::Zero();
    return body;
  };
  for (const bool static_first : {true, false}) {
    RigidBody mover = ball(Vec3(1.5f, 0.0f, 0.0f), 2.0f, 0.75f);
    mover.linear_velocity = Vec3(-4.0f, 0.0f, 0.0f);
    const RigidBody wall = static_box(Vec3(0.0f, 0.0f, 0.0f));
    std::vector<RigidBody> bodies =
        static_first ? std::vector{wall, mover} : std::vector{mover, wall};
    bodies.push_back(static_box(Vec3(0.0f, -0.5f, 0.0f)));
    const std::uint32_t wall_index = static_first ? 0 : 1;
    const std::uint32_t mover_index = 1 - wall_index;
    // The normal points from body a to body b.
    const Vec3 normal = static_first ? Vec3::UnitX() : Vec3(-Vec3::UnitX());
    const std::array contacts{
        body_contact(0, 1, Vec3(1.0f, 0.0f, 0.0f), normal),
        // Two static bodies touching: neither moves.
        body_contact(2, wall_index, Vec3(0.0f, -0.25f, 0.0f), Vec3::UnitY()),
    };
    EXPECT_EQ(one_pass(bodies, contacts, 0.0f), 1u);
    for (const std::uint32_t fixed : {wall_index, 2u}) {
      EXPECT_EQ(bodies[fixed].linear_velocity, Vec3::Zero());
      EXPECT_EQ(bodies[fixed].angular_velocity, Vec3::Zero());
    }
    expect_vec_near(bodies[mover_index].linear_velocity, Vec3(3.0f, 0.0f, 0.0f), kHandTolerance);
    EXPECT_EQ(bodies[mover_index].angular_velocity, Vec3::Zero());
  }
}

// Three equal balls in a row, ε = 1, the first rolling at 1 m/s into the other two at rest;
// returns the impulses, the passes and the three velocities along x after the response.
struct CradleResult {
  PaperResponseStats stats;
  Vec3 velocities = Vec3::Zero();
};

CradleResult cradle(bool front_first, std::uint32_t max_passes) {
  std::vector<RigidBody> bodies{ball(Vec3(0.0f, 0.0f, 0.0f), 2.0f, 1.0f),
                                ball(Vec3(1.0f, 0.0f, 0.0f), 2.0f, 1.0f),
                                ball(Vec3(2.0f, 0.0f, 0.0f), 2.0f, 1.0f)};
  bodies[0].linear_velocity = Vec3(1.0f, 0.0f, 0.0f);
  const Contact front = body_contact(0, 1, Vec3(0.5f, 0.0f, 0.0f), Vec3::UnitX());
  const Contact back = body_contact(1, 2, Vec3(1.5f, 0.0f, 0.0f), Vec3::UnitX());
  const std::array contacts = front_first ? std::array{front, back} : std::array{back, front};
  CradleResult result;
  result.stats = respond(bodies, contacts, 0.0f, max_passes);
  result.velocities = Vec3(bodies[0].linear_velocity.x(), bodies[1].linear_velocity.x(),
                           bodies[2].linear_velocity.x());
  return result;
}

TEST(PaperResponse, ContactsAreResolvedOneAfterAnotherInTheirOrder) {
  // In the order (0, 1), (1, 2) each impulse hands the velocity on, as in Newton's cradle:
  // (0, 0, v) in one pass, and a second pass finds nothing left to do.
  const CradleResult front = cradle(true, 1);
  EXPECT_EQ(front.stats.impulses, 2u);
  expect_vec_near(front.velocities, Vec3(0.0f, 0.0f, 1.0f), kHandTolerance);
  const CradleResult front_again = cradle(true, 8);
  EXPECT_EQ(front_again.stats.impulses, 2u);
  EXPECT_EQ(front_again.stats.passes, 2u);
  // In the order (1, 2), (0, 1) the first contact is not yet approaching when its turn comes:
  // one pass leaves (0, v, 0) with ball 1 driving into ball 2.
  const CradleResult back = cradle(false, 1);
  EXPECT_EQ(back.stats.impulses, 1u);
  EXPECT_EQ(back.stats.passes, 1u);
  expect_vec_near(back.velocities, Vec3(0.0f, 1.0f, 0.0f), kHandTolerance);
  // A second pass resolves it, and a third finds nothing approaching and ends the response.
  const CradleResult back_again = cradle(false, 8);
  EXPECT_EQ(back_again.stats.impulses, 2u);
  EXPECT_EQ(back_again.stats.passes, 3u);
  expect_vec_near(back_again.velocities, Vec3(0.0f, 0.0f, 1.0f), kHandTolerance);
}

TEST(PaperResponse, RepeatedContactIsAnsweredOnce) {
  // The same contact listed twice (two leaf spheres meeting the ground at one point): the second
  // sees the bounce of the first and is separating.
  std::vector<RigidBody> bodies{ball(Vec3(0.0f, 0.5f, 0.0f), 2.0f, 0.5f)};
  bodies[0].linear_velocity = Vec3(0.0f, -2.0f, 0.0f);
  const Contact contact = ground_contact(0, Vec3(0.0f, 0.0f, 0.0f));
  const std::array contacts{contact, contact};
  EXPECT_EQ(one_pass(bodies, contacts, 0.0f), 1u);
  expect_vec_near(bodies[0].linear_velocity, Vec3(0.0f, 1.0f, 0.0f), kHandTolerance);
}

TEST(PaperResponse, MixedRestitutionIsTheLarger) {
  EXPECT_EQ(mix_restitution(0.2f, 0.7f), 0.7f);
  EXPECT_EQ(mix_restitution(0.7f, 0.2f), 0.7f);
  EXPECT_EQ(mix_restitution(0.0f, 0.0f), 0.0f);
  EXPECT_EQ(mix_restitution(1.0f, 0.3f), 1.0f);
}

// Values are drawn one statement at a time: the order of a call's arguments is unspecified, and
// the same seed must give the same cases on every compiler.
Vec3 random_vector(std::mt19937& rng, float low, float high) {
  std::uniform_real_distribution<float> u(low, high);
  const float x = u(rng);
  const float y = u(rng);
  const float z = u(rng);
  return Vec3(x, y, z);
}

Vec3 random_vector(std::mt19937& rng, float scale) { return random_vector(rng, -scale, scale); }

// A normalised Gaussian 4-vector: uniform over rotations.
Quat random_rotation(std::mt19937& rng) {
  std::normal_distribution<float> normal;
  const float w = normal(rng);
  const float x = normal(rng);
  const float y = normal(rng);
  const float z = normal(rng);
  return Quat(w, x, y, z).normalized();
}

// A moving body with a random symmetric positive definite inertia about random axes.
RigidBody random_body(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.5f, 5.0f);
  RigidBody body;
  body.pose.translation = random_vector(rng, 3.0f);
  body.pose.rotation = random_rotation(rng);
  body.inverse_mass = 1.0f / u(rng);
  const Mat3 axes = random_rotation(rng).toRotationMatrix();
  body.inertia_body = axes * random_vector(rng, 0.5f, 5.0f).asDiagonal() * axes.transpose();
  body.inertia_body = 0.5f * (body.inertia_body + body.inertia_body.transpose());
  body.inverse_inertia_body = body.inertia_body.inverse();
  body.linear_velocity = random_vector(rng, 3.0f);
  body.angular_velocity = random_vector(rng, 3.0f);
  body.restitution = std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
  return body;
}

// Linear momentum, angular momentum about the origin and kinetic energy in double, with the
// mass taken as the exact reciprocal of the stored inverse so the check adds no rounding.
struct Totals {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
  double energy = 0.0;
};

Totals totals(std::span<const RigidBody> bodies) {
  Totals sum;
  for (const RigidBody& body : bodies) {
    const double mass = 1.0 / static_cast<double>(body.inverse_mass);
    const Eigen::Matrix3d rotation = body.pose.rotation.toRotationMatrix().cast<double>();
    const Eigen::Vector3d momentum = mass * body.linear_velocity.cast<double>();
    sum.linear += momentum;
    sum.angular += body.pose.translation.cast<double>().cross(momentum) +
                   rotation * body.inertia_body.cast<double>() * rotation.transpose() *
                       body.angular_velocity.cast<double>();
    sum.energy += body.kinetic_energy();
  }
  return sum;
}

TEST(PaperResponse, RandomContactsObeyTheImpulseLaws) {
  // For any approaching contact eq. 4 makes the contact points leave at −ε times the approach
  // speed, conserves linear momentum and angular momentum about any point (±J at one point), and
  // loses (1 − ε²) v_c² / (2 K) of kinetic energy, K being eq. 4's denominator. Tolerance: the
  // impulse passes through about 30 float operations on values up to a few times the largest
  // momentum; 64 ε of that scale (about 1e-5 relative) bounds the rounding, while an error in
  // any term of eq. 4 shifts these by per cent.
  std::mt19937 rng(2008);
  int approaching = 0;
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<RigidBody> bodies{random_body(rng), random_body(rng)};
    const Vec3 normal = random_vector(rng, 1.0f).normalized();
    const Vec3 point =
        0.5f * (bodies[0].pose.translation + bodies[1].pose.translation) + random_vector(rng, 0.5f);
    const std::array contacts{body_contact(0, 1, point, normal)};
    const float approach = normal.dot(bodies[1].velocity_at(point) - bodies[0].velocity_at(point));
    const float epsilon = mix_restitution(bodies[0].restitution, bodies[1].restitution);
    const Totals before = totals(bodies);
    const std::uint32_t impulses = one_pass(bodies, contacts, 0.0f);
    const Totals after = totals(bodies);
    if (!(approach < 0.0f)) {
      EXPECT_EQ(impulses, 0u);
      continue;
    }
    ++approaching;
    ASSERT_EQ(impulses, 1u);

    const Vec3 ra = point - bodies[0].pose.translation;
    const Vec3 rb = point - bodies[1].pose.translation;
    const auto inverse_effective_mass = [&](const RigidBody& body, const Vec3& r) {
      return static_cast<double>(body.inverse_mass) +
             normal.cast<double>().dot((body.inverse_inertia_world().cast<double>() *
                                        r.cast<double>().cross(normal.cast<double>()))
                                           .cross(r.cast<double>()));
    };
    const double denominator =
        inverse_effective_mass(bodies[0], ra) + inverse_effective_mass(bodies[1], rb);
    const double speed = std::abs(approach);
    const double momentum_scale =
        (before.linear.norm() + speed / denominator) * (1.0 + point.norm()) + before.angular.norm();
    const double tolerance = 64.0 * kFloatEpsilon;

    const float leave = normal.dot(bodies[1].velocity_at(point) - bodies[0].velocity_at(point));
    const double speed_scale = speed + bodies[0].linear_velocity.norm() +
                               bodies[1].linear_velocity.norm() +
                               (bodies[0].angular_velocity.norm() * ra.norm()) +
                               (bodies[1].angular_velocity.norm() * rb.norm());
    EXPECT_NEAR(leave, -epsilon * approach, tolerance * speed_scale) << "trial " << trial;
    EXPECT_LT((after.linear - before.linear).norm(), tolerance * momentum_scale)
        << "trial " << trial;
    EXPECT_LT((after.angular - before.angular).norm(), tolerance * momentum_scale)
        << "trial " << trial;
    const double loss =
        (1.0 - static_cast<double>(epsilon) * epsilon) * speed * speed / (2.0 * denominator);
    EXPECT_NEAR(before.energy - after.energy, loss, tolerance * before.energy) << "trial " << trial;
  }
  EXPECT_GT(approaching, 100);  // about half the random contacts approach
}

}  // namespace
}  // namespace sphys
