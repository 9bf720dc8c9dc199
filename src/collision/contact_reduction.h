#pragma once

// Contact reduction (the paper's §6: "which contacts are more representative"): the leaf-pair
// contacts of one body pair become a small manifold, so that the contacts per frame grow with the
// number of touching pairs, not with the depth of the sphere-trees. See docs/dynamics.md.

#include <cstdint>
#include <span>
#include <vector>

#include "sphys/contact.h"
#include "sphys/setting_limits.h"

namespace sphys {

// Reduces the contacts of one body pair (`run`, at least one) to at most `max_points`
// (1..kMaxManifoldPoints), appended to `reduced`:
//  - a run of at most `max_points` contacts is copied unchanged;
//  - otherwise the points are chosen among the run's own contacts (their ids and points kept, so
//    that warm starting can match them from step to step): the deepest first, then the one
//    farthest from it, then the one spanning the largest triangle with those two, then the one
//    adding the most area to it (measured in the plane across the run's mean normal), then, up to
//    `max_points`, the one farthest from those chosen. Every contact of the run joins the cluster
//    of its nearest chosen point; a chosen contact's normal becomes the depth-weighted mean of its
//    cluster's normals (normalised) and its depth the cluster's largest depth.
// Persistent: `kept` is the pair's manifold from the previous narrow phase (its pair record), and
// its leaf pairs are preferred while they stay nearly as good, so that a resting pair's manifold
// does not flip between two sets whose depths differ by rounding (each flip loses the
// warm-started impulses and kicks the body): the first point is a kept one whenever a kept one is
// within kPersistentDepth of the deepest, and a kept candidate's score is worth
// kPersistentScoreBonus times a new one's. Deterministic: ties go to the earlier contact.
// Contacts with negative depth (speculative) take part like the others. Allocates only when
// `reduced` or internal scratch must grow. One reducer per thread.
class ContactReducer {
 public:
  void reduce(std::span<const Contact> run, std::uint32_t max_points, std::span<const Contact> kept,
              std::vector<Contact>& reduced);
  // Reduces a run by parts: `parts[i]` names the pair of parts run[i] lies between (any key, the
  // same for the contacts of one pair of parts); the contacts of each pair of parts are reduced
  // on their own, as above, to at most kPointsPerPart, appended in the order the pairs of parts
  // first appear in the run.
  void reduce_by_parts(std::span<const Contact> run, std::span<const std::uint64_t> parts,
                       std::span<const Contact> kept, std::vector<Contact>& reduced);

  // Points per pair of parts: the deepest and the farthest from it. With one, a 1 m box of
  // depth-3 octree parts falling at 30 m/s onto another tipped on its parts' single points and
  // sank 6.8% of its size (the bound is 5%); with two it stays within it.
  static constexpr std::uint32_t kPointsPerPart = 2;

  // A depth this close to the deepest lets a kept contact stay the first point. The cluster's
  // deepest overlap is still the manifold's depth there, so nothing goes unresolved. unit: m
  static constexpr float kPersistentDepth = 0.001f;
  static constexpr float kPersistentScoreBonus = 1.25f;  // unit: dimensionless, > 1

 private:
  std::vector<std::uint32_t> chosen_;
  std::vector<std::uint32_t> cluster_;   // per contact: the slot of its nearest chosen one
  std::vector<float> nearest_distance_;  // per contact: its squared distance to that one
  std::vector<std::uint8_t> was_kept_;   // per contact of the run
  std::vector<std::uint8_t> part_done_;  // per contact of a run reduced by parts
  std::vector<Contact> part_run_;        // one pair of parts' contacts
};

}  // namespace sphys
