// Reference contact function in __float128 for the benchmarks (bench_contact,
// bench_near_contact): mu2 = max over lambda in [0, 1] of
// f(lambda) = lambda (1 - lambda) r12^T Q(lambda)^{-1} r12,
// Q(lambda) = (1 - lambda) Q1 + lambda Q2, formed from the double inputs and
// evaluated through an LDL^T factorisation of Q(lambda), all in __float128.
// Benchmarks only, not part of the library.
#pragma once

#include <cmath>

#include <quadmath.h>

namespace bench {

struct ReferenceEval {
  __float128 f, df, d2f;  // f(lambda) and its first two derivatives
};

// f, f' and f'' at lambda; false when Q(lambda) is not positive definite in
// __float128.
inline bool reference_eval(__float128 lam, double const r12[3], double const q1[6],
                           double const q2[6], ReferenceEval &e) {
  using F128 = __float128;
  F128 q[6], d[6];
  for (int i = 0; i < 6; ++i) {
    q[i] = (1 - lam) * (F128)q1[i] + lam * (F128)q2[i];
    d[i] = (F128)q2[i] - (F128)q1[i];
  }
  F128 const d0 = q[0];
  if (!(d0 > 0)) return false;
  F128 const l10 = q[1] / d0, l20 = q[2] / d0;
  F128 const d1 = q[3] - l10 * q[1];
  if (!(d1 > 0)) return false;
  F128 const ee = q[4] - l20 * q[1];
  F128 const l21 = ee / d1;
  F128 const d2 = q[5] - l20 * q[2] - l21 * ee;
  if (!(d2 > 0)) return false;
  auto solve = [&](F128 const b[3], F128 x[3]) {
    F128 const y0 = b[0], y1 = b[1] - l10 * y0, y2 = b[2] - l20 * y0 - l21 * y1;
    x[2] = y2 / d2;
    x[1] = y1 / d1 - l21 * x[2];
    x[0] = y0 / d0 - l10 * x[1] - l20 * x[2];
  };
  auto mul = [&](F128 const a[6], F128 const x[3], F128 y[3]) {
    y[0] = a[0] * x[0] + a[1] * x[1] + a[2] * x[2];
    y[1] = a[1] * x[0] + a[3] * x[1] + a[4] * x[2];
    y[2] = a[2] * x[0] + a[4] * x[1] + a[5] * x[2];
  };
  F128 const r[3] = {r12[0], r12[1], r12[2]};
  F128 s[3], u[3], v[3];
  solve(r, s);
  mul(d, s, u);
  solve(u, v);
  F128 const phi = r[0] * s[0] + r[1] * s[1] + r[2] * s[2];
  F128 const phi1 = -(s[0] * u[0] + s[1] * u[1] + s[2] * u[2]);
  F128 const phi2 = 2 * (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]);
  F128 const pp = lam * (1 - lam), p1 = 1 - 2 * lam;
  e.f = pp * phi;
  e.df = p1 * phi + pp * phi1;
  e.d2f = -2 * phi + 2 * p1 * phi1 + pp * phi2;
  return true;
}

// Maximiser of the concave f: bisection on the sign of f' down to a bracket
// of 2^-40, then Newton steps on f' in __float128 until the step is below
// 1e-30; mu2 = f at the final lambda (its error in lambda enters mu2 only
// to second order). NaN when Q(lambda) is not positive definite.
inline __float128 reference_mu2(double const r12[3], double const q1[6], double const q2[6]) {
  using F128 = __float128;
  F128 lo = 0, hi = 1;
  ReferenceEval e;
  for (int k = 0; k < 40; ++k) {
    F128 const m = (lo + hi) / 2;
    if (!reference_eval(m, r12, q1, q2, e)) return NAN;
    if (e.df > 0)
      lo = m;
    else
      hi = m;
  }
  F128 lam = (lo + hi) / 2;
  for (int k = 0; k < 8; ++k) {
    if (!reference_eval(lam, r12, q1, q2, e)) return NAN;
    F128 const step = -e.df / e.d2f;
    F128 next = lam + step;
    if (!(next > lo && next < hi)) break;
    lam = next;
    if (fabsq(step) < (F128)1e-30) break;
  }
  if (!reference_eval(lam, r12, q1, q2, e)) return NAN;
  return e.f;
}

}  // namespace bench
