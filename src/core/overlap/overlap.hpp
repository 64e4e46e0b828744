// Exact overlap predicate of two ellipsoids (docs/overlap.md).
//
// overlap() decides whether the interiors of the ellipsoids
//     E1 = {x : x^T Q1^{-1} x <= 1},  E2 = {x : (x - r)^T Q2^{-1} (x - r) <= 1}
// intersect, i.e. whether mu^2 < 1 (pw85 documentation, chapter 3, eq. (6)),
// exactly for the doubles given: floating-point filters whose verdicts carry
// rigorous error bounds, then, for the pairs they cannot decide, a Sturm
// sequence of the quartic
//     p(lambda) = det Q(lambda) - lambda (1 - lambda) r^T adj Q(lambda) r
// in exact integer arithmetic (overlap_exact.cpp).
//
// Preconditions, checked by the C layer: r, q1, q2 finite; q1, q2 positive
// definite in floating point (the exact stage re-checks positive
// definiteness exactly and returns kNotSpd if it fails).
#pragma once

#include "common/fp.hpp"
#include "common/status.hpp"
#include "common/sym3.hpp"
#include "dispatch/kernels.hpp"

namespace pw85 {

// Stage that decided a verdict (for benchmarks and tests of the filters).
enum OverlapStage : int {
  kStageTrivial = 0,   // r = 0
  kStageSpheres = 1,   // separating plane normal to r (O11)
  kStageFilter = 2,    // other double-precision certificates (quartic p, Newton)
  kStageExact = 3,     // Sturm sequence in exact integer arithmetic
};

// verdict = 1 (interiors intersect, mu^2 < 1) or 0 (mu^2 >= 1). Returns kOk,
// kNotSpd (exact check) or kInaccurate (the exact stage ran out of its fixed
// capacity: exponent spread of the inputs larger than documented); on error
// verdict is left unchanged. stage (may be null) receives the deciding stage.
Status overlap(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, int &verdict,
               int *stage = nullptr) noexcept;

// Safe range of the floating-point filters (docs/overlap.md, eq. (O9)):
// inputs with max |Q_ij| in [kOverlapRangeLo, kOverlapRangeHi] and
// |r_i| <= kOverlapRangeHi need no scaling.
constexpr double kOverlapRangeLo = 0x1p-60;
constexpr double kOverlapRangeHi = 0x1p60;

// Error bound of the filters' bounded values (docs/overlap.md, eq. (O3)):
// |fl(E) - E| <= kOverlapFilterC fl(P) + kOverlapFilterAbs for an
// expression of at most 16 rounded operations on any path, the absolute
// term covering gradual underflow in the safe range (O9).
constexpr double kOverlapFilterC = 32 * kU;
constexpr double kOverlapFilterAbs = 0x1p-800;

// The hot path of pw85_overlap: screens the arguments in one pass
// (screen.hpp: finite, L D L^T pivots of Q1 and Q2 positive, magnitudes in
// the safe range above) and returns false, with nothing written, when they
// fail it (the caller then validates them and calls overlap()). Otherwise
// sets status and verdict exactly as overlap() would and returns true.
inline bool overlap_screened(double const *r, double const *q1, double const *q2, int &verdict,
                             Status &status) noexcept {
  return kernels().overlap->screened(r, q1, q2, verdict, status);
}

// The screen and the first certificates of the filters ((O11), (O13),
// (O18) at tau0 and tau1) for W pairs at once, pair l = (r[l], q1[l],
// q2[l]) in lane l (overlap/filters.hpp, compiled in overlap_variants.cpp
// for each variant): verdict[l] = 1 or 0, exact and
// equal to pw85_overlap's, or -1 when the lane is not decided there (the
// caller then calls pw85_overlap). Reads 3 and 6 doubles at each pointer;
// any values (NaN included) are accepted. W is kOverlapLanes or
// kOverlapLanesV4; both run on every CPU, and overlap_lanes_width() is the
// one to use on this CPU (kOverlapLanesV4 on x86-64-v4: one AVX-512
// register per vector).
constexpr int kOverlapLanes = 4;
constexpr int kOverlapLanesV4 = 8;
inline int overlap_lanes_width() noexcept { return kernels().overlap->lanes_width; }
template <int W>
inline void overlap_lanes(double const *const r[W], double const *const q1[W],
                          double const *const q2[W], int verdict[W]) noexcept {
  static_assert(W == kOverlapLanes || W == kOverlapLanesV4, "the widths of OverlapKernels");
  if constexpr (W == kOverlapLanesV4)
    kernels().overlap->lanes8(r, q1, q2, verdict);
  else
    kernels().overlap->lanes4(r, q1, q2, verdict);
}

// The exact stage alone (no filter): same contract as overlap().
Status overlap_exact(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                     int &verdict) noexcept;

}  // namespace pw85
