#pragma once

// The plausible mode's solver settings (docs/dynamics.md).

#include <cstdint>
#include <string_view>

namespace sphys {

// The SIMD instructions the soft step solves its contacts with, 8 contacts' manifolds at a time.
// Every choice computes the same bits; they differ in speed only.
enum class SolverLanes : std::uint8_t {
  kAuto,      // SPHYS_SIMD from the environment where it is set, else the widest the CPU has
  kPortable,  // plain floats: any processor
  kSse2,      // two SSE2 registers: every x86-64 processor
  kAvx2,      // one AVX2 register: x86-64 processors with AVX2
};

// The lanes `requested` stands for on this processor: kAuto resolved (by SPHYS_SIMD, "auto",
// "portable", "sse2" or "avx2", where it is set). Throws sphys::Error for lanes this processor or
// build lacks, or an SPHYS_SIMD it cannot read, naming what was asked and what there is.
[[nodiscard]] SolverLanes resolve_solver_lanes(SolverLanes requested);
// "auto", "portable", "sse2" or "avx2", as the setting solver.lanes names them.
[[nodiscard]] std::string_view solver_lanes_name(SolverLanes lanes);

// Which contacts of a body pair the response sees (plausible mode).
enum class ContactSet {
  kAll,      // one per overlapping leaf pair, as the paper makes them
  kReduced,  // a small manifold per body pair (see SolverSettings::manifold_points)
};

// The plausible mode's solver, the soft step (Box2D v3's; Catto's Solver2D): in each collision
// pass, substeps that each integrate, solve the contacts once with a spring-damper push out of
// penetration and relax them once, then restitution. See docs/dynamics.md for what each figure
// does and why.
struct SolverSettings {
  // Solver substeps per collision pass, each one solve and one relax pass. With 4, a heap of
  // 10,000 bunnies slept 1.03 mm deep; with 6, 0.87 mm (docs/dynamics.md). unit: substeps
  std::uint32_t soft_substeps = 6;
  // The contacts' spring, as a frequency and a damping ratio. Capped at an eighth of the substep
  // rate; contacts with an immovable body are twice as stiff. unit: Hz
  float contact_hertz = 30.0f;
  float contact_damping_ratio = 10.0f;  // unit: dimensionless, 1 is critical damping
  bool warm_starting = true;            // start from the previous collision pass's impulses
  // Approach speeds below this get no restitution, so resting contacts do not bounce. unit: m/s
  float restitution_threshold = 1.0f;
  // Penetration left alone, so that resting contacts keep touching. unit: m
  float linear_slop = 0.0004f;
  // Largest speed at which the contact springs push bodies apart. unit: m/s
  float max_correction_speed = 3.0f;
  // Rolling resistance: each contact resists the relative turning of its bodies (rolling and
  // spinning) with a torque up to this arm times its normal force, as a soft tyre or a dent in
  // the ground does. Round bodies on a rounded sphere-tree would otherwise rock and roll for
  // ever. unit: m, >= 0
  float rolling_resistance = 0.01f;
  ContactSet contacts = ContactSet::kReduced;  // every leaf pair's contact, or a manifold per pair
  std::uint32_t manifold_points = 4;           // per body pair when reduced, 1..8
  // Two bodies that can close by more than this in a collision pass (their speculative reach), and
  // by no more than the smaller one's extent, keep two contacts per pair of parts instead of one
  // manifold (the detector's, src/collision/collision_detector.h): a few points spread over one
  // mean normal stop a resting pair, not a fast approach of two non-convex bodies. unit: m, >= 0
  float fast_pair_reach = 0.03f;
  // Contacts are made this far before spheres touch, plus how far each pair can close in a
  // collision pass (speculative contacts), so that fast bodies neither tunnel nor sink in. unit: m
  float contact_margin = 0.02f;
  // Widens contact_margin by how far each pair can close in the collision pass (the "plus" above);
  // off, the margin alone.
  bool speculative_contacts = true;
  // A body pair that moved relative to itself by at most this since its trees last descended
  // keeps its manifold, recomputed at the new poses from the same leaf pairs, instead of
  // descending and reducing again (the detector's). 0 descends every pair every collision
  // pass. Off by default: on a settling pile 2 mm saved 16% of the narrow phase but the wider
  // descent's extra gap contacts cost the solver more (docs/performance.md). unit: m, >= 0
  float reuse_distance = 0.0f;
  // The instructions of the contacts' passes (World::solver_lanes() names those resolved).
  SolverLanes lanes = SolverLanes::kAuto;
};

}  // namespace sphys
