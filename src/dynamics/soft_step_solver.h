#pragma once

// The plausible mode's solver: the soft step (Catto's Solver2D "soft step", as in Box2D v3; Bepu
// v2's substepping). One collision pass feeds several solver substeps, each of which integrates
// velocities, warm starts, solves the contacts once with a soft (spring-damper) position bias,
// integrates positions and relaxes the contacts once without the bias; restitution and the
// impulses kept for the next collision pass come once at the end. In the dynamics files "the
// step" is this soft step, one solve() over one collision pass: its start is the pass's start.
// Contact separations follow the bodies' motion within the step, so speculative contacts close
// their gaps exactly. The contacts are solved as manifolds in SIMD lanes, colour by colour of the
// constraint graph (contact_lanes.h, constraint_colouring.h). See docs/dynamics.md. The member
// functions are defined by job: the constraints in soft_step_constraints.cpp, the manifolds' blocks
// in soft_step_blocks.cpp, the stages and the step in soft_step_solver.cpp.

#include <array>
#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

#include "bodies/spin_batch.h"
#include "collision/collision_detector.h"
#include "dynamics/constraint_colouring.h"
#include "dynamics/contact_lanes.h"
#include "dynamics/contact_levels.h"
#include "dynamics/joint_solver.h"
#include "dynamics/soft_step_context.h"
#include "dynamics/soft_step_stats.h"
#include "dynamics/solver_bodies.h"
#include "sphys/body_store.h"
#include "sphys/contact.h"
#include "sphys/material.h"
#include "sphys/math.h"
#include "sphys/parallel.h"
#include "sphys/solver_settings.h"

namespace sphys {

class SoftStepSolver {
 public:
  // Advances the store's awake bodies through the context's collision pass, under gravity and the
  // contacts: their velocities and poses on return are those at the end of the pass. The other
  // bodies count as static. `materials[k]` is contact k's material; `memory[k]` is its warm start
  // on entry and what it leaves for the next pass on return. The colours' blocks are solved on the
  // context's threads, and the result does not depend on how many there are. `joints`, where
  // given, are solved with the contacts, each pass of theirs on one thread before the contacts'.
  SoftStepStats solve(BodyStore& bodies, std::span<const Contact> contacts,
                      std::span<ContactMemory> memory, std::span<const PairMaterial> materials,
                      const SoftStepContext& context, JointSolver* joints = nullptr);

  // The lanes the passes run in (resolved: resolve_solver_lanes()); the same bits whichever.
  void use_lanes(SolverLanes lanes);

 private:
  // Contacts per item of the threaded loops that prepare constraints and keep their impulses.
  // unit: contacts
  static constexpr std::size_t kConstraintsPerRun = 128;
  // Two bodies whose centres (of their manifold) slip against each other slower than this at the
  // step's start are at rest together, and static friction holds them (pack_lane()). A pair struck
  // or tumbling faster is left to Coulomb's friction: held to their anchors, the bunnies of a
  // falling stack landing on a heap went 6.1% of a bunny into each other, against 1.1% to 2.9%
  // over five seeds with this. unit: m/s
  static constexpr float kAtRestSpeed = 0.2f;

  // A spring-damper's effect on an impulse in one substep (Catto, "Soft Constraints", GDC 2011):
  // how much of the rigid impulse and of the accumulated one the soft impulse takes.
  struct Softness {
    float mass_scale = 1.0f;
    float impulse_scale = 0.0f;
  };
  // One contact point as prepared, before it is packed into a manifold's lane. Slot `ground`
  // (the last) is the ground plane's.
  struct Constraint {
    std::uint32_t a = 0;
    std::uint32_t b = 0;
    Vec3 ra = Vec3::Zero();  // contact point from each centre of mass at the step's start. unit: m
    Vec3 rb = Vec3::Zero();
    Vec3 normal = Vec3::UnitY();  // from a to b
    float mass = 0.0f;            // 1 / (inverse effective mass) along the normal. unit: kg
    // Separation at the step's start less the anchors' offset along the normal, so that adding
    // the anchors' current offset gives the current separation. unit: m
    float base_separation = 0.0f;
    float approach = 0.0f;  // relative normal speed before the step. unit: m/s
    bool a_moves = false;   // the body has mass here (neither static nor asleep nor the ground)
    bool b_moves = false;
    // The weight this contact carried in the last step, as a mass. unit: kg
    float carried = 0.0f;
    // What the body's inverse mass and inertia count for in this contact (scale_supported()).
    float scale_a = 1.0f;
    float scale_b = 1.0f;
    Softness soft;  // of the solve passes, for a penetrating contact
    // Warm started: the normal impulse (unit: N·s), and this contact's kept share of its
    // manifold's friction (world frame; unit: N·s) and twist (unit: N·m·s).
    float normal_impulse = 0.0f;
    Vec3 friction_impulse = Vec3::Zero();
    float twist_impulse = 0.0f;
    // Static friction's anchor, as the contact kept it (ContactMemory::creep and stuck).
    Vec3 creep = Vec3::Zero();  // unit: m
    bool stuck = false;
    std::uint32_t contact = 0;  // its index in the contacts given to solve()
  };
  // A manifold: constraints_[first, first + count) of one body pair, count <= kManifoldPoints.
  struct Manifold {
    std::uint32_t first = 0;
    std::uint32_t count = 0;
  };
  // The substeps' work as stages, each run over its items on the threads once the one before has
  // finished: the bodies' integration in runs of bodies, and each pass colour by colour (a block
  // per item), the overflow last (one item); restitution's pass once, after the last substep.
  // The joints' passes, where there are joints, are one item each, before the contacts' own.
  enum class Work : std::uint8_t {
    kIntegrateVelocities,
    kWarmStart,
    kSolve,
    kIntegratePositions,
    kRelax,
    kRestitute,
    kRestituteAgain,  // with the joints, after kRestitute: its bounces are not counted again
    kJointWarmStart,
    kJointSolve,
    kJointRelax,
    kJointShareBounce  // the joints' relax after kRestitute, where a contact bounced
  };
  struct Stage {
    Work work = Work::kSolve;
    std::uint32_t colour = 0;  // of a pass; kOverflowColour for the overflow
  };

  void load_bodies(const BodyStore& bodies, const Parallel& parallel);
  // Each body's level in the contact graph (ContactLevels): how many contacts it is from what
  // cannot move, into support_level_.
  void find_support_levels();
  // A pair's supported body (the lower level) counts in its contacts as at least as heavy as the
  // body it carries: Constraint::scale_a and scale_b, from support_level_.
  void scale_supported(Constraint& c) const;
  // A constraint's effective masses and spring from its bodies, as scaled.
  void set_masses(Constraint& c, const SoftStepContext& context) const;
  void prepare(std::span<const Contact> contacts, std::span<const ContactMemory> memory,
               const SoftStepContext& context, SoftStepStats& stats);
  // The constraints' body pairs (pair_first_, pairs_) and their manifolds (a body pair's,
  // kManifoldPoints at most: manifolds_, manifold_bodies_).
  void cut_manifolds(const Parallel& parallel);
  // The manifolds coloured and listed by colour, and each colour's blocks counted.
  void colour_manifolds();
  // Where colour c's manifolds start in by_colour_ (c up to kOverflowColour + 1, their end).
  [[nodiscard]] std::uint32_t colour_first(std::uint32_t colour) const {
    return count_begin_[colour * kManifoldPoints];
  }
  // The manifolds into their blocks' lanes, on the threads.
  void pack(std::span<const PairMaterial> materials, const SoftStepContext& context);
  template <int W>
  void pack_lane(std::uint32_t manifold, const PairMaterial& material,
                 const SoftStepContext& context, ManifoldBlock<W>& block, int lane) const;
  // The stages of `substeps` substeps: integrate velocities, warm start, solve, integrate
  // positions, relax, each pass after the joints' own where there are `joints`; then
  // restitution.
  void plan_stages(std::size_t awake, std::uint32_t substeps, bool warm_starting,
                   bool joints = false);
  void add_stage(Work work, std::uint32_t colour, std::uint32_t items);
  void add_pass(Work work);
  // Item `item` of a stage.
  void run_item(const Stage& stage, std::uint32_t item, BodyStore& bodies,
                const SoftStepContext& context);
  // A contact pass (warm start, solve, relax or restitution) over some blocks.
  template <int W>
  void run_pass(const LaneKernels<W>& kernels, Work work, std::span<ManifoldBlock<W>> blocks,
                const LaneBodies& lanes, const LaneSettings& settings);
  void integrate_velocities(std::span<const std::uint32_t> awake, const SoftStepContext& context);
  // A run of at most kBodiesPerItem awake bodies.
  void integrate_positions(std::span<const std::uint32_t> awake, BodyStore& bodies,
                           const SoftStepContext& context);
  void keep_impulses(std::span<ContactMemory> memory, const Parallel& parallel) const;
  [[nodiscard]] LaneBodies lane_bodies();
  // The slots as the joints see them, with the store's poses.
  [[nodiscard]] JointSolverBodies joint_bodies(const BodyStore& bodies);

  std::vector<Constraint> constraints_;
  std::vector<Manifold> manifolds_;
  std::vector<ManifoldBodies> manifold_bodies_;
  ConstraintColouring colouring_;
  ContactLevels levels_;
  std::span<const std::uint32_t> support_level_;                // per slot, levels_'s, this step's
  std::vector<std::uint8_t> immovable_;                         // per slot, for levels_
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs_;  // the constraints' body pairs
  std::vector<std::uint32_t> constrained_;  // per constraint, its contact (as Constraint::contact)
  std::vector<std::uint8_t> pair_starts_;   // per constraint, 1 where a body pair's begin
  std::vector<std::uint32_t> pair_first_;   // where each body pair's constraints begin
  std::vector<std::uint32_t> run_first_;    // place_in_runs()'s scratch
  std::vector<std::uint32_t> colours_;      // per manifold
  // Where each (colour, point count) group of manifolds starts in by_colour_, as group_by lists
  // them: by colour, and within a colour by point count, most first.
  std::vector<std::uint32_t> count_begin_;
  std::vector<std::uint32_t> by_colour_;
  // Colour c's blocks are blocks_[block_begin_[c], block_begin_[c + 1]); the overflow's
  // manifolds are solved one by one.
  std::vector<ManifoldBlock<kLaneWidth>> blocks_;
  std::vector<std::uint32_t> block_begin_;
  std::vector<ManifoldBlock<1>> overflow_;
  std::vector<Stage> stages_;
  std::vector<std::uint32_t> stage_items_;
  const LaneKernels<kLaneWidth>* kernels_ = &lane_kernels(SolverLanes::kPortable);
  SpinKernel spin_kernel_ = spin_kernel(SolverLanes::kPortable);  // the same lanes' integrator
  JointSolver* joints_ = nullptr;                                 // this solve's, if it has joints
  std::atomic<std::uint32_t> bounces_{0};  // restitution's pass, counted across its items
  // Per body, and one more slot at the end for the ground plane. Velocities are written only for
  // moving bodies, each by the one lane that holds it in a colour.
  std::vector<SolverVelocity> velocity_;
  std::vector<Vec3> position_;  // at the step's start. unit: m
  std::vector<Quat> rotation_;  // at the step's start
  std::vector<float> inverse_mass_;
  std::vector<Mat3> inverse_inertia_;  // world frame, at the step's start
  // Per slot, 1 for a body with a contact deeper than a resting one's give (prepare()): static
  // friction does not hold it while it is pushed out of the overlap.
  std::vector<std::uint8_t> pushed_out_;
  // The motion since the step's start, for the contacts' separations.
  std::vector<SolverMotion> motion_;
  // The forces applied for the step as the velocities they add per second (unit: m/s² and
  // rad/s²), per slot; sized and filled only in a step where some body has one.
  std::vector<SolverVelocity> acceleration_;
  bool forced_ = false;
  // The substep length the kept impulses were solved with: they are rescaled to a new one, as an
  // impulse per substep grows with its length. unit: s
  float kept_substep_dt_ = 0.0f;
};

}  // namespace sphys
