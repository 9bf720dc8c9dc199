#pragma once

// The collision detector's settings (CollisionDetector, collision_detector.h).

#include <cstdint>
#include <limits>

#include "sphys/collision_settings.h"
#include "sphys/setting_limits.h"

namespace sphys {

// The detector's settings: the world's collision settings and what the world derives from its
// solver settings and response mode (World's detector_settings(), world.cpp, the one place).
struct DetectorSettings : CollisionSettings {
  // Leaf spheres apart by up to this gap make contacts too, with negative depth, so that a
  // response can stop bodies before they touch. unit: m
  float contact_margin = 0.0f;
  // Speculative contacts: the gap allowed for a pair grows by how far the two can close in the
  // coming step, from the motions given by set_motion() (swept sphere bounds).
  bool speculative = false;
  // Contacts per body pair: 0 keeps one per overlapping leaf pair (the paper's); 1 to
  // kMaxManifoldPoints reduces each pair's to a manifold of at most that many (contact reduction,
  // docs/dynamics.md), persistent from one narrow phase to the next through the pair's record.
  std::uint32_t manifold_points = 0;
  // With reduced contacts, a body pair whose speculative reach (how far its bodies can close in
  // the coming step, from set_motion(); the pair's gap less the contact margin) exceeds this, and
  // is no more than the smaller body's extent (pair_kind.h says why), is reduced by parts
  // instead (ContactReducer::reduce_by_parts): a small manifold per pair of parts that meet, each
  // part a first-level node of its tree with the leaves below it. Two non-convex bodies closing
  // fast meet at several places at angles one manifold does not follow (docs/dynamics.md). A body
  // and the ground plane keep their manifold: the plane's contacts share its one normal. unit: m
  float fast_pair_reach = std::numeric_limits<float>::infinity();
  // A pair whose bodies moved relative to each other by at most this since its last descent keeps
  // its contacts, recomputed from the same leaf pairs at the new poses, instead of descending and
  // reducing again. The descent looks this much beyond the pair's gap, so no leaf pair it left out
  // can come within the gap meanwhile. 0 descends every pair every time; with a time-critical
  // budget every pair descends. unit: m, >= 0
  float reuse_distance = 0.0f;
  // The deepest and mean penetration of the leaf pairs in CollisionStats: a pass over every leaf
  // pair, so only on request.
  bool measure_penetration = false;
  // Fixed when the detector is made (set_settings() keeps it).
  BroadPhaseKind broad_phase = BroadPhaseKind::kSweepAndPrune;

  // Whether a time-critical budget is on (max_sphere_tests, max_microseconds).
  [[nodiscard]] bool has_budget() const { return max_sphere_tests > 0 || max_microseconds > 0.0; }
};

}  // namespace sphys
