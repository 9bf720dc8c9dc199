#pragma once

// Floats in lanes: the few operations the SIMD kernels do W at a time (the soft step's contact
// passes, the robot kinematics, the queries' sphere tests). Four kinds, each with the same
// operations, so that one template serves them all (dynamics/contact_lane_kernels.h,
// robot/robot_kinematics_kernel.h):
// - PortableLanes<W>: plain floats, for any processor, and W = 1 for the colour-less remainder;
// - Sse2Lanes: 4 lanes of SSE2, x86-64's baseline, always there on x86-64;
// - Sse2PairLanes: 8 lanes as two SSE2 registers, so that SSE2 solves the blocks AVX2 does;
// - Avx2Lanes: 8 lanes of AVX2, only where the translation unit is compiled with -mavx2.
// Every operation is one correctly rounded IEEE operation per lane, and min, max and select
// follow SSE's rules (min(a, b) is a < b ? a : b), so they all give the same bits lane for lane.
// None of them fuses a multiply and an add: the library is compiled with -ffp-contract=off.

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace sphys {

// Floats per row that load_rows and store_rows move between W rows and kRow lane vectors.
inline constexpr int kRow = 8;

template <int W>
struct PortableLanes {
  static constexpr int kWidth = W;
  struct Mask {
    std::array<bool, W> on{};
  };
  std::array<float, W> v{};

  static PortableLanes load(const float* p) {
    PortableLanes r;
    for (int i = 0; i < W; ++i) r.v[i] = p[i];
    return r;
  }
  static PortableLanes load_unaligned(const float* p) { return load(p); }
  static PortableLanes splat(float x) {
    PortableLanes r;
    r.v.fill(x);
    return r;
  }
  // Lane i takes base[index[i] * stride].
  static PortableLanes gather(const float* base, const std::uint32_t* index, std::size_t stride) {
    PortableLanes r;
    for (int i = 0; i < W; ++i) r.v[i] = base[index[i] * stride];
    return r;
  }
  void store(float* p) const {
    for (int i = 0; i < W; ++i) p[i] = v[i];
  }
  void store_unaligned(float* p) const { store(p); }
  // kRow floats of W rows at once: out[k] takes float k of row base + index[i] * stride in lane
  // i. The rows must each hold kRow readable floats.
  static void load_rows(const float* base, const std::uint32_t* index, std::size_t stride,
                        PortableLanes (&out)[kRow]) {
    for (int i = 0; i < W; ++i) {
      for (int k = 0; k < kRow; ++k) out[k].v[i] = base[index[i] * stride + k];
    }
  }
  // The reverse of load_rows, for the lanes whose `write` is not 0.
  static void store_rows(const PortableLanes (&in)[kRow], float* base, const std::uint32_t* index,
                         std::size_t stride, const std::uint32_t* write) {
    for (int i = 0; i < W; ++i) {
      if (write[i] == 0) continue;
      for (int k = 0; k < kRow; ++k) base[index[i] * stride + k] = in[k].v[i];
    }
  }
  template <class Op>
  friend PortableLanes each(const PortableLanes& a, const PortableLanes& b, Op op) {
    PortableLanes r;
    for (int i = 0; i < W; ++i) r.v[i] = op(a.v[i], b.v[i]);
    return r;
  }
  friend PortableLanes operator+(PortableLanes a, PortableLanes b) {
    return each(a, b, [](float x, float y) { return x + y; });
  }
  friend PortableLanes operator-(PortableLanes a, PortableLanes b) {
    return each(a, b, [](float x, float y) { return x - y; });
  }
  friend PortableLanes operator*(PortableLanes a, PortableLanes b) {
    return each(a, b, [](float x, float y) { return x * y; });
  }
  friend PortableLanes operator/(PortableLanes a, PortableLanes b) {
    return each(a, b, [](float x, float y) { return x / y; });
  }
  friend PortableLanes min(PortableLanes a, PortableLanes b) {
    return each(a, b, [](float x, float y) { return x < y ? x : y; });
  }
  friend PortableLanes max(PortableLanes a, PortableLanes b) {
    return each(a, b, [](float x, float y) { return x > y ? x : y; });
  }
  friend PortableLanes sqrt(PortableLanes a) {
    PortableLanes r;
    for (int i = 0; i < W; ++i) r.v[i] = std::sqrt(a.v[i]);
    return r;
  }
  template <class Compare>
  friend Mask compare(const PortableLanes& a, const PortableLanes& b, Compare compare) {
    Mask m;
    for (int i = 0; i < W; ++i) m.on[i] = compare(a.v[i], b.v[i]);
    return m;
  }
  friend Mask operator<(PortableLanes a, PortableLanes b) {
    return compare(a, b, [](float x, float y) { return x < y; });
  }
  friend Mask operator>(PortableLanes a, PortableLanes b) {
    return compare(a, b, [](float x, float y) { return x > y; });
  }
  friend Mask operator<=(PortableLanes a, PortableLanes b) {
    return compare(a, b, [](float x, float y) { return x <= y; });
  }
  friend Mask operator&(Mask a, Mask b) {
    Mask m;
    for (int i = 0; i < W; ++i) m.on[i] = a.on[i] && b.on[i];
    return m;
  }
  friend bool any(Mask m) {
    for (int i = 0; i < W; ++i) {
      if (m.on[i]) return true;
    }
    return false;
  }
  // Lane i's flag as bit i.
  friend std::uint32_t bits(Mask m) {
    std::uint32_t out = 0;
    for (int i = 0; i < W; ++i) out |= m.on[i] ? 1u << i : 0u;
    return out;
  }
  // a where the mask is on, else b.
  friend PortableLanes select(Mask m, PortableLanes a, PortableLanes b) {
    PortableLanes r;
    for (int i = 0; i < W; ++i) r.v[i] = m.on[i] ? a.v[i] : b.v[i];
    return r;
  }
};

#if defined(__SSE2__)
struct Sse2Lanes {
  static constexpr int kWidth = 4;
  struct Mask {
    __m128 on;
  };
  __m128 v;

  static Sse2Lanes load(const float* p) { return {_mm_load_ps(p)}; }
  static Sse2Lanes load_unaligned(const float* p) { return {_mm_loadu_ps(p)}; }
  static Sse2Lanes splat(float x) { return {_mm_set1_ps(x)}; }
  // Lane i takes base[index[i] * stride]: four scalar loads put together in registers.
  static Sse2Lanes gather(const float* base, const std::uint32_t* index, std::size_t stride) {
    return {_mm_setr_ps(base[index[0] * stride], base[index[1] * stride], base[index[2] * stride],
                        base[index[3] * stride])};
  }
  void store(float* p) const { _mm_store_ps(p, v); }
  void store_unaligned(float* p) const { _mm_storeu_ps(p, v); }
  // As PortableLanes::load_rows: each row's two halves, transposed four by four.
  static void load_rows(const float* base, const std::uint32_t* index, std::size_t stride,
                        Sse2Lanes (&out)[kRow]) {
    for (int half = 0; half < 2; ++half) {
      __m128 r0 = _mm_loadu_ps(base + index[0] * stride + 4 * half);
      __m128 r1 = _mm_loadu_ps(base + index[1] * stride + 4 * half);
      __m128 r2 = _mm_loadu_ps(base + index[2] * stride + 4 * half);
      __m128 r3 = _mm_loadu_ps(base + index[3] * stride + 4 * half);
      _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
      out[4 * half] = {r0};
      out[4 * half + 1] = {r1};
      out[4 * half + 2] = {r2};
      out[4 * half + 3] = {r3};
    }
  }
  static void store_rows(const Sse2Lanes (&in)[kRow], float* base, const std::uint32_t* index,
                         std::size_t stride, const std::uint32_t* write) {
    for (int half = 0; half < 2; ++half) {
      __m128 r[4] = {in[4 * half].v, in[4 * half + 1].v, in[4 * half + 2].v, in[4 * half + 3].v};
      _MM_TRANSPOSE4_PS(r[0], r[1], r[2], r[3]);
      for (int i = 0; i < 4; ++i) {
        if (write[i] != 0) _mm_storeu_ps(base + index[i] * stride + 4 * half, r[i]);
      }
    }
  }
  friend Sse2Lanes operator+(Sse2Lanes a, Sse2Lanes b) { return {_mm_add_ps(a.v, b.v)}; }
  friend Sse2Lanes operator-(Sse2Lanes a, Sse2Lanes b) { return {_mm_sub_ps(a.v, b.v)}; }
  friend Sse2Lanes operator*(Sse2Lanes a, Sse2Lanes b) { return {_mm_mul_ps(a.v, b.v)}; }
  friend Sse2Lanes operator/(Sse2Lanes a, Sse2Lanes b) { return {_mm_div_ps(a.v, b.v)}; }
  friend Sse2Lanes min(Sse2Lanes a, Sse2Lanes b) { return {_mm_min_ps(a.v, b.v)}; }
  friend Sse2Lanes max(Sse2Lanes a, Sse2Lanes b) { return {_mm_max_ps(a.v, b.v)}; }
  friend Sse2Lanes sqrt(Sse2Lanes a) { return {_mm_sqrt_ps(a.v)}; }
  friend Mask operator<(Sse2Lanes a, Sse2Lanes b) { return {_mm_cmplt_ps(a.v, b.v)}; }
  friend Mask operator>(Sse2Lanes a, Sse2Lanes b) { return {_mm_cmpgt_ps(a.v, b.v)}; }
  friend Mask operator<=(Sse2Lanes a, Sse2Lanes b) { return {_mm_cmple_ps(a.v, b.v)}; }
  friend Mask operator&(Mask a, Mask b) { return {_mm_and_ps(a.on, b.on)}; }
  friend bool any(Mask m) { return _mm_movemask_ps(m.on) != 0; }
  // Lane i's flag as bit i.
  friend std::uint32_t bits(Mask m) { return static_cast<std::uint32_t>(_mm_movemask_ps(m.on)); }
  friend Sse2Lanes select(Mask m, Sse2Lanes a, Sse2Lanes b) {
    return {_mm_or_ps(_mm_and_ps(m.on, a.v), _mm_andnot_ps(m.on, b.v))};
  }
};
// Eight lanes as two SSE2 registers, lanes 0-3 in `lo` and 4-7 in `hi`: each operation is
// Sse2Lanes' on each half.
struct Sse2PairLanes {
  static constexpr int kWidth = 8;
  struct Mask {
    Sse2Lanes::Mask lo, hi;
  };
  Sse2Lanes lo, hi;

  static Sse2PairLanes load(const float* p) { return {Sse2Lanes::load(p), Sse2Lanes::load(p + 4)}; }
  static Sse2PairLanes load_unaligned(const float* p) {
    return {Sse2Lanes::load_unaligned(p), Sse2Lanes::load_unaligned(p + 4)};
  }
  static Sse2PairLanes splat(float x) { return {Sse2Lanes::splat(x), Sse2Lanes::splat(x)}; }
  static Sse2PairLanes gather(const float* base, const std::uint32_t* index, std::size_t stride) {
    return {Sse2Lanes::gather(base, index, stride), Sse2Lanes::gather(base, index + 4, stride)};
  }
  void store(float* p) const {
    lo.store(p);
    hi.store(p + 4);
  }
  void store_unaligned(float* p) const {
    lo.store_unaligned(p);
    hi.store_unaligned(p + 4);
  }
  static void load_rows(const float* base, const std::uint32_t* index, std::size_t stride,
                        Sse2PairLanes (&out)[kRow]) {
    Sse2Lanes lo[kRow];
    Sse2Lanes hi[kRow];
    Sse2Lanes::load_rows(base, index, stride, lo);
    Sse2Lanes::load_rows(base, index + 4, stride, hi);
    for (int k = 0; k < kRow; ++k) out[k] = {lo[k], hi[k]};
  }
  static void store_rows(const Sse2PairLanes (&in)[kRow], float* base, const std::uint32_t* index,
                         std::size_t stride, const std::uint32_t* write) {
    Sse2Lanes lo[kRow];
    Sse2Lanes hi[kRow];
    for (int k = 0; k < kRow; ++k) {
      lo[k] = in[k].lo;
      hi[k] = in[k].hi;
    }
    Sse2Lanes::store_rows(lo, base, index, stride, write);
    Sse2Lanes::store_rows(hi, base, index + 4, stride, write + 4);
  }
  friend Sse2PairLanes operator+(Sse2PairLanes a, Sse2PairLanes b) {
    return {a.lo + b.lo, a.hi + b.hi};
  }
  friend Sse2PairLanes operator-(Sse2PairLanes a, Sse2PairLanes b) {
    return {a.lo - b.lo, a.hi - b.hi};
  }
  friend Sse2PairLanes operator*(Sse2PairLanes a, Sse2PairLanes b) {
    return {a.lo * b.lo, a.hi * b.hi};
  }
  friend Sse2PairLanes operator/(Sse2PairLanes a, Sse2PairLanes b) {
    return {a.lo / b.lo, a.hi / b.hi};
  }
  friend Sse2PairLanes min(Sse2PairLanes a, Sse2PairLanes b) {
    return {min(a.lo, b.lo), min(a.hi, b.hi)};
  }
  friend Sse2PairLanes max(Sse2PairLanes a, Sse2PairLanes b) {
    return {max(a.lo, b.lo), max(a.hi, b.hi)};
  }
  friend Sse2PairLanes sqrt(Sse2PairLanes a) { return {sqrt(a.lo), sqrt(a.hi)}; }
  friend Mask operator<(Sse2PairLanes a, Sse2PairLanes b) { return {a.lo < b.lo, a.hi < b.hi}; }
  friend Mask operator>(Sse2PairLanes a, Sse2PairLanes b) { return {a.lo > b.lo, a.hi > b.hi}; }
  friend Mask operator<=(Sse2PairLanes a, Sse2PairLanes b) { return {a.lo <= b.lo, a.hi <= b.hi}; }
  friend Mask operator&(Mask a, Mask b) { return {a.lo & b.lo, a.hi & b.hi}; }
  friend bool any(Mask m) { return any(m.lo) || any(m.hi); }
  friend std::uint32_t bits(Mask m) { return bits(m.lo) | (bits(m.hi) << 4); }
  friend Sse2PairLanes select(Mask m, Sse2PairLanes a, Sse2PairLanes b) {
    return {select(m.lo, a.lo, b.lo), select(m.hi, a.hi, b.hi)};
  }
};
#endif

#if defined(__AVX2__)
struct Avx2Lanes {
  static constexpr int kWidth = 8;
  struct Mask {
    __m256 on;
  };
  __m256 v;

  static Avx2Lanes load(const float* p) { return {_mm256_load_ps(p)}; }
  static Avx2Lanes load_unaligned(const float* p) { return {_mm256_loadu_ps(p)}; }
  static Avx2Lanes splat(float x) { return {_mm256_set1_ps(x)}; }
  // Lane i takes base[index[i] * stride], as Sse2Lanes::gather.
  static Avx2Lanes gather(const float* base, const std::uint32_t* index, std::size_t stride) {
    return {_mm256_setr_ps(base[index[0] * stride], base[index[1] * stride],
                           base[index[2] * stride], base[index[3] * stride],
                           base[index[4] * stride], base[index[5] * stride],
                           base[index[6] * stride], base[index[7] * stride])};
  }
  void store(float* p) const { _mm256_store_ps(p, v); }
  void store_unaligned(float* p) const { _mm256_storeu_ps(p, v); }
  // As PortableLanes::load_rows: eight rows of eight, transposed.
  static void load_rows(const float* base, const std::uint32_t* index, std::size_t stride,
                        Avx2Lanes (&out)[kRow]) {
    __m256 r[8];
    for (int i = 0; i < 8; ++i) r[i] = _mm256_loadu_ps(base + index[i] * stride);
    transpose(r);
    for (int k = 0; k < kRow; ++k) out[k] = {r[k]};
  }
  static void store_rows(const Avx2Lanes (&in)[kRow], float* base, const std::uint32_t* index,
                         std::size_t stride, const std::uint32_t* write) {
    __m256 r[8];
    for (int k = 0; k < kRow; ++k) r[k] = in[k].v;
    transpose(r);
    for (int i = 0; i < 8; ++i) {
      if (write[i] != 0) _mm256_storeu_ps(base + index[i] * stride, r[i]);
    }
  }
  // An 8 × 8 transpose in registers: r[k] lane i becomes r[i] lane k.
  static void transpose(__m256 (&r)[8]) {
    const __m256 t0 = _mm256_unpacklo_ps(r[0], r[1]);
    const __m256 t1 = _mm256_unpackhi_ps(r[0], r[1]);
    const __m256 t2 = _mm256_unpacklo_ps(r[2], r[3]);
    const __m256 t3 = _mm256_unpackhi_ps(r[2], r[3]);
    const __m256 t4 = _mm256_unpacklo_ps(r[4], r[5]);
    const __m256 t5 = _mm256_unpackhi_ps(r[4], r[5]);
    const __m256 t6 = _mm256_unpacklo_ps(r[6], r[7]);
    const __m256 t7 = _mm256_unpackhi_ps(r[6], r[7]);
    const __m256 u0 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(1, 0, 1, 0));
    const __m256 u1 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2));
    const __m256 u2 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0));
    const __m256 u3 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(3, 2, 3, 2));
    const __m256 u4 = _mm256_shuffle_ps(t4, t6, _MM_SHUFFLE(1, 0, 1, 0));
    const __m256 u5 = _mm256_shuffle_ps(t4, t6, _MM_SHUFFLE(3, 2, 3, 2));
    const __m256 u6 = _mm256_shuffle_ps(t5, t7, _MM_SHUFFLE(1, 0, 1, 0));
    const __m256 u7 = _mm256_shuffle_ps(t5, t7, _MM_SHUFFLE(3, 2, 3, 2));
    r[0] = _mm256_permute2f128_ps(u0, u4, 0x20);
    r[1] = _mm256_permute2f128_ps(u1, u5, 0x20);
    r[2] = _mm256_permute2f128_ps(u2, u6, 0x20);
    r[3] = _mm256_permute2f128_ps(u3, u7, 0x20);
    r[4] = _mm256_permute2f128_ps(u0, u4, 0x31);
    r[5] = _mm256_permute2f128_ps(u1, u5, 0x31);
    r[6] = _mm256_permute2f128_ps(u2, u6, 0x31);
    r[7] = _mm256_permute2f128_ps(u3, u7, 0x31);
  }
  friend Avx2Lanes operator+(Avx2Lanes a, Avx2Lanes b) { return {_mm256_add_ps(a.v, b.v)}; }
  friend Avx2Lanes operator-(Avx2Lanes a, Avx2Lanes b) { return {_mm256_sub_ps(a.v, b.v)}; }
  friend Avx2Lanes operator*(Avx2Lanes a, Avx2Lanes b) { return {_mm256_mul_ps(a.v, b.v)}; }
  friend Avx2Lanes operator/(Avx2Lanes a, Avx2Lanes b) { return {_mm256_div_ps(a.v, b.v)}; }
  friend Avx2Lanes min(Avx2Lanes a, Avx2Lanes b) { return {_mm256_min_ps(a.v, b.v)}; }
  friend Avx2Lanes max(Avx2Lanes a, Avx2Lanes b) { return {_mm256_max_ps(a.v, b.v)}; }
  friend Avx2Lanes sqrt(Avx2Lanes a) { return {_mm256_sqrt_ps(a.v)}; }
  // Ordered, non-signalling: false with a NaN, as SSE's cmplt and cmpgt.
  friend Mask operator<(Avx2Lanes a, Avx2Lanes b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ)}; }
  friend Mask operator>(Avx2Lanes a, Avx2Lanes b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ)}; }
  friend Mask operator<=(Avx2Lanes a, Avx2Lanes b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LE_OQ)}; }
  friend Mask operator&(Mask a, Mask b) { return {_mm256_and_ps(a.on, b.on)}; }
  friend bool any(Mask m) { return _mm256_movemask_ps(m.on) != 0; }
  friend std::uint32_t bits(Mask m) { return static_cast<std::uint32_t>(_mm256_movemask_ps(m.on)); }
  friend Avx2Lanes select(Mask m, Avx2Lanes a, Avx2Lanes b) {
    return {_mm256_blendv_ps(b.v, a.v, m.on)};
  }
};
#endif

}  // namespace sphys
