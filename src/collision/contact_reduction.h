#pragma once

// Contact reduction (the paper's §6: "which contacts are more representative"): the leaf-pair
// contacts of one body pair become a small manifold, so that the contacts per frame grow with the
// number of touching pairs, not with the depth of the sphere-trees. See docs/dynamics.md.

#include <cstdint>
#include <span>
#include <vector>

#include "sphys/contact.h"

namespace sphys {

// Largest manifold a body pair may be reduced to.
inline constexpr std::uint32_t kMaxManifoldPoints = 8;

// Appends to `reduced` at most `max_points` (1..kMaxManifoldPoints) contacts for each run of
// consecutive contacts with the same (body_a, body_b), in the order the runs come:
//  - a run of at most `max_points` contacts is copied unchanged;
//  - otherwise the points are chosen among the run's own contacts (their ids and points kept, so
//    that warm starting can match them from step to step): the deepest first, then the one
//    farthest from it, then the one spanning the largest triangle with those two, then the one
//    adding the most area to it (measured in the plane across the run's mean normal), then, up to
//    `max_points`, the one farthest from those chosen. Every contact of the run joins the cluster
//    of its nearest chosen point; a chosen contact's normal becomes the depth-weighted mean of its
//    cluster's normals (normalised) and its depth the cluster's largest depth.
// Deterministic: ties go to the earlier contact. Contacts with negative depth (speculative) take
// part like the others. Allocates only when `reduced` or internal scratch must grow.
class ContactReducer {
 public:
  void reduce(std::span<const Contact> contacts, std::uint32_t max_points,
              std::vector<Contact>& reduced);

 private:
  std::vector<std::uint32_t> chosen_;
  std::vector<std::uint32_t> cluster_;
};

}  // namespace sphys
