#pragma once

// A rigid body's mass properties and state, and the semi-implicit Euler integrator.

#include "sphys/math.h"

namespace sphys {

// How far a rotation may be from unit length: a given one beyond it is refused rather than
// normalised, and a body's beyond it after a step means the state has gone bad.
// unit: dimensionless
inline constexpr float kUnitQuaternionTolerance = 1e-3f;

// What a body is made of and how it moves. The body frame has its origin at the centre of mass;
// `pose` places it in the world. A static body never moves and has infinite mass (its inverse
// mass and inverse inertia are zero).
struct RigidBody {
  Transform pose;                            // unit: m
  Vec3 linear_velocity = Vec3::Zero();       // of the centre of mass, world frame. unit: m/s
  Vec3 angular_velocity = Vec3::Zero();      // world frame. unit: rad/s
  float inverse_mass = 0.0f;                 // unit: 1/kg
  Mat3 inverse_inertia_body = Mat3::Zero();  // about the centre of mass, body axes. unit: 1/(kg·m²)
  Mat3 inertia_body = Mat3::Zero();          // unit: kg·m²
  float restitution = 0.3f;                  // unit: dimensionless, 0..1
  float friction = 0.5f;                     // Coulomb coefficient. unit: dimensionless
  bool is_static = false;                    // never moves: infinite mass, no velocities

  // I⁻¹ in the world frame: R I_body⁻¹ Rᵀ.
  [[nodiscard]] Mat3 inverse_inertia_world() const;
  // Velocity of the body's material point at world position `point`. unit: m/s
  [[nodiscard]] Vec3 velocity_at(const Vec3& point) const {
    return linear_velocity + angular_velocity.cross(point - pose.translation);
  }
  // 1 / inverse_mass; 0 for a static body (infinite mass). unit: kg
  [[nodiscard]] float mass() const { return inverse_mass > 0.0f ? 1.0f / inverse_mass : 0.0f; }
  // ½ m v² + ½ ωᵀ I ω. unit: J
  [[nodiscard]] double kinetic_energy() const;
};

// I⁻¹ in the world frame, R I_body⁻¹ Rᵀ, at orientation `rotation`. unit: 1/(kg·m²)
[[nodiscard]] Mat3 world_inverse_inertia(const Quat& rotation, const Mat3& inverse_inertia_body);
// ½ m v² + ½ ωᵀ I ω, with I = `inertia_body` at `rotation`; 0 for a static body (inverse mass 0).
// unit: J
[[nodiscard]] double kinetic_energy(const Quat& rotation, const Vec3& linear_velocity,
                                    const Vec3& angular_velocity, float inverse_mass,
                                    const Mat3& inertia_body);

// Semi-implicit (symplectic) Euler, after the world's first half (v += g dt, then the response),
// for a moving body: x += v dt; the orientation turns by ω_mid dt (q += ½ dt (0,
// ω_mid) q, then renormalised), with ω_mid the angular velocity at the middle of the turn. The
// world angular momentum I ω is kept across the turn (ω' = I'⁻¹ I ω), so a torque-free body
// conserves it instead of keeping ω fixed while its inertia turns. Paper mode's integrator;
// the plausible mode's keeps the spin more closely (src/bodies/spin_integrator.h).
void integrate_position(Transform& pose, const Vec3& linear_velocity, Vec3& angular_velocity,
                        const Mat3& inertia_body, const Mat3& inverse_inertia_body, float dt);
// The same for a RigidBody; static bodies are left alone.
void integrate_position(RigidBody& body, float dt);

}  // namespace sphys
