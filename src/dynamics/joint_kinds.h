#pragma once

// Each joint type's rows, one file each (joint_hinge.cpp, joint_slider.cpp, joint_ball.cpp,
// joint_weld.cpp, joint_distance.cpp): their warm start, one solve, and the state the joint
// reports. docs/joints.md lists every type's rows.

#include "dynamics/joint_model.h"
#include "dynamics/joint_rows.h"

namespace sphys {

struct JointKind {
  // Applies the impulses the joint's rows applied in the last substep.
  void (*warm_start)(const JointModel& joint, JointBody& a, JointBody& b);
  // One solve (pass.use_bias) or relax of its rows, in order, at the bodies' current poses.
  void (*solve)(JointModel& joint, const PreparedJoint& prepared, const JointPass& pass,
                JointBody& a, JointBody& b);
  // Its position, speed and gap at the bodies' poses and velocities, and the force and torque of
  // its last substep's impulses over `inverse_h` (unit: 1/s).
  JointState (*measure)(const JointModel& joint, const JointBody& a, const JointBody& b,
                        float inverse_h);
};

[[nodiscard]] const JointKind& hinge_kind();
[[nodiscard]] const JointKind& slider_kind();
[[nodiscard]] const JointKind& ball_kind();
[[nodiscard]] const JointKind& weld_kind();
[[nodiscard]] const JointKind& distance_kind();

// The point rows of a hinge, ball or weld: body b's anchor held to body a's, with the joint's
// carried stiffness while solving (soft_step: PreparedJoint::spring_mass), rigid while relaxing.
void solve_point(const JointGeometry& g, JointModel& joint, const PreparedJoint& prepared,
                 const JointPass& pass, JointBody& a, JointBody& b);
[[nodiscard]] RowBlock<3> point_rows(const JointGeometry& g);

// A hinge's or slider's friction along its row: a rigid row holding rate 0 whose impulse stays
// within ± JointDesc::friction h, as a motor at speed 0 (Box2D v3's ragdoll), solving and
// relaxing alike. `impulse` is its impulse so far in the substep.
void solve_row_friction(const Row& row, const JointModel& joint, const JointPass& pass,
                        JointBody& a, JointBody& b, float& impulse);
// A ball joint's friction: three rigid rows holding the relative turning at 0, their impulse a
// torque impulse of length at most JointDesc::friction h, the same about every axis.
void solve_turn_friction(const JointModel& joint, const JointPass& pass, JointBody& a, JointBody& b,
                         Vec3& impulse);

}  // namespace sphys
