#pragma once

// The bodies of a block's lanes as the soft step's kernels see them: gathered from the solver's
// rows by slot, pushed by impulses, scattered back; and a manifold's friction frame.

#include <cstdint>

#include "dynamics/contact_lanes.h"
#include "dynamics/lane_vectors.h"

namespace sphys::lanes {

// One body of each lane, gathered from the solver's rows by slot and scattered back.
template <class F>
struct LaneBody {
  static constexpr int W = F::kWidth;
  V3<F> linear;
  V3<F> angular;
  F rest[2];  // the row's floats past the velocities, written back as they were

  static LaneBody gather(const LaneBodies& bodies, const std::uint32_t (&slot)[W]) {
    F row[kRow];
    F::load_rows(bodies.velocity, slot, kBodyRow, row);
    return {{row[0], row[1], row[2]}, {row[3], row[4], row[5]}, {row[6], row[7]}};
  }
  // Written back only where the lane's body moves: immovable bodies are shared by lanes and by
  // blocks on other threads, and keep their zero velocities.
  void scatter(const LaneBodies& bodies, const std::uint32_t (&slot)[W],
               const std::uint32_t (&moves)[W]) const {
    const F row[kRow] = {linear.x,  linear.y,  linear.z, angular.x,
                         angular.y, angular.z, rest[0],  rest[1]};
    F::store_rows(row, bodies.velocity, slot, kBodyRow, moves);
  }
};

// Each lane's body motion since the step's start: translation and rotation matrix.
template <class F>
struct LaneMotion {
  static constexpr int W = F::kWidth;
  V3<F> moved;
  F turned[9];

  static LaneMotion gather(const LaneBodies& bodies, const std::uint32_t (&slot)[W]) {
    F first[kRow];
    F second[kRow];
    F::load_rows(bodies.motion, slot, kBodyRow, first);
    F::load_rows(bodies.motion + kRow, slot, kBodyRow, second);
    return {{first[0], first[1], first[2]},
            {first[3], first[4], first[5], first[6], first[7], second[0], second[1], second[2],
             second[3]}};
  }
};

// A lane's two bodies as a contact sees them: velocities, inverse masses and world inverse
// inertias (3 × 3, column-major, loaded once per block).
template <class F>
struct LanePair {
  static constexpr int W = F::kWidth;
  LaneBody<F> a;
  LaneBody<F> b;
  F inverse_mass_a;
  F inverse_mass_b;
  F inverse_inertia_a[9];
  F inverse_inertia_b[9];

  LanePair(const ManifoldBlock<W>& m, const LaneBodies& bodies)
      : a(LaneBody<F>::gather(bodies, m.body_a)),
        b(LaneBody<F>::gather(bodies, m.body_b)),
        inverse_mass_a(F::load(m.inverse_mass_a)),
        inverse_mass_b(F::load(m.inverse_mass_b)) {
    for (int k = 0; k < 9; ++k) {
      inverse_inertia_a[k] = F::load(m.inverse_inertia_a[k]);
      inverse_inertia_b[k] = F::load(m.inverse_inertia_b[k]);
    }
  }
  void scatter(const ManifoldBlock<W>& m, const LaneBodies& bodies) const {
    a.scatter(bodies, m.body_a, m.a_moves);
    b.scatter(bodies, m.body_b, m.b_moves);
  }
  // The velocity of b's point at rb relative to a's point at ra. unit: m/s
  [[nodiscard]] V3<F> relative_velocity(const V3<F>& ra, const V3<F>& rb) const {
    return b.linear + cross(b.angular, rb) - a.linear - cross(a.angular, ra);
  }
  // An impulse at the point (ra from a's centre, rb from b's): a takes minus, b plus.
  void push(const V3<F>& ra, const V3<F>& rb, const V3<F>& impulse) {
    a.linear = a.linear - inverse_mass_a * impulse;
    b.linear = b.linear + inverse_mass_b * impulse;
    a.angular = a.angular - times<F>(inverse_inertia_a, cross(ra, impulse));
    b.angular = b.angular + times<F>(inverse_inertia_b, cross(rb, impulse));
  }
  // An angular impulse on b, its opposite on a.
  void turn(const V3<F>& impulse) {
    a.angular = a.angular - times<F>(inverse_inertia_a, impulse);
    b.angular = b.angular + times<F>(inverse_inertia_b, impulse);
  }
};

// The manifold's friction frame: its normal, tangent1 and tangent2 = normal × tangent1.
template <class F>
struct FrictionFrame {
  V3<F> normal, tangent1, tangent2;

  explicit FrictionFrame(const ManifoldBlock<F::kWidth>& m)
      : normal(load3<F>(m.friction_normal)),
        tangent1(load3<F>(m.tangent1)),
        tangent2(cross(normal, tangent1)) {}
};

}  // namespace sphys::lanes
