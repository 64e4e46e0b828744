// Vectors of doubles (GCC vector extensions) and their lane-by-lane
// helpers, for the loops that process several pairs at once
// (overlap/filters.hpp, contact/default.hpp; docs/batch.md,
// "Throughput") and for the kernels that hold one pair's entries in the
// lanes of a vector (derivatives/adjugate.hpp, eval/f_coefficients_dd.hpp,
// eval/f_dd.hpp). The operations the vector extensions do not spell (fused
// multiply-add, two-source permutes, mask registers, masked loads and
// stores) are the small functions below: the library's only intrinsics.
#pragma once

#include <cmath>

#include "common/isa.hpp"

#if PW85_ISA_LEVELS || PW85_ISA_STATIC_FMA || PW85_ISA_FMA
#include <immintrin.h>
#endif

// Every function taking or returning a vector is always inline into the
// instruction-set variants of its callers (no vector crosses a call), so
// GCC's note that the ABI of a 32-byte vector argument depends on AVX does
// not apply.
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace pw85 {
namespace lanes {

// A vector of W doubles, for any W (4: AVX2, 8: AVX-512; a width the
// target lacks is split by GCC).
template <int W>
struct Width {
  typedef double type __attribute__((vector_size(8 * W)));
};
template <int W>
using VecD = typename Width<W>::type;

// The width of the lane loops that do not choose one per instruction set.
constexpr int kLanes = 4;

constexpr long long kSign = static_cast<long long>(0x8000000000000000ULL);

// Knuth's two_sum lane by lane (arith/dd.hpp): s = a + b rounded and
// e = a + b - s, exactly; T = double or a vector type. s and e may be a
// and b. (The vectors by reference: Clang rejects a 32-byte vector passed
// by value to a function compiled without AVX, even inlined.)
template <class T>
PW85_ALWAYS_INLINE void two_sum(T const &a, T const &b, T &s, T &e) noexcept {
  T const x = a, y = b;
  s = x + y;
  T const bb = s - x;
  e = (x - (s - bb)) + (y - bb);
}

// Number of lanes of a vector type.
template <class T>
constexpr int width() noexcept {
  return static_cast<int>(sizeof(T) / sizeof(double));
}
// The mask type of a vector type (that of its comparisons): 0 or -1 per
// lane.
template <class T>
using MaskOf = decltype(T{} < T{});
template <int W>
using MaskD = MaskOf<VecD<W>>;

// The unsigned mask type of a vector type: 0 or ~0 per lane.
template <int W>
struct UMaskWidth {
  typedef unsigned long long type __attribute__((vector_size(8 * W)));
};
template <class T>
using UMaskOf = typename UMaskWidth<width<T>()>::type;

// Comparisons lane by lane as unsigned masks: lt(x, y) is x < y, and so on
// (y a vector or a double). GCC 12 folds the & or | of two comparisons
// that give the signed mask type (x < y as written) into a bitwise
// operation on the comparisons' vectors of booleans, whose type is chosen
// for the instruction set of the function the source is written in: in a
// portable always-inline body inlined into an x86-64-v4 function, that
// operation on 512-bit comparisons is then compiled lane by lane (vcomisd,
// setcc, insertions). Converted to the unsigned mask type, a comparison is
// not folded so and compiles to vcmppd into a mask register and a masked
// move (pw85_overlap_pairs on x86-64-v4, against the signed masks and vmax
// below as a select: build/bench/bench_batch --reps 7). Code that may be
// inlined into an x86-64-v4 function combines comparisons with these.
#define PW85_LANES_COMPARISON(name, op)                                          \
  template <class T>                                                             \
  PW85_ALWAYS_INLINE UMaskOf<T> name(T x, T y) noexcept {                        \
    return reinterpret_cast<UMaskOf<T>>(x op y);                                 \
  }                                                                              \
  template <class T>                                                             \
  PW85_ALWAYS_INLINE UMaskOf<T> name(T x, double y) noexcept {                   \
    return reinterpret_cast<UMaskOf<T>>(x op y);                                 \
  }
PW85_LANES_COMPARISON(lt, <)
PW85_LANES_COMPARISON(le, <=)
PW85_LANES_COMPARISON(gt, >)
PW85_LANES_COMPARISON(ge, >=)
PW85_LANES_COMPARISON(eq, ==)
PW85_LANES_COMPARISON(ne, !=)
#undef PW85_LANES_COMPARISON

template <class T>
PW85_ALWAYS_INLINE T vabs(T x) noexcept {
  typedef MaskOf<T> Bits;
  return reinterpret_cast<T>(reinterpret_cast<Bits>(x) & (Bits{} + ~kSign));
}
// m ? a : b, lane by lane.
template <class K, class T>
PW85_ALWAYS_INLINE T select(K m, T a, T b) noexcept {
  return reinterpret_cast<T>((m & reinterpret_cast<K>(a)) | (~m & reinterpret_cast<K>(b)));
}
// a > b ? a : b (a NaN in a gives b), as v2::max of screen.hpp; as a
// vector conditional, one vmaxpd on x86 (objdump of overlap_variants.cpp).
template <class T>
PW85_ALWAYS_INLINE T vmax(T a, T b) noexcept { return a > b ? a : b; }
// std::copysign(x, y), lane by lane.
template <class T>
PW85_ALWAYS_INLINE T copysign(T x, T y) noexcept {
  typedef MaskOf<T> Bits;
  return reinterpret_cast<T>((reinterpret_cast<Bits>(x) & (Bits{} + ~kSign)) |
                             (reinterpret_cast<Bits>(y) & (Bits{} + kSign)));
}
template <class T>
PW85_ALWAYS_INLINE T vsqrt(T x) noexcept {
  T y;
  for (int l = 0; l < width<T>(); ++l) y[l] = std::sqrt(x[l]);
  return y;
}
// std::isfinite, lane by lane: x - x is 0 for finite x, NaN otherwise.
template <class T>
PW85_ALWAYS_INLINE MaskOf<T> finite(T x) noexcept { return (x - x) == 0.0; }
template <class K>
PW85_ALWAYS_INLINE bool any(K m) noexcept {
  long long a = 0;
  for (int l = 0; l < width<K>(); ++l) a |= m[l];
  return a != 0;
}

// The mask with every lane set, and the negation of a mask (0 or -1 per
// lane; for one pair, K = bool: true and !m).
template <class K>
PW85_ALWAYS_INLINE K all_set() noexcept { return ~K{}; }
template <>
PW85_ALWAYS_INLINE bool all_set<bool>() noexcept { return true; }
template <class K>
PW85_ALWAYS_INLINE K mask_not(K m) noexcept { return ~m; }
PW85_ALWAYS_INLINE bool mask_not(bool m) noexcept { return !m; }

// out[i][l] = p[l][i] for i < N, l < W: N doubles at each of W pointers,
// element i of pair l in lane l of out[i]. For W = 8, elements 4k ... 4k + 3
// are loaded as one 256-bit vector per pair and those pairs of elements
// after them as one 128-bit vector per pair, then transposed by shuffles:
// written lane by lane, GCC 12 builds these vectors in pieces through the
// stack (pw85_overlap_pairs on x86-64-v4, the two ways:
// build/bench/bench_batch --reps 7).
template <int N, int W>
PW85_ALWAYS_INLINE void gather(double const *const p[W], VecD<W> out[N]) noexcept {
  int i = 0;
#if defined(__has_builtin)
#if __has_builtin(__builtin_shufflevector)
  if constexpr (W == 8) {
    typedef VecD<2> V2;
    typedef VecD<4> V4;
    typedef VecD<8> V8;
    for (; i + 4 <= N; i += 4) {
      V4 w[8];
      for (int l = 0; l < 8; ++l) __builtin_memcpy(&w[l], p[l] + i, sizeof(V4));
      V8 z[4];  // z[j] = elements of pairs j and j + 4
      for (int j = 0; j < 4; ++j)
        z[j] = __builtin_shufflevector(w[j], w[j + 4], 0, 1, 2, 3, 4, 5, 6, 7);
      V8 const t0 = __builtin_shufflevector(z[0], z[1], 0, 8, 2, 10, 4, 12, 6, 14);
      V8 const t1 = __builtin_shufflevector(z[0], z[1], 1, 9, 3, 11, 5, 13, 7, 15);
      V8 const t2 = __builtin_shufflevector(z[2], z[3], 0, 8, 2, 10, 4, 12, 6, 14);
      V8 const t3 = __builtin_shufflevector(z[2], z[3], 1, 9, 3, 11, 5, 13, 7, 15);
      out[i] = __builtin_shufflevector(t0, t2, 0, 1, 8, 9, 4, 5, 12, 13);
      out[i + 1] = __builtin_shufflevector(t1, t3, 0, 1, 8, 9, 4, 5, 12, 13);
      out[i + 2] = __builtin_shufflevector(t0, t2, 2, 3, 10, 11, 6, 7, 14, 15);
      out[i + 3] = __builtin_shufflevector(t1, t3, 2, 3, 10, 11, 6, 7, 14, 15);
    }
    for (; i + 2 <= N; i += 2) {
      V2 h[8];
      for (int l = 0; l < 8; ++l) __builtin_memcpy(&h[l], p[l] + i, sizeof(V2));
      V4 y[4];  // pairs {0, 2}, {1, 3}, {4, 6}, {5, 7}
      for (int j = 0; j < 4; ++j) {
        int const l = (j & 1) + 4 * (j >> 1);
        y[j] = __builtin_shufflevector(h[l], h[l + 2], 0, 1, 2, 3);
      }
      V8 const z0 = __builtin_shufflevector(y[0], y[2], 0, 1, 2, 3, 4, 5, 6, 7);  // even pairs
      V8 const z1 = __builtin_shufflevector(y[1], y[3], 0, 1, 2, 3, 4, 5, 6, 7);  // odd pairs
      out[i] = __builtin_shufflevector(z0, z1, 0, 8, 2, 10, 4, 12, 6, 14);
      out[i + 1] = __builtin_shufflevector(z0, z1, 1, 9, 3, 11, 5, 13, 7, 15);
    }
  }
#endif
#endif
  for (; i < N; ++i) {
    VecD<W> v = {};
    for (int l = 0; l < W; ++l) v[l] = p[l][i];
    out[i] = v;
  }
}

#if PW85_ISA_STATIC_FMA || PW85_ISA_FMA
// Four lanes with the fused multiply-add, for code inlined into
// PW85_TARGET_FMA functions (or any code of a build that targets FMA).
typedef VecD<4> Lanes4;

// a b + c and a b - c, each with one rounding.
PW85_ALWAYS_INLINE PW85_TARGET_FMA Lanes4 fma(Lanes4 a, Lanes4 b, Lanes4 c) noexcept {
  return _mm256_fmadd_pd(a, b, c);
}
PW85_ALWAYS_INLINE PW85_TARGET_FMA Lanes4 fms(Lanes4 a, Lanes4 b, Lanes4 c) noexcept {
  return _mm256_fmsub_pd(a, b, c);
}
// Four doubles at p, any alignment.
PW85_ALWAYS_INLINE PW85_TARGET_FMA Lanes4 load4(double const *p) noexcept {
  return _mm256_loadu_pd(p);
}
// Lane l of the result: lane I_l of (a, b), 0-3 from a, 4-7 from b.
template <int I0, int I1, int I2, int I3>
PW85_ALWAYS_INLINE PW85_TARGET_FMA Lanes4 shuffle(Lanes4 a, Lanes4 b) noexcept {
#if defined(__clang__)
  return __builtin_shufflevector(a, b, I0, I1, I2, I3);
#else
  typedef long long Index4 __attribute__((vector_size(32)));
  return __builtin_shuffle(a, b, Index4{I0, I1, I2, I3});
#endif
}
#endif

#if PW85_ISA_LEVELS
// Eight lanes on x86-64-v4, for code inlined into PW85_TARGET_V4
// functions.
typedef VecD<8> Lanes8;
typedef long long LaneIndex8 __attribute__((vector_size(64)));
typedef unsigned char LaneBits8;  // bit l: lane l

// a b + c and a b - c, each with one rounding.
PW85_V4_INLINE Lanes8 fma(Lanes8 a, Lanes8 b, Lanes8 c) noexcept {
  return _mm512_fmadd_pd(a, b, c);
}
PW85_V4_INLINE Lanes8 fms(Lanes8 a, Lanes8 b, Lanes8 c) noexcept {
  return _mm512_fmsub_pd(a, b, c);
}
// c - a b, one rounding.
PW85_V4_INLINE Lanes8 fnma(Lanes8 a, Lanes8 b, Lanes8 c) noexcept {
  return _mm512_fnmadd_pd(a, b, c);
}
// Lane l of the result: lane idx[l] of (a, b), 0-7 from a, 8-15 from b.
PW85_V4_INLINE Lanes8 permute(Lanes8 a, LaneIndex8 idx, Lanes8 b) noexcept {
  return _mm512_permutex2var_pd(a, reinterpret_cast<__m512i>(idx), b);
}
// In the lanes of k, lane idx[l] of v (idx 0-7); in the others, lane l
// of src.
PW85_V4_INLINE Lanes8 permute_into(Lanes8 src, LaneBits8 k, Lanes8 v, LaneIndex8 idx) noexcept {
  return _mm512_mask_permutexvar_pd(src, k, reinterpret_cast<__m512i>(idx), v);
}
// Comparisons as bits (one compare into a mask register).
PW85_V4_INLINE LaneBits8 gt_bits(Lanes8 a, Lanes8 b) noexcept {
  return _mm512_cmp_pd_mask(a, b, _CMP_GT_OQ);
}
PW85_V4_INLINE LaneBits8 le_bits(Lanes8 a, Lanes8 b) noexcept {
  return _mm512_cmp_pd_mask(a, b, _CMP_LE_OQ);
}
PW85_V4_INLINE LaneBits8 eq_bits(Lanes8 a, Lanes8 b) noexcept {
  return _mm512_cmp_pd_mask(a, b, _CMP_EQ_OQ);
}
// The lanes of a mask as bits, and back.
PW85_V4_INLINE LaneBits8 bits(UMaskOf<Lanes8> m) noexcept {
  return _mm512_movepi64_mask(reinterpret_cast<__m512i>(m));
}
PW85_V4_INLINE LaneBits8 bits(MaskD<8> m) noexcept {
  return _mm512_movepi64_mask(reinterpret_cast<__m512i>(m));
}
PW85_V4_INLINE MaskD<8> mask_of(LaneBits8 k) noexcept {
  return reinterpret_cast<MaskD<8>>(_mm512_movm_epi64(k));
}
// k ? a : b lane by lane, k as bits.
PW85_V4_INLINE Lanes8 blend(LaneBits8 k, Lanes8 a, Lanes8 b) noexcept {
  return _mm512_mask_blend_pd(k, b, a);
}
PW85_V4_INLINE LaneIndex8 blend(LaneBits8 k, LaneIndex8 a, LaneIndex8 b) noexcept {
  return reinterpret_cast<LaneIndex8>(
      _mm512_mask_blend_epi64(k, reinterpret_cast<__m512i>(b), reinterpret_cast<__m512i>(a)));
}
// k ? v : 0 lane by lane, k as bits.
PW85_V4_INLINE Lanes8 keep(LaneBits8 k, Lanes8 v) noexcept { return _mm512_maskz_mov_pd(k, v); }
// The first n doubles at p in lanes 0 .. n - 1, zeros above (reads n only).
PW85_V4_INLINE Lanes8 load_first(double const *p, int n) noexcept {
  return _mm512_maskz_loadu_pd(static_cast<__mmask8>((1u << n) - 1u), p);
}
// Lanes 0 .. n - 1 of v to the n doubles at p (writes n only).
PW85_V4_INLINE void store_first(double *p, int n, Lanes8 v) noexcept {
  _mm512_mask_storeu_pd(p, static_cast<__mmask8>((1u << n) - 1u), v);
}
PW85_V4_INLINE void store(double *p, Lanes8 v) noexcept { _mm512_storeu_pd(p, v); }
PW85_V4_INLINE Lanes8 load(double const *p) noexcept { return _mm512_loadu_pd(p); }
PW85_V4_INLINE Lanes8 broadcast(double x) noexcept { return _mm512_set1_pd(x); }
PW85_V4_INLINE LaneIndex8 broadcast_index(long long i) noexcept {
  return reinterpret_cast<LaneIndex8>(_mm512_set1_epi64(i));
}
PW85_V4_INLINE double lane0(Lanes8 v) noexcept { return _mm512_cvtsd_f64(v); }
#endif

// The same helpers for one pair (T = double), so that code templated on the
// vector type (eval/f_rational_dd.hpp, contact/rational_step.hpp,
// contact/start.hpp, eval/f_adj.hpp) serves the one-pair path too.
PW85_ALWAYS_INLINE double vabs(double x) noexcept { return std::fabs(x); }
PW85_ALWAYS_INLINE double vsqrt(double x) noexcept { return std::sqrt(x); }
PW85_ALWAYS_INLINE double select(bool m, double a, double b) noexcept { return m ? a : b; }
PW85_ALWAYS_INLINE double copysign(double x, double y) noexcept { return std::copysign(x, y); }
PW85_ALWAYS_INLINE bool finite(double x) noexcept { return std::isfinite(x); }
PW85_ALWAYS_INLINE bool any(bool m) noexcept { return m; }
PW85_ALWAYS_INLINE bool lt(double x, double y) noexcept { return x < y; }
PW85_ALWAYS_INLINE bool le(double x, double y) noexcept { return x <= y; }
PW85_ALWAYS_INLINE bool gt(double x, double y) noexcept { return x > y; }
PW85_ALWAYS_INLINE bool ge(double x, double y) noexcept { return x >= y; }

// m and not n, lane by lane, for the masks of the comparisons above.
template <class Mask>
PW85_ALWAYS_INLINE Mask and_not(Mask m, Mask n) noexcept { return m & ~n; }
PW85_ALWAYS_INLINE bool and_not(bool m, bool n) noexcept { return m & !n; }

}  // namespace lanes
}  // namespace pw85
