#include "sphys/rigid_body.h"

namespace sphys {

Mat3 world_inverse_inertia(const Quat& rotation, const Mat3& inverse_inertia_body) {
  const Mat3 turn = rotation.toRotationMatrix();
  return turn * inverse_inertia_body * turn.transpose();
}

double kinetic_energy(const Quat& rotation, const Vec3& linear_velocity,
                      const Vec3& angular_velocity, float inverse_mass, const Mat3& inertia_body) {
  if (!(inverse_mass > 0.0f)) return 0.0;
  const Mat3 turn = rotation.toRotationMatrix();
  const Eigen::Vector3d omega_body = (turn.transpose() * angular_velocity).cast<double>();
  const double linear = linear_velocity.cast<double>().squaredNorm() / inverse_mass;
  const double angular = omega_body.dot(inertia_body.cast<double>() * omega_body);
  return 0.5 * (linear + angular);
}

Mat3 RigidBody::inverse_inertia_world() const {
  return world_inverse_inertia(pose.rotation, inverse_inertia_body);
}

double RigidBody::kinetic_energy() const {
  if (is_static) return 0.0;
  return sphys::kinetic_energy(pose.rotation, linear_velocity, angular_velocity, inverse_mass,
                               inertia_body);
}

namespace {

// ω = R I_body⁻¹ Rᵀ L: the angular velocity of angular momentum L at orientation q.
Vec3 angular_velocity_of(const Mat3& inverse_inertia_body, const Quat& q, const Vec3& momentum) {
  const Mat3 rotation = q.toRotationMatrix();
  return rotation * (inverse_inertia_body * (rotation.transpose() * momentum));
}

// q turned by ω over dt, to first order, renormalised.
Quat turned(const Quat& q, const Vec3& w, float dt) {
  Quat result = q;
  result.coeffs() += (0.5f * dt) * (Quat(0.0f, w.x(), w.y(), w.z()) * q).coeffs();
  result.normalize();
  return result;
}

// Fixed-point iterations of the implicit midpoint rule for the orientation.
constexpr int kMidpointIterations = 2;

}  // namespace

void integrate_position(Transform& pose, const Vec3& linear_velocity, Vec3& angular_velocity,
                        const Mat3& inertia_body, const Mat3& inverse_inertia_body, float dt) {
  pose.translation += linear_velocity * dt;

  // A torque-free body keeps its world angular momentum L = I ω while its inertia turns with it,
  // so ω changes. The turn uses ω at the middle of the step (implicit midpoint, solved by a few
  // fixed-point iterations): with ω held at its start value the kinetic energy of an asymmetric
  // spinning body drifts by percents over seconds.
  const Quat start = pose.rotation;
  const Mat3 rotation = start.toRotationMatrix();
  const Vec3 momentum = rotation * (inertia_body * (rotation.transpose() * angular_velocity));
  Vec3 w_mid = angular_velocity;
  for (int i = 0; i < kMidpointIterations; ++i) {
    w_mid = angular_velocity_of(inverse_inertia_body, turned(start, w_mid, 0.5f * dt), momentum);
  }
  pose.rotation = turned(start, w_mid, dt);
  angular_velocity = angular_velocity_of(inverse_inertia_body, pose.rotation, momentum);
}

void integrate_position(RigidBody& body, float dt) {
  if (body.is_static) return;
  integrate_position(body.pose, body.linear_velocity, body.angular_velocity, body.inertia_body,
                     body.inverse_inertia_body, dt);
}

}  // namespace sphys
