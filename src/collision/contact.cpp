#include "sphys/contact.h"

#include <cmath>

namespace sphys {

Vec3 fallback_normal(const Vec3& center_of_mass_a, const Vec3& center_of_mass_b) {
  const Vec3 d = center_of_mass_b - center_of_mass_a;
  const float length = d.norm();
  // Same relative threshold as for sphere centres, against the distance from the origin: below it
  // the direction is rounding noise.
  const float scale = center_of_mass_a.norm() + center_of_mass_b.norm();
  if (length > 0.0f && length >= kCoincidentCentreFraction * scale) return d / length;
  return Vec3::UnitY();
}

bool sphere_sphere_contact(const Sphere& a, const Sphere& b, const Vec3& fallback,
                           Contact& contact) {
  const Vec3 v = b.center - a.center;  // paper eq. 1
  const float length = v.norm();
  const float reach = a.radius + b.radius;
  const bool coincident = !(length >= kCoincidentCentreFraction * reach);
  contact.normal = coincident ? fallback : Vec3(v / length);  // paper eq. 2
  contact.point = a.center + (a.radius / reach) * v;          // paper eq. 3
  contact.depth = reach - length;
  return coincident;
}

void sphere_plane_contact(float plane_height, const Sphere& sphere, Contact& contact) {
  contact.normal = Vec3::UnitY();
  contact.point = sphere.center - sphere.radius * Vec3::UnitY();
  contact.depth = plane_height - contact.point.y();
}

}  // namespace sphys
