// The joints' passes of the soft step: each active joint's two bodies loaded from the soft step's
// slots, its rows solved by its type (joint_kinds.h), the velocities stored back.

#include "dynamics/joint_solver.h"

#include <algorithm>
#include <cmath>

#include "dynamics/substep_change.h"

namespace sphys {
namespace {

const JointKind& kind_of(JointType type) {
  switch (type) {
    case JointType::kHinge:
      return hinge_kind();
    case JointType::kSlider:
      return slider_kind();
    case JointType::kBall:
      return ball_kind();
    case JointType::kWeld:
      return weld_kind();
    case JointType::kDistance:
      return distance_kind();
  }
  return ball_kind();
}

float mass_or_zero(float inverse_mass) { return inverse_mass > 0.0f ? 1.0f / inverse_mass : 0.0f; }

JointImpulses scaled(const JointImpulses& impulses, float scale) {
  return {.linear = scale * impulses.linear,
          .angular = scale * impulses.angular,
          .spring = scale * impulses.spring,
          .motor = scale * impulses.motor,
          .lower = scale * impulses.lower,
          .upper = scale * impulses.upper,
          .cone = scale * impulses.cone,
          .friction = scale * impulses.friction};
}

}  // namespace

JointBody JointSolver::load(const JointSolverBodies& bodies, std::uint32_t slot) const {
  JointBody body;
  body.linear = bodies.velocity[slot].linear;
  body.angular = bodies.velocity[slot].angular;
  body.inverse_mass = bodies.inverse_mass[slot];
  body.inverse_inertia = bodies.inverse_inertia[slot];
  if (slot < bodies.poses.size()) body.pose = bodies.poses[slot];
  return body;
}

void JointSolver::store(const JointSolverBodies& bodies, std::uint32_t slot,
                        const JointBody& body) {
  if (!(bodies.inverse_mass[slot] > 0.0f)) return;  // it does not move: nothing changed
  bodies.velocity[slot].linear = body.linear;
  bodies.velocity[slot].angular = body.angular;
}

void JointSolver::prepare(const JointSolverBodies& bodies, const SoftStepContext& context) {
  const auto ground = static_cast<std::uint32_t>(bodies.velocity.size() - 1);
  const float h = context.substep_dt;
  const float rescale = kept_h_ > 0.0f ? h / kept_h_ : 1.0f;
  const float last_h = kept_h_;
  kept_h_ = h;
  // The joints' rows are as stiff as the contacts against an immovable body (twice the contacts'
  // frequency, as Box2D v3's joints).
  pass_ = {.h = h,
           .inverse_h = 1.0f / h,
           .use_bias = true,
           .stiff = {.bias_rate = context.bias_rate_immovable,
                     .relative = 1.0f / context.spring_immovable},
           .spring = context.spring_immovable,
           .bias_rate = context.bias_rate_immovable};
  // The impulse that holds up a kilogram against gravity for a substep. unit: N·s/kg
  const float weight_per_substep = context.gravity.norm() * h;
  active_.clear();
  prepared_.clear();
  for (std::uint32_t j = 0; j < joints_.size(); ++j) {
    JointModel& joint = joints_[j];
    if (!joint.alive) continue;
    PreparedJoint prepared;
    prepared.a = joint.body_a == kWorldSlot ? ground : joint.body_a;
    prepared.b = joint.body_b == kWorldSlot ? ground : joint.body_b;
    const float inverse_mass_a = bodies.inverse_mass[prepared.a];
    const float inverse_mass_b = bodies.inverse_mass[prepared.b];
    if (!(inverse_mass_a > 0.0f) && !(inverse_mass_b > 0.0f)) continue;
    joint.impulses = context.warm_starting ? scaled(joint.impulses, rescale) : JointImpulses{};
    const float load = joint.desc.type == JointType::kDistance ? std::abs(joint.impulses.spring)
                                                               : joint.impulses.linear.norm();
    const float carried = weight_per_substep > 0.0f ? load / weight_per_substep : 0.0f;
    prepared.spring_mass =
        std::max({mass_or_zero(inverse_mass_a), mass_or_zero(inverse_mass_b), carried});
    prepared.spring = spring_softness(joint.desc.spring.hertz, joint.desc.spring.damping_ratio, h);
    active_.push_back(j);
    prepared_.push_back(prepared);
  }
  // Only where a joint is at work, so that a scene without joints steps as before, bit for bit.
  if (!active_.empty()) shift_to_substep(bodies, context.gravity, last_h, h);
}

void JointSolver::warm_start(const JointSolverBodies& bodies) {
  for (std::size_t k = 0; k < active_.size(); ++k) {
    const PreparedJoint& prepared = prepared_[k];
    JointBody a = load(bodies, prepared.a);
    JointBody b = load(bodies, prepared.b);
    const JointModel& joint = joints_[active_[k]];
    kind_of(joint.desc.type).warm_start(joint, a, b);
    store(bodies, prepared.a, a);
    store(bodies, prepared.b, b);
  }
}

void JointSolver::solve(const JointSolverBodies& bodies, bool use_bias) {
  pass_.use_bias = use_bias;
  for (std::size_t k = 0; k < active_.size(); ++k) {
    const PreparedJoint& prepared = prepared_[k];
    JointBody a = load(bodies, prepared.a);
    JointBody b = load(bodies, prepared.b);
    JointModel& joint = joints_[active_[k]];
    kind_of(joint.desc.type).solve(joint, prepared, pass_, a, b);
    store(bodies, prepared.a, a);
    store(bodies, prepared.b, b);
  }
}

void JointSolver::finish(const JointSolverBodies& bodies) {
  for (std::size_t k = 0; k < active_.size(); ++k) {
    const PreparedJoint& prepared = prepared_[k];
    JointModel& joint = joints_[active_[k]];
    joint.state =
        kind_of(joint.desc.type)
            .measure(joint, load(bodies, prepared.a), load(bodies, prepared.b), pass_.inverse_h);
  }
}

}  // namespace sphys
