// A distance joint: one linear row along the line between the anchors (Box2D v3's distance
// joint). Without a spring it is a rod of JointDesc::length, as stiff as every joint's rows; with
// one, a spring of that rest length (none for hertz 0: a rope), held between the limits' minimum
// and maximum length when they are on.

#include <algorithm>
#include <cmath>

#include "dynamics/joint_kinds.h"

namespace sphys {
namespace {

// Anchors closer than this have no direction between them: the row takes body a's axis. unit: m
constexpr float kShortestLine = 1e-6f;

Row line_row(const JointGeometry& g, float& length) {
  length = g.d.norm();
  const Vec3 direction = length > kShortestLine ? Vec3(g.d / length) : g.axis_a();
  return linear_rows<1>(Eigen::Matrix<float, 3, 1>(direction), g.ra, g.rb);
}

// The rod's length: the joint's, within its limits when they are on. unit: m
float rod_length(const JointDesc& desc) {
  return desc.limit.enabled ? std::clamp(desc.length, desc.limit.lower, desc.limit.upper)
                            : desc.length;
}

void warm_start_distance(const JointModel& joint, JointBody& a, JointBody& b) {
  float length = 0.0f;
  warm_start_axis(line_row(joint_geometry(joint, a, b), length), joint.impulses, a, b);
}

void solve_distance(JointModel& joint, const PreparedJoint& prepared, const JointPass& pass,
                    JointBody& a, JointBody& b) {
  float length = 0.0f;
  const Row row = line_row(joint_geometry(joint, a, b), length);
  const JointDesc& desc = joint.desc;
  if (!desc.spring.enabled) {
    const RowSoftness soft =
        pass.use_bias ? carried_softness(pass.spring, pass.bias_rate, prepared.spring_mass)
                      : RowSoftness{};
    solve_row(row, length - rod_length(desc), 0.0f, soft, a, b, joint.impulses.spring);
    return;
  }
  solve_axis(row, length, length - desc.length, joint, prepared, pass, a, b);
}

JointState measure_distance(const JointModel& joint, const JointBody& a, const JointBody& b,
                            float inverse_h) {
  const JointGeometry g = joint_geometry(joint, a, b);
  const JointDesc& desc = joint.desc;
  JointState state;
  const Row row = line_row(g, state.position);
  state.speed = rate(row, a, b);
  if (!desc.spring.enabled) {
    state.gap = std::abs(state.position - rod_length(desc));
  } else if (desc.limit.enabled) {
    state.gap =
        std::max({0.0f, desc.limit.lower - state.position, state.position - desc.limit.upper});
  }
  state.force = inverse_h * axis_impulse(joint.impulses) * row.linear.col(0);
  return state;
}

}  // namespace

const JointKind& distance_kind() {
  static constexpr JointKind kKind{warm_start_distance, solve_distance, measure_distance};
  return kKind;
}

}  // namespace sphys
