// PW85_METHOD_NEWTON: safeguarded Halley iteration on f'(lambda) = 0 (that
// is, on the residual g = -f' of pw85 1.0, chapter 5, eqs. (4)-(5)), with f
// and its derivatives evaluated in double through LDL^T of Q(lambda)
// (src/core/f_ldl.hpp, docs/methods.md eqs. (M1)-(M5)).
//
//  - f is concave on [0, 1] (docs/methods.md, eq. (M3)), so f' decreases
//    from f'(0) = r^T Q1^{-1} r > 0 to f'(1) = -r^T Q2^{-1} r < 0 and the
//    root is bracketed by [lo, hi] = [0, 1]; every evaluation shrinks the
//    bracket, and a step that leaves it is replaced by bisection;
//  - starting point (eq. (M7)): lambda0 = h1 / (h1 + h2), h_i = (r^T Q_i r)^(1/2),
//    exact for two spheres;
//  - stopping test (eq. (M9)): once the estimated error of the maximum of
//    the cubic Taylor model at lambda is below 1e-16 f, mu2 is that maximum
//    (no further evaluation); or the step is below the rounding of lambda.
#include <cmath>

#include "common/fp.hpp"
#include "contact/contact.hpp"
#include "eval/f_ldl.hpp"
#include "contact/newton.hpp"

namespace pw85 {

namespace {
constexpr double kExtrapGap = 1e-6;
constexpr double kExtrapBudget = 1e-16;
constexpr int kMaxIter = 60;
}  // namespace

bool newton_iterate(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, Sym3 const &d,
                    double lambda, NewtonState &st, int &iterations) noexcept {
  double lo = 0.0, hi = 1.0;
  FEval &e = st.e;
  // Every field is written on every return: mu2 = e.f at lambda = e.lambda
  // (no extrapolation, rel not yet computed) until the stopping test (M9)
  // says otherwise; NaN while no evaluation has succeeded.
  e = FEval{};
  e.f = std::nan("");
  st.mu2 = st.lambda = std::nan("");
  st.step = st.trunc = st.edf = 0.0;
  st.rel = -1.0;
  for (int it = 0; it < kMaxIter; ++it) {
    ++iterations;
    FEval cur;
    if (!f_eval(lambda, r, q1, q2, d, cur)) return false;
    e = cur;
    st.lambda = e.lambda;
    st.mu2 = e.f;
    if (e.df > 0.0)
      lo = lambda;
    else
      hi = lambda;
    double const a = -e.d2f;  // > 0 for a concave f
    double step;
    double const den = 2.0 * e.d2f * e.d2f - e.df * e.d3f;
    if (a > 0.0 && den > 0.0)
      step = -2.0 * e.df * e.d2f / den;  // Halley, eq. (M8)
    else if (a > 0.0)
      step = e.df / a;  // Newton
    else
      step = 0.5 * (lo + hi) - lambda;
    double next = lambda + step;
    bool const inside = next > lo && next < hi;
    // Near the maximum (gap f'^2 / (2|f''|) below 1e-6 f): the maximum of the
    // cubic Taylor model at lambda gives max f with a truncation error of
    // order gap^2 (eq. (M9)); its other error is (error of f') * step. Stop
    // when these are below 1e-16 f, or when f' is at its rounding-noise level
    // (no double iteration can do better).
    if (a > 0.0 && inside && e.df * e.df <= 2.0 * a * kExtrapGap * e.f) {
      double const rel = phi_error(e, r, q1, q2) / e.phi + 4.0 * kU;
      double const p = lambda * (1.0 - lambda);
      double const edf = rel * (std::fabs(1.0 - 2.0 * lambda) * e.phi + p * std::fabs(e.dphi));
      // Truncation of the cubic model: bounded by the size of its last term
      // |f''' delta^3| / 6 (the remainder f'''' delta^4 / 24 is much smaller
      // near the maximum), counted twice below (eq. (M9)).
      double const trunc = std::fabs(e.d3f * step * step * step) / 6.0;
      double const err = edf * std::fabs(step) + edf * edf / (2.0 * a) + 2.0 * trunc;
      if (err <= kExtrapBudget * e.f || std::fabs(e.df) <= 2.0 * edf) {
        st.lambda = next;
        st.step = step;
        st.mu2 = e.f + step * (e.df + step * (0.5 * e.d2f + step * e.d3f / 6.0));
        st.trunc = trunc;
        st.rel = rel;
        st.edf = edf;
        return true;
      }
    }
    if (!inside) {
      next = 0.5 * (lo + hi);
      step = next - lambda;
    }
    if (std::fabs(step) <= 2.0 * kU * lambda) {
      st.lambda = lambda;
      st.step = 0.0;
      st.mu2 = e.f;
      st.trunc = 0.0;
      st.rel = -1.0;
      return true;
    }
    lambda = next;
  }
  return false;
}

// Estimate of |mu2 - max f| for the result of newton_iterate (eq. (M10)):
// error of the computed f (eq. (M6)), plus, for the extrapolated value, the
// error of f' times the step and the truncation of the Taylor model; when
// the iteration ended without extrapolation, the gap to the maximum with f'
// widened by its own error.
double newton_error(NewtonState const &st, Vec3 const &r, Sym3 const &q1,
                    Sym3 const &q2) noexcept {
  newton_fill_error_terms(const_cast<NewtonState &>(st), r, q1, q2);
  FEval const &e = st.e;
  double const a = -e.d2f;
  if (!(a > 0.0)) return e.f;
  return st.rel * std::fabs(st.mu2) + newton_lambda_error(st);
}

void newton_fill_error_terms(NewtonState &st, Vec3 const &r, Sym3 const &q1,
                             Sym3 const &q2) noexcept {
  if (st.rel >= 0.0) return;
  FEval const &e = st.e;
  double const p = e.lambda * (1.0 - e.lambda);
  st.rel = phi_error(e, r, q1, q2) / e.phi + 4.0 * kU;
  st.edf = st.rel * (std::fabs(1.0 - 2.0 * e.lambda) * e.phi + p * std::fabs(e.dphi));
}

double newton_lambda_error(NewtonState const &st) noexcept {
  FEval const &e = st.e;
  double const a = -e.d2f;
  if (!(a > 0.0)) return e.f;
  if (st.step != 0.0)
    return st.edf * std::fabs(st.step) + st.edf * st.edf / (2.0 * a) + 2.0 * st.trunc;
  double const g = std::fabs(e.df) + st.edf;
  return g * g / (2.0 * a);
}

Status contact_newton(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                      MethodResult &res) noexcept {
  res.iterations = 0;
  Sym3 const d = difference(q2, q1);
  NewtonState st;
  st.e.f = std::nan("");
  bool const ok = newton_iterate(r, q1, q2, d, fixed_point_start(r, q1, q2), st, res.iterations);
  if (!ok && !std::isfinite(st.e.f)) {
    res.mu2 = std::nan("");
    res.lambda = std::nan("");
    res.mu2_error = std::nan("");
    return kNoConvergence;
  }
  res.mu2 = st.mu2;
  res.lambda = st.lambda;
  res.mu2_error = newton_error(st, r, q1, q2);
  if (!ok) return kNoConvergence;
  return res.mu2_error <= kNewtonRelAccuracy * res.mu2 ? kOk : kInaccurate;
}

}  // namespace pw85
