#include "collision/pair_kind.h"

#include <cmath>

#include "collision/collision_detector.h"

namespace sphys {
namespace {

// How far any point of a body within `extent` of its origin can have moved between two of its
// poses (relative ones here): the origin's move plus the turn's reach. unit: m
float pose_change(const Transform& from, const Transform& to, float extent) {
  Quat turn = from.rotation.conjugate() * to.rotation;
  const float angle = 2.0f * std::atan2(turn.vec().norm(), std::abs(turn.w()));
  return (to.translation - from.translation).norm() + angle * extent;
}

bool reuse_holds(const PairFacts& pair, const DetectorSettings& settings) {
  const PairCache::Record& record = *pair.record;
  if (settings.reuse_distance <= 0.0f || settings.has_budget() || record.descent_margin < 0.0f) {
    return false;
  }
  const float moved = pose_change(record.relative, *pair.relative, pair.extent_b);
  return moved <= settings.reuse_distance && pair.margin + moved <= record.descent_margin;
}

// Parts say where two bodies will meet only while they close by less than the smaller's extent:
// beyond, every part pair of the two falls within the gap (a 1 km bunny thrown at 10⁴ m/s went
// non-finite with them), and the manifold is as good a guess.
bool closing_fast(const PairFacts& pair, const DetectorSettings& settings) {
  const float reach = pair.margin - settings.contact_margin;
  return reach > settings.fast_pair_reach && reach <= pair.smaller_extent;
}

}  // namespace

PairKind pair_kind(const PairFacts& pair, const DetectorSettings& settings) {
  if (pair.crowded) return PairKind::kCrowded;
  if (reuse_holds(pair, settings)) return PairKind::kReused;
  if (settings.manifold_points == 0) return PairKind::kPaper;
  if (!pair.plane && closing_fast(pair, settings)) return PairKind::kFastByParts;
  return PairKind::kManifold;
}

}  // namespace sphys
