// The function f of Perram and Wertheim and the residual g of pw85's Newton
// refinement, evaluated through a Cholesky factorisation of Q(lambda).
//
//   f(lambda) = lambda (1 - lambda) r^T Q^{-1} r,  Q = (1 - lambda) Q1 + lambda Q2
//       (pw85 documentation, chapter 4, eqs. (1)-(4))
//   g(lambda) = mu2^2 - mu1^2 = (2 lambda - 1) r^T s + lambda (1 - lambda) s^T u
//   g'(lambda) = 2 r^T s + 2 (1 - 2 lambda) s^T u - 2 lambda (1 - lambda) u^T v
//       (chapter 5, eqs. (4)-(5)), with s = Q^{-1} r, u = (Q2 - Q1) s,
//       v = Q^{-1} u.
//
// The error of these double-precision evaluations grows with the condition
// number of Q(lambda); see docs/ for the measured consequences.
#pragma once

#include "common/sym3.hpp"

namespace pw85 {

// f(lambda). Returns false when Q(lambda) is not numerically positive definite.
inline bool f_cholesky(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                       double &f) noexcept {
  Sym3 l;
  if (!cholesky(interpolate(q1, q2, lambda), l)) return false;
  Vec3 const s = cholesky_solve(l, r);
  f = lambda * (1.0 - lambda) * dot(r, s);
  return std::isfinite(f);
}

struct Residual {
  double f;   // f(lambda)
  double g;   // g(lambda) = mu2^2 - mu1^2
  double dg;  // g'(lambda)
};

inline bool residual_cholesky(double lambda, Vec3 const &r, Sym3 const &q1,
                              Sym3 const &q2, Residual &out) noexcept {
  Sym3 l;
  if (!cholesky(interpolate(q1, q2, lambda), l)) return false;
  Vec3 const s = cholesky_solve(l, r);
  Vec3 const u = multiply(difference(q2, q1), s);
  Vec3 const v = cholesky_solve(l, u);
  double const rs = dot(r, s);
  double const su = dot(s, u);
  double const uv = dot(u, v);
  double const lambda_1m = lambda * (1.0 - lambda);
  out.f = lambda_1m * rs;
  out.g = (2.0 * lambda - 1.0) * rs + lambda_1m * su;
  out.dg = 2.0 * rs + 2.0 * (1.0 - 2.0 * lambda) * su - 2.0 * lambda_1m * uv;
  return std::isfinite(out.f) && std::isfinite(out.g) && std::isfinite(out.dg);
}

}  // namespace pw85
