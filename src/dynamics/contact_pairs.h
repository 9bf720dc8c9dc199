#pragma once

// What both plausible solvers do per contact and per body pair: place a contact's constraint,
// mark where each pair's contacts begin, resist the pair's relative turning, and keep friction in
// its cone. Templates over a solver's own constraint type, which names its bodies a and b,
// whether each moves, its anchors, normal and tangents, the pair's size and its rolling mass and
// impulse, and its contact's index.

#include <cmath>
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

// A body pair's contacts come one after another (the detector and the reducer emit them by
// pair): its first constraint gets the pair's size and the rolling resistance's mass, the inverse
// of the sum of the two bodies' inverse world inertias.
template <class Constraint>
void mark_pairs(std::vector<Constraint>& constraints, const std::vector<Mat3>& inverse_inertia) {
  for (std::size_t first = 0; first < constraints.size();) {
    std::size_t end = first + 1;
    while (end < constraints.size() && same_bodies(constraints[end], constraints[first])) ++end;
    Constraint& c = constraints[first];
    c.pair_size = static_cast<std::uint32_t>(end - first);
    const Mat3 sum = inverse_inertia[c.a] + inverse_inertia[c.b];
    // A body with no inverse inertia at all (a point mass) cannot be turned.
    if (sum.determinant() > 0.0f) c.rolling_mass = sum.inverse();
    first = end;
  }
}

// Rolling resistance: an angular impulse against the pair's relative turning (rolling and
// spinning), at most the resistance arm times the pair's normal impulse. Once per pair rather
// than per contact: the same bound on the whole, for a quarter of the work with four contacts.
// `first` is the pair's first constraint, the rest follow it.
template <class Constraint>
void resist_rolling(Constraint& first, float arm, std::vector<Vec3>& angular,
                    const std::vector<Mat3>& inverse_inertia) {
  float pair_normal_impulse = 0.0f;
  for (std::uint32_t k = 0; k < first.pair_size; ++k) {
    pair_normal_impulse += (&first)[k].normal_impulse;
  }
  const Vec3 turning = angular[first.b] - angular[first.a];
  Vec3 rolling = first.rolling_impulse - first.rolling_mass * turning;
  // Squares compared first: the square root is paid only when the bound bites.
  const float limit = arm * pair_normal_impulse;
  const float length_squared = rolling.squaredNorm();
  if (length_squared > limit * limit) rolling *= limit / std::sqrt(length_squared);
  const Vec3 change = rolling - first.rolling_impulse;
  if (first.a_moves) angular[first.a] -= inverse_inertia[first.a] * change;
  if (first.b_moves) angular[first.b] += inverse_inertia[first.b] * change;
  first.rolling_impulse = rolling;
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
