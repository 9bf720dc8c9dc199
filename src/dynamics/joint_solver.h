#pragma once

// The joints' part of the soft step (soft_step_solver.h): prepared once a collision pass, then
// in each substep warm started, solved with the soft bias and relaxed without it, each pass over
// every joint in slot order on one thread, before the contacts' pass of the same kind (as Box2D
// v3 solves its joints before its contacts). One thread and one order make the same bits
// whatever the threads and lanes of the contacts. docs/joints.md.

#include <cstdint>
#include <span>
#include <vector>

#include "dynamics/joint_kinds.h"
#include "dynamics/joint_model.h"
#include "dynamics/soft_step_context.h"
#include "dynamics/solver_bodies.h"
#include "sphys/math.h"

namespace sphys {

// The soft step's bodies, as the joints solve them: its slots' velocities (the ground plane's
// last, also the world's side of a joint to it), masses of the step's start, and the store's
// poses as the substeps move them.
struct JointSolverBodies {
  std::span<SolverVelocity> velocity;
  std::span<const float> inverse_mass;    // unit: 1/kg
  std::span<const Mat3> inverse_inertia;  // world frame. unit: 1/(kg·m²)
  std::span<const Transform> poses;       // per body slot (none for the ground plane's)
};

class JointSolver {
 public:
  // The world's joints by slot, dead ones included: the solver reads and updates them in place
  // (their impulses and states) until set again.
  void set_joints(std::span<JointModel> joints) { joints_ = joints; }
  // Once a collision pass, after the soft step loaded its bodies: the joints with a moving body,
  // their impulses warm started (rescaled to a new substep length) or zeroed, and what their rows
  // share in the pass.
  void prepare(const JointSolverBodies& bodies, const SoftStepContext& context);
  // Whether the pass has no joint to solve.
  [[nodiscard]] bool empty() const { return active_.empty(); }
  // The substep passes, as the contacts': warm start, solve (use_bias) and relax.
  void warm_start(const JointSolverBodies& bodies);
  void solve(const JointSolverBodies& bodies, bool use_bias);
  // After the pass: each solved joint's state (JointState) at the bodies' final poses and
  // velocities.
  void finish(const JointSolverBodies& bodies);

 private:
  [[nodiscard]] JointBody load(const JointSolverBodies& bodies, std::uint32_t slot) const;
  static void store(const JointSolverBodies& bodies, std::uint32_t slot, const JointBody& body);

  std::span<JointModel> joints_;
  std::vector<std::uint32_t> active_;    // the joints solved in this pass, in slot order
  std::vector<PreparedJoint> prepared_;  // per active joint
  JointPass pass_;
  // The substep length the kept impulses were solved with: an impulse per substep grows with its
  // length, so they are rescaled to a new one (as the contacts'). unit: s
  float kept_h_ = 0.0f;
};

}  // namespace sphys
