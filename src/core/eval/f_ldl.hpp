// f and its first three derivatives in double precision through a
// square-root-free LDL^T factorisation of Q(lambda), with a forward error
// estimate of f. Shared by the NEWTON and DEFAULT methods (docs/methods.md).
//
//   Q(lambda)  = (1 - lambda) Q1 + lambda Q2,   D = Q2 - Q1,
//   phi        = r^T Q^{-1} r,          f = p phi,  p = lambda (1 - lambda)
//   phi'       = -s^T D s,              s = Q^{-1} r,  u = D s
//   phi''      = 2 u^T v,               v = Q^{-1} u
//   phi'''     = -6 v^T D v
//   f'   = p' phi + p phi'                       (p' = 1 - 2 lambda, p'' = -2)
//   f''  = -2 phi + 2 p' phi' + p phi''
//   f''' = -6 phi' + 3 p' phi'' + p phi'''
// (docs/methods.md, eqs. (M1)-(M4); phi' is eq. (4) of chapter 5 of the
// pw85 1.0 documentation up to the factor relating g = -f'.)
//
// Error estimate of phi (docs/methods.md, eq. (M6)): the computed s solves
// (Q + dQ) s = r with |dQ| <= c u |L| |D| |L^T| (Higham, Accuracy and
// Stability of Numerical Algorithms, 2nd ed., theorem 10.4, for the LDL^T
// variant), the interpolation adds |dQ| <= u ((1-lambda)|Q1| + lambda|Q2|)
// and the final dot product c' u |r|^T |s|, so
//   |dphi| <~ u (c1 sum_i d_i t_i^2 + c2 |s|^T Qabs |s| + c3 |r|^T |s|),
//   t = |L^T| |s|.
#pragma once

#include <cmath>

#include "common/fp.hpp"
#include "eval/f_derivatives.hpp"
#include "common/sym3.hpp"

namespace pw85 {

// Unit lower-triangular L = [1 0 0; l10 1 0; l20 l21 1] and D = diag(d),
// stored with the reciprocals of the pivots.
struct Ldl {
  double l10, l20, l21;
  double d0, d1, d2;
  double id0, id1, id2;
};

inline bool ldl(Sym3 const &q, Ldl &f) noexcept {
  f.d0 = q[0];
  if (!(f.d0 > 0.0)) return false;
  f.id0 = 1.0 / f.d0;
  f.l10 = q[1] * f.id0;
  f.l20 = q[2] * f.id0;
  f.d1 = q[3] - f.l10 * q[1];
  if (!(f.d1 > 0.0)) return false;
  f.id1 = 1.0 / f.d1;
  double const e = q[4] - f.l20 * q[1];
  f.l21 = e * f.id1;
  f.d2 = q[5] - f.l20 * q[2] - f.l21 * e;
  if (!(f.d2 > 0.0)) return false;
  f.id2 = 1.0 / f.d2;
  return true;
}

inline Vec3 ldl_solve(Ldl const &f, Vec3 const &b) noexcept {
  double const y0 = b[0];
  double const y1 = b[1] - f.l10 * y0;
  double const y2 = b[2] - f.l20 * y0 - f.l21 * y1;
  Vec3 x;
  x[2] = y2 * f.id2;
  x[1] = y1 * f.id1 - f.l21 * x[2];
  x[0] = y0 * f.id0 - f.l10 * x[1] - f.l20 * x[2];
  return x;
}

struct FEval {
  double lambda;
  double phi, dphi;          // phi, phi'
  double f, df, d2f, d3f;    // f and its derivatives
  Ldl l;
  Vec3 s;
};

// Evaluates everything listed above at lambda. Returns false when Q(lambda)
// is not numerically positive definite or a value is not finite.
inline bool f_eval(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                   Sym3 const &d, FEval &e) noexcept {
  e.lambda = lambda;
  if (!ldl(interpolate(q1, q2, lambda), e.l)) return false;
  e.s = ldl_solve(e.l, r);
  Vec3 const u = multiply(d, e.s);
  Vec3 const v = ldl_solve(e.l, u);
  Vec3 const w = multiply(d, v);
  set_f_derivatives(lambda, r, e.s, u, v, w, e);
  return std::isfinite(e.f) && std::isfinite(e.df) && std::isfinite(e.d2f) &&
         std::isfinite(e.d3f);
}

// Estimate of the absolute error of the computed phi (eq. (M6)).
inline double phi_error(FEval const &e, Vec3 const &r, Sym3 const &q1,
                        Sym3 const &q2) noexcept {
  Ldl const &l = e.l;
  double const a0 = std::fabs(e.s[0]), a1 = std::fabs(e.s[1]), a2 = std::fabs(e.s[2]);
  double const t0 = a0 + std::fabs(l.l10) * a1 + std::fabs(l.l20) * a2;
  double const t1 = a1 + std::fabs(l.l21) * a2;
  double const t2 = a2;
  double const b = l.d0 * t0 * t0 + l.d1 * t1 * t1 + l.d2 * t2 * t2;
  double const lm = 1.0 - e.lambda, lp = e.lambda;
  double qa[kSym];
  for (int i = 0; i < kSym; ++i) qa[i] = lm * std::fabs(q1[i]) + lp * std::fabs(q2[i]);
  double const sq = qa[0] * a0 * a0 + qa[3] * a1 * a1 + qa[5] * a2 * a2 +
                    2.0 * (qa[1] * a0 * a1 + qa[2] * a0 * a2 + qa[4] * a1 * a2);
  double const rs = std::fabs(r[0]) * a0 + std::fabs(r[1]) * a1 + std::fabs(r[2]) * a2;
  return kU * (4.0 * b + 2.0 * sq + 3.0 * rs);
}

}  // namespace pw85
