#pragma once

// The soft step's contacts in lanes: manifolds (up to four contact points of one body pair, and
// the pair's rolling resistance) packed W to a block, structure of arrays, so that one pass
// solves W manifolds at a time. The manifolds of a block belong to one colour of the constraint
// graph (constraint_colouring.h): no moving body appears twice in it, so its lanes never touch the
// same velocities and the order of blocks inside a colour changes nothing. Plain floats only (no
// Eigen): contact_lanes_avx2.cpp is compiled for AVX2 apart from the rest of the library.

#include <cstddef>
#include <cstdint>
#include <span>

#include "sphys/solver_settings.h"

namespace sphys {

// Contact points per manifold: a body pair's contacts beyond this go to another manifold of the
// same pair (another colour).
inline constexpr int kManifoldPoints = 4;

// Manifolds per block, whatever the instructions: AVX2 solves a block in one register a value,
// SSE2 in two, plain floats one lane after another, so that every choice packs the same blocks.
inline constexpr int kLaneWidth = 8;

// W manifolds, lane by lane. Every array is a multiple of 4 W bytes, so that each starts on a
// W-float boundary of the 32-byte-aligned block. A lane with no manifold, or a point past a
// manifold's last, is all zeros (and names the ground's slot): solving it changes nothing.
//
// A manifold is solved as a whole (as Box3D's contact solver does): its bodies are loaded once,
// each point's normal row is solved in turn, then friction once for the manifold, at the centre
// of its points: two tangent rows solved together (a 2 × 2 effective mass) bounded by μ times the
// points' normal impulses summed, and a twist row about the normal bounded by μ times each
// point's normal impulse times its lever arm from the centre. Where the bodies stuck, the tangent
// rows also pull the centre back to its anchor in the solve passes (static friction).
template <int W>
struct alignas(32) ManifoldBlock {
  // What a point keeps is little, so that a pass streams little memory: the Jacobians' angular
  // parts (r × n) and the inverse inertias times them are made afresh in each pass from the
  // anchors and the lane's inverse inertias.
  struct Point {
    float normal[3][W];  // from body a to body b
    float ra[3][W];      // contact point from each centre of mass at the step's start. unit: m
    float rb[3][W];
    float mass[W];  // 1 / inverse effective mass along the normal. unit: kg
    // The soft spring's share of the rigid impulse and of the accumulated one (a penetrating
    // contact's solve passes).
    float mass_scale[W];
    float impulse_scale[W];
    // Separation at the step's start less the anchors' offset along the normal. unit: m
    float base_separation[W];
    float approach[W];            // the fastest approach met by the solve passes. unit: m/s
    float max_normal_impulse[W];  // over the step: did the contact push at all. unit: N s
    float impulse[W];             // accumulated along the normal. unit: N s
    float lever[W];               // from the friction centre, for the twist's bound. unit: m
  };
  Point points[kManifoldPoints];
  float inverse_mass_a[W];  // unit: 1/kg, zero for an immovable body
  float inverse_mass_b[W];
  float inverse_inertia_a[9][W];  // world frame, column-major. unit: 1/(kg m²)
  float inverse_inertia_b[9][W];
  float friction[W];
  float restitution[W];
  float bias_rate[W];  // push-out speed per metre of penetration. unit: 1/s
  // Friction at the centre: the points' mean normal and a tangent (tangent2 is normal ×
  // tangent1), the centre from each body's centre of mass at the step's start (unit: m), the
  // inverse of the tangent rows' 2 × 2 effective mass (t1t1, t1t2, t2t2; unit: kg) and the twist
  // row's mass (unit: kg m²).
  float friction_normal[3][W];
  float tangent1[3][W];
  float centre_a[3][W];
  float centre_b[3][W];
  float tangent_mass[3][W];
  float twist_mass[W];
  float friction_impulse[2][W];  // accumulated along tangent1 and tangent2. unit: N s
  float twist_impulse[W];        // accumulated about the normal, on body b. unit: N m s
  // Static friction's anchor: 1 where the bodies stuck at the end of the last step, else 0; how
  // far the centre had crept along tangent1 and tangent2 since, less the centre's offsets
  // (centre_b - centre_a), so that adding the centres' current offset gives the creep now (unit:
  // m); and the anchor spring's share of the rigid impulse and of the accumulated one.
  float stuck[W];
  float base_creep[2][W];
  float anchor_mass_scale[W];
  float anchor_impulse_scale[W];
  // Rolling resistance: the inverse of the two inverse inertias' sum (column-major; unit: kg m²)
  // and the accumulated angular impulse on body b (unit: N m s).
  float rolling_mass[9][W];
  float rolling_impulse[3][W];
  std::uint32_t body_a[W];  // slots in the solver's body arrays
  std::uint32_t body_b[W];
  std::uint32_t a_moves[W];  // 1 when the body takes impulses (written back), else 0
  std::uint32_t b_moves[W];
  std::uint32_t contact[kManifoldPoints][W];  // the point's contact, for its kept impulses
  std::uint32_t point_count;                  // the most points of any lane
};

// Floats per slot in the solver's body rows (a cache line): the lanes load and store a body as
// one row, transposed W rows at a time.
inline constexpr std::size_t kBodyRow = 16;

// The bodies' velocities and their motion since the step's start, one row of kBodyRow floats per
// slot each: linear velocity (floats 0-2, unit: m/s) and angular velocity (3-5, unit: rad/s);
// translation (0-2, unit: m) and rotation matrix, column-major (3-11), since the step's start.
struct LaneBodies {
  float* velocity;
  const float* motion;
};

struct LaneSettings {
  float substep_dt = 0.0f;                // unit: s
  float inverse_substep_dt = 0.0f;        // unit: 1/s
  float gravity[3] = {0.0f, 0.0f, 0.0f};  // unit: m/s²
  float linear_slop = 0.0f;               // unit: m
  float max_correction_speed = 0.0f;      // unit: m/s
  float max_anchor_speed = 0.0f;          // static friction's pull back to its anchor. unit: m/s
  float rolling_resistance = 0.0f;        // the arm; 0 is off. unit: m
  float restitution_threshold = 0.0f;     // unit: m/s
};

// What a pass does to blocks of one width. `bias`: the solve pass (soft push out of penetration)
// rather than the relax. restitute returns the number of points that bounced.
template <int W>
struct LaneKernels {
  void (*warm_start)(std::span<ManifoldBlock<W>> blocks, const LaneBodies& bodies);
  void (*solve)(std::span<ManifoldBlock<W>> blocks, const LaneBodies& bodies,
                const LaneSettings& settings, bool bias);
  std::uint32_t (*restitute)(std::span<ManifoldBlock<W>> blocks, const LaneBodies& bodies,
                             const LaneSettings& settings);
};

// The passes in these lanes (resolved: not kAuto), bit for bit the same whichever they are.
const LaneKernels<kLaneWidth>& lane_kernels(SolverLanes lanes);
// AVX2's, from contact_lanes_avx2.cpp (the one file compiled for AVX2); null where the build has
// none (not x86-64). Only for a processor with AVX2.
const LaneKernels<kLaneWidth>* avx2_lane_kernels();
// One manifold at a time, plain floats: the manifolds no colour could take.
const LaneKernels<1>& single_lane_kernels();

}  // namespace sphys
