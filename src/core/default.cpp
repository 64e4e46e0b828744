// PW85_METHOD_DEFAULT (docs/methods.md, section "DEFAULT"):
//  1. the NEWTON iteration in double (newton.cpp) with its error estimate
//     (eq. (M10));
//  2. if the estimate is below kFastRel * mu2, that result is returned (the
//     fast path, taken by most pairs);
//  3. otherwise f and f' are re-evaluated in double-double at the current
//     lambda (f_dd.hpp, eq. (M11)) and Newton steps on f' are taken with the
//     double-precision f'' as slope, until the gap f'^2 / (2|f''|) is below
//     2^-60 f. Since mu2 = max f, an error delta on lambda changes mu2 by
//     |f''| delta^2 / 2 only: the accuracy of mu2 is the accuracy of the
//     double-double f, about kappa(Q) 2^-104 relative.
//  4. when the double iteration failed (Q(lambda) not numerically positive
//     definite in double), the root of f' is bracketed by bisection on the
//     sign of the double-double f'.
#include <cmath>

#include "contact.hpp"
#include "f_dd.hpp"
#include "newton.hpp"

namespace pw85 {

namespace {
constexpr double kU = 0x1p-53;
// Fast path when the estimated relative error is below this.
constexpr double kFastRel = 4e-15;
constexpr double kDDGapTol = 0x1p-60;
constexpr int kDDMaxNewton = 6;
constexpr int kDDMaxBisect = 80;
}  // namespace

Status contact_default(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                       MethodResult &res) noexcept {
  res.iterations = 0;
  Sym3 const d = difference(q2, q1);
  NewtonState st;
  FEval &e = st.e;
  e.f = std::nan("");
  bool const ok = newton_iterate(r, q1, q2, d, newton_start(r, q1, q2), st, res.iterations);
  double rel_double = 1.0;  // estimated relative error of the double phi
  if (std::isfinite(e.f)) {
    double const err = newton_error(st, r, q1, q2);
    if (ok && err <= kFastRel * st.mu2) {
      res.mu2 = st.mu2;
      res.lambda = st.lambda;
      res.mu2_error = err;
      return kOk;
    }
    rel_double = phi_error(e, r, q1, q2) / e.phi;
  }
  // Slow path: double-double.
  // Relative error of the double-double phi: the double estimate with u
  // replaced by u^2 (times 8 for the extra operations of double-double),
  // plus the final rounding to double.
  double const rel_dd = 8.0 * rel_double * kU + 2.0 * kU;
  FEvalDD fd;
  double lambda;
  double a = std::isfinite(e.f) ? -e.d2f : 0.0;  // -f'' > 0
  if (std::isfinite(e.f) && a > 0.0) {
    lambda = (st.lambda > 0.0 && st.lambda < 1.0) ? st.lambda : e.lambda;
    for (int k = 0; k < kDDMaxNewton; ++k) {
      ++res.iterations;
      if (!f_eval_dd(lambda, r, q1, q2, fd)) break;
      double const gap = fd.df * fd.df / (2.0 * a);
      if (gap <= kDDGapTol * fd.f) {
        res.mu2 = fd.f;
        res.lambda = lambda;
        res.mu2_error = rel_dd * fd.f + gap;
        return res.mu2_error <= kDefaultRelAccuracy * res.mu2 ? kOk : kInaccurate;
      }
      double next = lambda + fd.df / a;
      if (!(next > 0.0 && next < 1.0) || next == lambda) break;
      // Refresh the slope where the double evaluation still works.
      FEval e2;
      if (f_eval(next, r, q1, q2, d, e2) && e2.d2f < 0.0) a = -e2.d2f;
      lambda = next;
    }
  }
  // Fallback: bisection on the sign of the double-double f'.
  double lo = 0.0, hi = 1.0;
  lambda = 0.5;
  bool have = false;
  FEvalDD best{};
  double best_lambda = 0.5;
  for (int k = 0; k < kDDMaxBisect && hi - lo > 4.0 * kU * hi; ++k) {
    ++res.iterations;
    lambda = 0.5 * (lo + hi);
    if (!f_eval_dd(lambda, r, q1, q2, fd)) break;
    if (!have || fd.f > best.f) {
      best = fd;
      best_lambda = lambda;
      have = true;
    }
    if (fd.df > 0.0)
      lo = lambda;
    else
      hi = lambda;
  }
  if (!have) {
    res.mu2 = std::isfinite(e.f) ? st.mu2 : std::nan("");
    res.lambda = std::isfinite(e.f) ? st.lambda : std::nan("");
    res.mu2_error = std::isfinite(e.f) ? newton_error(st, r, q1, q2) : std::nan("");
    return kNoConvergence;
  }
  res.mu2 = best.f;
  res.lambda = best_lambda;
  // Gap bound (f concave): f* - f(last) <= |f'(last)| (hi - lo), last = the
  // last bisection point, an end of [lo, hi]; f(best) >= f(last).
  res.mu2_error = rel_dd * best.f + std::fabs(fd.df) * (hi - lo);
  return res.mu2_error <= kDefaultRelAccuracy * res.mu2 ? kOk : kInaccurate;
}

}  // namespace pw85
