#include "collision/pair_kind.h"

#include <cmath>

namespace sphys {
namespace {

// How far any point of a body within `extent` of its origin can have moved between two of its
// poses (relative ones here): the origin's move plus the turn's reach. unit: m
float pose_change(const Transform& from, const Transform& to, float extent) {
  Quat turn = from.rotation.conjugate() * to.rotation;
  const float angle = 2.0f * std::atan2(turn.vec().norm(), std::abs(turn.w()));
  return (to.translation - from.translation).norm() + angle * extent;
}

}  // namespace

bool moved_within_reuse(const PairFacts& pair, const DetectorSettings& settings) {
  const PairCache::Record& record = *pair.record;
  const float moved = pose_change(record.relative, *pair.relative, pair.extent_b);
  return moved <= settings.reuse_distance && pair.margin + moved <= record.descent_margin;
}

}  // namespace sphys
