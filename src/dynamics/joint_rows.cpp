// The joints' shared parts: softness, geometry, and the spring, motor and limits along a row.

#include "dynamics/joint_rows.h"

#include <cmath>
#include <numbers>

namespace sphys {

RowSoftness spring_softness(float hertz, float zeta, float h) {
  const float omega = 2.0f * std::numbers::pi_v<float> * hertz;
  const float a1 = 2.0f * zeta + h * omega;
  const float a2 = h * omega * a1;
  if (!(a2 > 0.0f)) return {};
  return {.bias_rate = omega / a1, .relative = 1.0f / a2};
}

RowSoftness carried_softness(float spring, float bias_rate, float mass) {
  if (!(mass > 0.0f)) return {.bias_rate = bias_rate, .relative = 1.0f / spring};
  return {.bias_rate = bias_rate, .absolute = 1.0f / (mass * spring)};
}

JointGeometry joint_geometry(const JointModel& joint, const JointBody& a, const JointBody& b) {
  JointGeometry g;
  g.ra = a.pose.rotation * joint.desc.anchor_a;
  g.rb = b.pose.rotation * joint.desc.anchor_b;
  g.d = (b.pose.translation + g.rb) - (a.pose.translation + g.ra);
  g.frame_a = a.pose.rotation * joint.frame_a;
  g.frame_b = b.pose.rotation * joint.frame_b;
  g.axes_a = g.frame_a.toRotationMatrix();
  return g;
}

float twist_angle(const JointGeometry& g) {
  const Quat relative = g.frame_a.conjugate() * g.frame_b;
  float angle = 2.0f * std::atan2(relative.x(), relative.w());
  constexpr float kPi = std::numbers::pi_v<float>;
  if (angle > kPi) angle -= 2.0f * kPi;
  if (angle <= -kPi) angle += 2.0f * kPi;
  return angle;
}

float angle_error(float angle, float target) {
  return std::remainder(angle - target, 2.0f * std::numbers::pi_v<float>);
}

Vec3 rotation_error(const JointGeometry& g) {
  const Quat turn = g.frame_b * g.frame_a.conjugate();
  // The shorter way round: q and −q are the same rotation.
  const float sign = turn.w() < 0.0f ? -2.0f : 2.0f;
  return sign * turn.vec();
}

void solve_limit(const Row& row, float error, const JointPass& pass, JointBody& a, JointBody& b,
                 float& impulse) {
  RowSoftness soft;
  if (error > 0.0f) {
    soft.bias_rate = pass.inverse_h;  // speculative: stop exactly at the bound
  } else if (pass.use_bias) {
    soft = pass.stiff;
  }
  solve_row(row, error, 0.0f, soft, a, b, impulse, 0.0f);
}

namespace {

Row flipped(const Row& row) { return {-row.linear, -row.angular_a, -row.angular_b}; }

}  // namespace

void solve_axis(const Row& row, float position, float spring_error, JointModel& joint,
                const PreparedJoint& prepared, const JointPass& pass, JointBody& a, JointBody& b) {
  const JointDesc& desc = joint.desc;
  JointImpulses& impulses = joint.impulses;
  // A spring of no stiffness has no damping either: it is left out (a rope).
  if (desc.spring.enabled && desc.spring.hertz > 0.0f) {
    solve_row(row, spring_error, 0.0f, prepared.spring, a, b, impulses.spring);
  }
  if (desc.motor.enabled) {
    const float most = desc.motor.max_effort * pass.h;
    solve_row(row, 0.0f, desc.motor.speed, RowSoftness{}, a, b, impulses.motor, -most, most);
  }
  if (desc.limit.enabled) {
    solve_limit(row, position - desc.limit.lower, pass, a, b, impulses.lower);
    solve_limit(flipped(row), desc.limit.upper - position, pass, a, b, impulses.upper);
  }
}

float axis_impulse(const JointImpulses& impulses) {
  return impulses.spring + impulses.motor + impulses.lower - impulses.upper;
}

void warm_start_axis(const Row& row, const JointImpulses& impulses, JointBody& a, JointBody& b) {
  apply(row, axis_impulse(impulses), a, b);
}

}  // namespace sphys
