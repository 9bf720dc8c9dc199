// The spin integrator's kernel over a double lane type D (core/simd_double.h), four bodies at a
// time. Included inside an anonymous namespace by each file that instantiates it (spin_lanes.cpp,
// spin_lanes_avx2.cpp), so that no instance compiled for AVX2 can stand in for another.
//
// The rule is rigid_body.h's: in the body frame the angular momentum follows Euler's equations,
// dL_b/dt = L_b × I⁻¹ L_b, by the implicit midpoint rule (fixed-point iterations), which keeps
// |L_b|² and the kinetic energy ½ L_b·I⁻¹L_b, both quadratic in L_b; the orientation turns by the
// midpoint's ω. Double throughout, so that rounding adds up to no drift over thousands of
// substeps (in float, the rotation matrix's own rounding drifted the energy by 5e-4 in 10 s at
// 240 Hz). Each sum is grouped as the rule was first written with Eigen's fixed-size products
// (noted where it matters), so that the lanes give the bits that rule gave.

namespace spin {

// Fixed-point iterations of the implicit midpoint rule for the body-frame angular momentum. Each
// shrinks the error by about h |ω| (1/80 for 3 rad/s at 240 Hz): four leave the quadratic
// invariants below float rounding per step.
constexpr int kMomentumIterations = 4;
// An iteration that moves the midpoint by less than this share of |L| is a body's last: the next
// would change it by about h |ω| times as little, far below float rounding. unit: dimensionless
constexpr double kMomentumConvergence = 1e-12;
// Beyond this turn per step (h |ω|) the iterations stop converging. unit: rad
constexpr double kMostMomentumTurn = 0.5;

template <class D>
struct V3d {
  D x, y, z;
};

template <class D>
struct Quatd {
  D x, y, z, w;
};

// A column-major 3 × 3 matrix.
template <class D>
struct M3d {
  D m[9];
  [[nodiscard]] const D& at(int row, int column) const { return m[row + 3 * column]; }
};

template <class D>
V3d<D> load3(const double (&p)[3][kDoubleLanes]) {
  return {D::load(p[0]), D::load(p[1]), D::load(p[2])};
}

template <class D>
M3d<D> load9(const double (&p)[9][kDoubleLanes]) {
  M3d<D> r;
  for (int k = 0; k < 9; ++k) r.m[k] = D::load(p[k]);
  return r;
}

// x² + y² + z², summed as ((x² + y²) + z²).
template <class D>
D squared_norm(const V3d<D>& v) {
  return (v.x * v.x + v.y * v.y) + v.z * v.z;
}

// m v for a matrix held by value: the first two rows summed left to right, the third as
// a + (b + c) (Eigen's fixed-size product: a packet of two rows, then one row alone).
template <class D>
V3d<D> times(const M3d<D>& m, const V3d<D>& v) {
  return {(m.at(0, 0) * v.x + m.at(0, 1) * v.y) + m.at(0, 2) * v.z,
          (m.at(1, 0) * v.x + m.at(1, 1) * v.y) + m.at(1, 2) * v.z,
          m.at(2, 0) * v.x + (m.at(2, 1) * v.y + m.at(2, 2) * v.z)};
}

// m v for a matrix converted from float on the fly: every row as a + (b + c).
template <class D>
V3d<D> times_converted(const M3d<D>& m, const V3d<D>& v) {
  return {m.at(0, 0) * v.x + (m.at(0, 1) * v.y + m.at(0, 2) * v.z),
          m.at(1, 0) * v.x + (m.at(1, 1) * v.y + m.at(1, 2) * v.z),
          m.at(2, 0) * v.x + (m.at(2, 1) * v.y + m.at(2, 2) * v.z)};
}

// mᵀ v, every row summed left to right.
template <class D>
V3d<D> times_transposed(const M3d<D>& m, const V3d<D>& v) {
  return {(m.at(0, 0) * v.x + m.at(1, 0) * v.y) + m.at(2, 0) * v.z,
          (m.at(0, 1) * v.x + m.at(1, 1) * v.y) + m.at(2, 1) * v.z,
          (m.at(0, 2) * v.x + m.at(1, 2) * v.y) + m.at(2, 2) * v.z};
}

template <class D>
V3d<D> cross(const V3d<D>& a, const V3d<D>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// q / |q| where |q| > 0, with |q|² summed as (x² + z²) + (y² + w²) (two lanes of two).
template <class D>
Quatd<D> normalised(const Quatd<D>& q) {
  const D norm_squared = (q.x * q.x + q.z * q.z) + (q.y * q.y + q.w * q.w);
  const typename D::Mask nonzero = norm_squared > D::splat(0.0);
  const D norm = sqrt(norm_squared);
  return {select(nonzero, q.x / norm, q.x), select(nonzero, q.y / norm, q.y),
          select(nonzero, q.z / norm, q.z), select(nonzero, q.w / norm, q.w)};
}

template <class D>
M3d<D> rotation_matrix(const Quatd<D>& q) {
  const D two = D::splat(2.0);
  const D one = D::splat(1.0);
  const D tx = two * q.x;
  const D ty = two * q.y;
  const D tz = two * q.z;
  const D twx = tx * q.w;
  const D twy = ty * q.w;
  const D twz = tz * q.w;
  const D txx = tx * q.x;
  const D txy = ty * q.x;
  const D txz = tz * q.x;
  const D tyy = ty * q.y;
  const D tyz = tz * q.y;
  const D tzz = tz * q.z;
  return {{one - (tyy + tzz), txy + twz, txz - twy, txy - twz, one - (txx + tzz), tyz + twx,
           txz + twy, tyz - twx, one - (txx + tyy)}};
}

// q turned by ω over h, to first order, renormalised: q + ½ h (0, ω) q, with the product's sums
// grouped as two lanes of two.
template <class D>
Quatd<D> turned(const Quatd<D>& q, const V3d<D>& w, double h) {
  const D zero = D::splat(0.0);
  const Quatd<D> product = {
      (zero * q.x + w.y * q.z) - (w.z * q.y - w.x * q.w),
      (zero * q.y + w.y * q.w) + (w.z * q.x - w.x * q.z),
      (zero * q.z - w.y * q.x) + (w.z * q.w + w.x * q.y),
      (zero * q.w - w.y * q.y) - (w.z * q.z + w.x * q.x),
  };
  const D half_step = D::splat(0.5 * h);
  return normalised(Quatd<D>{q.x + half_step * product.x, q.y + half_step * product.y,
                             q.z + half_step * product.z, q.w + half_step * product.w});
}

template <class D>
void store_quat(const Quatd<D>& q, double (&p)[4][kDoubleLanes]) {
  q.x.store(p[0]);
  q.y.store(p[1]);
  q.z.store(p[2]);
  q.w.store(p[3]);
}

template <class D>
void turn_batch(SpinBatch& batch, double step) {
  using Mask = typename D::Mask;
  const Quatd<D> start =
      normalised(Quatd<D>{D::load(batch.rotation[0]), D::load(batch.rotation[1]),
                          D::load(batch.rotation[2]), D::load(batch.rotation[3])});
  const M3d<D> inverse_inertia = load9<D>(batch.inverse_inertia);
  const M3d<D> start_rotation = rotation_matrix(start);
  const V3d<D> omega = load3<D>(batch.angular_velocity);
  const V3d<D> momentum =
      times_converted(load9<D>(batch.inertia), times_transposed(start_rotation, omega));
  // |ω| h, squared: the body frame's ω is the world's turned.
  const D turn = D::splat(step * step) * squared_norm(omega);
  const Mask turns_too_far = not_at_most(turn, D::splat(kMostMomentumTurn * kMostMomentumTurn));
  // Until an iteration moves the midpoint by less than kMomentumConvergence of |L|: a body at rest
  // in a pile converges in two or three, a tumbling one takes all four.
  const D settled = D::splat(kMomentumConvergence * kMomentumConvergence) * squared_norm(momentum);
  const D half_step = D::splat(0.5 * step);
  V3d<D> middle = momentum;
  Mask converged = turns_too_far;
  for (int i = 0; i < kMomentumIterations && bits(converged) != (1u << kDoubleLanes) - 1; ++i) {
    const V3d<D> push = cross(middle, times(inverse_inertia, middle));
    const V3d<D> next = {momentum.x + half_step * push.x, momentum.y + half_step * push.y,
                         momentum.z + half_step * push.z};
    const V3d<D> moved = {next.x - middle.x, next.y - middle.y, next.z - middle.z};
    const Mask now_converged = squared_norm(moved) <= settled;
    middle = {select(converged, middle.x, next.x), select(converged, middle.y, next.y),
              select(converged, middle.z, next.z)};
    converged = converged | now_converged;
  }
  batch.turns_too_far = bits(turns_too_far);

  const D two = D::splat(2.0);
  const V3d<D> end = {two * middle.x - momentum.x, two * middle.y - momentum.y,
                      two * middle.z - momentum.z};
  const Quatd<D> rotation =
      turned(start, times(start_rotation, times(inverse_inertia, middle)), step);
  store_quat(rotation, batch.turned_rotation);
  const V3d<D> turned_omega = times(rotation_matrix(rotation), times(inverse_inertia, end));
  turned_omega.x.store(batch.turned_angular_velocity[0]);
  turned_omega.y.store(batch.turned_angular_velocity[1]);
  turned_omega.z.store(batch.turned_angular_velocity[2]);
}

}  // namespace spin
