// The soft step's stages: the substeps' integration and passes planned as stages and run on the
// threads, colour by colour; the contacts' set-up is soft_step_constraints.cpp's, their blocks
// soft_step_blocks.cpp's.

#include "dynamics/soft_step_solver.h"

#include <algorithm>
#include <array>
#include <numbers>

#include "bodies/spin_integrator.h"
#include "dynamics/contact_lanes.h"
#include "dynamics/solver_bodies.h"
#include "sphys/rigid_body.h"

namespace sphys {
namespace {

// A spring stiffer than this fraction of the substep rate is not resolved by the substeps: its
// stiffness is capped there (as Box2D v3 does). unit: dimensionless
constexpr float kMostHertzPerSubstepRate = 0.125f;

// Contacts with an immovable body (the ground, a static or sleeping body) are this much stiffer:
// nothing on the other side gives way, and a pile's weight ends on them. unit: dimensionless
constexpr float kImmovableStiffness = 2.0f;

// Static friction pulls a crept contact back to its anchor no faster than this: creep comes at
// millimetres a second, and a pull at the contact spring's push speed (up to 3 m/s) kept piles
// stirring: five of the paper's piles came to rest at frames 552 to 695 with it, 475 to 682 with
// this, a fifth of the speed below which bodies count as still. unit: m/s
constexpr float kMostAnchorSpeed = 0.01f;

// No body turns more than this in a substep (as Box2D bounds rotation): a turn that large is
// beyond what the integrator and the contacts' separations follow, and bodies squeezed between two
// 10⁹ times heavier ones were spun up to 10¹⁹ rad/s and overflowed. 283 rad/s at 60 frames of 6
// substeps a second. unit: rad
constexpr float kMostTurnPerSubstep = 0.25f * std::numbers::pi_v<float>;

}  // namespace

void SoftStepSolver::use_lanes(SolverLanes lanes) {
  kernels_ = &lane_kernels(lanes);
  spin_kernel_ = spin_kernel(lanes);
}

LaneBodies SoftStepSolver::lane_bodies() {
  return {velocity_.data()->linear.data(), motion_.data()->moved.data()};
}

JointSolverBodies SoftStepSolver::joint_bodies(const BodyStore& bodies) {
  return {velocity_, inverse_mass_, inverse_inertia_, bodies.poses()};
}

// Turns of the joints' relax and the restitution after the step's restitution pass, where there
// are joints. Two welded boxes dropped level on a floor with friction bounced, over 2 s, 8 to
// 16 mm off one body's height with 1 to 3 turns, 2 mm with 4, 1.4 mm with 6 or 8.
constexpr int kJointRestitutionRounds = 4;

// Awake bodies in runs of this many per item of an integration stage. unit: bodies
constexpr std::uint32_t kBodiesPerItem = 64;

void SoftStepSolver::add_stage(Work work, std::uint32_t colour, std::uint32_t items) {
  if (items == 0) return;
  stages_.push_back({work, colour});
  stage_items_.push_back(items);
}

void SoftStepSolver::add_pass(Work work) {
  for (std::uint32_t colour = 0; colour < kColours; ++colour) {
    add_stage(work, colour, block_begin_[colour + 1] - block_begin_[colour]);
  }
  add_stage(work, kOverflowColour, overflow_.empty() ? 0u : 1u);
}

void SoftStepSolver::plan_stages(std::size_t awake, std::uint32_t substeps, bool warm_starting,
                                 bool joints) {
  stages_.clear();
  stage_items_.clear();
  const auto runs = static_cast<std::uint32_t>((awake + kBodiesPerItem - 1) / kBodiesPerItem);
  const std::uint32_t joint_items = joints ? 1 : 0;  // one thread, one order: the same bits
  for (std::uint32_t i = 0; i < substeps; ++i) {
    add_stage(Work::kIntegrateVelocities, 0, runs);
    if (warm_starting) {
      add_stage(Work::kJointWarmStart, 0, joint_items);
      add_pass(Work::kWarmStart);
    }
    add_stage(Work::kJointSolve, 0, joint_items);
    add_pass(Work::kSolve);
    add_stage(Work::kIntegratePositions, 0, runs);
    add_stage(Work::kJointRelax, 0, joint_items);
    add_pass(Work::kRelax);
  }
  add_pass(Work::kRestitute);
  // The bounces and the joints together: a bounce given to one of two welded boxes is the pair's
  // only once the joint shares it, and the share changes the bounce, so the joints' relax and the
  // restitution take turns (a Gauss–Seidel pass over both). Two welded boxes dropped on a
  // frictionless floor then stay within 1.3 mm of one body for 2 s, 1.5 cm without; a scene
  // without joints plans none of it, and a pass where nothing bounced skips it (its joints'
  // impulses, the forces they report, are then the substeps' alone).
  if (!joints) return;
  for (int round = 0; round < kJointRestitutionRounds; ++round) {
    add_stage(Work::kJointShareBounce, 0, joint_items);
    add_pass(Work::kRestituteAgain);
  }
}

void SoftStepSolver::run_item(const Stage& stage, std::uint32_t item, BodyStore& bodies,
                              const SoftStepContext& context) {
  switch (stage.work) {
    case Work::kJointWarmStart:
      joints_->warm_start(joint_bodies(bodies));
      return;
    case Work::kJointShareBounce:
      if (bounces_.load() == 0) return;
      [[fallthrough]];
    case Work::kJointSolve:
    case Work::kJointRelax:
      joints_->solve(joint_bodies(bodies), stage.work == Work::kJointSolve);
      return;
    default:
      break;
  }
  if (stage.work == Work::kIntegrateVelocities || stage.work == Work::kIntegratePositions) {
    const std::span<const std::uint32_t> awake = bodies.awake();
    const std::size_t first = std::size_t{item} * kBodiesPerItem;
    const std::span<const std::uint32_t> run =
        awake.subspan(first, std::min<std::size_t>(kBodiesPerItem, awake.size() - first));
    if (stage.work == Work::kIntegrateVelocities) {
      integrate_velocities(run, context);
    } else {
      integrate_positions(run, bodies, context);
    }
    return;
  }
  const LaneBodies lanes = lane_bodies();
  if (stage.colour == kOverflowColour) {
    run_pass(single_lane_kernels(), stage.work, std::span(overflow_), lanes, context.lanes);
    return;
  }
  run_pass(*kernels_, stage.work, std::span(blocks_.data() + block_begin_[stage.colour] + item, 1),
           lanes, context.lanes);
}

template <int W>
void SoftStepSolver::run_pass(const LaneKernels<W>& kernels, Work work,
                              std::span<ManifoldBlock<W>> blocks, const LaneBodies& lanes,
                              const LaneSettings& settings) {
  switch (work) {
    case Work::kWarmStart:
      kernels.warm_start(blocks, lanes);
      return;
    case Work::kSolve:
    case Work::kRelax:
      kernels.solve(blocks, lanes, settings, work == Work::kSolve);
      return;
    case Work::kRestitute:
      bounces_.fetch_add(kernels.restitute(blocks, lanes, settings));
      return;
    case Work::kRestituteAgain:
      if (bounces_.load() != 0) (void)kernels.restitute(blocks, lanes, settings);
      return;
    case Work::kIntegrateVelocities:
    case Work::kIntegratePositions:
    case Work::kJointWarmStart:
    case Work::kJointSolve:
    case Work::kJointRelax:
    case Work::kJointShareBounce:
      return;  // run_item's, per run of bodies or on the joints
  }
}

namespace {

// At most `most_spin` (unit: rad/s), the direction kept.
void bound_spin(Vec3& angular, float most_spin) {
  const float spin = angular.norm();
  if (spin > most_spin) angular *= most_spin / spin;
}

}  // namespace

void SoftStepSolver::integrate_velocities(std::span<const std::uint32_t> awake,
                                          const SoftStepContext& context) {
  const Vec3 gained = context.gravity * context.substep_dt;
  for (const std::uint32_t i : awake) velocity_[i].linear += gained;
  if (!forced_) return;
  for (const std::uint32_t i : awake) {
    velocity_[i].linear += acceleration_[i].linear * context.substep_dt;
    velocity_[i].angular += acceleration_[i].angular * context.substep_dt;
  }
}

// The bodies' poses by the solved velocities (rigid_body.h's integrator), and their motion since
// the step's start for the contacts' separations.
void SoftStepSolver::integrate_positions(std::span<const std::uint32_t> awake, BodyStore& bodies,
                                         const SoftStepContext& context) {
  const std::span<Transform> poses = bodies.poses();
  const float most_spin = kMostTurnPerSubstep / context.substep_dt;
  // The angular velocity changes too: the angular momentum is kept as the inertia turns.
  std::array<SpinningBody, kBodiesPerItem> spinning;
  for (std::size_t k = 0; k < awake.size(); ++k) {
    const std::uint32_t i = awake[k];
    bound_spin(velocity_[i].angular, most_spin);
    spinning[k] = {&poses[i], &velocity_[i].linear, &velocity_[i].angular,
                   &bodies.inertias_body()[i], &bodies.inverse_inertias_body()[i]};
  }
  integrate_positions_keeping_spin(std::span(spinning.data(), awake.size()), context.substep_dt,
                                   spin_kernel_);
  for (const std::uint32_t i : awake) {
    motion_[i] = {poses[i].translation - position_[i],
                  (poses[i].rotation * rotation_[i].conjugate()).toRotationMatrix()};
  }
}

SoftStepContext::SoftStepContext(const SolverSettings& settings, const Vec3& step_gravity,
                                 float pass_dt, std::uint32_t pass_substeps,
                                 const Parallel& threads)
    : substeps(pass_substeps),
      substep_dt(pass_dt / static_cast<float>(pass_substeps)),
      gravity(step_gravity),
      warm_starting(settings.warm_starting),
      lanes{.substep_dt = substep_dt,
            .inverse_substep_dt = 1.0f / substep_dt,
            .gravity = {step_gravity.x(), step_gravity.y(), step_gravity.z()},
            .linear_slop = settings.linear_slop,
            .max_correction_speed = settings.max_correction_speed,
            .max_anchor_speed = kMostAnchorSpeed,
            .rolling_resistance = settings.rolling_resistance,
            .restitution_threshold = settings.restitution_threshold},
      parallel(threads) {
  const float hertz = std::min(settings.contact_hertz, kMostHertzPerSubstepRate / substep_dt);
  const auto spring = [&](float omega, float& a2, float& bias_rate) {
    const float a1 = 2.0f * settings.contact_damping_ratio + substep_dt * omega;
    a2 = substep_dt * omega * a1;
    bias_rate = omega / a1;
  };
  const float omega = 2.0f * std::numbers::pi_v<float> * hertz;
  spring(omega, spring_moving, bias_rate_moving);
  spring(kImmovableStiffness * omega, spring_immovable, bias_rate_immovable);
}

SoftStepStats SoftStepSolver::solve(BodyStore& bodies, std::span<const Contact> contacts,
                                    std::span<ContactMemory> memory,
                                    std::span<const PairMaterial> materials,
                                    const SoftStepContext& context, JointSolver* joints) {
  SoftStepStats stats;
  const Parallel& parallel = context.parallel;
  load_bodies(bodies, parallel);
  if (joints != nullptr) joints->prepare(joint_bodies(bodies), context);
  joints_ = joints != nullptr && !joints->empty() ? joints : nullptr;
  prepare(contacts, memory, context, stats);
  pack(materials, context);
  plan_stages(bodies.awake().size(), context.substeps, context.warm_starting, joints_ != nullptr);
  bounces_.store(0);
  parallel.for_each_in_stages(stage_items_, [&](std::size_t stage, std::uint32_t item) {
    run_item(stages_[stage], item, bodies, context);
  });
  stats.bounces = bounces_.load();
  // The relax and restitution passes come after the last substep bounded the turns: the
  // velocities the step leaves keep the same bound (else a light body squeezed between two 10⁹
  // times heavier ones gained spin from step to step until its square overflowed).
  const float most_spin = kMostTurnPerSubstep / context.substep_dt;
  const std::span<const std::uint32_t> awake = bodies.awake();
  parallel.for_each_run(awake.size(), kConstraintsPerRun, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) bound_spin(velocity_[awake[k]].angular, most_spin);
  });
  if (joints_ != nullptr) joints_->finish(joint_bodies(bodies));
  store_solver_velocities(velocity_, parallel, bodies);
  keep_impulses(memory, parallel);
  kept_substep_dt_ = context.substep_dt;
  return stats;
}

}  // namespace sphys
