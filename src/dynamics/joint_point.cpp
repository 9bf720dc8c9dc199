// The point rows that hold two anchors together, shared by the hinge, the ball and the weld.

#include "dynamics/joint_kinds.h"

namespace sphys {

RowBlock<3> point_rows(const JointGeometry& g) {
  return linear_rows<3>(Mat3::Identity(), g.ra, g.rb);
}

void solve_point(const JointGeometry& g, JointModel& joint, const PreparedJoint& prepared,
                 const JointPass& pass, JointBody& a, JointBody& b) {
  const RowSoftness soft = pass.use_bias
                               ? carried_softness(pass.spring, pass.bias_rate, prepared.spring_mass)
                               : RowSoftness{};
  solve_rows(point_rows(g), RowVector<3>(g.d), RowVector<3>::Zero(), soft, a, b,
             joint.impulses.linear);
}

}  // namespace sphys
