#pragma once

// The plausible mode's solver settings (docs/dynamics.md).

#include <cstdint>

namespace sphys {

// Which contacts of a body pair the response sees (plausible mode).
enum class ContactSet {
  kAll,      // one per overlapping leaf pair, as the paper makes them
  kReduced,  // a small manifold per body pair (see SolverSettings::manifold_points)
};

// How the plausible mode solves its contacts (docs/dynamics.md).
enum class SolverMethod {
  // Box2D v3's soft step: one collision pass, then substeps that each integrate, solve the
  // contacts once with a spring-damper push out of penetration, and relax them once.
  kSoftStep,
  // Sequential impulses over the whole step (velocity_iterations passes), split-impulse
  // penetration recovery and shock propagation.
  kSequentialImpulses,
};

// The plausible mode's solver. See docs/dynamics.md for what each figure does and why.
struct SolverSettings {
  SolverMethod method = SolverMethod::kSequentialImpulses;
  // Soft step: solver substeps per collision pass, each one solve and one relax pass.
  std::uint32_t soft_substeps = 4;
  // Soft step: the contacts' spring, as a frequency and a damping ratio. Capped at an eighth of
  // the substep rate; contacts with an immovable body are twice as stiff. unit: Hz
  float contact_hertz = 30.0f;
  float contact_damping_ratio = 10.0f;  // unit: dimensionless, 1 is critical damping
  // The passes below, position_iterations, shock propagation and position_correction are the
  // sequential-impulse method's.
  std::uint32_t velocity_iterations = 20;  // passes over the contacts for velocities per step
  // A step cut into n substeps shares its velocity passes out, velocity_iterations / n each
  // (rounded up), but gives each substep at least this many: each substep starts from the last
  // one's impulses, so a short substep needs fewer passes than a whole step. unit: passes
  std::uint32_t substep_velocity_iterations = 10;
  std::uint32_t position_iterations = 8;  // passes for the split-impulse penetration recovery
  bool warm_starting = true;              // start from the previous step's impulses
  // After the passes, solve the contacts once more level by level from the ground up, each level
  // against the one below held fixed, so that no body of a pile is left sinking into its support.
  bool shock_propagation = true;
  // Shock propagation acts on contacts still closing faster than this after the passes (a blow
  // passed on through a pile), and leaves slower ones (resting contacts) to the solver. unit: m/s
  float shock_speed = 0.5f;
  // Approach speeds below this get no restitution, so resting contacts do not bounce. unit: m/s
  float restitution_threshold = 1.0f;
  // Penetration left alone, so that resting contacts keep touching. unit: m
  float linear_slop = 0.0004f;
  // Fraction of the penetration beyond the slop removed per step. unit: dimensionless, 0..1
  float position_correction = 0.2f;
  // Largest speed of the penetration recovery (both methods). unit: m/s
  float max_correction_speed = 3.0f;
  // Rolling resistance: each contact resists the relative turning of its bodies (rolling and
  // spinning) with a torque up to this arm times its normal force, as a soft tyre or a dent in
  // the ground does. Round bodies on a rounded sphere-tree would otherwise rock and roll for
  // ever. unit: m, >= 0
  float rolling_resistance = 0.01f;
  ContactSet contacts = ContactSet::kReduced;
  std::uint32_t manifold_points = 4;  // per body pair when reduced, 1..8
  // Contacts are made this far before spheres touch, plus how far each pair can close in a step
  // (speculative contacts), so that fast bodies neither tunnel nor sink in. unit: m
  float contact_margin = 0.02f;
  bool speculative_contacts = true;
  // A body pair that moved relative to itself by at most this since its trees last descended
  // keeps its manifold, recomputed at the new poses from the same leaf pairs, instead of
  // descending and reducing again (CollisionSettings::reuse_distance). 0 descends every pair every
  // substep. Off by default: on a settling pile 2 mm saved 16% of the narrow phase but the wider
  // descent's extra gap contacts cost the solver more (docs/performance.md). unit: m, >= 0
  float reuse_distance = 0.0f;
};

}  // namespace sphys
