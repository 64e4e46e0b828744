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

#include "contact.hpp"
#include "f_cholesky.hpp"

namespace pw85 {

namespace {

constexpr double kU = 0x1p-53;
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

struct Poly {
  double a0, a1, a2, b0, b1, b2, b3;
};

// h' and h'' at lambda; also a and b.
inline void log_derivs(Poly const &c, double lambda, double &h1, double &h2, double &a,
                       double &b) noexcept {
  double const t = lambda, s = 1.0 - lambda;
  a = s * s * c.a0 + s * t * c.a1 + t * t * c.a2;
  double const da = -2.0 * s * c.a0 + (s - t) * c.a1 + 2.0 * t * c.a2;
  double const d2a = 2.0 * (c.a0 - c.a1 + c.a2);
  b = s * s * s * c.b0 + s * s * t * c.b1 + s * t * t * c.b2 + t * t * t * c.b3;
  double const db = -3.0 * s * s * c.b0 + s * (s - 2.0 * t) * c.b1 +
                    t * (2.0 * s - t) * c.b2 + 3.0 * t * t * c.b3;
  double const d2b = 6.0 * s * c.b0 + (2.0 * t - 4.0 * s) * c.b1 +
                     (2.0 * s - 4.0 * t) * c.b2 + 6.0 * t * c.b3;
  double const ia = 1.0 / a, ib = 1.0 / b, it = 1.0 / t, is = 1.0 / s;
  double const la = da * ia, lb = db * ib;
  h1 = it - is + la - lb;
  h2 = -it * it - is * is + d2a * ia - la * la - d2b * ib + lb * lb;
}

}  // namespace

Status contact_rational(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                        MethodResult &res) noexcept {
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
  Poly const c{a0.v, a1.v, a2.v, b0.v, b1.v, b2.v, b3.v};
  double const ea[3] = {rel_err(a0), rel_err(a1), rel_err(a2)};
  double const eb[4] = {rel_err(b0), rel_err(b1), rel_err(b2), rel_err(b3)};

  // Start: balance of the radii along r, eq. (M7).
  double const h1s = std::sqrt(dot(r, multiply(q1, r)));
  double const h2s = std::sqrt(dot(r, multiply(q2, r)));
  double lambda = h1s / (h1s + h2s);
  if (!(lambda > 0.0 && lambda < 1.0)) lambda = 0.5;
  double lo = 0.0, hi = 1.0, h1 = 0.0, h2 = -1.0, av = 0.0, bv = 0.0;
  bool converged = false;
  res.iterations = 0;
  for (int it = 0; it < kMaxIter; ++it) {
    ++res.iterations;
    log_derivs(c, lambda, h1, h2, av, bv);
    if (h1 > 0.0)
      lo = lambda;
    else
      hi = lambda;
    if (h2 < 0.0 && h1 * h1 <= -2.0 * h2 * kGapTol) {
      converged = true;
      break;
    }
    double next = h2 < 0.0 ? lambda - h1 / h2 : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::fabs(next - lambda) <= 2.0 * kU * lambda) {
      converged = true;
      break;
    }
    lambda = next;
  }
  double const t = lambda, s = 1.0 - lambda;
  double const f = s * t * av / bv;
  // Error estimate: relative errors of the coefficients weighted by their
  // (positive) Bernstein terms, plus rounding of the evaluation, plus the gap
  // h'^2 / (2|h''|) (relative, in log f).
  double const ta[3] = {s * s * c.a0, s * t * c.a1, t * t * c.a2};
  double const tb[4] = {s * s * s * c.b0, s * s * t * c.b1, s * t * t * c.b2, t * t * t * c.b3};
  double rel = 12.0 * kU;
  for (int i = 0; i < 3; ++i) rel += ea[i] * std::fabs(ta[i]) / std::fabs(av);
  for (int i = 0; i < 4; ++i) rel += eb[i] * std::fabs(tb[i]) / std::fabs(bv);
  double const gap = h2 < 0.0 ? h1 * h1 / (-2.0 * h2) : 1.0;
  res.mu2 = f;
  res.lambda = lambda;
  res.mu2_error = (rel + gap) * std::fabs(f);
  if (!(std::isfinite(f) && f > 0.0 && std::isfinite(res.mu2_error))) {
    // Coefficients destroyed by rounding: report f at lambda through a
    // Cholesky evaluation, flagged.
    double fc;
    if (!f_cholesky(lambda, r, q1, q2, fc)) fc = 0.0;
    res.mu2 = fc;
    res.mu2_error = fc;
    return kInaccurate;
  }
  if (!converged) return kNoConvergence;
  return res.mu2_error <= kRationalRelAccuracy * res.mu2 ? kOk : kInaccurate;
}

}  // namespace pw85
