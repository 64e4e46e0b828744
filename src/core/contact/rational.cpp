// PW85_METHOD_RATIONAL: the rational-fraction formulation of f
// (docs/methods.md, eqs. (M12)-(M14)). With s = 1 - lambda, t = lambda,
//   Q^{-1} = adj(Q) / det(Q),
//   det(s Q1 + t Q2)   = s^3 b0 + s^2 t b1 + s t^2 b2 + t^3 b3,
//       b0 = det Q1, b1 = tr(adj(Q1) Q2), b2 = tr(Q1 adj(Q2)), b3 = det Q2,
//   r^T adj(s Q1 + t Q2) r = s^2 a0 + s t a1 + t^2 a2,
//       a0 = r^T adj(Q1) r, a1 = r^T M(Q1, Q2) r, a2 = r^T adj(Q2) r,
//       M(Q1, Q2) = adj(Q1 + Q2) - adj(Q1) - adj(Q2) (the mixed adjugate),
//   f(lambda) = s t a(lambda) / b(lambda).
// For positive definite Q1, Q2 all seven coefficients are positive, so a and b
// are evaluated in this (Bernstein) form without cancellation; the whole
// conditioning sits in the coefficients, computed once per pair in double
// with a running error bound (each coefficient carries the sum of the
// absolute values of its terms). The maximum is found by a safeguarded
// Newton iteration on h' = (log f)', h = log s + log t + log a - log b,
// which is decreasing (f is concave, hence log-concave), bracketed in [0, 1].
#include <cmath>

#include "common/fp.hpp"
#include "contact/contact.hpp"
#include "eval/f_cholesky.hpp"
#include "contact/newton.hpp"
#include "contact/rational.hpp"

namespace pw85 {

namespace {

constexpr double kGapTol = 0x1p-56;
constexpr int kMaxIter = 100;
// Error of a coefficient <= kCoefErr * u * (sum of |terms|) (estimate).
constexpr double kCoefErr = 6.0;

// A value and the sum of the absolute values of the terms that made it.
struct RV {
  double v, a;
};
inline RV operator*(RV x, RV y) noexcept { return RV{x.v * y.v, x.a * y.a}; }
inline RV operator+(RV x, RV y) noexcept { return RV{x.v + y.v, x.a + y.a}; }
inline RV operator-(RV x, RV y) noexcept { return RV{x.v - y.v, x.a + y.a}; }
inline RV rv(double x) noexcept { return RV{x, std::fabs(x)}; }

struct Adj {
  RV c00, c01, c02, c11, c12, c22;
};

// Adjugate (cofactor matrix) of a symmetric 3x3 matrix.
inline Adj adjugate(RV const a[6]) noexcept {
  // a = {a00, a01, a02, a11, a12, a22}
  return Adj{a[3] * a[5] - a[4] * a[4], a[2] * a[4] - a[1] * a[5],
             a[1] * a[4] - a[2] * a[3], a[0] * a[5] - a[2] * a[2],
             a[1] * a[2] - a[0] * a[4], a[0] * a[3] - a[1] * a[1]};
}

// Mixed adjugate M(A, B): polarisation of each product of adjugate().
inline Adj mixed_adjugate(RV const a[6], RV const b[6]) noexcept {
  return Adj{a[3] * b[5] + b[3] * a[5] - (a[4] * b[4] + b[4] * a[4]),
             a[2] * b[4] + b[2] * a[4] - (a[1] * b[5] + b[1] * a[5]),
             a[1] * b[4] + b[1] * a[4] - (a[2] * b[3] + b[2] * a[3]),
             a[0] * b[5] + b[0] * a[5] - (a[2] * b[2] + b[2] * a[2]),
             a[1] * b[2] + b[1] * a[2] - (a[0] * b[4] + b[0] * a[4]),
             a[0] * b[3] + b[0] * a[3] - (a[1] * b[1] + b[1] * a[1])};
}

// tr(C B) for symmetric C (as Adj) and B.
inline RV trace_product(Adj const &c, RV const b[6]) noexcept {
  RV const two{2.0, 2.0};
  return c.c00 * b[0] + c.c11 * b[3] + c.c22 * b[5] +
         two * (c.c01 * b[1] + c.c02 * b[2] + c.c12 * b[4]);
}

// r^T C r.
inline RV quad_form(Adj const &c, RV const rr[6]) noexcept { return trace_product(c, rr); }

inline double rel_err(RV x) noexcept {
  return x.v > 0.0 ? kCoefErr * kU * x.a / x.v : 1.0;
}

}  // namespace

void rational_coefficients(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                           RationalCoefs &c) noexcept {
  RV a[6], b[6], rr[6];
  for (int i = 0; i < 6; ++i) {
    a[i] = rv(q1[i]);
    b[i] = rv(q2[i]);
  }
  rr[0] = rv(r[0] * r[0]);
  rr[1] = rv(r[0] * r[1]);
  rr[2] = rv(r[0] * r[2]);
  rr[3] = rv(r[1] * r[1]);
  rr[4] = rv(r[1] * r[2]);
  rr[5] = rv(r[2] * r[2]);
  Adj const ca = adjugate(a), cb = adjugate(b), cm = mixed_adjugate(a, b);
  RV const b0 = a[0] * ca.c00 + a[1] * ca.c01 + a[2] * ca.c02;
  RV const b3 = b[0] * cb.c00 + b[1] * cb.c01 + b[2] * cb.c02;
  RV const b1 = trace_product(ca, b), b2 = trace_product(cb, a);
  RV const a0 = quad_form(ca, rr), a1 = quad_form(cm, rr), a2 = quad_form(cb, rr);
  RV const av[3] = {a0, a1, a2}, bv[4] = {b0, b1, b2, b3};
  for (int i = 0; i < 3; ++i) {
    c.a[i] = av[i].v;
    c.ea[i] = rel_err(av[i]);
  }
  for (int i = 0; i < 4; ++i) {
    c.b[i] = bv[i].v;
    c.eb[i] = rel_err(bv[i]);
  }
}

void rational_maximise(RationalCoefs const &c, double lambda, RationalMax &m) noexcept {
  double const a0 = c.a[0], a1 = c.a[1], a2 = c.a[2];
  double const b0 = c.b[0], b1 = c.b[1], b2 = c.b[2], b3 = c.b[3];
  double const d2a = 2.0 * (a0 - a1 + a2);
  double const d3b = 6.0 * (b3 - b2 + b1 - b0);
  double lo = 0.0, hi = 1.0;
  double s = 1.0 - lambda, t = lambda, av = 0.0, bv = 1.0, gap = 0.0;
  m.converged = false;
  m.iterations = 0;
  for (int it = 0; it < kMaxIter; ++it) {
    ++m.iterations;
    t = lambda;
    s = 1.0 - lambda;
    // a, b and their derivatives (Bernstein form, eq. (M13)).
    av = s * (s * a0 + t * a1) + t * t * a2;
    double const da = -2.0 * s * a0 + (s - t) * a1 + 2.0 * t * a2;
    bv = s * s * (s * b0 + t * b1) + t * t * (s * b2 + t * b3);
    double const db = -3.0 * s * s * b0 + s * (s - 2.0 * t) * b1 +
                      t * (2.0 * s - t) * b2 + 3.0 * t * t * b3;
    double const d2b = 6.0 * s * b0 + (2.0 * t - 4.0 * s) * b1 +
                       (2.0 * s - 4.0 * t) * b2 + 6.0 * t * b3;
    // N = (s - t) a b + s t (a' b - a b'), f' = N / b^2, and N', N''
    // (eq. (M14)).
    double const st = s * t, smt = s - t, ab = av * bv;
    double const n0 = smt * ab + st * (da * bv - av * db);
    double const n1 = -2.0 * ab + 2.0 * smt * da * bv + st * (d2a * bv - av * d2b);
    double const n2 = -6.0 * da * bv - 2.0 * av * db +
                      smt * (3.0 * d2a * bv + 2.0 * da * db - av * d2b) +
                      st * (d2a * db - da * d2b - av * d3b);
    if (n0 > 0.0)
      lo = lambda;
    else
      hi = lambda;
    // Relative gap to the maximum: (log f)'^2 / (2 |(log f)''|), with
    // (log f)' = N / (s t a b) and (log f)'' ~ N' / (s t a b); converged when
    // below kGapTol (tested without division).
    double const scale = -2.0 * n1 * st * ab;
    if (n1 < 0.0 && n0 * n0 <= kGapTol * scale) {
      gap = n0 * n0 / scale;
      m.converged = true;
      break;
    }
    double step;
    double const den = 2.0 * n1 * n1 - n0 * n2;
    if (n1 < 0.0 && den > 0.0)
      step = -2.0 * n0 * n1 / den;  // Halley
    else if (n1 < 0.0)
      step = -n0 / n1;  // Newton
    else
      step = 0.5 * (lo + hi) - lambda;
    double next = lambda + step;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::fabs(next - lambda) <= 2.0 * kU * lambda) {
      m.converged = true;
      break;
    }
    lambda = next;
  }
  m.lambda = lambda;
  m.f = s * t * av / bv;
  m.gap = m.converged ? gap : 1.0;
  // Error of f from the coefficients: their relative errors weighted by the
  // (positive) Bernstein terms, plus the rounding of the evaluation.
  double const ta[3] = {s * s * a0, s * t * a1, t * t * a2};
  double const tb[4] = {s * s * s * b0, s * s * t * b1, s * t * t * b2, t * t * t * b3};
  double rel = 12.0 * kU;
  for (int i = 0; i < 3; ++i) rel += c.ea[i] * std::fabs(ta[i]);
  rel = 12.0 * kU + (rel - 12.0 * kU) / std::fabs(av);
  double relb = 0.0;
  for (int i = 0; i < 4; ++i) relb += c.eb[i] * std::fabs(tb[i]);
  m.rel_coef = rel + relb / std::fabs(bv);
}

Status contact_rational(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                        MethodResult &res) noexcept {
  RationalCoefs c;
  rational_coefficients(r, q1, q2, c);
  RationalMax m;
  rational_maximise(c, fixed_point_start(r, q1, q2), m);
  res.iterations = m.iterations;
  double const lambda = m.lambda, f = m.f;
  res.mu2 = f;
  res.lambda = lambda;
  res.mu2_error = (m.rel_coef + m.gap) * std::fabs(f);
  if (!(std::isfinite(f) && f > 0.0 && std::isfinite(res.mu2_error))) {
    // Coefficients destroyed by rounding: report f at lambda through a
    // Cholesky evaluation, flagged.
    double fc;
    if (!f_cholesky(lambda, r, q1, q2, fc)) fc = 0.0;
    res.mu2 = fc;
    res.mu2_error = fc;
    return kInaccurate;
  }
  if (!m.converged) return kNoConvergence;
  return res.mu2_error <= kRationalRelAccuracy * res.mu2 ? kOk : kInaccurate;
}

}  // namespace pw85
