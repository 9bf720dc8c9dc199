#pragma once

// A contact as the solver's constraint: its bodies' slots, whether each moves, its anchors, normal
// and tangents; and whether two constraints share their body pair. Templates over the solver's
// own constraint type, which names these fields.

#include <cstdint>
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

}  // namespace sphys
