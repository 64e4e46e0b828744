// Starting points of the iterations (docs/methods.md, eqs. (M7), (M19), (M20)),
// inline so that the instruction-set variants of DEFAULT (default.cpp)
// compile them for their level; also used by NEWTON and RATIONAL.
#pragma once

#include <cmath>

#include "isa.hpp"
#include "sym3.hpp"

namespace pw85 {

// Eq. (M7): lambda0 = h1 / (h1 + h2), h_i = (r^T Q_i r)^(1/2); the fallback
// of fixed_point_start.
inline double newton_start(Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept {
  double const h1 = std::sqrt(dot(r, multiply(q1, r)));
  double const h2 = std::sqrt(dot(r, multiply(q2, r)));
  double const l0 = h1 / (h1 + h2);
  return (l0 > 0.0 && l0 < 1.0) ? l0 : 0.5;
}

namespace detail {

// a_i = n^T Q_i n, i = 1, 2, and adj(q) r below: what dot(n, multiply(q, n))
// and multiply(adjugate3(q), r) of sym3.hpp compute, summed as short trees
// (the dependency chain is the cost of the start). The two orders give
// starts that differ in the last bits, which moves some results by an ulp
// (tests/test-contact.c's point bounds, set at the measured maxima, notice).
inline void support_squares(Vec3 const &n, Sym3 const &q1, Sym3 const &q2, double &a1,
                            double &a2) noexcept {
  double const n00 = n[0] * n[0], n11 = n[1] * n[1], n22 = n[2] * n[2];
  double const n01 = 2.0 * n[0] * n[1], n02 = 2.0 * n[0] * n[2], n12 = 2.0 * n[1] * n[2];
  a1 = (q1[0] * n00 + q1[3] * n11) + (q1[5] * n22 + q1[1] * n01) + (q1[2] * n02 + q1[4] * n12);
  a2 = (q2[0] * n00 + q2[3] * n11) + (q2[5] * n22 + q2[1] * n01) + (q2[2] * n02 + q2[4] * n12);
}

inline Vec3 adj_times(Sym3 const &q, Vec3 const &r) noexcept {
  Sym3 const c = adjugate3(q);
  return Vec3{{c[0] * r[0] + (c[1] * r[1] + c[2] * r[2]),
               c[1] * r[0] + (c[3] * r[1] + c[4] * r[2]),
               c[2] * r[0] + (c[4] * r[1] + c[5] * r[2])}};
}

}  // namespace detail

// Eq. (M19). At the maximiser, n = Q(lambda*)^{-1} r is the common normal and
// lambda* = h1(n) / (h1(n) + h2(n)), h_i(n) = (n^T Q_i n)^(1/2); iterating
// that map from lambda = 1/2 approaches lambda* fast while far from it (it is
// exact for spheres). n is needed only up to a factor: with x = h1 / h2 =
// lambda / (1 - lambda),
//   adj(Q(lambda)) r ~ adj(Q1) r + x M r + x^2 adj(Q2) r,
// M the mixed adjugate (eq. (M13)), M r = adj(Q1 + Q2) r - adj(Q1) r -
// adj(Q2) r. The three vectors do not depend on lambda and are formed in
// parallel at the start. Multiplied by h2^2 / (a1 + a2), a_i = h_i^2, the
// next n is (a2 n1 + sqrt(a1 a2) M r + a1 n2) / (a1 + a2): one square root
// on the dependency chain of a step and no division there (the reciprocal
// of a1 + a2 is formed while the square root runs; the factor keeps n from
// over- or underflowing over the steps). The result is the Aitken
// extrapolation of the three iterates (eq. (M20)).
PW85_ALWAYS_INLINE double fixed_point_start(Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept {
  constexpr int kSteps = 3;
  Sym3 q12;
  for (int i = 0; i < kSym; ++i) q12[i] = q1[i] + q2[i];
  Vec3 const n12 = detail::adj_times(q12, r), n1 = detail::adj_times(q1, r),
             n2 = detail::adj_times(q2, r);
  Vec3 mr;
  for (int i = 0; i < kDim; ++i) mr[i] = n12[i] - (n1[i] + n2[i]);
  double a1, a2;
  detail::support_squares(n12, q1, q2, a1, a2);  // step 1: lambda = 1/2, n = adj(Q1 + Q2) r
  static_assert(kSteps >= 3, "Aitken's extrapolation needs three iterates");
  double lam[kSteps - 1];  // lambda after steps 1 .. kSteps - 1
  for (int k = 1; k < kSteps; ++k) {
    // Range: with every magnitude in (2^-60, 2^60) (methods.cpp rescales
    // the others), a_i <= ~2^420, and a_i >= ~2^-460 for eigenvalue ratios
    // up to 2^40, so a1 a2 stays a normal double. Beyond, an overflow makes
    // lambda NaN ((M7) below) and an underflow gives a worse start, never a
    // wrong result. sqrt(a1) sqrt(a2) would avoid both; it measured ~2 %
    // slower (A/B, one more square root per step).
    double const g = std::sqrt(a1 * a2), scale = 1.0 / (a1 + a2);
    lam[k - 1] = a1 / (a1 + g);  // h1 / (h1 + h2), off the chain
    double const c1 = a2 * scale, cm = g * scale, c2 = a1 * scale;
    Vec3 n;
    for (int i = 0; i < kDim; ++i) n[i] = c1 * n1[i] + (cm * mr[i] + c2 * n2[i]);
    detail::support_squares(n, q1, q2, a1, a2);
  }
  double const h1 = std::sqrt(a1), h2 = std::sqrt(a2);
  double const l3 = h1 / (h1 + h2);
  // Eq. (M20): Aitken's extrapolation of the last three iterates (the map
  // converges linearly), kept when the correction is at most 10 times the
  // last step (contraction ratio below ~0.9, or oscillation) and lands in
  // (0, 1); a zero or NaN denominator fails the test.
  double const e1 = l3 - lam[kSteps - 2], e0 = lam[kSteps - 2] - lam[kSteps - 3];
  double const corr = e1 * e1 / (e1 - e0);
  double const l = std::fabs(corr) <= 10.0 * std::fabs(e1) ? l3 - corr : l3;
  return l > 0.0 && l < 1.0 ? l : (l3 > 0.0 && l3 < 1.0 ? l3 : newton_start(r, q1, q2));
}

}  // namespace pw85
