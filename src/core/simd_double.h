#pragma once

// Doubles in four lanes: the few operations the spin integrator's kernel
// (bodies/spin_kernel.h) does four bodies at a time. Three kinds with the same operations:
// - PortableDoubleLanes: plain doubles, for any processor;
// - Sse2DoubleLanes: two SSE2 registers of two, x86-64's baseline;
// - Avx2DoubleLanes: one AVX2 register, only where the translation unit is compiled with -mavx2.
// Every operation is one correctly rounded IEEE operation per lane and none fuses a multiply and
// an add (the library is compiled with -ffp-contract=off), so they all give the same bits.

#include <array>
#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace sphys {

// The lanes of every double lane set. unit: lanes
inline constexpr int kDoubleLanes = 4;

struct PortableDoubleLanes {
  struct Mask {
    std::array<bool, kDoubleLanes> on{};
  };
  std::array<double, kDoubleLanes> v{};

  static PortableDoubleLanes load(const double* p) {
    PortableDoubleLanes r;
    for (int i = 0; i < kDoubleLanes; ++i) r.v[i] = p[i];
    return r;
  }
  static PortableDoubleLanes splat(double x) {
    PortableDoubleLanes r;
    r.v.fill(x);
    return r;
  }
  void store(double* p) const {
    for (int i = 0; i < kDoubleLanes; ++i) p[i] = v[i];
  }
  template <class Op>
  friend PortableDoubleLanes each(const PortableDoubleLanes& a, const PortableDoubleLanes& b,
                                  Op op) {
    PortableDoubleLanes r;
    for (int i = 0; i < kDoubleLanes; ++i) r.v[i] = op(a.v[i], b.v[i]);
    return r;
  }
  friend PortableDoubleLanes operator+(PortableDoubleLanes a, PortableDoubleLanes b) {
    return each(a, b, [](double x, double y) { return x + y; });
  }
  friend PortableDoubleLanes operator-(PortableDoubleLanes a, PortableDoubleLanes b) {
    return each(a, b, [](double x, double y) { return x - y; });
  }
  friend PortableDoubleLanes operator*(PortableDoubleLanes a, PortableDoubleLanes b) {
    return each(a, b, [](double x, double y) { return x * y; });
  }
  friend PortableDoubleLanes operator/(PortableDoubleLanes a, PortableDoubleLanes b) {
    return each(a, b, [](double x, double y) { return x / y; });
  }
  friend PortableDoubleLanes sqrt(PortableDoubleLanes a) {
    PortableDoubleLanes r;
    for (int i = 0; i < kDoubleLanes; ++i) r.v[i] = std::sqrt(a.v[i]);
    return r;
  }
  template <class Compare>
  friend Mask compare(const PortableDoubleLanes& a, const PortableDoubleLanes& b, Compare compare) {
    Mask m;
    for (int i = 0; i < kDoubleLanes; ++i) m.on[i] = compare(a.v[i], b.v[i]);
    return m;
  }
  friend Mask operator<=(PortableDoubleLanes a, PortableDoubleLanes b) {
    return compare(a, b, [](double x, double y) { return x <= y; });
  }
  friend Mask operator>(PortableDoubleLanes a, PortableDoubleLanes b) {
    return compare(a, b, [](double x, double y) { return x > y; });
  }
  // !(a <= b): true with a NaN.
  friend Mask not_at_most(PortableDoubleLanes a, PortableDoubleLanes b) {
    return compare(a, b, [](double x, double y) { return !(x <= y); });
  }
  friend Mask operator|(Mask a, Mask b) {
    Mask m;
    for (int i = 0; i < kDoubleLanes; ++i) m.on[i] = a.on[i] || b.on[i];
    return m;
  }
  // Lane i's flag as bit i.
  friend std::uint32_t bits(Mask m) {
    std::uint32_t out = 0;
    for (int i = 0; i < kDoubleLanes; ++i) out |= m.on[i] ? 1u << i : 0u;
    return out;
  }
  // a where the mask is on, else b.
  friend PortableDoubleLanes select(Mask m, PortableDoubleLanes a, PortableDoubleLanes b) {
    PortableDoubleLanes r;
    for (int i = 0; i < kDoubleLanes; ++i) r.v[i] = m.on[i] ? a.v[i] : b.v[i];
    return r;
  }
};

#if defined(__SSE2__)
// Lanes 0-1 in `lo`, 2-3 in `hi`.
struct Sse2DoubleLanes {
  struct Mask {
    __m128d lo, hi;
  };
  __m128d lo, hi;

  static Sse2DoubleLanes load(const double* p) { return {_mm_load_pd(p), _mm_load_pd(p + 2)}; }
  static Sse2DoubleLanes splat(double x) { return {_mm_set1_pd(x), _mm_set1_pd(x)}; }
  void store(double* p) const {
    _mm_store_pd(p, lo);
    _mm_store_pd(p + 2, hi);
  }
  friend Sse2DoubleLanes operator+(Sse2DoubleLanes a, Sse2DoubleLanes b) {
    return {_mm_add_pd(a.lo, b.lo), _mm_add_pd(a.hi, b.hi)};
  }
  friend Sse2DoubleLanes operator-(Sse2DoubleLanes a, Sse2DoubleLanes b) {
    return {_mm_sub_pd(a.lo, b.lo), _mm_sub_pd(a.hi, b.hi)};
  }
  friend Sse2DoubleLanes operator*(Sse2DoubleLanes a, Sse2DoubleLanes b) {
    return {_mm_mul_pd(a.lo, b.lo), _mm_mul_pd(a.hi, b.hi)};
  }
  friend Sse2DoubleLanes operator/(Sse2DoubleLanes a, Sse2DoubleLanes b) {
    return {_mm_div_pd(a.lo, b.lo), _mm_div_pd(a.hi, b.hi)};
  }
  friend Sse2DoubleLanes sqrt(Sse2DoubleLanes a) { return {_mm_sqrt_pd(a.lo), _mm_sqrt_pd(a.hi)}; }
  friend Mask operator<=(Sse2DoubleLanes a, Sse2DoubleLanes b) {
    return {_mm_cmple_pd(a.lo, b.lo), _mm_cmple_pd(a.hi, b.hi)};
  }
  friend Mask operator>(Sse2DoubleLanes a, Sse2DoubleLanes b) {
    return {_mm_cmpgt_pd(a.lo, b.lo), _mm_cmpgt_pd(a.hi, b.hi)};
  }
  friend Mask not_at_most(Sse2DoubleLanes a, Sse2DoubleLanes b) {
    return {_mm_cmpnle_pd(a.lo, b.lo), _mm_cmpnle_pd(a.hi, b.hi)};
  }
  friend Mask operator|(Mask a, Mask b) { return {_mm_or_pd(a.lo, b.lo), _mm_or_pd(a.hi, b.hi)}; }
  friend std::uint32_t bits(Mask m) {
    return static_cast<std::uint32_t>(_mm_movemask_pd(m.lo) | (_mm_movemask_pd(m.hi) << 2));
  }
  friend Sse2DoubleLanes select(Mask m, Sse2DoubleLanes a, Sse2DoubleLanes b) {
    return {_mm_or_pd(_mm_and_pd(m.lo, a.lo), _mm_andnot_pd(m.lo, b.lo)),
            _mm_or_pd(_mm_and_pd(m.hi, a.hi), _mm_andnot_pd(m.hi, b.hi))};
  }
};
#endif

#if defined(__AVX2__)
struct Avx2DoubleLanes {
  struct Mask {
    __m256d on;
  };
  __m256d v;

  static Avx2DoubleLanes load(const double* p) { return {_mm256_load_pd(p)}; }
  static Avx2DoubleLanes splat(double x) { return {_mm256_set1_pd(x)}; }
  void store(double* p) const { _mm256_store_pd(p, v); }
  friend Avx2DoubleLanes operator+(Avx2DoubleLanes a, Avx2DoubleLanes b) {
    return {_mm256_add_pd(a.v, b.v)};
  }
  friend Avx2DoubleLanes operator-(Avx2DoubleLanes a, Avx2DoubleLanes b) {
    return {_mm256_sub_pd(a.v, b.v)};
  }
  friend Avx2DoubleLanes operator*(Avx2DoubleLanes a, Avx2DoubleLanes b) {
    return {_mm256_mul_pd(a.v, b.v)};
  }
  friend Avx2DoubleLanes operator/(Avx2DoubleLanes a, Avx2DoubleLanes b) {
    return {_mm256_div_pd(a.v, b.v)};
  }
  friend Avx2DoubleLanes sqrt(Avx2DoubleLanes a) { return {_mm256_sqrt_pd(a.v)}; }
  // Ordered, non-signalling: false with a NaN, as SSE2's cmple and cmpgt.
  friend Mask operator<=(Avx2DoubleLanes a, Avx2DoubleLanes b) {
    return {_mm256_cmp_pd(a.v, b.v, _CMP_LE_OQ)};
  }
  friend Mask operator>(Avx2DoubleLanes a, Avx2DoubleLanes b) {
    return {_mm256_cmp_pd(a.v, b.v, _CMP_GT_OQ)};
  }
  // Unordered: true with a NaN, as SSE2's cmpnle.
  friend Mask not_at_most(Avx2DoubleLanes a, Avx2DoubleLanes b) {
    return {_mm256_cmp_pd(a.v, b.v, _CMP_NLE_UQ)};
  }
  friend Mask operator|(Mask a, Mask b) { return {_mm256_or_pd(a.on, b.on)}; }
  friend std::uint32_t bits(Mask m) { return static_cast<std::uint32_t>(_mm256_movemask_pd(m.on)); }
  friend Avx2DoubleLanes select(Mask m, Avx2DoubleLanes a, Avx2DoubleLanes b) {
    return {_mm256_blendv_pd(b.v, a.v, m.on)};
  }
};
#endif

}  // namespace sphys
