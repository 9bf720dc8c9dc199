#pragma once

// The bodies of a world in one store, one slot per body, in structure-of-arrays form: every stage
// of a step (bounds and narrow phase, solver, integration, sleep) reads and writes the same arrays
// through spans, so no stage keeps a copy of a body to be brought up to date (the soft step loads
// the awake bodies' velocities into working arrays for one solve and writes them back). The awake
// bodies are also listed densely (awake()), so that the stages that work on moving bodies only
// never pass over the sleeping and static ones. The store is the one owner of per-slot arrays:
// it says which body a slot holds (BodyId: the slot's generation and whether it is alive), and
// it grows the per-slot arrays of other owners (SlotArrays) with its own.

#include <cstdint>
#include <span>
#include <vector>

#include "sphys/body_id.h"
#include "sphys/math.h"
#include "sphys/rigid_body.h"

namespace sphys {

class BodyStore;

// Arrays indexed by body slot that another part of a world keeps (the sleep tracker's still
// times, the detector's trees). Attached to a store, they grow with its own arrays, so that no
// owner keeps its arrays in step with the store by hand. The link undoes itself from either
// side: arrays destroyed first leave their store, and a store destroyed first lets go of them,
// so the two may die in any order.
class SlotArrays {
 public:
  // Every array is to have at least `slots` slots; a new slot's values are the owner's defaults.
  virtual void grow_slots(std::uint32_t slots) = 0;

 protected:
  SlotArrays() = default;
  ~SlotArrays();
  // Attached by address.
  SlotArrays(const SlotArrays&) = delete;
  SlotArrays& operator=(const SlotArrays&) = delete;

 private:
  friend class BodyStore;
  BodyStore* attached_to_ = nullptr;
};

namespace detail {

// The state of a store's bodies, one array per quantity, indexed by slot: what copying a store
// copies.
struct BodyArrays {
  std::vector<Transform> pose_;              // the body frame, origin at the centre of mass
  std::vector<Vec3> linear_velocity_;        // of the centre of mass. unit: m/s
  std::vector<Vec3> angular_velocity_;       // world frame. unit: rad/s
  std::vector<float> inverse_mass_;          // 0 for a static body. unit: 1/kg
  std::vector<Mat3> inertia_body_;           // about the centre of mass, body axes. unit: kg·m²
  std::vector<Mat3> inverse_inertia_body_;   // unit: 1/(kg·m²)
  std::vector<Mat3> inverse_inertia_world_;  // R I_body⁻¹ Rᵀ. unit: 1/(kg·m²)
  std::vector<float> extent_;  // farthest point of the shape from the centre of mass. unit: m
  // |v| + |ω| · extent as of the body's last finalize or change of velocity. unit: m/s
  std::vector<float> fastest_point_speed_;
  std::vector<float> restitution_;         // unit: dimensionless, 0..1
  std::vector<float> friction_;            // Coulomb coefficient. unit: dimensionless
  std::vector<std::uint8_t> alive_;        // 1 while the slot holds a body
  std::vector<std::uint8_t> dynamic_;      // 1 for a body alive and not static
  std::vector<std::uint8_t> moving_;       // 1 for a dynamic body that is awake
  std::vector<std::uint32_t> generation_;  // from 1, moved on when the slot's body leaves
  std::vector<std::uint32_t> free_;        // freed slots, the last freed last
  // Forces and torques applied for the next step (world frame), and the slots that have one.
  std::vector<Vec3> force_;            // unit: N
  std::vector<Vec3> torque_;           // unit: N·m
  std::vector<std::uint32_t> forced_;  // the slots given a force or torque since the last clear
  std::uint32_t dynamic_bodies_ = 0;   // how many slots are dynamic
  std::vector<std::uint32_t> awake_;   // the moving slots, in increasing order
};

}  // namespace detail

// A world's bodies, one slot each, in arrays indexed by slot (the top of this file says why).
class BodyStore : private detail::BodyArrays {
 public:
  BodyStore() = default;
  ~BodyStore();
  // A copy is a snapshot of the bodies: the arrays attached to the store stay with it alone.
  BodyStore(const BodyStore& other) : detail::BodyArrays(other) {}
  // Takes the other's bodies; the arrays attached to this store grow to its slots.
  BodyStore& operator=(const BodyStore& other);

  // Puts a body in a slot, the last one freed first, else a new one, and returns the slot. A
  // static body keeps no velocities and no inverse mass. `extent`: the farthest point of its
  // shape from the centre of mass. unit: m
  std::uint32_t add(const RigidBody& body, float extent);
  // Frees the slot: not alive, and neither moving nor counted from then on. Its generation moves
  // on, so that the removed body's id names nothing any more.
  void remove(std::uint32_t slot);

  // Grows `arrays` to the store's slots now and with the store from then on, until detached (or
  // attached to another store, or destroyed).
  void attach(SlotArrays& arrays);
  // Stops growing `arrays` with the store; nothing when they are not attached to it.
  void detach(SlotArrays& arrays);

  // How many slots there are, free ones included: the size of every per-slot array.
  [[nodiscard]] std::uint32_t slots() const { return static_cast<std::uint32_t>(pose_.size()); }
  // The id of a slot's body, or of the next one to be added there when the slot is free.
  [[nodiscard]] BodyId id_of(std::uint32_t slot) const { return {slot, generation_[slot]}; }
  // True for the id of a body in the store; false for the null id, a removed body's, or one
  // never given.
  [[nodiscard]] bool alive(BodyId id) const {
    return id.index < slots() && generation_[id.index] == id.generation && alive_[id.index] != 0;
  }
  // A copy of the body in a slot.
  [[nodiscard]] RigidBody body(std::uint32_t slot) const;
  // True while the slot holds a body.
  [[nodiscard]] bool alive(std::uint32_t slot) const { return alive_[slot] != 0; }
  // True for a slot that holds a static body (it never moves).
  [[nodiscard]] bool is_static(std::uint32_t slot) const {
    return alive_[slot] != 0 && dynamic_[slot] == 0;
  }
  // True for a dynamic body that sleeps; false for an awake, a static or no body.
  [[nodiscard]] bool asleep(std::uint32_t slot) const {
    return dynamic_[slot] != 0 && moving_[slot] == 0;
  }
  // Puts dynamic bodies to sleep (their velocities become zero) or wakes them, and lists the
  // awake ones again (once for all of them: a pass over the slots).
  void set_asleep(std::span<const std::uint32_t> slots, bool asleep);
  // The same for one slot.
  void set_asleep(std::uint32_t slot, bool asleep) { set_asleep({&slot, 1}, asleep); }

  // How many bodies are alive and not static (asleep or not).
  [[nodiscard]] std::uint32_t dynamic_bodies() const { return dynamic_bodies_; }
  // Per slot, 1 for a body that is alive and not static (asleep or not), else 0.
  [[nodiscard]] std::span<const std::uint8_t> dynamic() const { return dynamic_; }
  // Per slot, 1 for a dynamic body that is awake, else 0.
  [[nodiscard]] std::span<const std::uint8_t> moving() const { return moving_; }
  // The slots of the awake dynamic bodies, in increasing order, kept listed by every change.
  [[nodiscard]] std::span<const std::uint32_t> awake() const { return awake_; }

  // The arrays, indexed by slot. Poses place the body frame, whose origin is the centre of mass.
  [[nodiscard]] std::span<Transform> poses() { return pose_; }
  // The poses, read only.
  [[nodiscard]] std::span<const Transform> poses() const { return pose_; }
  // Velocities of the centres of mass, world frame. unit: m/s
  [[nodiscard]] std::span<Vec3> linear_velocities() { return linear_velocity_; }
  // The linear velocities, read only. unit: m/s
  [[nodiscard]] std::span<const Vec3> linear_velocities() const { return linear_velocity_; }
  // World frame. unit: rad/s
  [[nodiscard]] std::span<Vec3> angular_velocities() { return angular_velocity_; }
  // The angular velocities, read only. unit: rad/s
  [[nodiscard]] std::span<const Vec3> angular_velocities() const { return angular_velocity_; }
  // 0 for a static body or a free slot. unit: 1/kg
  [[nodiscard]] std::span<const float> inverse_masses() const { return inverse_mass_; }
  // About the centre of mass, body axes. unit: kg·m²
  [[nodiscard]] std::span<const Mat3> inertias_body() const { return inertia_body_; }
  // The inverses of inertias_body(). unit: 1/(kg·m²)
  [[nodiscard]] std::span<const Mat3> inverse_inertias_body() const {
    return inverse_inertia_body_;
  }
  // R I_body⁻¹ Rᵀ at the pose of the last update_world_inertia(slot): whoever turns a body
  // updates it. unit: 1/(kg·m²)
  [[nodiscard]] std::span<const Mat3> inverse_inertias_world() const {
    return inverse_inertia_world_;
  }
  // Sets the slot's inverse_inertias_world() from its rotation now.
  void update_world_inertia(std::uint32_t slot);
  // Farthest point of the body's shape from its centre of mass. unit: m
  [[nodiscard]] std::span<const float> extents() const { return extent_; }
  // The bodies' restitution coefficients. unit: dimensionless, 0..1
  [[nodiscard]] std::span<const float> restitutions() const { return restitution_; }
  // The bodies' Coulomb friction coefficients. unit: dimensionless
  [[nodiscard]] std::span<const float> frictions() const { return friction_; }

  // Adds a force through the centre of mass (unit: N) and a torque (unit: N·m), world frame, to
  // what acts on the body through the next step (as gravity does, in every collision pass).
  void add_force(std::uint32_t slot, const Vec3& force, const Vec3& torque);
  // The forces through the centres of mass for the next step, world frame. unit: N
  [[nodiscard]] std::span<const Vec3> forces() const { return force_; }
  // The torques for the next step, world frame. unit: N·m
  [[nodiscard]] std::span<const Vec3> torques() const { return torque_; }
  // The slots given a force or torque since the last clear_forces().
  [[nodiscard]] std::span<const std::uint32_t> forced() const { return forced_; }
  // The forces end with the step they acted through.
  void clear_forces();

  // ½ m v² + ½ ωᵀ I ω of a slot's body (0 for a static one). unit: J
  [[nodiscard]] double kinetic_energy(std::uint32_t slot) const;
  // True while the body's pose and velocities are finite and its rotation is a unit quaternion
  // (within kUnitQuaternionTolerance): a quaternion with huge coefficients normalises to zero
  // (its norm overflows), finite but no rotation, the same failure.
  [[nodiscard]] bool finite(std::uint32_t slot) const;
  // The speed of each body's fastest point, |v| + |ω| · extent, as measured when the body was
  // last finished (once a collision pass, with its pose and inertia) or its velocity was set: the
  // one place it is kept, read by the collision passes' count, sleep and the rest figures.
  // unit: m/s
  [[nodiscard]] std::span<const float> fastest_point_speeds() const { return fastest_point_speed_; }
  // Measures the slot's fastest point speed from its velocities now and keeps it.
  float measure_fastest_point_speed(std::uint32_t slot) {
    fastest_point_speed_[slot] =
        linear_velocity_[slot].norm() + angular_velocity_[slot].norm() * extent_[slot];
    return fastest_point_speed_[slot];
  }

 private:
  // The arrays attached to this store, not to its copies.
  std::vector<SlotArrays*> attached_;
};

}  // namespace sphys
