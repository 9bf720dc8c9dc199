#include "sphys/world.h"

#include <chrono>
#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>

#include "dynamics/paper_response.h"
#include "sphys/error.h"

namespace sphys {
namespace {

using Clock = std::chrono::steady_clock;

double elapsed_ms(Clock::time_point since) {
  return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

// Relative tolerance of the inertia's symmetry: the tensor comes from float or double sums.
constexpr float kInertiaSymmetryTolerance = 1e-4f;
// How far a given rotation may be from unit length before it is refused rather than normalised.
constexpr float kUnitQuaternionTolerance = 1e-3f;

void check_body(const BodyDesc& desc) {
  if (!desc.tree || desc.tree->empty()) throw Error("a body needs a non-empty sphere-tree");
  if (!desc.pose.translation.allFinite()) throw Error("a body's position must be finite");
  if (!desc.pose.rotation.coeffs().allFinite() ||
      std::abs(desc.pose.rotation.norm() - 1.0f) > kUnitQuaternionTolerance) {
    throw Error("a body's orientation must be a unit quaternion");
  }
  if (!desc.linear_velocity.allFinite() || !desc.angular_velocity.allFinite()) {
    throw Error("a body's velocities must be finite");
  }
  if (!(desc.restitution >= 0.0f && desc.restitution <= 1.0f)) {
    throw Error("restitution must be between 0 and 1, got " + std::to_string(desc.restitution));
  }
  if (!(desc.friction >= 0.0f) || !std::isfinite(desc.friction)) {
    throw Error("friction must be finite and not negative, got " + std::to_string(desc.friction));
  }
  if (desc.is_static) return;
  if (!(desc.mass > 0.0f) || !std::isfinite(desc.mass)) {
    throw Error("a moving body's mass must be positive and finite, got " +
                std::to_string(desc.mass));
  }
  const Mat3& inertia = desc.inertia;
  if (!inertia.allFinite() || (inertia - inertia.transpose()).cwiseAbs().maxCoeff() >
                                  kInertiaSymmetryTolerance * inertia.cwiseAbs().maxCoeff()) {
    throw Error("a body's inertia tensor must be finite and symmetric");
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(inertia);
  if (!(eigen.eigenvalues().minCoeff() > 0.0f)) {
    throw Error("a body's inertia tensor must be positive definite");
  }
}

}  // namespace

World::World(const WorldSettings& settings) : settings_(settings), detector_(settings.collision) {
  if (!settings.gravity.allFinite()) throw Error("gravity must be finite");
  if (settings.paper_passes < 1) throw Error("paper_passes must be at least 1");
  if (!(settings.ground_restitution >= 0.0f && settings.ground_restitution <= 1.0f)) {
    throw Error("the ground's restitution must be between 0 and 1");
  }
}

BodyId World::add_body(const BodyDesc& desc) {
  check_body(desc);
  Transform pose = desc.pose;
  pose.rotation.normalize();
  const BodyId id = detector_.add_body(desc.tree, pose, desc.is_static);
  if (bodies_.size() <= id.index) {
    bodies_.resize(id.index + 1);
    alive_.resize(id.index + 1, 0);
  }
  RigidBody& body = bodies_[id.index];
  body = RigidBody{};
  body.pose = pose;
  body.restitution = desc.restitution;
  body.friction = desc.friction;
  body.is_static = desc.is_static;
  if (!desc.is_static) {
    body.linear_velocity = desc.linear_velocity;
    body.angular_velocity = desc.angular_velocity;
    body.inverse_mass = 1.0f / desc.mass;
    // Symmetrised so that rounding in the caller's tensor cannot make the inverse lopsided.
    body.inertia_body = 0.5f * (desc.inertia + desc.inertia.transpose());
    body.inverse_inertia_body = body.inertia_body.inverse();
  }
  alive_[id.index] = 1;
  return id;
}

void World::remove_body(BodyId id) {
  detector_.remove_body(id);
  bodies_[id.index] = RigidBody{};
  bodies_[id.index].is_static = true;  // an empty slot neither moves nor counts
  alive_[id.index] = 0;
}

void World::set_velocity(BodyId id, const Vec3& linear, const Vec3& angular) {
  if (!linear.allFinite() || !angular.allFinite()) {
    throw Error("a body's velocities must be finite");
  }
  RigidBody& body = bodies_[id.index];
  if (body.is_static) return;
  body.linear_velocity = linear;
  body.angular_velocity = angular;
}

const StepStats& World::step(float dt) {
  if (!(dt > 0.0f) || !std::isfinite(dt)) {
    throw Error("the time step must be positive and finite, got " + std::to_string(dt));
  }
  if (stopped_) return stats_;
  const Clock::time_point step_start = Clock::now();
  StepStats stats;

  const Clock::time_point velocities_start = Clock::now();
  for (RigidBody& body : bodies_) integrate_velocity(body, settings_.gravity, dt);
  stats.integration_ms = elapsed_ms(velocities_start);

  const CollisionStats& detection = detector_.detect(contacts_);
  stats.broad_phase_ms = detection.broad_phase_ms;
  stats.narrow_phase_ms = detection.narrow_phase_ms;
  stats.contacts_ms = detection.contacts_ms;
  stats.bodies = detection.bodies;
  stats.candidate_pairs = detection.candidate_pairs;
  stats.sphere_tests = detection.sphere_tests;
  stats.leaf_pairs = detection.leaf_pairs;
  stats.contacts = detection.contacts;
  stats.pairs_cut_short = detection.pairs_cut_short;
  stats.coincident_centres = detection.coincident_centres;

  const Clock::time_point response_start = Clock::now();
  switch (settings_.response) {
    case ResponseMode::kPaper: {
      const PaperResponseStats response = apply_paper_response(
          bodies_, contacts_, settings_.ground_restitution, settings_.paper_passes);
      stats.impulses = response.impulses;
      stats.response_passes = response.passes;
      break;
    }
  }
  stats.response_ms = elapsed_ms(response_start);

  const Clock::time_point positions_start = Clock::now();
  for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
    RigidBody& body = bodies_[i];
    if (body.is_static) continue;
    integrate_position(body, dt);
    detector_.set_pose({i}, body.pose);
  }
  stats.integration_ms += elapsed_ms(positions_start);

  for (const Contact& contact : contacts_) {
    stats.deepest_penetration = std::max(stats.deepest_penetration, contact.depth);
  }
  for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
    const RigidBody& body = bodies_[i];
    if (body.is_static) continue;
    // A quaternion with huge coefficients normalises to zero (its norm overflows), finite but no
    // rotation: that is the same failure.
    if (!body.finite() ||
        !(std::abs(body.pose.rotation.squaredNorm() - 1.0f) < kUnitQuaternionTolerance)) {
      stats.non_finite_body = i;
      stopped_ = true;
      break;
    }
    stats.kinetic_energy += body.kinetic_energy();
  }
  stats.step_ms = elapsed_ms(step_start);
  stats_ = stats;
  return stats_;
}

}  // namespace sphys
