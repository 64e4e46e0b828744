// Argument screens of the hot paths, called from the core so that they are
// compiled into each instruction-set variant of those paths: the
// positive-definiteness certificate of spd.hpp for two matrices in two
// lanes, and the one-pass screens of pw85_overlap (overlap/overlap.cpp) and
// pw85_contact_function_method (contact/methods.cpp). A matrix they do not
// certify takes the general path, whose validation (positive_definite)
// makes the same decision exactly.
#pragma once

#include <cmath>
#include <cstring>

#include "common/fp.hpp"
#include "common/magnitude.hpp"
#include "common/spd.hpp"

namespace pw85 {

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

// certain_spd (spd.hpp) for q1 and q2 at once, given as their three lane
// pairs a01, a23, a45 and b01, b23, b45: each lane performs the operations
// of spd_shifted_pivots, so the decision is certain_spd's for each matrix.
inline bool certain_spd_pair(v2::D2 a01, v2::D2 a23, v2::D2 a45, v2::D2 b01, v2::D2 b23,
                             v2::D2 b45) noexcept {
  using v2::D2;
  D2 const x0 = v2::lo_lanes(a01, b01), x1 = v2::hi_lanes(a01, b01);
  D2 const x2 = v2::lo_lanes(a23, b23), x3 = v2::hi_lanes(a23, b23);
  D2 const x4 = v2::lo_lanes(a45, b45), x5 = v2::hi_lanes(a45, b45);
  D2 d0, d1, d2;
  spd_shifted_pivots(x0, x1, x2, x3, x4, x5, d0, d1, d2);
  D2 const big{kMaxDouble, kMaxDouble};
  v2::I2 const ok = (d0 > 0.0) & (d1 > 0.0) & (d2 > 0.0) & (d2 <= big);
  return (ok[0] & ok[1]) != 0;
}

// One pass over the arguments of pw85_overlap: true when q1 and q2 pass the
// certificate above, |r_i| <= hi, |Q_ij| <= hi and max |Q_ij| >= lo; so
// everything is finite (a NaN entry of a matrix reaches one of its pivots,
// whose test fails; a NaN in r fails |r_i| <= hi). One combined test at the
// end instead of an early exit per test. False does not mean invalid: the
// caller then takes the general path (validation, scaling). Pointers must be
// non-null.
inline bool screen_overlap_pair(double const *r, double const *q1, double const *q2, double lo,
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
  return r_ok & (qm >= lo) & (qm <= hi) & certain_spd_pair(a01, a23, a45, b01, b23, b45);
}

// The same kind of screen for pw85_contact_function_method: true when q1 and
// q2 pass certain_spd_pair and max |r_i|, max |Q1_ij|, max |Q2_ij| each lie
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
  return in & certain_spd_pair(a01, a23, a45, b01, b23, b45);
}

}  // namespace pw85
