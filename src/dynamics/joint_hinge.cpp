// A hinge (revolute joint): three point rows hold the anchors together, two angular rows keep
// body b's axis on body a's, and one angular row about the axis carries the friction, the spring,
// the motor and the limits (Box2D v3's revolute joint, in 3D as Jolt's HingeConstraint).

#include "dynamics/joint_kinds.h"

namespace sphys {
namespace {

void warm_start_hinge(const JointModel& joint, JointBody& a, JointBody& b) {
  const JointGeometry g = joint_geometry(joint, a, b);
  const Row about = angular_rows<1>(g.axis_a());
  apply(about, joint.impulses.friction.x(), a, b);
  warm_start_axis(about, joint.impulses, a, b);
  apply(angular_rows<2>(g.across()), RowVector<2>(joint.impulses.angular.head<2>()), a, b);
  apply(point_rows(g), RowVector<3>(joint.impulses.linear), a, b);
}

void solve_hinge(JointModel& joint, const PreparedJoint& prepared, const JointPass& pass,
                 JointBody& a, JointBody& b) {
  const JointGeometry g = joint_geometry(joint, a, b);
  const float angle = twist_angle(g);
  const Row about = angular_rows<1>(g.axis_a());
  solve_row_friction(about, joint, pass, a, b, joint.impulses.friction.x());
  solve_axis(about, angle, angle_error(angle, joint.desc.spring.target), joint, prepared, pass, a,
             b);
  // Body b's axis off body a's: a × b, the small turn that took it there.
  const Eigen::Matrix<float, 3, 2> axes = g.across();
  const Vec3 off = g.axis_a().cross(g.axis_b());
  RowVector<2> turned = joint.impulses.angular.head<2>();
  solve_rows(angular_rows<2>(axes), RowVector<2>(axes.transpose() * off), RowVector<2>::Zero(),
             pass.use_bias ? pass.stiff : RowSoftness{}, a, b, turned);
  joint.impulses.angular.head<2>() = turned;
  solve_point(g, joint, prepared, pass, a, b);
}

JointState measure_hinge(const JointModel& joint, const JointBody& a, const JointBody& b,
                         float inverse_h) {
  const JointGeometry g = joint_geometry(joint, a, b);
  const JointImpulses& impulses = joint.impulses;
  JointState state;
  state.position = twist_angle(g);
  state.speed = rate(angular_rows<1>(g.axis_a()), a, b);
  state.gap = g.d.norm();
  state.force = inverse_h * impulses.linear;
  state.torque = inverse_h * (g.across() * impulses.angular.head<2>() +
                              (axis_impulse(impulses) + impulses.friction.x()) * g.axis_a());
  return state;
}

}  // namespace

const JointKind& hinge_kind() {
  static constexpr JointKind kKind{warm_start_hinge, solve_hinge, measure_hinge};
  return kKind;
}

}  // namespace sphys
