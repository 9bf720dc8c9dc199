#pragma once

// Three-vectors of lanes and the few operations the soft step's kernels use on them, written
// once over a lane type F (core/simd.h), so that every lane does the same arithmetic.

#include "dynamics/contact_lanes.h"

namespace sphys::lanes {

template <class F>
struct V3 {
  F x, y, z;
};

template <class F>
V3<F> operator+(const V3<F>& a, const V3<F>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class F>
V3<F> operator-(const V3<F>& a, const V3<F>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class F>
V3<F> operator*(const F& s, const V3<F>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class F>
F dot(const V3<F>& a, const V3<F>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class F>
V3<F> cross(const V3<F>& a, const V3<F>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

template <class F>
V3<F> load3(const float (&p)[3][F::kWidth]) {
  return {F::load(p[0]), F::load(p[1]), F::load(p[2])};
}
template <class F>
void store3(const V3<F>& a, float (&p)[3][F::kWidth]) {
  a.x.store(p[0]);
  a.y.store(p[1]);
  a.z.store(p[2]);
}
// A column-major 3 × 3 matrix (9 lanes) times a vector.
template <class F>
V3<F> times(const float (&m)[9][F::kWidth], const V3<F>& v) {
  return {F::load(m[0]) * v.x + F::load(m[3]) * v.y + F::load(m[6]) * v.z,
          F::load(m[1]) * v.x + F::load(m[4]) * v.y + F::load(m[7]) * v.z,
          F::load(m[2]) * v.x + F::load(m[5]) * v.y + F::load(m[8]) * v.z};
}
template <class F>
V3<F> times(const F (&m)[9], const V3<F>& v) {
  return {m[0] * v.x + m[3] * v.y + m[6] * v.z, m[1] * v.x + m[4] * v.y + m[7] * v.z,
          m[2] * v.x + m[5] * v.y + m[8] * v.z};
}

}  // namespace sphys::lanes
