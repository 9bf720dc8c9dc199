#include "sphys/contact.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sphys {
namespace {

// A 64-bit finaliser (splitmix64's): every input bit flips about half of the output bits, so that
// neighbouring seeds (the keys of pairs of neighbouring slots) give unrelated draws.
constexpr std::uint64_t mixed_bits(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

}  // namespace

Vec3 fallback_normal(const Vec3& center_of_mass_a, const Vec3& center_of_mass_b,
                     std::uint64_t pair_seed) {
  const Vec3 d = center_of_mass_b - center_of_mass_a;
  const float length = d.norm();
  // Same relative threshold as for sphere centres, against the distance from the origin: below it
  // the direction is rounding noise.
  const float scale = center_of_mass_a.norm() + center_of_mass_b.norm();
  if (length > 0.0f && length >= kCoincidentCentreFraction * scale) return d / length;
  // Bodies at one point, as a game may spawn them: a direction drawn from the pair, uniform on the
  // sphere (z uniform in [-1, 1], the azimuth uniform), so that a crowd of them spreads every way
  // rather than standing up in a column, as one common direction would make it.
  constexpr float kUnit = 1.0f / 16777216.0f;  // 2^-24: 24 random bits to a float in [0, 1)
  const std::uint64_t bits = mixed_bits(pair_seed);
  const float z = 1.0f - 2.0f * static_cast<float>(bits >> 40) * kUnit;
  const float azimuth =
      2.0f * std::numbers::pi_v<float> * static_cast<float>((bits >> 16) & 0xffffffu) * kUnit;
  const float across = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return Vec3(across * std::cos(azimuth), z, across * std::sin(azimuth)).normalized();
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
