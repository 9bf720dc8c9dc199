#include "sphys/world.h"

#include <chrono>
#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>

#include "collision/contact_reduction.h"
#include "dynamics/contact_solver.h"
#include "dynamics/paper_response.h"
#include "sphys/error.h"
#include "world/sleep_tracker.h"

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
// A body slower than this many times the sleep speed should be resting: its speed is jitter.
constexpr float kSettlingFactor = 10.0f;
// More threads than any machine has is a mistake in the settings, not a wish.
constexpr std::uint32_t kMaxThreads = 1024;

void check_material(float restitution, float friction) {
  if (!(restitution >= 0.0f && restitution <= 1.0f)) {
    throw Error("restitution must be between 0 and 1, got " + std::to_string(restitution));
  }
  if (!(friction >= 0.0f) || !std::isfinite(friction)) {
    throw Error("friction must be finite and not negative, got " + std::to_string(friction));
  }
}

void check_settings(const WorldSettings& settings) {
  if (!settings.gravity.allFinite()) throw Error("gravity must be finite");
  if (settings.paper_passes < 1) throw Error("paper_passes must be at least 1");
  if (!(settings.ground_restitution >= 0.0f && settings.ground_restitution <= 1.0f)) {
    throw Error("the ground's restitution must be between 0 and 1");
  }
  if (!(settings.ground_friction >= 0.0f) || !std::isfinite(settings.ground_friction)) {
    throw Error("the ground's friction must be finite and not negative");
  }
  if (settings.threads > kMaxThreads) {
    throw Error("threads must be at most " + std::to_string(kMaxThreads) + " (0: all), got " +
                std::to_string(settings.threads));
  }
  if (settings.substeps < 1 || settings.substeps > 64) {
    throw Error("substeps must be between 1 and 64, got " + std::to_string(settings.substeps));
  }
  if (settings.max_substeps < 1 || settings.max_substeps > 64) {
    throw Error("max_substeps must be between 1 and 64, got " +
                std::to_string(settings.max_substeps));
  }
  if (!(settings.substep_travel > 0.0f) || !std::isfinite(settings.substep_travel)) {
    throw Error("substep_travel must be positive and finite, got " +
                std::to_string(settings.substep_travel));
  }
  if (!(settings.collision.max_microseconds >= 0.0) ||
      !std::isfinite(settings.collision.max_microseconds)) {
    throw Error("the detection time budget must be finite and not negative, got " +
                std::to_string(settings.collision.max_microseconds) + " µs");
  }
  const SolverSettings& solver = settings.solver;
  if (solver.velocity_iterations < 1) throw Error("velocity_iterations must be at least 1");
  if (solver.manifold_points < 1 || solver.manifold_points > kMaxManifoldPoints) {
    throw Error("manifold_points must be between 1 and " + std::to_string(kMaxManifoldPoints) +
                ", got " + std::to_string(solver.manifold_points));
  }
  const auto non_negative = [](float value, const char* name) {
    if (!(value >= 0.0f) || !std::isfinite(value)) {
      std::string message = name;
      message += " must be finite and not negative, got ";
      message += std::to_string(value);
      throw Error(message);
    }
  };
  non_negative(solver.restitution_threshold, "restitution_threshold");
  non_negative(solver.linear_slop, "linear_slop");
  non_negative(solver.max_correction_speed, "max_correction_speed");
  non_negative(solver.contact_margin, "contact_margin");
  non_negative(solver.shock_speed, "shock_speed");
  non_negative(solver.rolling_resistance, "rolling_resistance");
  non_negative(settings.sleep.speed, "the sleep speed");
  non_negative(settings.sleep.time, "the sleep time");
  if (!(solver.position_correction >= 0.0f && solver.position_correction <= 1.0f)) {
    throw Error("position_correction must be between 0 and 1");
  }
}

// The detector's settings for a response mode: the paper makes contacts from overlaps only.
CollisionSettings collision_settings(const WorldSettings& settings) {
  CollisionSettings collision = settings.collision;
  const bool plausible = settings.response == ResponseMode::kPlausible;
  collision.contact_margin = plausible ? settings.solver.contact_margin : 0.0f;
  collision.speculative = plausible && settings.solver.speculative_contacts;
  return collision;
}

// The farthest point of a tree from its body's origin (the centre of mass). unit: m
float tree_extent(const SphereTree& tree) {
  return tree.root().center.norm() + tree.subtree_radius(0);
}

std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t{a} << 32) | b;
}

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
  check_material(desc.restitution, desc.friction);
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

World::World(const WorldSettings& settings)
    : settings_(settings),
      detector_(collision_settings(settings)),
      reducer_(std::make_unique<ContactReducer>()),
      solver_(std::make_unique<ContactSolver>()),
      sleep_(std::make_unique<SleepTracker>()) {
  check_settings(settings);
  parallel_ = std::make_unique<Parallel>(settings.threads);
  detector_.set_parallel(parallel_.get());
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

BodyId World::add_body(const BodyDesc& desc) {
  check_body(desc);
  Transform pose = desc.pose;
  pose.rotation.normalize();
  const BodyId id = detector_.add_body(desc.tree, pose, desc.is_static);
  if (bodies_.size() <= id.index) {
    bodies_.resize(id.index + 1);
    alive_.resize(id.index + 1, 0);
    extent_.resize(id.index + 1, 0.0f);
    sleep_->resize(id.index + 1);
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
  extent_[id.index] = tree_extent(*desc.tree);
  return id;
}

void World::wake(std::uint32_t index) {
  sleep_changes_.clear();
  sleep_->wake(index, sleep_changes_);
  for (const std::uint32_t body : sleep_changes_) detector_.set_asleep({body}, false);
}

void World::remove_body(BodyId id) {
  wake(id.index);  // the bodies it slept with lose a support
  detector_.remove_body(id);
  bodies_[id.index] = RigidBody{};
  bodies_[id.index].is_static = true;  // an empty slot neither moves nor counts
  alive_[id.index] = 0;
  std::erase_if(pair_materials_, [&](const auto& entry) {
    return static_cast<std::uint32_t>(entry.first >> 32) == id.index ||
           static_cast<std::uint32_t>(entry.first) == id.index;
  });
  solver_->forget();
  reducer_->forget();
}

void World::set_detection_budget(std::uint64_t max_sphere_tests, double max_microseconds) {
  WorldSettings settings = settings_;
  settings.collision.max_sphere_tests = max_sphere_tests;
  settings.collision.max_microseconds = max_microseconds;
  check_settings(settings);
  settings_ = settings;
  detector_.set_settings(collision_settings(settings_));
}

void World::set_velocity(BodyId id, const Vec3& linear, const Vec3& angular) {
  if (!linear.allFinite() || !angular.allFinite()) {
    throw Error("a body's velocities must be finite");
  }
  RigidBody& body = bodies_[id.index];
  if (body.is_static) return;
  body.linear_velocity = linear;
  body.angular_velocity = angular;
  wake(id.index);
}

void World::apply_impulse(BodyId id, const Vec3& impulse, const Vec3& point) {
  if (!impulse.allFinite() || !point.allFinite()) {
    throw Error("an impulse and its point must be finite");
  }
  RigidBody& body = bodies_[id.index];
  if (body.is_static) return;
  body.linear_velocity += body.inverse_mass * impulse;
  body.angular_velocity +=
      body.inverse_inertia_world() * (point - body.pose.translation).cross(impulse);
  wake(id.index);
}

void World::set_pair_material(BodyId a, BodyId b, const PairMaterial& material) {
  check_material(material.restitution, material.friction);
  pair_materials_[pair_key(a.index, b.index)] = material;
}

bool World::asleep(BodyId id) const { return sleep_->asleep(id.index); }

float World::fastest_point_speed(std::uint32_t index) const {
  const RigidBody& body = bodies_[index];
  return body.linear_velocity.norm() + body.angular_velocity.norm() * extent_[index];
}

std::uint32_t World::substeps_for(float dt) const {
  const std::uint32_t fewest = settings_.substeps;
  const std::uint32_t most = std::max(fewest, settings_.max_substeps);
  if (settings_.response != ResponseMode::kPlausible || most == fewest) return fewest;
  // The speed at the end of the step under gravity alone, an upper bound for a falling body.
  const float gravity_speed = settings_.gravity.norm() * dt;
  float needed = 0.0f;  // substeps, fractional
  for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
    if (alive_[i] == 0 || bodies_[i].is_static || sleep_->asleep(i) || !(extent_[i] > 0.0f)) {
      continue;
    }
    const float travel = (fastest_point_speed(i) + gravity_speed) * dt;
    needed = std::max(needed, travel / (settings_.substep_travel * extent_[i]));
  }
  // A non-finite speed is left to the step to find and report.
  if (!(needed <= static_cast<float>(most))) return needed > 0.0f ? most : fewest;
  return std::clamp(static_cast<std::uint32_t>(std::ceil(needed)), fewest, most);
}

const StepStats& World::step(float dt) {
  if (!(dt > 0.0f) || !std::isfinite(dt)) {
    throw Error("the time step must be positive and finite, got " + std::to_string(dt));
  }
  if (stopped_) return stats_;
  const Clock::time_point step_start = Clock::now();
  StepStats stats;
  const std::uint32_t substeps = substeps_for(dt);
  stats.substeps = substeps;
  const float substep_dt = dt / static_cast<float>(substeps);
  for (std::uint32_t i = 0; i < substeps && !stopped_; ++i) substep(substep_dt, stats);
  measure_rest(stats);
  stats.step_ms = elapsed_ms(step_start);
  stats_ = stats;
  return stats_;
}

// Leaf-pair contacts into leaf_contacts_, with the detector's figures and the penetration added
// to the step's.
void World::detect(StepStats& stats) {
  const CollisionStats& detection = detector_.detect(leaf_contacts_);
  stats.broad_phase_ms += detection.broad_phase_ms;
  stats.narrow_phase_ms += detection.narrow_phase_ms;
  stats.contacts_ms += detection.contacts_ms;
  stats.bodies = detection.bodies;
  stats.candidate_pairs += detection.candidate_pairs;
  stats.sphere_tests += detection.sphere_tests;
  stats.leaf_pairs += detection.leaf_pairs;
  stats.pairs_cut_short += detection.pairs_cut_short;
  stats.coincident_centres += detection.coincident_centres;
  double depth_sum = stats.mean_penetration * stats.penetrating_contacts;
  for (const Contact& contact : leaf_contacts_) {
    if (contact.depth <= 0.0f) continue;
    stats.deepest_penetration = std::max(stats.deepest_penetration, contact.depth);
    depth_sum += contact.depth;
    ++stats.penetrating_contacts;
  }
  stats.mean_penetration =
      stats.penetrating_contacts > 0 ? depth_sum / stats.penetrating_contacts : 0.0;
}

// Figures of one substep are added to the step's: times and counts summed, extremes kept.
void World::substep(float dt, StepStats& stats) {
  const bool plausible = settings_.response == ResponseMode::kPlausible;
  moving_.assign(bodies_.size(), 0);
  dynamic_.assign(bodies_.size(), 0);
  for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
    dynamic_[i] = alive_[i] != 0 && !bodies_[i].is_static ? 1 : 0;
    moving_[i] = dynamic_[i] != 0 && !sleep_->asleep(i) ? 1 : 0;
  }

  const Clock::time_point velocities_start = Clock::now();
  for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
    if (moving_[i] == 0) continue;
    RigidBody& body = bodies_[i];
    integrate_velocity(body, settings_.gravity, dt);
    if (plausible) {
      const Vec3 displacement = body.linear_velocity * dt;
      const float turn_reach = body.angular_velocity.norm() * dt * extent_[i];
      // Speeds whose squares overflow single precision leave no bound on the motion to detect
      // with: the simulation has gone non-finite in all but name.
      if (!std::isfinite(displacement.norm()) || !std::isfinite(turn_reach)) {
        stats.non_finite_body = i;
        stopped_ = true;
        return;
      }
      detector_.set_motion({i}, displacement, turn_reach);
    }
  }
  stats.integration_ms += elapsed_ms(velocities_start);

  detect(stats);

  const Clock::time_point response_start = Clock::now();
  if (plausible) {
    respond(dt, stats);
  } else {
    contacts_.swap(leaf_contacts_);
    const PaperResponseStats response = apply_paper_response(
        bodies_, contacts_, settings_.ground_restitution, settings_.paper_passes);
    stats.impulses += response.impulses;
    stats.response_passes += response.passes;
  }
  stats.contacts += static_cast<std::uint32_t>(contacts_.size());
  stats.response_ms += elapsed_ms(response_start);

  const Clock::time_point positions_start = Clock::now();
  integrate_positions(dt, plausible);
  stats.integration_ms += elapsed_ms(positions_start);

  for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
    if (dynamic_[i] == 0) continue;
    const RigidBody& body = bodies_[i];
    // A quaternion with huge coefficients normalises to zero (its norm overflows), finite but no
    // rotation: that is the same failure.
    if (!body.finite() ||
        !(std::abs(body.pose.rotation.squaredNorm() - 1.0f) < kUnitQuaternionTolerance)) {
      stats.non_finite_body = i;
      stopped_ = true;
      return;
    }
  }
  if (plausible) {
    speeds_.assign(bodies_.size(), 0.0f);
    for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
      if (moving_[i] != 0) speeds_[i] = fastest_point_speed(i);
    }
    sleep_changes_.clear();
    stats.islands = sleep_->update(speeds_, dynamic_, dt, settings_.sleep, sleep_changes_);
    for (const std::uint32_t body : sleep_changes_) {
      bodies_[body].linear_velocity.setZero();
      bodies_[body].angular_velocity.setZero();
      detector_.set_asleep({body}, true);
    }
  }
}

// The response's contacts from leaf_contacts_: all of them, or a manifold per body pair.
void World::reduce_contacts() {
  const SolverSettings& solver = settings_.solver;
  if (solver.contacts == ContactSet::kReduced) {
    contacts_.clear();
    reducer_->reduce(leaf_contacts_, solver.manifold_points, contacts_);
  } else {
    contacts_.swap(leaf_contacts_);
  }
}

// Plausible mode: contact reduction, islands and waking, then the sequential-impulse solver.
void World::respond(float dt, StepStats& stats) {
  const SolverSettings& solver = settings_.solver;
  reduce_contacts();

  // Wake the sleeping islands a restless body touches. The detector skipped the pairs of bodies
  // that slept until now: without their contacts a blow on a sleeping pile would pass through
  // its top body unopposed for a step. So detect again with them awake, which may show them
  // touching other sleeping islands, until nothing more wakes.
  for (;;) {
    sleep_->build_islands(contacts_, dynamic_);
    sleep_changes_.clear();
    sleep_->wake_disturbed(settings_.sleep, sleep_changes_);
    if (sleep_changes_.empty()) break;
    for (const std::uint32_t body : sleep_changes_) {
      detector_.set_asleep({body}, false);
      // Still until the solver moves them: no motion from before they slept.
      detector_.set_motion({body}, Vec3::Zero(), 0.0f);
      moving_[body] = 1;
    }
    detect(stats);
    reduce_contacts();
  }

  materials_.resize(contacts_.size());
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const Contact& contact = contacts_[k];
    const RigidBody& b = bodies_[contact.body_b];
    if (contact.body_a == kGroundPlaneBody) {
      materials_[k] = {mix_friction(settings_.ground_friction, b.friction),
                       mix_restitution(settings_.ground_restitution, b.restitution)};
      continue;
    }
    const RigidBody& a = bodies_[contact.body_a];
    const auto pair = pair_materials_.empty()
                          ? pair_materials_.end()
                          : pair_materials_.find(pair_key(contact.body_a, contact.body_b));
    materials_[k] = pair != pair_materials_.end()
                        ? pair->second
                        : PairMaterial{mix_friction(a.friction, b.friction),
                                       mix_restitution(a.restitution, b.restitution)};
  }
  const ContactSolverStats solved = solver_->solve(bodies_, moving_, contacts_, materials_, solver,
                                                   settings_.gravity, dt, *parallel_);
  stats.impulses += solved.constraints;
  stats.warm_started += solved.warm_started;
  stats.bounces += solved.bounces;
  stats.response_passes += solver.velocity_iterations;
}

void World::integrate_positions(float dt, bool plausible) {
  for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
    if (moving_[i] == 0) continue;
    RigidBody& body = bodies_[i];
    integrate_position(body, dt);
    if (plausible) {
      correct_position(body, solver_->position_linear()[i], solver_->position_angular()[i], dt);
    }
    detector_.set_pose({i}, body.pose);
  }
}

// Bodies at rest, how fast the resting ones still move, and the kinetic energy, at the end of
// the step.
void World::measure_rest(StepStats& stats) {
  touching_.assign(bodies_.size(), 0);
  for (const Contact& contact : contacts_) {
    if (contact.body_a != kGroundPlaneBody) touching_[contact.body_a] = 1;
    touching_[contact.body_b] = 1;
  }
  double jitter_sum = 0.0;
  std::uint32_t resting = 0;
  for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
    if (alive_[i] == 0 || bodies_[i].is_static) continue;
    stats.kinetic_energy += bodies_[i].kinetic_energy();
    ++stats.moving_bodies;
    if (sleep_->asleep(i)) {
      ++stats.bodies_asleep;
      ++stats.bodies_at_rest;
      ++resting;
      continue;
    }
    const float speed = fastest_point_speed(i);
    if (speed < settings_.sleep.speed) ++stats.bodies_at_rest;
    if (touching_[i] != 0 && speed < kSettlingFactor * settings_.sleep.speed) {
      jitter_sum += speed;
      ++resting;
    }
  }
  stats.jitter = resting > 0 ? jitter_sum / resting : 0.0;
}

}  // namespace sphys
