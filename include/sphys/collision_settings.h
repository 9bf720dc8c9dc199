#pragma once

// What a world's collision detection is asked to do (WorldSettings::collision and broad_phase).
// The contact settings belong to the solver (SolverSettings): the world derives the detector's
// own from both (src/collision/collision_detector.h, DetectorSettings).

#include <cstdint>
#include <optional>

namespace sphys {

// Which broad phase a world runs. Both list the same pairs in the same order.
enum class BroadPhaseKind : std::uint8_t {
  kSweepAndPrune,  // one Sweep & Prune over every body (the paper's, §3.1)
  kCells,          // Sweep & Prune per cell of a coarse grid (CellSweepAndPrune)
};

// The most levels a world or a check may be asked to use (CollisionSettings::tree_depth,
// ConfigurationCheckSettings::tree_depth). unit: levels
inline constexpr int kMostTreeDepth = 16;

// What detection does each collision pass: the trees' levels used, the time-critical budgets, the
// ground plane and crowds.
struct CollisionSettings {
  // Levels of every sphere-tree used, the root included; 0 uses them all (a depth-3 tree used as
  // depth 2: the nodes of the last used level are the leaves). unit: levels
  int tree_depth = 0;
  // Level whose spheres (with their subtree radii) bound a body for the broad phase: 0 is the
  // root's bound, cheapest to update; deeper levels give tighter boxes. unit: level
  int bounds_level = 0;
  // Time-critical narrow phase (paper §3.2): budgets for the narrow phase of a detection, shared
  // by the pairs in order; 0 turns a budget off. With both off, detection is exact.
  std::uint64_t max_sphere_tests = 0;  // unit: sphere tests per detection
  double max_microseconds = 0.0;       // unit: µs of descent per detection
  // The exact half-space ground y <= height (sphere against plane), instead of or besides a
  // static body carrying the paper's octree of a thin box. unit: m
  std::optional<float> ground_plane_height;
  // Crowds (docs/collision.md, "Crowds"): where bodies piled on each other overlap more than this
  // many others each on average, the broad phase pairs a body that overlaps more than this many
  // (a crowded one) with only its nearest half as many crowded ones, and such a pair makes one
  // contact from its trees' roots, its depth capped, so that a step's work stays bounded while
  // they part. 0 turns it off. unit: overlapping bodies per body
  std::uint32_t crowd_pairs_per_body = 32;
};

}  // namespace sphys
