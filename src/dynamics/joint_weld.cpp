// A weld (fixed joint): three angular rows lock the bodies' relative rotation and three point
// rows hold the anchors together. Stiff, as every joint's rows, or soft by its own spring
// (JointDesc::spring's frequency and damping ratio), which then acts in the relax pass too, as
// Box2D v3's weld joint with its linear and angular hertz.

#include "dynamics/joint_kinds.h"

namespace sphys {
namespace {

void warm_start_weld(const JointModel& joint, JointBody& a, JointBody& b) {
  const JointGeometry g = joint_geometry(joint, a, b);
  apply(angular_rows<3>(Mat3::Identity()), RowVector<3>(joint.impulses.angular), a, b);
  apply(point_rows(g), RowVector<3>(joint.impulses.linear), a, b);
}

void solve_weld(JointModel& joint, const PreparedJoint& prepared, const JointPass& pass,
                JointBody& a, JointBody& b) {
  const JointGeometry g = joint_geometry(joint, a, b);
  const bool soft = joint.desc.spring.enabled && joint.desc.spring.hertz > 0.0f;
  const RowSoftness locked = pass.use_bias ? pass.stiff : RowSoftness{};
  solve_rows(angular_rows<3>(Mat3::Identity()), RowVector<3>(rotation_error(g)),
             RowVector<3>::Zero(), soft ? prepared.spring : locked, a, b, joint.impulses.angular);
  if (soft) {
    solve_rows(point_rows(g), RowVector<3>(g.d), RowVector<3>::Zero(), prepared.spring, a, b,
               joint.impulses.linear);
  } else {
    solve_point(g, joint, prepared, pass, a, b);
  }
}

JointState measure_weld(const JointModel& joint, const JointBody& a, const JointBody& b,
                        float inverse_h) {
  const JointGeometry g = joint_geometry(joint, a, b);
  JointState state;
  state.gap = g.d.norm();
  state.force = inverse_h * joint.impulses.linear;
  state.torque = inverse_h * joint.impulses.angular;
  return state;
}

}  // namespace

const JointKind& weld_kind() {
  static constexpr JointKind kKind{warm_start_weld, solve_weld, measure_weld};
  return kKind;
}

}  // namespace sphys
