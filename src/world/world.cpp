#include "sphys/world.h"

#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>

#include "core/stopwatch.h"
#include "dynamics/soft_step_solver.h"
#include "sphys/error.h"
#include "sphys/settings_table.h"
#include "world/sleep_tracker.h"
#include "world/world_access.h"

namespace sphys {
namespace {

// Relative tolerance of the inertia's symmetry: the tensor comes from float or double sums.
constexpr float kInertiaSymmetryTolerance = 1e-4f;

void check_material(float restitution, float friction) {
  if (!(restitution >= 0.0f && restitution <= 1.0f)) {
    throw Error("restitution must be between 0 and 1, got " + std::to_string(restitution));
  }
  if (!(friction >= 0.0f) || !std::isfinite(friction)) {
    throw Error("friction must be finite and not negative, got " + std::to_string(friction));
  }
}

// The detector's settings: the world's own, with the contacts the solver asks for in plausible
// mode and the paper's (every overlapping leaf pair, made afresh) in paper mode.
DetectorSettings detector_settings(const WorldSettings& settings) {
  DetectorSettings collision;
  static_cast<CollisionSettings&>(collision) = settings.collision;
  const bool plausible = settings.response == ResponseMode::kPlausible;
  collision.contact_margin = plausible ? settings.solver.contact_margin : 0.0f;
  collision.speculative = plausible && settings.solver.speculative_contacts;
  collision.manifold_points = plausible && settings.solver.contacts == ContactSet::kReduced
                                  ? settings.solver.manifold_points
                                  : 0;
  collision.fast_pair_reach = settings.solver.fast_pair_reach;
  // Paper mode makes every overlapping leaf pair a contact afresh, as published.
  collision.reuse_distance = plausible ? settings.solver.reuse_distance : 0.0f;
  collision.measure_penetration = settings.plausibility_figures;
  // The same pairs either way: the paper's one Sweep & Prune for its mode, the cells (flat cost
  // per body as piles spread) for the plausible one.
  collision.broad_phase = settings.broad_phase.value_or(plausible ? BroadPhaseKind::kCells
                                                                  : BroadPhaseKind::kSweepAndPrune);
  return collision;
}

// The farthest point of a tree from its body's origin (the centre of mass). unit: m
float tree_extent(const SphereTree& tree) {
  return tree.root().center.norm() + tree.subtree_radius(0);
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
      store_(std::make_unique<BodyStore>()),
      detector_(std::make_unique<CollisionDetector>(detector_settings(settings))),
      solver_(std::make_unique<SoftStepSolver>()),
      sleep_(std::make_unique<SleepTracker>(*store_)),
      access_(std::make_unique<WorldAccess>()) {
  check_world_settings(settings);
  solver_lanes_ = resolve_solver_lanes(settings.solver.lanes);
  solver_->use_lanes(solver_lanes_);
  parallel_ = std::make_unique<Parallel>(settings.threads);
  detector_->set_parallel(parallel_.get());
  detector_->set_bodies(*store_);
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

std::uint64_t World::pair_key(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t{a} << 32) | b;
}

World::Reading::Reading(const World& world) : access_(world.access_.get()) {
  access_->hold_shared("World::Reading");
}

World::Reading::~Reading() { access_->release_shared(); }

std::uint32_t World::checked_slot(BodyId id) const {
  if (id.is_null()) throw Error("the null body id (BodyId{}) names no body");
  if (!store_->alive(id)) {
    throw Error("no body with id " + std::to_string(id.index) + "." +
                std::to_string(id.generation) + " in the world (removed, or never added)");
  }
  return id.index;
}

std::uint32_t World::slot_of(BodyId id) const {
  const WorldAccess::Shared turn(*access_, "slot_of");
  return checked_slot(id);
}

RigidBody World::body(BodyId id) const {
  const WorldAccess::Shared turn(*access_, "body");
  return store_->body(checked_slot(id));
}

const SphereTree& World::tree(BodyId id) const {
  const WorldAccess::Shared turn(*access_, "tree");
  return detector_->tree(checked_slot(id));
}

std::shared_ptr<const SphereTree> World::shared_tree(BodyId id) const {
  const WorldAccess::Shared turn(*access_, "shared_tree");
  return detector_->shared_tree(checked_slot(id));
}

bool World::alive(BodyId id) const {
  const WorldAccess::Shared turn(*access_, "alive");
  return store_->alive(id);
}

std::uint32_t World::body_slots() const {
  const WorldAccess::Shared turn(*access_, "body_slots");
  return store_->slots();
}

const StepStats& World::stats() const {
  const WorldAccess::Shared turn(*access_, "stats");
  return stats_;
}

std::span<const Contact> World::contacts() const {
  const WorldAccess::Shared turn(*access_, "contacts");
  return detector_->contacts();
}

bool World::stopped() const {
  const WorldAccess::Shared turn(*access_, "stopped");
  return stopped_;
}

SolverLanes World::solver_lanes() const { return solver_lanes_; }

const WorldSettings& World::settings() const {
  const WorldAccess::Shared turn(*access_, "settings");
  return settings_;
}

Aabb World::bounds(BodyId body) const {
  const WorldAccess::Shared turn(*access_, "bounds");
  return detector_->bounds(checked_slot(body));
}

const BodyStore& World::bodies() const {
  const WorldAccess::Shared turn(*access_, "bodies");
  return *store_;
}

BodyId World::id_of(std::uint32_t slot) const {
  const WorldAccess::Shared turn(*access_, "id_of");
  if (slot >= store_->slots()) {
    throw Error("no body slot " + std::to_string(slot) + " in the world, which has " +
                std::to_string(store_->slots()));
  }
  return store_->id_of(slot);
}

BodyId World::add_body(const BodyDesc& desc) {
  const WorldAccess::Alone turn(*access_, WorldAccess::Holder::kChange, "add_body");
  check_body(desc);
  RigidBody body;
  body.pose = desc.pose;
  body.pose.rotation.normalize();
  body.restitution = desc.restitution;
  body.friction = desc.friction;
  body.is_static = desc.is_static;
  if (!desc.is_static) {
    body.linear_velocity = desc.linear_velocity;
    body.angular_velocity = desc.angular_velocity;
    body.inverse_mass = 1.0f / desc.mass;
    // Symmetrised so that rounding in the caller's tensor cannot make the inverse lopsided.
    body.inertia_body = 0.5f * (desc.inertia + desc.inertia.transpose());
    body.inverse_inertia_body = inverse_or_zero(body.inertia_body);
  }
  const std::uint32_t slot = store_->add(body, tree_extent(*desc.tree));
  try {
    sleep_->unsettle(slot);  // a slot used before keeps its last body's still time
    detector_->add_body(slot, desc.tree);
  } catch (...) {
    store_->remove(slot);  // no half-added body: the slot is free again
    throw;
  }
  return store_->id_of(slot);
}

void World::wake(std::uint32_t index) {
  sleep_changes_.clear();
  sleep_->wake(index, settings_.sleep, sleep_changes_);
  sleep_->unsettle(index);
}

void World::remove_body(BodyId id) {
  const WorldAccess::Alone turn(*access_, WorldAccess::Holder::kChange, "remove_body");
  const std::uint32_t index = checked_slot(id);
  // The sleeping bodies it touched (which may rest on it, asleep, awake or static) lose a
  // support.
  wake(index);
  removed_neighbours_.clear();
  detector_->paired_bodies(index, removed_neighbours_);
  for (const std::uint32_t neighbour : removed_neighbours_) wake(neighbour);
  detector_->remove_body(index);
  store_->remove(index);
  sleep_->parted();
  std::erase_if(pair_materials_, [&](const auto& entry) {
    return static_cast<std::uint32_t>(entry.first >> 32) == index ||
           static_cast<std::uint32_t>(entry.first) == index;
  });
}

void World::set_detection_budget(std::uint64_t max_sphere_tests, double max_microseconds) {
  const WorldAccess::Alone turn(*access_, WorldAccess::Holder::kChange, "set_detection_budget");
  WorldSettings settings = settings_;
  settings.collision.max_sphere_tests = max_sphere_tests;
  settings.collision.max_microseconds = max_microseconds;
  check_world_settings(settings);
  settings_ = settings;
  detector_->set_settings(detector_settings(settings_));
}

void World::set_velocity(BodyId id, const Vec3& linear, const Vec3& angular) {
  const WorldAccess::Alone turn(*access_, WorldAccess::Holder::kChange, "set_velocity");
  const std::uint32_t index = checked_slot(id);
  if (!linear.allFinite() || !angular.allFinite()) {
    throw Error("a body's velocities must be finite");
  }
  if (store_->is_static(index)) return;
  wake(index);
  store_->linear_velocities()[index] = linear;
  store_->angular_velocities()[index] = angular;
}

void World::apply_impulse(BodyId id, const Vec3& impulse, const Vec3& point) {
  const WorldAccess::Alone turn(*access_, WorldAccess::Holder::kChange, "apply_impulse");
  const std::uint32_t index = checked_slot(id);
  if (!impulse.allFinite() || !point.allFinite()) {
    throw Error("an impulse and its point must be finite");
  }
  if (store_->is_static(index)) return;
  wake(index);
  BodyStore& store = *store_;
  store.linear_velocities()[index] += store.inverse_masses()[index] * impulse;
  store.angular_velocities()[index] += store.inverse_inertias_world()[index] *
                                       (point - store.poses()[index].translation).cross(impulse);
}

void World::apply_force(BodyId id, const Vec3& force, const Vec3& point) {
  const WorldAccess::Alone turn(*access_, WorldAccess::Holder::kChange, "apply_force");
  const std::uint32_t index = checked_slot(id);
  if (!force.allFinite() || !point.allFinite()) throw Error("a force and its point must be finite");
  if (store_->is_static(index)) return;
  wake(index);
  store_->add_force(index, force, (point - store_->poses()[index].translation).cross(force));
}

void World::apply_torque(BodyId id, const Vec3& torque) {
  const WorldAccess::Alone turn(*access_, WorldAccess::Holder::kChange, "apply_torque");
  const std::uint32_t index = checked_slot(id);
  if (!torque.allFinite()) throw Error("a torque must be finite");
  if (store_->is_static(index)) return;
  wake(index);
  store_->add_force(index, Vec3::Zero(), torque);
}

void World::set_pair_material(BodyId a, BodyId b, const PairMaterial& material) {
  const WorldAccess::Alone turn(*access_, WorldAccess::Holder::kChange, "set_pair_material");
  const std::uint32_t ia = checked_slot(a);
  const std::uint32_t ib = checked_slot(b);
  check_material(material.restitution, material.friction);
  pair_materials_[pair_key(ia, ib)] = material;
}

bool World::asleep(BodyId id) const {
  const WorldAccess::Shared turn(*access_, "asleep");
  return store_->asleep(checked_slot(id));
}

std::uint32_t World::substeps_for(float dt) const {
  const std::uint32_t fewest = settings_.substeps;
  const std::uint32_t most = std::max(fewest, settings_.max_substeps);
  if (settings_.response != ResponseMode::kPlausible || most == fewest) return fewest;
  // The speed at the end of the step under gravity alone, an upper bound for a falling body.
  const float gravity_speed = settings_.gravity.norm() * dt;
  float needed = 0.0f;  // substeps, fractional
  const std::span<const float> extents = store_->extents();
  for (const std::uint32_t i : store_->awake()) {
    // A crowded body's pairs are overlaps served at its root (CollisionSettings::
    // crowd_pairs_per_body): there is nothing for it to pass through unseen, and a crowd parting
    // would otherwise run every pass of the step for all its bodies.
    if (!(extents[i] > 0.0f) || detector_->crowded(i)) continue;
    const float travel = (store_->fastest_point_speed(i) + gravity_speed) * dt;
    needed = std::max(needed, travel / (settings_.substep_travel * extents[i]));
  }
  // A non-finite speed is left to the step to find and report.
  if (!(needed <= static_cast<float>(most))) return needed > 0.0f ? most : fewest;
  return std::clamp(static_cast<std::uint32_t>(std::ceil(needed)), fewest, most);
}

const StepStats& World::step(float dt) {
  const WorldAccess::Alone turn(*access_, WorldAccess::Holder::kStep, "step");
  if (!(dt > 0.0f) || !std::isfinite(dt)) {
    throw Error("the time step must be positive and finite, got " + std::to_string(dt));
  }
  if (stopped_) return stats_;
  const StepClock::time_point step_start = StepClock::now();
  StepStats stats;
  const std::uint32_t substeps = substeps_for(dt);
  stats.substeps = substeps;
  const float substep_dt = dt / static_cast<float>(substeps);
  // Islands whose bodies parted in the last step are built afresh, once a step.
  if (settings_.response == ResponseMode::kPlausible) {
    const StepClock::time_point split_start = StepClock::now();
    sleep_->split_islands(detector_->contacts());
    stats.sleep_ms += elapsed_ms(split_start);
  }
  for (std::uint32_t i = 0; i < substeps && !stopped_; ++i) substep(substep_dt, stats);
  store_->clear_forces();
  stats.movable_bodies = store_->dynamic_bodies();
  stats.bodies_asleep = stats.movable_bodies - static_cast<std::uint32_t>(store_->awake().size());
  if (settings_.plausibility_figures) measure_rest(stats);
  stats.step_ms = elapsed_ms(step_start);
  stats_ = stats;
  return stats_;
}

// The stages of one substep. Figures of a substep are added to the step's: times and counts
// summed, extremes kept.
void World::substep(float dt, StepStats& stats) {
  const bool plausible = settings_.response == ResponseMode::kPlausible;
  integrate_velocities(dt, plausible, stats);  // world/integrate_velocities.cpp
  if (stopped_) return;
  detect_contacts(stats);                     // world/detect_contacts.cpp
  if (plausible) wake_touched(dt, stats);     // world/detect_contacts.cpp
  respond(dt, plausible, stats);              // world/respond.cpp
  integrate_positions(dt, plausible, stats);  // world/integrate_positions.cpp
  if (stopped_) return;
  if (plausible) update_sleep(dt, stats);  // world/update_sleep.cpp
}

}  // namespace sphys
