#pragma once

// What the narrow phase does with one of its jobs (a candidate pair, or a body against the ground
// plane): decided once per job by pair_kind(), from what is known before the job's leaves are
// looked for, and dispatched on in narrow_phase.cpp, once where the leaves come from
// (CollisionDetector::pair_leaves) and once where they become contacts (make_contacts).

#include <cstdint>

#include "collision/detector_settings.h"
#include "collision/pair_cache.h"
#include "sphys/math.h"

namespace sphys {

enum class PairKind : std::uint8_t {
  // Two crowded bodies (collision/crowd.h): their roots' one contact, its depth capped; never
  // reused.
  kCrowded,
  // Moved little since its last descent (DetectorSettings::reuse_distance): the record's leaf
  // pairs at the new poses, each contact with its kept depth offset and normal.
  kReused,
  // One contact per leaf pair within the gap (the paper's, eq. 1-3; manifold_points 0).
  kPaper,
  // Two bodies closing fast (DetectorSettings::fast_pair_reach): a small manifold per pair of
  // parts that meet.
  kFastByParts,
  // One manifold of at most manifold_points, persistent through the record.
  kManifold,
};

// What pair_kind() reads of a job.
struct PairFacts {
  const PairCache::Record* record = nullptr;  // as the job's last narrow phase left it
  // Body b's pose in body a's frame (the world's, against the ground plane).
  const Transform* relative = nullptr;
  float margin = 0.0f;          // the gap up to which its spheres make contacts. unit: m
  float extent_b = 0.0f;        // how far body b reaches from its origin. unit: m
  float smaller_extent = 0.0f;  // the smaller of the two bodies' extents. unit: m
  bool plane = false;           // a body against the ground plane
  bool crowded = false;         // both bodies crowded (CollisionDetector::crowded)
};

// Whether a pair moved little enough since its last descent to be reused, given that reuse is on,
// no budget is, and its last descent is valid (pair_kind.cpp).
[[nodiscard]] bool moved_within_reuse(const PairFacts& pair, const DetectorSettings& settings);

// Parts say where two bodies will meet only while they close by less than the smaller's extent:
// beyond, every part pair of the two falls within the gap (a 1 km bunny thrown at 10⁴ m/s went
// non-finite with them), and the manifold is as good a guess.
[[nodiscard]] inline bool closing_fast(const PairFacts& pair, const DetectorSettings& settings) {
  const float reach = pair.margin - settings.contact_margin;
  return reach > settings.fast_pair_reach && reach <= pair.smaller_extent;
}

// The first that holds of: crowded; reusable (it moved by at most reuse_distance since its last
// descent, and its gap grown by that move is within the gap that descent looked up to, so no leaf
// pair it left out can have come within the gap); paper (no reduction); fast (not against the
// plane, whose contacts share one normal: the bodies can close in the step by more than
// fast_pair_reach and by no more than the smaller's extent, see closing_fast()); manifold. No
// pair is reused under a time-critical budget.
// Inline: it runs once per pair in the narrow phase, the hottest code of a step.
[[nodiscard]] inline PairKind pair_kind(const PairFacts& pair, const DetectorSettings& settings) {
  if (pair.crowded) return PairKind::kCrowded;
  if (settings.reuse_distance > 0.0f && !settings.has_budget() &&
      pair.record->descent_margin >= 0.0f && moved_within_reuse(pair, settings)) {
    return PairKind::kReused;
  }
  if (settings.manifold_points == 0) return PairKind::kPaper;
  if (!pair.plane && closing_fast(pair, settings)) return PairKind::kFastByParts;
  return PairKind::kManifold;
}

}  // namespace sphys
