#include "collision/contact_reduction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "core/buffers.h"
#include "sphys/error.h"

namespace sphys {
namespace {

// Added to every contact's weight in the depth-weighted means, so that touching and speculative
// contacts still count, and a run with no overlap at all gets the plain mean. A tenth of a
// millimetre is well below the overlaps the solver leaves, so overlapping contacts dominate.
// unit: m
constexpr float kDepthWeightFloor = 1e-4f;

// A weighted sum of unit normals shorter than this fraction of its total weight comes from normals
// that (nearly) cancel: its direction is rounding noise, so a fallback normal is used instead.
// unit: dimensionless
constexpr float kCancelledMeanFraction = 1e-4f;

constexpr std::uint32_t kNoCandidate = std::numeric_limits<std::uint32_t>::max();

float normal_weight(float depth) { return std::max(depth, 0.0f) + kDepthWeightFloor; }

class WeightedNormalSum {
 public:
  void add(const Contact& contact) {
    const float weight = normal_weight(contact.depth);
    sum_ += weight * contact.normal;
    total_weight_ += weight;
  }

  [[nodiscard]] Vec3 mean_or(const Vec3& fallback) const {
    const float length = sum_.norm();
    if (!(length > kCancelledMeanFraction * total_weight_)) return fallback;
    return sum_ / length;
  }

 private:
  Vec3 sum_ = Vec3::Zero();
  float total_weight_ = 0.0f;
};

std::uint32_t deepest_index(std::span<const Contact> run) {
  std::uint32_t deepest = 0;
  for (std::uint32_t i = 1; i < run.size(); ++i) {
    if (run[i].depth > run[deepest].depth) deepest = i;
  }
  return deepest;
}

// The plane across the run's normal is where the manifold must be wide to stop the bodies tipping;
// spread along the normal says nothing about that.
Vec3 run_plane_normal(std::span<const Contact> run) {
  WeightedNormalSum sum;
  for (const Contact& contact : run) sum.add(contact);
  return sum.mean_or(run[deepest_index(run)].normal);
}

float plane_distance_squared(const Vec3& p, const Vec3& q, const Vec3& normal) {
  const Vec3 offset = q - p;
  return (offset - normal.dot(offset) * normal).squaredNorm();
}

// Twice the area of the triangle's projection onto the plane across `normal`, positive when it
// winds counter-clockwise seen from the side `normal` points to. The triple product needs no
// basis of the plane.
float twice_signed_area(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& normal) {
  return normal.dot((b - a).cross(c - a));
}

// The area by which `p` grows the triangle abc's convex hull (times two): the triangles that p
// makes with the edges it lies outside of are exactly what the hull gains (p inside: nothing).
// This is the quad's hull area less the triangle's, so the 4th point maximises the quad's area.
float twice_area_added(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                       const Vec3& normal) {
  const float winding = twice_signed_area(a, b, c, normal) >= 0.0f ? 1.0f : -1.0f;
  const float outside_ab = -winding * twice_signed_area(a, b, p, normal);
  const float outside_bc = -winding * twice_signed_area(b, c, p, normal);
  const float outside_ca = -winding * twice_signed_area(c, a, p, normal);
  return std::max(outside_ab, 0.0f) + std::max(outside_bc, 0.0f) + std::max(outside_ca, 0.0f);
}

// Each contact's nearest chosen point across the plane, kept up to date as points are chosen:
// its squared distance and the chosen point's slot.
struct Nearest {
  std::vector<float>& distance_squared;
  std::vector<std::uint32_t>& slot;

  void start(std::size_t contacts) {
    fill_buffer(distance_squared, contacts, std::numeric_limits<float>::infinity());
    resize_buffer(slot, contacts);
  }
  // `chosen` (a contact of `run`) is the chosen point of slot `new_slot`; ties keep the earlier
  // slot.
  void add(std::span<const Contact> run, std::uint32_t chosen, std::uint32_t new_slot,
           const Vec3& normal) {
    for (std::size_t i = 0; i < run.size(); ++i) {
      const float distance = plane_distance_squared(run[chosen].point, run[i].point, normal);
      if (distance < distance_squared[i]) {
        distance_squared[i] = distance;
        slot[i] = new_slot;
      }
    }
  }
};

// The candidate with the largest positive `score(point, distance_squared_to_chosen)` among those
// apart from every chosen point, so that no point is chosen twice; a contact kept in the previous
// call scores kPersistentScoreBonus times more; ties go to the earlier one.
template <typename Score>
std::uint32_t best_candidate(std::span<const Contact> run, std::span<const std::uint8_t> was_kept,
                             const Nearest& nearest, Score score) {
  std::uint32_t best = kNoCandidate;
  float best_score = 0.0f;
  for (std::uint32_t i = 0; i < run.size(); ++i) {
    const float apart = nearest.distance_squared[i];
    if (!(apart > 0.0f)) continue;
    float candidate_score = score(run[i].point, apart);
    if (was_kept[i] != 0) candidate_score *= ContactReducer::kPersistentScoreBonus;
    if (candidate_score > best_score) {
      best = i;
      best_score = candidate_score;
    }
  }
  return best;
}

std::uint32_t next_point(std::span<const Contact> run, std::span<const std::uint8_t> was_kept,
                         std::span<const std::uint32_t> chosen, const Nearest& nearest,
                         const Vec3& normal) {
  std::uint32_t next = kNoCandidate;
  if (chosen.size() == 2) {
    const Vec3& a = run[chosen[0]].point;
    const Vec3& b = run[chosen[1]].point;
    next = best_candidate(run, was_kept, nearest, [&](const Vec3& p, float) {
      return std::abs(twice_signed_area(a, b, p, normal));
    });
  } else if (chosen.size() == 3) {
    const Vec3& a = run[chosen[0]].point;
    const Vec3& b = run[chosen[1]].point;
    const Vec3& c = run[chosen[2]].point;
    next = best_candidate(run, was_kept, nearest, [&](const Vec3& p, float) {
      return twice_area_added(p, a, b, c, normal);
    });
  }
  // Collinear contacts (an edge resting on a face) add no area: spreading them along their line
  // still gives the solver the widest support there is.
  if (next == kNoCandidate) {
    next = best_candidate(run, was_kept, nearest, [](const Vec3&, float apart) { return apart; });
  }
  return next;
}

// The deepest contact, or the deepest of those kept in the previous call when one is within
// kPersistentDepth of it.
std::uint32_t first_point(std::span<const Contact> run, std::span<const std::uint8_t> was_kept) {
  const std::uint32_t deepest = deepest_index(run);
  std::uint32_t first = deepest;
  for (std::uint32_t i = 0; i < run.size(); ++i) {
    if (was_kept[i] == 0 ||
        !(run[i].depth >= run[deepest].depth - ContactReducer::kPersistentDepth)) {
      continue;
    }
    if (was_kept[first] == 0 || run[i].depth > run[first].depth) first = i;
  }
  return first;
}

// Up to `max_points` contacts, each as far from the chosen ones as the rules above ask, and every
// contact's nearest chosen one (`nearest`).
void choose_points(std::span<const Contact> run, std::span<const std::uint8_t> was_kept,
                   std::uint32_t max_points, const Vec3& normal, std::vector<std::uint32_t>& chosen,
                   Nearest& nearest) {
  chosen.clear();
  nearest.start(run.size());
  std::uint32_t next = first_point(run, was_kept);
  while (true) {
    nearest.add(run, next, static_cast<std::uint32_t>(chosen.size()), normal);
    chosen.push_back(next);
    if (chosen.size() == max_points) return;
    next = next_point(run, was_kept, chosen, nearest, normal);
    if (next == kNoCandidate) return;  // every remaining contact coincides with a chosen one
  }
}

// A chosen contact stands for its whole cluster (the contacts nearest to it): the cluster's
// deepest overlap must still be resolved, and its normals together describe the surface there
// better than any single one.
void append_cluster_contacts(std::span<const Contact> run, std::span<const std::uint32_t> chosen,
                             std::span<const std::uint32_t> cluster,
                             std::vector<Contact>& reduced) {
  std::array<WeightedNormalSum, kMaxManifoldPoints> normals{};
  const std::size_t first = reduced.size();
  for (const std::uint32_t c : chosen) reduced.push_back(run[c]);
  for (std::size_t i = 0; i < run.size(); ++i) {
    normals[cluster[i]].add(run[i]);
    Contact& merged = reduced[first + cluster[i]];
    merged.depth = std::max(merged.depth, run[i].depth);
  }
  for (std::size_t slot = 0; slot < chosen.size(); ++slot) {
    Contact& merged = reduced[first + slot];
    merged.normal = normals[slot].mean_or(merged.normal);
  }
}

bool same_leaves(const Contact& a, const Contact& b) {
  return a.leaf_a == b.leaf_a && a.leaf_b == b.leaf_b;
}

}  // namespace

void ContactReducer::reduce(std::span<const Contact> run, std::uint32_t max_points,
                            std::span<const Contact> kept, std::vector<Contact>& reduced) {
  if (max_points < 1 || max_points > kMaxManifoldPoints) {
    throw Error("contact reduction: max_points must be in 1.." +
                std::to_string(kMaxManifoldPoints) + ", got " + std::to_string(max_points));
  }
  if (run.size() <= max_points) {
    reduced.insert(reduced.end(), run.begin(), run.end());
    return;
  }
  chosen_.reserve(kMaxManifoldPoints);
  resize_buffer(was_kept_, run.size());
  for (std::size_t i = 0; i < run.size(); ++i) {
    was_kept_[i] = std::any_of(kept.begin(), kept.end(),
                               [&](const Contact& k) { return same_leaves(k, run[i]); });
  }
  const Vec3 normal = run_plane_normal(run);
  Nearest nearest{nearest_distance_, cluster_};
  choose_points(run, was_kept_, max_points, normal, chosen_, nearest);
  append_cluster_contacts(run, chosen_, cluster_, reduced);
}

void ContactReducer::reduce_by_parts(std::span<const Contact> run,
                                     std::span<const std::uint64_t> parts,
                                     std::span<const Contact> kept, std::vector<Contact>& reduced) {
  fill_buffer(part_done_, run.size(), std::uint8_t{0});
  for (std::size_t i = 0; i < run.size(); ++i) {
    if (part_done_[i] != 0) continue;
    part_run_.clear();
    for (std::size_t j = i; j < run.size(); ++j) {
      if (parts[j] != parts[i]) continue;
      part_run_.push_back(run[j]);
      part_done_[j] = 1;
    }
    reduce(part_run_, kPointsPerPart, kept, reduced);
  }
}

}  // namespace sphys
