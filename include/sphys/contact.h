#pragma once

// Contact data from overlapping spheres (paper §3.3, eq. 1-3), and the exact half-space plane.

#include <cstdint>

#include "sphys/math.h"
#include "sphys/sphere_tree.h"

namespace sphys {

// Contact::body_a of a contact with the exact ground plane.
inline constexpr std::uint32_t kGroundPlaneBody = 0xFFFFFFFFu;

// One contact between two bodies, made from one overlapping pair of spheres.
struct Contact {
  std::uint32_t body_a = 0;     // slot of body a, or kGroundPlaneBody for the ground plane
  std::uint32_t body_b = 0;     // slot of body b
  Vec3 point = Vec3::Zero();    // unit: m, world frame
  Vec3 normal = Vec3::UnitY();  // unit vector from body a towards body b, world frame
  float depth = 0.0f;           // overlap along the normal; 0 when touching. unit: m
  std::uint32_t leaf_a = 0;     // node of body a's sphere-tree (a stable feature id)
  std::uint32_t leaf_b = 0;     // node of body b's sphere-tree
};

// Centres closer than this fraction of r1 + r2 count as coincident: their direction is rounding
// noise, so the normal comes from the fallback instead. unit: dimensionless
inline constexpr float kCoincidentCentreFraction = 1e-6f;

// True when two spheres overlap or touch (closed test: touching spheres overlap, depth 0).
[[nodiscard]] inline bool spheres_overlap(const Vec3& center_a, float radius_a,
                                          const Vec3& center_b, float radius_b) {
  const float reach = radius_a + radius_b;
  return (center_b - center_a).squaredNorm() <= reach * reach;
}

// The normal to use when two spheres' centres coincide: the unit direction from body a's centre of
// mass to body b's, or when those coincide too, a direction drawn from `pair_seed` (the same seed
// gives the same direction; seeds spread uniformly over the sphere). Both points in the world
// frame, unit: m.
[[nodiscard]] Vec3 fallback_normal(const Vec3& center_of_mass_a, const Vec3& center_of_mass_b,
                                   std::uint64_t pair_seed);

// Fills contact.point, .normal and .depth for sphere a (of body a) and sphere b (of body b), both
// in the world frame, and leaves the ids alone:
//   v = C2 - C1 (eq. 1), n = v / |v| (eq. 2), P = C1 + r1 / (r1 + r2) v (eq. 3),
//   depth = r1 + r2 - |v| (negative when the spheres are apart).
// When the centres coincide (|v| < kCoincidentCentreFraction (r1 + r2)) the normal is
// `fallback` (see fallback_normal(); it must be a unit vector) and the function returns true so
// that the caller can count the case; otherwise it returns false.
[[nodiscard]] bool sphere_sphere_contact(const Sphere& a, const Sphere& b, const Vec3& fallback,
                                         Contact& contact);

// Fills contact.point, .normal and .depth for the half-space y <= plane_height (body a) and a
// sphere (body b) in the world frame, and leaves the ids alone. The normal is +y (from the plane
// towards the sphere), depth = plane_height - (C.y - r) (negative when the sphere is above the
// plane), and the point is the sphere's lowest point C - r·y: the limit of eq. 3 when the plane is
// taken as a sphere whose radius grows without bound.
void sphere_plane_contact(float plane_height, const Sphere& sphere, Contact& contact);

}  // namespace sphys
