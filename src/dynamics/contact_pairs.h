#pragma once

// A contact as the solver's constraint: its bodies' slots, whether each moves, its anchors and
// normal (a template over the solver's own constraint type, which names these fields); and
// whether two contacts share their body pair.

#include <cstdint>
#include <vector>

#include "sphys/contact.h"
#include "sphys/math.h"

namespace sphys {

// The solver slot of a contact's first body: the ground plane is slot `ground`.
inline std::uint32_t first_slot(const Contact& contact, std::uint32_t ground) {
  return contact.body_a == kGroundPlaneBody ? ground : contact.body_a;
}

// Whether a contact makes a constraint: one of its bodies moves.
inline bool constrains(const Contact& contact, std::uint32_t ground,
                       const std::vector<float>& inverse_mass) {
  return inverse_mass[first_slot(contact, ground)] > 0.0f || inverse_mass[contact.body_b] > 0.0f;
}

// Fills c's bodies, whether each moves, its anchors from the bodies' centres and its normal, for a
// contact that constrains().
template <class Constraint>
void place_constraint(const Contact& contact, std::uint32_t ground,
                      const std::vector<float>& inverse_mass, const std::vector<Vec3>& position,
                      Constraint& c) {
  c.a = first_slot(contact, ground);
  c.b = contact.body_b;
  c.a_moves = inverse_mass[c.a] > 0.0f;
  c.b_moves = inverse_mass[c.b] > 0.0f;
  c.ra = contact.point - position[c.a];
  c.rb = contact.point - position[c.b];
  c.normal = contact.normal;
}

// Whether two contacts are between the same two bodies, in the same order (a body pair's
// contacts come one after another, its first body first).
inline bool same_pair(const Contact& x, const Contact& y) {
  return x.body_a == y.body_a && x.body_b == y.body_b;
}

}  // namespace sphys
