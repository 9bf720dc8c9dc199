#include "sphys/world.h"

#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>

#include "core/id_errors.h"
#include "sphys/error.h"
#include "world/pipeline.h"
#include "world/world_state.h"

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

World::World(const WorldSettings& settings) : state_(std::make_unique<WorldState>(settings)) {}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

World::Reading::Reading(const World& world) : access_(&world.state_->access) {
  access_->hold_shared("World::Reading");
}

World::Reading::~Reading() { access_->release_shared(); }

namespace {

// The slot of a body in the world, for a call that holds its turn.
std::uint32_t checked_slot(const WorldState& world, BodyId id) {
  return slot_named(id, world.store.alive(id), "body", "BodyId");
}

}  // namespace

std::uint32_t World::slot_of(BodyId id) const {
  const WorldAccess::Shared turn(state_->access, "slot_of");
  return checked_slot(*state_, id);
}

RigidBody World::body(BodyId id) const {
  const WorldAccess::Shared turn(state_->access, "body");
  return state_->store.body(checked_slot(*state_, id));
}

const SphereTree& World::tree(BodyId id) const {
  const WorldAccess::Shared turn(state_->access, "tree");
  return state_->detector.tree(checked_slot(*state_, id));
}

std::shared_ptr<const SphereTree> World::shared_tree(BodyId id) const {
  const WorldAccess::Shared turn(state_->access, "shared_tree");
  return state_->detector.shared_tree(checked_slot(*state_, id));
}

bool World::alive(BodyId id) const {
  const WorldAccess::Shared turn(state_->access, "alive");
  return state_->store.alive(id);
}

std::uint32_t World::body_slots() const {
  const WorldAccess::Shared turn(state_->access, "body_slots");
  return state_->store.slots();
}

const StepStats& World::stats() const {
  const WorldAccess::Shared turn(state_->access, "stats");
  return state_->stats;
}

std::span<const Contact> World::contacts() const {
  const WorldAccess::Shared turn(state_->access, "contacts");
  return state_->detector.contacts();
}

bool World::stopped() const {
  const WorldAccess::Shared turn(state_->access, "stopped");
  return state_->stopped;
}

SolverLanes World::solver_lanes() const { return state_->solver_lanes; }

const WorldSettings& World::settings() const {
  const WorldAccess::Shared turn(state_->access, "settings");
  return state_->settings;
}

Aabb World::bounds(BodyId body) const {
  const WorldAccess::Shared turn(state_->access, "bounds");
  return state_->detector.bounds(checked_slot(*state_, body));
}

const BodyStore& World::bodies() const {
  const WorldAccess::Shared turn(state_->access, "bodies");
  return state_->store;
}

BodyId World::id_of(std::uint32_t slot) const {
  const WorldAccess::Shared turn(state_->access, "id_of");
  if (slot >= state_->store.slots()) {
    throw Error("no body slot " + std::to_string(slot) + " in the world, which has " +
                std::to_string(state_->store.slots()));
  }
  return state_->store.id_of(slot);
}

BodyId World::add_body(const BodyDesc& desc) {
  WorldState& world = *state_;
  const WorldAccess::Alone turn(world.access, WorldAccess::Holder::kChange, "add_body");
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
  const std::uint32_t slot = world.store.add(body, tree_extent(*desc.tree));
  try {
    world.sleep.unsettle(slot);  // a slot used before keeps its last body's still time
    world.detector.add_body(slot, desc.tree);
  } catch (...) {
    world.store.remove(slot);  // no half-added body: the slot is free again
    throw;
  }
  return world.store.id_of(slot);
}

void World::remove_body(BodyId id) {
  WorldState& world = *state_;
  const WorldAccess::Alone turn(world.access, WorldAccess::Holder::kChange, "remove_body");
  const std::uint32_t index = checked_slot(world, id);
  if (world.robots && world.robots->holds(id)) {
    throw Error("remove_body: the body is a robot's link; remove_robot removes a robot whole");
  }
  // The sleeping bodies it touched (which may rest on it, asleep, awake or static) lose a
  // support.
  world.wake(index);
  world.removed_neighbours.clear();
  world.detector.paired_bodies(index, world.removed_neighbours);
  for (const std::uint32_t neighbour : world.removed_neighbours) world.wake(neighbour);
  world.remove_joints_on(index);
  world.detector.remove_body(index);
  world.store.remove(index);
  world.sleep.parted();
  std::erase_if(world.pair_materials, [&](const auto& entry) {
    return static_cast<std::uint32_t>(entry.first >> 32) == index ||
           static_cast<std::uint32_t>(entry.first) == index;
  });
}

void World::set_detection_budget(std::uint64_t max_sphere_tests, double max_microseconds) {
  const WorldAccess::Alone turn(state_->access, WorldAccess::Holder::kChange,
                                "set_detection_budget");
  state_->set_detection_budget(max_sphere_tests, max_microseconds);
}

void World::set_velocity(BodyId id, const Vec3& linear, const Vec3& angular) {
  WorldState& world = *state_;
  const WorldAccess::Alone turn(world.access, WorldAccess::Holder::kChange, "set_velocity");
  const std::uint32_t index = checked_slot(world, id);
  if (!linear.allFinite() || !angular.allFinite()) {
    throw Error("a body's velocities must be finite");
  }
  if (world.store.is_static(index)) return;
  world.wake(index);
  world.store.linear_velocities()[index] = linear;
  world.store.angular_velocities()[index] = angular;
  world.store.measure_fastest_point_speed(index);
}

void World::apply_impulse(BodyId id, const Vec3& impulse, const Vec3& point) {
  WorldState& world = *state_;
  const WorldAccess::Alone turn(world.access, WorldAccess::Holder::kChange, "apply_impulse");
  const std::uint32_t index = checked_slot(world, id);
  if (!impulse.allFinite() || !point.allFinite()) {
    throw Error("an impulse and its point must be finite");
  }
  if (world.store.is_static(index)) return;
  world.wake(index);
  BodyStore& store = world.store;
  store.linear_velocities()[index] += store.inverse_masses()[index] * impulse;
  store.angular_velocities()[index] += store.inverse_inertias_world()[index] *
                                       (point - store.poses()[index].translation).cross(impulse);
  store.measure_fastest_point_speed(index);
}

void World::apply_force(BodyId id, const Vec3& force, const Vec3& point) {
  WorldState& world = *state_;
  const WorldAccess::Alone turn(world.access, WorldAccess::Holder::kChange, "apply_force");
  const std::uint32_t index = checked_slot(world, id);
  if (!force.allFinite() || !point.allFinite()) throw Error("a force and its point must be finite");
  if (world.store.is_static(index)) return;
  world.wake(index);
  world.store.add_force(index, force,
                        (point - world.store.poses()[index].translation).cross(force));
}

void World::apply_torque(BodyId id, const Vec3& torque) {
  WorldState& world = *state_;
  const WorldAccess::Alone turn(world.access, WorldAccess::Holder::kChange, "apply_torque");
  const std::uint32_t index = checked_slot(world, id);
  if (!torque.allFinite()) throw Error("a torque must be finite");
  if (world.store.is_static(index)) return;
  world.wake(index);
  world.store.add_force(index, Vec3::Zero(), torque);
}

void World::set_pair_material(BodyId a, BodyId b, const PairMaterial& material) {
  WorldState& world = *state_;
  const WorldAccess::Alone turn(world.access, WorldAccess::Holder::kChange, "set_pair_material");
  const std::uint32_t ia = checked_slot(world, a);
  const std::uint32_t ib = checked_slot(world, b);
  check_material(material.restitution, material.friction);
  world.pair_materials[pair_key(ia, ib)] = material;
}

bool World::asleep(BodyId id) const {
  const WorldAccess::Shared turn(state_->access, "asleep");
  return state_->store.asleep(checked_slot(*state_, id));
}

const StepStats& World::step(float dt) {
  WorldState& world = *state_;
  const WorldAccess::Alone turn(world.access, WorldAccess::Holder::kStep, "step");
  if (!(dt > 0.0f) || !std::isfinite(dt)) {
    throw Error("the time step must be positive and finite, got " + std::to_string(dt));
  }
  if (!world.stopped) {
    if (world.robots) world.robots->before_step(world, dt);
    world.stats = run_step(world, dt);
  }
  return world.stats;
}

}  // namespace sphys
