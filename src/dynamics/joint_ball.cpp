// A ball joint (spherical): three point rows hold the anchors together; an optional friction
// resists its turning about every axis (three angular rows); an optional swing cone
// keeps the angle between the bodies' axes within its half-angle (one angular row across both
// axes), and an optional twist limit bounds the turn about them (one angular row about their
// mean), with the spring and motor on the twist as a hinge's.

#include <cmath>

#include "dynamics/joint_kinds.h"

namespace sphys {
namespace {

// Below this sine the axes are taken as aligned (no swing direction) or opposed (no twist axis).
// unit: dimensionless
constexpr float kSmallestSine = 1e-6f;

// The cone's row: the swing angle's rate is the relative turning about a × b, normalised; the
// row's position is the room left in the cone, cone angle − swing angle (unit: rad). False when
// the axes are aligned.
bool cone_row(const JointGeometry& g, float cone_angle, Row& row, float& room) {
  const Vec3 a = g.axis_a();
  const Vec3 b = g.axis_b();
  const Vec3 normal = a.cross(b);
  const float sine = normal.norm();
  if (sine < kSmallestSine) return false;
  row = angular_rows<1>(Eigen::Matrix<float, 3, 1>(-normal / sine));
  room = cone_angle - std::atan2(sine, a.dot(b));
  return true;
}

// The twist's row, about the axes' mean. False when they are opposed.
bool twist_row(const JointGeometry& g, Row& row) {
  const Vec3 mean = g.axis_a() + g.axis_b();
  const float length = mean.norm();
  if (length < kSmallestSine) return false;
  row = angular_rows<1>(Eigen::Matrix<float, 3, 1>(mean / length));
  return true;
}

void warm_start_ball(const JointModel& joint, JointBody& a, JointBody& b) {
  const JointGeometry g = joint_geometry(joint, a, b);
  apply(angular_rows<3>(Mat3::Identity()), RowVector<3>(joint.impulses.friction), a, b);
  Row row;
  float room = 0.0f;
  if (cone_row(g, joint.desc.cone.angle, row, room)) apply(row, joint.impulses.cone, a, b);
  if (twist_row(g, row)) warm_start_axis(row, joint.impulses, a, b);
  apply(point_rows(g), RowVector<3>(joint.impulses.linear), a, b);
}

void solve_ball(JointModel& joint, const PreparedJoint& prepared, const JointPass& pass,
                JointBody& a, JointBody& b) {
  const JointGeometry g = joint_geometry(joint, a, b);
  solve_turn_friction(joint, pass, a, b, joint.impulses.friction);
  Row row;
  float room = 0.0f;
  if (joint.desc.cone.enabled && cone_row(g, joint.desc.cone.angle, row, room)) {
    solve_limit(row, room, pass, a, b, joint.impulses.cone);
  }
  if (twist_row(g, row)) {
    const float twist = twist_angle(g);
    solve_axis(row, twist, angle_error(twist, joint.desc.spring.target), joint, prepared, pass, a,
               b);
  }
  solve_point(g, joint, prepared, pass, a, b);
}

JointState measure_ball(const JointModel& joint, const JointBody& a, const JointBody& b,
                        float inverse_h) {
  const JointGeometry g = joint_geometry(joint, a, b);
  const JointImpulses& impulses = joint.impulses;
  JointState state;
  state.position = twist_angle(g);
  state.gap = g.d.norm();
  state.force = inverse_h * impulses.linear;
  state.torque = inverse_h * impulses.friction;
  Row row;
  float room = 0.0f;
  if (cone_row(g, joint.desc.cone.angle, row, room)) {
    state.torque += inverse_h * impulses.cone * row.angular_b.col(0);
  }
  if (twist_row(g, row)) {
    state.speed = rate(row, a, b);
    state.torque += inverse_h * axis_impulse(impulses) * row.angular_b.col(0);
  }
  return state;
}

}  // namespace

const JointKind& ball_kind() {
  static constexpr JointKind kKind{warm_start_ball, solve_ball, measure_ball};
  return kKind;
}

}  // namespace sphys
