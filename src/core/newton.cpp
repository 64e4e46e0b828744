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

#include "contact.hpp"
#include "f_ldl.hpp"
#include "newton.hpp"

namespace pw85 {

namespace {
constexpr double kU = 0x1p-53;
constexpr double kExtrapGap = 1e-6;
constexpr double kExtrapBudget = 1e-16;
constexpr int kMaxIter = 60;
}  // namespace

double newton_start(Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept {
  double const h1 = std::sqrt(dot(r, multiply(q1, r)));
  double const h2 = std::sqrt(dot(r, multiply(q2, r)));
  double const l0 = h1 / (h1 + h2);
  return (l0 > 0.0 && l0 < 1.0) ? l0 : 0.5;
}

namespace {

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

}  // namespace

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
// over- or underflowing over the steps).
double fixed_point_start(Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept {
  constexpr int kSteps = 3;
  Sym3 q12;
  for (int i = 0; i < kSym; ++i) q12[i] = q1[i] + q2[i];
  Vec3 const n12 = adj_times(q12, r), n1 = adj_times(q1, r), n2 = adj_times(q2, r);
  Vec3 mr;
  for (int i = 0; i < kDim; ++i) mr[i] = n12[i] - (n1[i] + n2[i]);
  double a1, a2;
  support_squares(n12, q1, q2, a1, a2);  // step 1: lambda = 1/2, n = adj(Q1 + Q2) r
  for (int k = 1; k < kSteps; ++k) {
    // Range: with every magnitude in (2^-60, 2^60) (methods.cpp rescales
    // the others), a_i <= ~2^420, and a_i >= ~2^-460 for eigenvalue ratios
    // up to 2^40, so a1 a2 stays a normal double. Beyond, an overflow makes
    // lambda NaN ((M7) below) and an underflow gives a worse start, never a
    // wrong result. sqrt(a1) sqrt(a2) would avoid both; it measured ~2 %
    // slower (A/B, one more square root per step).
    double const g = std::sqrt(a1 * a2), scale = 1.0 / (a1 + a2);
    double const c1 = a2 * scale, cm = g * scale, c2 = a1 * scale;
    Vec3 n;
    for (int i = 0; i < kDim; ++i) n[i] = c1 * n1[i] + (cm * mr[i] + c2 * n2[i]);
    support_squares(n, q1, q2, a1, a2);
  }
  double const h1 = std::sqrt(a1), h2 = std::sqrt(a2);
  double const l = h1 / (h1 + h2);
  return l > 0.0 && l < 1.0 ? l : newton_start(r, q1, q2);  // NaN, 0 or 1: (M7)
}

bool newton_iterate(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, Sym3 const &d,
                    double lambda, NewtonState &st, int &iterations) noexcept {
  double lo = 0.0, hi = 1.0;
  FEval &e = st.e;
  for (int it = 0; it < kMaxIter; ++it) {
    ++iterations;
    FEval cur;
    if (!f_eval(lambda, r, q1, q2, d, cur)) return false;
    e = cur;
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
  st.lambda = e.lambda;
  st.step = 0.0;
  st.mu2 = e.f;
  st.trunc = 0.0;
  st.rel = -1.0;
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
