// Argument screens of the hot paths, called from the core so that they are
// compiled into each instruction-set variant of those paths: the positive
// definiteness test by L D L^T pivots (ldl_positive, one matrix; the C
// layer's validation uses it too), the same test for two matrices in two
// lanes, and the one-pass screens of pw85_overlap (overlap/overlap.cpp) and
// pw85_contact_function_method (contact/methods.cpp).
#pragma once

#include <cmath>
#include <cstring>

#include "common/fp.hpp"
#include "common/magnitude.hpp"
#include "common/scaling.hpp"

namespace pw85 {

// Positive definiteness by the pivots of L D L^T of the symmetric matrix a
// (Sym3 storage): all > 0. No square roots; the same decisions as a
// Cholesky factorisation up to rounding. a must be finite.
inline bool ldl_positive(double const *a) noexcept {
  double const d0 = a[0];
  if (!(d0 > 0.0)) return false;
  double const i0 = 1.0 / d0;
  double const l1 = a[1] * i0, l2 = a[2] * i0;
  double const d1 = a[3] - l1 * a[1];
  if (!(d1 > 0.0)) return false;
  double const e = a[4] - l2 * a[1];
  double const d2 = a[5] - l2 * a[2] - (e / d1) * e;  // no overflow of e * e
  return d2 > 0.0 && d2 <= kMaxDouble;   // false for NaN, +Inf
}

// Positive definiteness of a matrix of any magnitude: ldl_positive of a
// itself, or of 2^-e a, e the exponent of max |a_ij| (exact scaling, unless
// entries below 2^e 2^-1074 are flushed). The scaled test decides matrices
// of subnormal or huge entries (whose pivots 1/a_00, a_ij a_ik / a_ii leave
// the double range); the unscaled one those whose entries span more than
// the double range, e.g. diag(DBL_MAX, 4.9e-324, 1), where the scaling
// flushes the small entries to 0.
inline bool ldl_positive_scaled(double const *a) noexcept {
  if (ldl_positive(a)) return true;
  int const e = max_exponent(a, 6);
  double b[6];
  scale_by_power_of_two(a, b, 6, -e);
  return ldl_positive(b);
}

// Two-lane helpers (GCC/Clang vector extension, one SSE2 register).
namespace v2 {
typedef double D2 __attribute__((vector_size(16)));
typedef long long I2 __attribute__((vector_size(16)));
inline D2 load(double const *p) noexcept {
  D2 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline D2 abs(D2 x) noexcept {
  return reinterpret_cast<D2>(reinterpret_cast<I2>(x) & I2{0x7fffffffffffffffLL, 0x7fffffffffffffffLL});
}
inline D2 max(D2 a, D2 b) noexcept { return a > b ? a : b; }  // NaN in a: b
#if defined(__clang__)
inline D2 lo_lanes(D2 a, D2 b) noexcept { return __builtin_shufflevector(a, b, 0, 2); }
inline D2 hi_lanes(D2 a, D2 b) noexcept { return __builtin_shufflevector(a, b, 1, 3); }
#else
inline D2 lo_lanes(D2 a, D2 b) noexcept { return __builtin_shuffle(a, b, I2{0, 2}); }
inline D2 hi_lanes(D2 a, D2 b) noexcept { return __builtin_shuffle(a, b, I2{1, 3}); }
#endif
}  // namespace v2

// The L D L^T pivot test of ldl_positive (above: all pivots
// > 0 and finite) for q1 and q2 at once, given as their three lane pairs
// a01, a23, a45 and b01, b23, b45: each lane performs exactly the scalar
// operations of ldl_positive (same decisions), computed whatever the earlier
// pivots were (ldl_positive stops at the first pivot <= 0; here that
// pivot's test makes the combined result false all the same).
inline bool ldl_pivots_positive(v2::D2 a01, v2::D2 a23, v2::D2 a45, v2::D2 b01, v2::D2 b23,
                                v2::D2 b45) noexcept {
  using v2::D2;
  D2 const x0 = v2::lo_lanes(a01, b01), x1 = v2::hi_lanes(a01, b01);
  D2 const x2 = v2::lo_lanes(a23, b23), x3 = v2::hi_lanes(a23, b23);
  D2 const x4 = v2::lo_lanes(a45, b45), x5 = v2::hi_lanes(a45, b45);
  D2 const i0 = 1.0 / x0;
  D2 const l1 = x1 * i0, l2 = x2 * i0;
  D2 const d1 = x3 - l1 * x1;
  D2 const e = x4 - l2 * x1;
  D2 const d2 = x5 - l2 * x2 - (e / d1) * e;
  D2 const big{kMaxDouble, kMaxDouble};
  v2::I2 const ok = (x0 > 0.0) & (d1 > 0.0) & (d2 > 0.0) & (d2 <= big);
  return (ok[0] & ok[1]) != 0;
}

// One pass over the arguments of pw85_overlap: true when q1 and q2 pass the
// pivot test above, |r_i| <= hi, |Q_ij| <= hi and max |Q_ij| >= lo; so
// everything is finite (a NaN entry of a matrix reaches one of its pivots,
// whose test fails; a NaN in r fails |r_i| <= hi). One combined test at the
// end instead of an early exit per pivot. False does not mean invalid: the
// caller then takes the general path (validation, scaling). Pointers must be
// non-null.
inline bool screen_pair_ldl(double const *r, double const *q1, double const *q2, double lo,
                            double hi) noexcept {
  using v2::D2;
  D2 const a01 = v2::load(q1), a23 = v2::load(q1 + 2), a45 = v2::load(q1 + 4);
  D2 const b01 = v2::load(q2), b23 = v2::load(q2 + 2), b45 = v2::load(q2 + 4);
  // max |Q_ij| over both matrices. A NaN in a matrix may be skipped here;
  // it reaches a pivot below, whose test fails.
  D2 const m = v2::max(v2::max(v2::max(v2::abs(a01), v2::abs(a23)), v2::max(v2::abs(a45), v2::abs(b01))),
                       v2::max(v2::abs(b23), v2::abs(b45)));
  double const qm = m[0] > m[1] ? m[0] : m[1];
  bool const r_ok =
      (std::fabs(r[0]) <= hi) & (std::fabs(r[1]) <= hi) & (std::fabs(r[2]) <= hi);
  return r_ok & (qm >= lo) & (qm <= hi) & ldl_pivots_positive(a01, a23, a45, b01, b23, b45);
}

// The same kind of screen for pw85_contact_function_method: true when q1 and
// q2 pass ldl_positive and max |r_i|, max |Q1_ij|, max |Q2_ij| each lie
// strictly inside (lo, hi) (so r != 0 and everything is finite: a NaN entry
// of a matrix fails a pivot, a NaN in r fails |r_i| < hi). False: take the
// general path (validation, then the dispatcher's scaling).
inline bool screen_contact_pair(double const *r, double const *q1, double const *q2,
                                double lo, double hi) noexcept {
  // The two matrices side by side in the two lanes.
  using v2::D2;
  D2 const a01 = v2::load(q1), a23 = v2::load(q1 + 2), a45 = v2::load(q1 + 4);
  D2 const b01 = v2::load(q2), b23 = v2::load(q2 + 2), b45 = v2::load(q2 + 4);
  // A NaN in a matrix may be skipped by the maxima; it reaches a pivot below.
  D2 const ma = v2::max(v2::max(v2::abs(a01), v2::abs(a23)), v2::abs(a45));
  D2 const mb = v2::max(v2::max(v2::abs(b01), v2::abs(b23)), v2::abs(b45));
  double const m1 = ma[0] > ma[1] ? ma[0] : ma[1], m2 = mb[0] > mb[1] ? mb[0] : mb[1];
  double const r0 = std::fabs(r[0]), r1 = std::fabs(r[1]), r2 = std::fabs(r[2]);
  // max |r_i| > lo as "some |r_i| > lo": the maximum written as nested
  // conditionals was compiled to a branch on r0 > r1, taken at random.
  bool const in = (r0 < hi) & (r1 < hi) & (r2 < hi) & ((r0 > lo) | (r1 > lo) | (r2 > lo)) &
                  (m1 > lo) & (m1 < hi) & (m2 > lo) & (m2 < hi);
  return in & ldl_pivots_positive(a01, a23, a45, b01, b23, b45);
}

}  // namespace pw85
