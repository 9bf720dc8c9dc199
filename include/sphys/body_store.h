#pragma once

// The bodies of a world in one store, one slot per body, in structure-of-arrays form: every stage
// of a step (bounds and narrow phase, solver, integration, sleep) reads and writes the same arrays
// through spans, so no stage keeps a copy of a body to be brought up to date (the solvers load
// the awake bodies' velocities into working arrays for one solve and write them back). The awake
// bodies are also listed densely (awake()), so that the stages that work on moving bodies only
// never pass over the sleeping and static ones.

#include <cstdint>
#include <span>
#include <vector>

#include "sphys/math.h"
#include "sphys/rigid_body.h"

namespace sphys {

class BodyStore {
 public:
  // Puts a body in a slot, the last one freed first, else a new one, and returns the slot. A
  // static body keeps no velocities and no inverse mass. `extent`: the farthest point of its
  // shape from the centre of mass. unit: m
  std::uint32_t add(const RigidBody& body, float extent);
  // Frees the slot: not alive, and neither moving nor counted from then on.
  void remove(std::uint32_t slot);

  [[nodiscard]] std::uint32_t slots() const { return static_cast<std::uint32_t>(pose_.size()); }
  // A copy of the body in a slot.
  [[nodiscard]] RigidBody body(std::uint32_t slot) const;
  [[nodiscard]] bool alive(std::uint32_t slot) const { return alive_[slot] != 0; }
  [[nodiscard]] bool is_static(std::uint32_t slot) const {
    return alive_[slot] != 0 && dynamic_[slot] == 0;
  }
  [[nodiscard]] bool asleep(std::uint32_t slot) const {
    return dynamic_[slot] != 0 && moving_[slot] == 0;
  }
  // Puts a dynamic body to sleep (its velocities become zero) or wakes it.
  void set_asleep(std::uint32_t slot, bool asleep);

  // How many bodies are alive and not static (asleep or not).
  [[nodiscard]] std::uint32_t dynamic_bodies() const { return dynamic_bodies_; }
  // Per slot, 1 for a body that is alive and not static (asleep or not), else 0.
  [[nodiscard]] std::span<const std::uint8_t> dynamic() const { return dynamic_; }
  // Per slot, 1 for a dynamic body that is awake, else 0.
  [[nodiscard]] std::span<const std::uint8_t> moving() const { return moving_; }
  // The slots of the awake dynamic bodies, in increasing order. Listed again at the first call
  // after a change, so not to be called first from two threads at once (World lists it before
  // each of its calls returns).
  [[nodiscard]] std::span<const std::uint32_t> awake() const;

  // The arrays, indexed by slot. Poses place the body frame, whose origin is the centre of mass.
  [[nodiscard]] std::span<Transform> poses() { return pose_; }
  [[nodiscard]] std::span<const Transform> poses() const { return pose_; }
  [[nodiscard]] std::span<Vec3> linear_velocities() { return linear_velocity_; }  // unit: m/s
  [[nodiscard]] std::span<const Vec3> linear_velocities() const { return linear_velocity_; }
  // World frame. unit: rad/s
  [[nodiscard]] std::span<Vec3> angular_velocities() { return angular_velocity_; }
  [[nodiscard]] std::span<const Vec3> angular_velocities() const { return angular_velocity_; }
  [[nodiscard]] std::span<const float> inverse_masses() const { return inverse_mass_; }  // 1/kg
  // About the centre of mass, body axes. unit: kg·m² and 1/(kg·m²)
  [[nodiscard]] std::span<const Mat3> inertias_body() const { return inertia_body_; }
  [[nodiscard]] std::span<const Mat3> inverse_inertias_body() const {
    return inverse_inertia_body_;
  }
  // R I_body⁻¹ Rᵀ at the pose of the last update_world_inertia(slot): whoever turns a body
  // updates it. unit: 1/(kg·m²)
  [[nodiscard]] std::span<const Mat3> inverse_inertias_world() const {
    return inverse_inertia_world_;
  }
  void update_world_inertia(std::uint32_t slot);
  // Farthest point of the body's shape from its centre of mass. unit: m
  [[nodiscard]] std::span<const float> extents() const { return extent_; }
  [[nodiscard]] std::span<const float> restitutions() const { return restitution_; }
  [[nodiscard]] std::span<const float> frictions() const { return friction_; }

  // ½ m v² + ½ ωᵀ I ω of a slot's body (0 for a static one). unit: J
  [[nodiscard]] double kinetic_energy(std::uint32_t slot) const;
  // True while the body's pose and velocities are finite and its rotation is a unit quaternion
  // (within kUnitQuaternionTolerance): a quaternion with huge coefficients normalises to zero
  // (its norm overflows), finite but no rotation, the same failure.
  [[nodiscard]] bool finite(std::uint32_t slot) const;
  // The speed of the body's fastest point, |v| + |ω| · extent. unit: m/s
  [[nodiscard]] float fastest_point_speed(std::uint32_t slot) const {
    return linear_velocity_[slot].norm() + angular_velocity_[slot].norm() * extent_[slot];
  }

 private:
  std::vector<Transform> pose_;
  std::vector<Vec3> linear_velocity_;
  std::vector<Vec3> angular_velocity_;
  std::vector<float> inverse_mass_;
  std::vector<Mat3> inertia_body_;
  std::vector<Mat3> inverse_inertia_body_;
  std::vector<Mat3> inverse_inertia_world_;
  std::vector<float> extent_;
  std::vector<float> restitution_;
  std::vector<float> friction_;
  std::vector<std::uint8_t> alive_;
  std::vector<std::uint8_t> dynamic_;
  std::vector<std::uint8_t> moving_;
  std::vector<std::uint32_t> free_;  // freed slots, the last freed last
  std::uint32_t dynamic_bodies_ = 0;
  mutable std::vector<std::uint32_t> awake_;  // awake(), valid while !awake_stale_
  mutable bool awake_stale_ = false;
};

}  // namespace sphys
