// Argument validation shared by the extern "C" entry points.
#pragma once

#include <cmath>

#include "common/status.hpp"
#include "common/screen.hpp"
#include "common/sym3.hpp"

namespace pw85 {
namespace capi {

inline void fill_nan(double *p, int n) noexcept {
  for (int i = 0; i < n; ++i) p[i] = std::nan("");
}

// A pair of ellipsoids: r12 finite, q1 and q2 finite and positive definite.
inline Status validate_pair(double const *r12, double const *q1, double const *q2) noexcept {
  if (r12 == nullptr || q1 == nullptr || q2 == nullptr) return kInvalidArgument;
  if (!all_finite(r12, kDim) || !all_finite(q1, kSym) || !all_finite(q2, kSym))
    return kInvalidArgument;
  if (!is_positive_definite(load_sym3(q1)) || !is_positive_definite(load_sym3(q2)))
    return kNotSpd;
  return kOk;
}

// Positive definiteness by the pivots of L D L^T of the symmetric matrix a
// (Sym3 storage): all > 0. No square roots; same decisions as the Cholesky
// factorisation of validate_pair up to rounding. a must be finite.
inline bool ldl_positive(double const *a) noexcept {
  double const d0 = a[0];
  if (!(d0 > 0.0)) return false;
  double const i0 = 1.0 / d0;
  double const l1 = a[1] * i0, l2 = a[2] * i0;
  double const d1 = a[3] - l1 * a[1];
  if (!(d1 > 0.0)) return false;
  double const e = a[4] - l2 * a[1];
  double const d2 = a[5] - l2 * a[2] - (e / d1) * e;  // no overflow of e * e
  return d2 > 0.0 && d2 <= 0x1.fffffffffffffp1023;   // false for NaN, +Inf
}

// The contract of validate_pair with ldl_positive for the matrices (the
// entry points on hot paths: pw85_overlap, pw85_contact_function_method).
inline Status validate_pair_ldl(double const *r12, double const *q1, double const *q2) noexcept {
  if (r12 == nullptr || q1 == nullptr || q2 == nullptr) return kInvalidArgument;
  if (!all_finite(r12, kDim) || !all_finite(q1, kSym) || !all_finite(q2, kSym))
    return kInvalidArgument;
  if (!ldl_positive(q1) || !ldl_positive(q2)) return kNotSpd;
  return kOk;
}

// The same kind of screen for pw85_contact_function_method: true when q1 and
// q2 pass ldl_positive and max |r_i|, max |Q1_ij|, max |Q2_ij| each lie
// strictly inside (lo, hi) (so r != 0 and everything is finite: a NaN entry
// of a matrix fails a pivot, a NaN in r fails |r_i| < hi). False: take the
// general path (validate_pair_ldl, then the dispatcher's scaling).
inline bool screen_contact_pair(double const *r, double const *q1, double const *q2,
                                double lo, double hi) noexcept {
  // The two matrices side by side in the two lanes (src/core/screen.hpp).
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

}  // namespace capi
}  // namespace pw85
