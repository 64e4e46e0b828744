// pw85 1.0's contact-function algorithm (pw85 documentation, chapter 5):
//  1. maximise f on [0, 1] with Brent's method (GSL's gsl_min_fminimizer_brent
//     on -f, stopped when the bracket is narrower than PW85_LAMBDA_ATOL or
//     after PW85_MAX_ITER iterations);
//  2. refine with PW85_NR_ITER Newton steps on the residual g = mu2^2 - mu1^2
//     (eqs. (4)-(5));
//  3. keep whichever of the two estimates has the smaller |g|.
//
// Differences from pw85 1.0, none of which changes a result that pw85 1.0
// computed correctly:
//  - GSL is never given input that would make it call its error handler
//    (whose default aborts the process): the bracket is checked before
//    gsl_min_fminimizer_set_with_values, and the function handed to GSL
//    always returns a finite value;
//  - the minimiser lives on the stack (no allocation per call, no shared
//    state between threads);
//  - r and Q are rescaled by powers of two (exact) so that f neither
//    underflows nor overflows;
//  - a Newton step that leaves [0, 1] or fails ends the refinement.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>

#include "contact/contact.hpp"
#include "eval/f_cholesky.hpp"
#include "eval/f_dd.hpp"
#include "common/magnitude.hpp"
#include "common/scaling.hpp"

namespace pw85 {

// These three mirror PW85_LAMBDA_ATOL, PW85_MAX_ITER, PW85_NR_ITER of
// include/pw85.h (checked there by static_assert in src/capi).
constexpr double kBrentLambdaAtol = 1e-6;
constexpr int kBrentMaxIter = 25;
constexpr int kBrentNewtonIter = 3;

namespace {

struct FParams {
  Vec3 r;
  Sym3 q1, q2;
  bool failed;
};

// -f(lambda) for GSL. Never returns a non-finite value (GSL would call its
// error handler); a failed evaluation is recorded and reported as f = 0,
// which Brent then treats as a poor point.
double f_neg_for_gsl(double lambda, void *params) {
  auto *p = static_cast<FParams *>(params);
  double f;
  if (!f_cholesky(lambda, p->r, p->q1, p->q2, f)) {
    p->failed = true;
    return 0.0;
  }
  return -f;
}

}  // namespace

Status contact_brent(Vec3 const &r_in, Sym3 const &q1_in, Sym3 const &q2_in,
                     ContactResult &res) noexcept {
  res.iterations = 0;
  res.er = res.eq = 0;
  if (r_in[0] == 0.0 && r_in[1] == 0.0 && r_in[2] == 0.0) {
    // f vanishes identically: mu^2 = 0, every lambda is a maximiser.
    res.mu2 = res.mu2_rescaled = 0.0;
    res.lambda = 0.5;
    return kOk;
  }
  // r' = 2^-er r and Q' = 2^-eq Q give mu2' = 2^(eq - 2 er) mu2, exactly.
  int const er = max_exponent(r_in.x, kDim);
  int const eq = std::max(max_exponent(q1_in.a, kSym), max_exponent(q2_in.a, kSym));
  FParams p;
  scale_pair(r_in, q1_in, q2_in, -er, -eq, p.r, p.q1, p.q2);
  p.failed = false;
  int const mu2_exponent = 2 * er - eq;
  res.er = er;
  res.eq = eq;

  // Step 1: Brent. f(0) = f(1) = 0 < f(1/2), so [0, 1] brackets the maximum;
  // GSL is only called once that has been checked.
  gsl_function fn;
  fn.function = &f_neg_for_gsl;
  fn.params = &p;
  double const f_mid = f_neg_for_gsl(0.5, &p);
  double lambda_brent = 0.5;
  bool brent_converged = false;
  alignas(std::max_align_t) unsigned char state[256];
  if (!p.failed && f_mid < 0.0 && gsl_min_fminimizer_brent->size <= sizeof state) {
    gsl_min_fminimizer s;
    s.type = gsl_min_fminimizer_brent;
    s.state = state;
    gsl_min_fminimizer_set_with_values(&s, &fn, 0.5, f_mid, 0.0, -0.0, 1.0, -0.0);
    for (int iter = 0; iter < kBrentMaxIter; ++iter) {
      ++res.iterations;
      gsl_min_fminimizer_iterate(&s);
      lambda_brent = gsl_min_fminimizer_x_minimum(&s);
      double const lo = gsl_min_fminimizer_x_lower(&s);
      double const hi = gsl_min_fminimizer_x_upper(&s);
      if (gsl_min_test_interval(lo, hi, kBrentLambdaAtol, 0.0) == GSL_SUCCESS) {
        brent_converged = true;
        break;
      }
    }
  }

  // Step 2: Newton on g from the Brent estimate.
  Residual best;
  if (!residual_cholesky(lambda_brent, p.r, p.q1, p.q2, best)) {
    res.mu2 = res.mu2_rescaled = std::nan("");
    res.lambda = lambda_brent;
    return kNoConvergence;
  }
  double best_lambda = lambda_brent;
  Residual current = best;
  double lambda = lambda_brent;
  for (int i = 0; i < kBrentNewtonIter; ++i) {
    double const next = lambda - current.g / current.dg;
    Residual trial;
    if (!(next >= 0.0 && next <= 1.0) ||
        !residual_cholesky(next, p.r, p.q1, p.q2, trial))
      break;
    lambda = next;
    current = trial;
  }
  // Step 3: keep the estimate with the smaller residual.
  if (std::fabs(current.g) < std::fabs(best.g)) {
    best = current;
    best_lambda = lambda;
  }
  // mu^2 = f(lambda) in the stationary form lambda (1 - lambda)(2 r^T s -
  // s^T Q s) with compensated sums (src/core/f_dd.hpp): the error of the
  // double-precision solve s = Q^{-1} r then enters only to second order,
  // instead of growing with the condition number of Q(lambda). The
  // iteration itself is pw85 1.0's; only this last evaluation differs.
  {
    Sym3 l;
    if (cholesky(interpolate(p.q1, p.q2, best_lambda), l)) {
      double const f = f_stationary(best_lambda, p.r, p.q1, p.q2, cholesky_solve(l, p.r));
      if (std::isfinite(f) && f >= 0.0) best.f = f;
    }
  }
  res.mu2_rescaled = best.f;
  res.mu2 = std::ldexp(best.f, mu2_exponent);
  res.lambda = best_lambda;
  // Brent's bracket did not close, but the refined residual may still show
  // convergence: |g| is on the scale of mu^2.
  if (!brent_converged && !(std::fabs(best.g) <= 1.5e-8 * best.f))
    return kNoConvergence;
  return kOk;
}

}  // namespace pw85
