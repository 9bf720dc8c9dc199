#include "sphys/body_store.h"

#include <algorithm>
#include <cmath>

namespace sphys {

std::uint32_t BodyStore::add(const RigidBody& body, float extent) {
  std::uint32_t slot = 0;
  if (free_.empty()) {
    slot = slots();
    pose_.emplace_back();
    linear_velocity_.emplace_back();
    angular_velocity_.emplace_back();
    inverse_mass_.emplace_back();
    inertia_body_.emplace_back();
    inverse_inertia_body_.emplace_back();
    inverse_inertia_world_.emplace_back();
    extent_.emplace_back();
    fastest_point_speed_.emplace_back();
    restitution_.emplace_back();
    friction_.emplace_back();
    force_.emplace_back(Vec3::Zero());
    torque_.emplace_back(Vec3::Zero());
    alive_.emplace_back();
    dynamic_.emplace_back();
    moving_.emplace_back();
    generation_.push_back(1);
    for (SlotArrays* arrays : attached_) arrays->grow_slots(slots());
  } else {
    slot = free_.back();
    free_.pop_back();
  }
  const bool moves = !body.is_static;
  pose_[slot] = body.pose;
  linear_velocity_[slot] = moves ? body.linear_velocity : Vec3(Vec3::Zero());
  angular_velocity_[slot] = moves ? body.angular_velocity : Vec3(Vec3::Zero());
  inverse_mass_[slot] = moves ? body.inverse_mass : 0.0f;
  inertia_body_[slot] = moves ? body.inertia_body : Mat3(Mat3::Zero());
  inverse_inertia_body_[slot] = moves ? body.inverse_inertia_body : Mat3(Mat3::Zero());
  extent_[slot] = extent;
  restitution_[slot] = body.restitution;
  friction_[slot] = body.friction;
  alive_[slot] = 1;
  dynamic_[slot] = moves ? 1 : 0;
  moving_[slot] = moves ? 1 : 0;
  if (moves) {
    ++dynamic_bodies_;
    awake_.insert(std::lower_bound(awake_.begin(), awake_.end(), slot), slot);
  }
  update_world_inertia(slot);
  measure_fastest_point_speed(slot);
  return slot;
}

void BodyStore::remove(std::uint32_t slot) {
  if (moving_[slot] != 0) awake_.erase(std::lower_bound(awake_.begin(), awake_.end(), slot));
  linear_velocity_[slot].setZero();
  angular_velocity_[slot].setZero();
  fastest_point_speed_[slot] = 0.0f;
  inverse_mass_[slot] = 0.0f;
  force_[slot].setZero();
  torque_[slot].setZero();
  alive_[slot] = 0;
  if (dynamic_[slot] != 0) --dynamic_bodies_;
  dynamic_[slot] = 0;
  moving_[slot] = 0;
  // Generation 0 is the null id's: a slot reused 2³² times starts again from 1.
  if (++generation_[slot] == 0) generation_[slot] = 1;
  free_.push_back(slot);
}

BodyStore& BodyStore::operator=(const BodyStore& other) {
  detail::BodyArrays::operator=(other);
  for (SlotArrays* arrays : attached_) arrays->grow_slots(slots());
  return *this;
}

SlotArrays::~SlotArrays() {
  if (attached_to_ != nullptr) attached_to_->detach(*this);
}

BodyStore::~BodyStore() {
  for (SlotArrays* arrays : attached_) arrays->attached_to_ = nullptr;
}

void BodyStore::attach(SlotArrays& arrays) {
  if (arrays.attached_to_ == this) return;
  if (arrays.attached_to_ != nullptr) arrays.attached_to_->detach(arrays);
  arrays.attached_to_ = this;
  attached_.push_back(&arrays);
  arrays.grow_slots(slots());
}

void BodyStore::detach(SlotArrays& arrays) {
  if (arrays.attached_to_ != this) return;
  arrays.attached_to_ = nullptr;
  std::erase(attached_, &arrays);
}

RigidBody BodyStore::body(std::uint32_t slot) const {
  RigidBody body;
  body.pose = pose_[slot];
  body.linear_velocity = linear_velocity_[slot];
  body.angular_velocity = angular_velocity_[slot];
  body.inverse_mass = inverse_mass_[slot];
  body.inertia_body = inertia_body_[slot];
  body.inverse_inertia_body = inverse_inertia_body_[slot];
  body.restitution = restitution_[slot];
  body.friction = friction_[slot];
  body.is_static = dynamic_[slot] == 0;
  return body;
}

void BodyStore::set_asleep(std::span<const std::uint32_t> slots, bool asleep) {
  bool changed = false;
  for (const std::uint32_t slot : slots) {
    if (dynamic_[slot] == 0 || (moving_[slot] == 0) == asleep) continue;
    moving_[slot] = asleep ? 0 : 1;
    if (asleep) {
      linear_velocity_[slot].setZero();
      angular_velocity_[slot].setZero();
      fastest_point_speed_[slot] = 0.0f;
    }
    changed = true;
  }
  if (!changed) return;
  awake_.clear();
  for (std::uint32_t i = 0; i < this->slots(); ++i) {
    if (moving_[i] != 0) awake_.push_back(i);
  }
}

void BodyStore::add_force(std::uint32_t slot, const Vec3& force, const Vec3& torque) {
  if (force_[slot].isZero(0.0f) && torque_[slot].isZero(0.0f)) forced_.push_back(slot);
  force_[slot] += force;
  torque_[slot] += torque;
}

void BodyStore::clear_forces() {
  for (const std::uint32_t slot : forced_) {
    force_[slot].setZero();
    torque_[slot].setZero();
  }
  forced_.clear();
}

void BodyStore::update_world_inertia(std::uint32_t slot) {
  inverse_inertia_world_[slot] =
      world_inverse_inertia(pose_[slot].rotation, inverse_inertia_body_[slot]);
}

bool BodyStore::finite(std::uint32_t slot) const {
  const Transform& pose = pose_[slot];
  return pose.translation.allFinite() && pose.rotation.coeffs().allFinite() &&
         linear_velocity_[slot].allFinite() && angular_velocity_[slot].allFinite() &&
         std::abs(pose.rotation.squaredNorm() - 1.0f) < kUnitQuaternionTolerance;
}

double BodyStore::kinetic_energy(std::uint32_t slot) const {
  return sphys::kinetic_energy(pose_[slot].rotation, linear_velocity_[slot],
                               angular_velocity_[slot], inverse_mass_[slot], inertia_body_[slot]);
}

}  // namespace sphys
