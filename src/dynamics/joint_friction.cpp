// Friction in a joint (JointDesc::friction): rigid rows that hold the bodies' relative motion at
// rest with a bounded impulse, as Box2D v3's ragdoll holds its joints with motors at speed 0 and
// a small most torque, so that limbs come to rest and sleep instead of swinging for ever.

#include "dynamics/joint_kinds.h"

namespace sphys {

void solve_row_friction(const Row& row, const JointModel& joint, const JointPass& pass,
                        JointBody& a, JointBody& b, float& impulse) {
  if (!(joint.desc.friction > 0.0f)) return;
  const float most = joint.desc.friction * pass.h;
  solve_row(row, 0.0f, 0.0f, RowSoftness{}, a, b, impulse, -most, most);
}

void solve_turn_friction(const JointModel& joint, const JointPass& pass, JointBody& a, JointBody& b,
                         Vec3& impulse) {
  if (!(joint.desc.friction > 0.0f)) return;
  // The three rows about the world's axes: their effective mass is the inverse of the bodies'
  // inverse inertias summed. The impulse is bounded as a vector, not axis by axis, so that the
  // friction is the same whichever way the joint turns.
  const Mat3 k = a.inverse_inertia + b.inverse_inertia;
  Mat3 inverse;
  bool invertible = false;
  k.computeInverseWithCheck(inverse, invertible);
  if (!invertible) return;
  const Vec3 before = impulse;
  impulse -= inverse * (b.angular - a.angular);
  const float most = joint.desc.friction * pass.h;
  const float length = impulse.norm();
  if (length > most) impulse *= most / length;
  apply(angular_rows<3>(Mat3::Identity()), RowVector<3>(impulse - before), a, b);
}

}  // namespace sphys
