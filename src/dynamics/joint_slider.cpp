// A slider (prismatic joint): three angular rows lock the bodies' relative rotation, two linear
// rows across the axis keep body b's anchor on body a's axis, and one linear row along the axis
// carries the friction, the spring, the motor and the limits (Box2D v3's prismatic joint, in 3D).
// The linear rows act on body a at the point where body b's anchor is, so that they pass no torque
// between the bodies beyond the force's own.

#include "dynamics/joint_kinds.h"

namespace sphys {
namespace {

Row along(const JointGeometry& g) {
  return linear_rows<1>(Eigen::Matrix<float, 3, 1>(g.axis_a()), g.ra + g.d, g.rb);
}

RowBlock<2> across_rows(const JointGeometry& g) {
  return linear_rows<2>(g.across(), g.ra + g.d, g.rb);
}

void warm_start_slider(const JointModel& joint, JointBody& a, JointBody& b) {
  const JointGeometry g = joint_geometry(joint, a, b);
  apply(along(g), joint.impulses.friction.x(), a, b);
  warm_start_axis(along(g), joint.impulses, a, b);
  apply(angular_rows<3>(Mat3::Identity()), RowVector<3>(joint.impulses.angular), a, b);
  apply(across_rows(g), RowVector<2>(joint.impulses.linear.head<2>()), a, b);
}

void solve_slider(JointModel& joint, const PreparedJoint& prepared, const JointPass& pass,
                  JointBody& a, JointBody& b) {
  const JointGeometry g = joint_geometry(joint, a, b);
  const float position = g.d.dot(g.axis_a());
  solve_row_friction(along(g), joint, pass, a, b, joint.impulses.friction.x());
  solve_axis(along(g), position, position - joint.desc.spring.target, joint, prepared, pass, a, b);
  solve_rows(angular_rows<3>(Mat3::Identity()), RowVector<3>(rotation_error(g)),
             RowVector<3>::Zero(), pass.use_bias ? pass.stiff : RowSoftness{}, a, b,
             joint.impulses.angular);
  RowVector<2> held = joint.impulses.linear.head<2>();
  const RowSoftness soft = pass.use_bias
                               ? carried_softness(pass.spring, pass.bias_rate, prepared.spring_mass)
                               : RowSoftness{};
  solve_rows(across_rows(g), RowVector<2>(g.across().transpose() * g.d), RowVector<2>::Zero(), soft,
             a, b, held);
  joint.impulses.linear.head<2>() = held;
}

JointState measure_slider(const JointModel& joint, const JointBody& a, const JointBody& b,
                          float inverse_h) {
  const JointGeometry g = joint_geometry(joint, a, b);
  const JointImpulses& impulses = joint.impulses;
  JointState state;
  state.position = g.d.dot(g.axis_a());
  state.speed = rate(along(g), a, b);
  state.gap = (g.d - state.position * g.axis_a()).norm();
  state.force = inverse_h * (g.across() * impulses.linear.head<2>() +
                             (axis_impulse(impulses) + impulses.friction.x()) * g.axis_a());
  state.torque = inverse_h * impulses.angular;
  return state;
}

}  // namespace

const JointKind& slider_kind() {
  static constexpr JointKind kKind{warm_start_slider, solve_slider, measure_slider};
  return kKind;
}

}  // namespace sphys
