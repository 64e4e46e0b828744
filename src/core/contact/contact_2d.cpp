// The Perram-Wertheim contact function of two ellipses (2D), for comparison
// with the closed-form DCA of dca_2d.cpp (d(u) = 1 / sqrt(F(u))).
//
//   f(lambda)   = lambda (1 - lambda) r^T s,   s = Q(lambda)^{-1} r,
//                 Q(lambda) = (1 - lambda) Q1 + lambda Q2
//                 (pw85 documentation, chapter 4, eqs. (1)-(4), in 2D);
//   f'(lambda)  = (1 - 2 lambda) r^T s - lambda (1 - lambda) s^T D s,
//   f''(lambda) = -2 r^T s - 2 (1 - 2 lambda) s^T D s
//                 + 2 lambda (1 - lambda) (D s)^T Q^{-1} (D s),  D = Q2 - Q1
//                 (docs/dca.md, eqs. (C1)-(C2)).
//
// f is concave on [0, 1] with f'(0) = r^T Q1^{-1} r > 0 and
// f'(1) = -r^T Q2^{-1} r < 0, so f' has one root: it is found by Newton's
// method on f' inside a bracket that every evaluation shrinks, with a
// bisection step whenever Newton's step leaves the bracket. The first
// iterate is the exact maximiser for two circles,
// lambda0 = rho1 / (rho1 + rho2), rho_i = (r^T Q_i^{-1} r)^{-1/2}.
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/fp.hpp"
#include "dca/dca.hpp"
#include "common/magnitude.hpp"
#include "common/scaling.hpp"

namespace pw85 {

namespace {

constexpr int kMaxIter = 100;

struct Derivatives {
  double f, df, d2f;
};

bool evaluate(double lambda, Vec2 const &r, Sym2 const &q1, Sym2 const &q2,
              Derivatives &out) noexcept {
  Sym2 q, dq;
  for (int i = 0; i < 3; ++i) {
    q[i] = (1.0 - lambda) * q1[i] + lambda * q2[i];
    dq[i] = q2[i] - q1[i];
  }
  Vec2 s, v;
  if (!solve(q, r, s)) return false;
  Vec2 const ds = multiply(dq, s);
  if (!solve(q, ds, v)) return false;
  double const rs = dot(r, s), sds = dot(s, ds), dsv = dot(ds, v);
  double const l1m = lambda * (1.0 - lambda);
  out.f = l1m * rs;
  out.df = (1.0 - 2.0 * lambda) * rs - l1m * sds;
  out.d2f = -2.0 * rs - 2.0 * (1.0 - 2.0 * lambda) * sds + 2.0 * l1m * dsv;
  return std::isfinite(out.f) && std::isfinite(out.df) && std::isfinite(out.d2f);
}

}  // namespace

Status contact_function_2d(Vec2 const &r_in, Sym2 const &q1_in, Sym2 const &q2_in,
                           double &mu2, double &lambda, int &iterations) noexcept {
  iterations = 0;
  if (r_in[0] == 0.0 && r_in[1] == 0.0) {
    mu2 = 0.0;
    lambda = 0.5;
    return kOk;
  }
  // Exact rescaling: r' = 2^-er r, Q' = 2^-eq Q give mu2' = 2^(eq - 2 er) mu2.
  int const er = max_exponent(r_in.x, 2);
  double qs[6] = {q1_in[0], q1_in[1], q1_in[2], q2_in[0], q2_in[1], q2_in[2]};
  int const eq = max_exponent(qs, 6);
  Vec2 r;
  Sym2 q1, q2;
  scale_pair(r_in, q1_in, q2_in, -er, -eq, r, q1, q2);
  Vec2 s1, s2;
  if (!solve(q1, r, s1) || !solve(q2, r, s2)) {
    mu2 = lambda = std::nan("");
    return kNotSpd;
  }
  double const rho1 = 1.0 / std::sqrt(dot(r, s1)), rho2 = 1.0 / std::sqrt(dot(r, s2));
  double lo = 0.0, hi = 1.0;
  double x = rho1 / (rho1 + rho2);
  if (!(x > 0.0 && x < 1.0)) x = 0.5;
  Derivatives der;
  bool converged = false;
  double best_x = x;
  for (int it = 0; it < kMaxIter; ++it) {
    if (!evaluate(x, r, q1, q2, der)) break;
    ++iterations;
    best_x = x;
    if (der.df == 0.0) {
      converged = true;
      break;
    }
    if (der.df > 0.0)
      lo = x;
    else
      hi = x;
    double next = (der.d2f < 0.0) ? x - der.df / der.d2f : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    double const step = next - x;
    x = next;
    if (std::fabs(step) <= 2.0 * kEps * std::fmax(x, 1.0 - x) || hi - lo <= 2.0 * kEps) {
      if (evaluate(x, r, q1, q2, der)) best_x = x;
      converged = true;
      break;
    }
  }
  if (!evaluate(best_x, r, q1, q2, der)) {
    mu2 = lambda = std::nan("");
    return kNoConvergence;
  }
  mu2 = std::ldexp(der.f, 2 * er - eq);
  lambda = best_x;
  return converged ? kOk : kNoConvergence;
}

}  // namespace pw85
