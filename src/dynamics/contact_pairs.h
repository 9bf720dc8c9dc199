#pragma once

// What both plausible solvers do per contact and per body pair: place a contact's constraint,
// gather each body pair's rolling resistance, resist the pair's relative turning, and keep
// friction in its cone. Templates over a solver's own constraint type, which names its bodies a
// and b, whether each moves, its anchors, normal and tangents, its normal impulse, its pair's
// rolling (`pair`, `rolls`) and its contact's index.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "dynamics/tangent_basis.h"
#include "sphys/contact.h"
#include "sphys/math.h"

namespace sphys {

// Fills c's bodies (the ground plane as slot `ground`), whether each moves, its anchors from the
// bodies' centres and its normal and tangents. False when neither body moves: no constraint.
template <class Constraint>
bool place_constraint(const Contact& contact, std::uint32_t ground,
                      const std::vector<float>& inverse_mass, const std::vector<Vec3>& position,
                      Constraint& c) {
  c.a = contact.body_a == kGroundPlaneBody ? ground : contact.body_a;
  c.b = contact.body_b;
  c.a_moves = inverse_mass[c.a] > 0.0f;
  c.b_moves = inverse_mass[c.b] > 0.0f;
  if (!c.a_moves && !c.b_moves) return false;
  c.ra = contact.point - position[c.a];
  c.rb = contact.point - position[c.b];
  c.normal = contact.normal;
  tangent_basis(c.normal, c.tangent1, c.tangent2);
  return true;
}

// Whether two constraints act between the same two bodies (the same body pair).
template <class Constraint>
bool same_bodies(const Constraint& x, const Constraint& y) {
  return x.a == y.a && x.b == y.b;
}

// A constraint whose bodies have no rolling resistance between them (it is off).
inline constexpr std::uint32_t kNoRollingPair = std::numeric_limits<std::uint32_t>::max();

// Rolling resistance of one touching body pair: one angular constraint per pair rather than per
// contact, the same bound on the whole for a quarter of the work with four contacts.
struct RollingPair {
  std::uint32_t a = 0;  // the bodies' slots, as the pair's constraints name them
  std::uint32_t b = 0;
  bool a_moves = false;
  bool b_moves = false;
  // Inverse of the sum of the two bodies' inverse world inertias: the angular impulse that stops
  // their relative turning. unit: kg m²
  Mat3 mass = Mat3::Zero();
  Vec3 impulse = Vec3::Zero();  // angular, on body b. unit: N m s
  // The pair's contacts' normal impulses summed, kept current as they change
  // (set_normal_impulse), so that the bound needs no walk over them. unit: N s
  float normal_impulse = 0.0f;
};

// A body pair's contacts come one after another (the detector and the reducer emit them by
// pair): one RollingPair each, named by all of its constraints (`pair`); its first constraint
// does the pair's rolling resistance in a pass (`rolls`). Call once the constraints' normal
// impulses are set (warm started).
template <class Constraint>
void gather_rolling_pairs(std::vector<Constraint>& constraints,
                          const std::vector<Mat3>& inverse_inertia,
                          std::vector<RollingPair>& pairs) {
  pairs.clear();
  for (std::size_t first = 0; first < constraints.size();) {
    const Constraint& c = constraints[first];
    RollingPair pair{.a = c.a, .b = c.b, .a_moves = c.a_moves, .b_moves = c.b_moves};
    const Mat3 sum = inverse_inertia[c.a] + inverse_inertia[c.b];
    pair.mass = inverse_or_zero(sum);
    std::size_t end = first;
    for (; end < constraints.size() && same_bodies(constraints[end], c); ++end) {
      constraints[end].pair = static_cast<std::uint32_t>(pairs.size());
      constraints[end].rolls = end == first;
      pair.normal_impulse += constraints[end].normal_impulse;
    }
    pairs.push_back(pair);
    first = end;
  }
}

// Sets c's accumulated normal impulse, keeping its pair's sum current.
template <class Constraint>
void set_normal_impulse(Constraint& c, float total, std::vector<RollingPair>& pairs) {
  if (c.pair != kNoRollingPair) pairs[c.pair].normal_impulse += total - c.normal_impulse;
  c.normal_impulse = total;
}

// Rolling resistance: an angular impulse against the pair's relative turning (rolling and
// spinning), at most the resistance arm times the pair's normal impulse.
inline void resist_rolling(RollingPair& pair, float arm, std::vector<Vec3>& angular,
                           const std::vector<Mat3>& inverse_inertia) {
  const Vec3 turning = angular[pair.b] - angular[pair.a];
  Vec3 rolling = pair.impulse - pair.mass * turning;
  // The sum kept by changes may round a hair below zero when every contact lets go. Squares
  // compared first: the square root is paid only when the bound bites.
  const float limit = arm * std::max(pair.normal_impulse, 0.0f);
  const float length_squared = rolling.squaredNorm();
  if (length_squared > limit * limit) rolling *= limit / std::sqrt(length_squared);
  const Vec3 change = rolling - pair.impulse;
  if (pair.a_moves) angular[pair.a] -= inverse_inertia[pair.a] * change;
  if (pair.b_moves) angular[pair.b] += inverse_inertia[pair.b] * change;
  pair.impulse = rolling;
}

// Coulomb: the tangential impulse (t1, t2) is scaled back into the disc of radius `limit` (μ λn).
inline void keep_in_friction_disc(float& t1, float& t2, float limit) {
  const float length_squared = t1 * t1 + t2 * t2;
  if (length_squared > limit * limit) {
    const float scale = limit / std::sqrt(length_squared);
    t1 *= scale;
    t2 *= scale;
  }
}

}  // namespace sphys
