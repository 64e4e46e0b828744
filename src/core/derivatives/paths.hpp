// The derivatives from DEFAULT's solution, written once and compiled into
// each variant by derivatives_variants.cpp: the fast path (E8) of fast.hpp,
// otherwise the refined path (E7) (docs/derivatives.md; derivatives.cpp
// for the equations). Compiled without contraction (src/meson.build), like
// the rest of the derivatives.
#pragma once

#include <cmath>
#include <limits>

#include "common/fp.hpp"
#include "common/isa.hpp"
#include "contact/contact.hpp"
#include "derivatives/derivatives.hpp"
#include "derivatives/fast.hpp"
#include "eval/f_dd.hpp"

namespace pw85 {
namespace derivative_paths {

constexpr int kMaxRefine = 10;  // refinement steps per solve (contraction ~cond u each)
constexpr int kMaxNewton = 6;   // Newton steps on f' = 0
// Largest |dl| / min(lambda, 1 - lambda) for which the first-order moves
// along the last Newton step dl are accurate (second-order terms ~ its square).
constexpr double kFirstOrder = 0x1p-46, kFirstOrderLast = 0x1p-30;
constexpr int kFields = 29;  // doubles in Derivatives
// The doubles of Derivatives that fields computes: all, or the first 11
// (mu2, lambda, d_r12, d_theta1, d_theta2).
constexpr int kForceFields = 11;
inline int computed_fields(DerivativeFields fields) noexcept {
  return fields == DerivativeFields::kAll ? kFields : kForceFields;
}

// The fields that fields does not compute (d_q1, d_q2, hess_r12) set to NaN.
inline void drop_unrequested(DerivativeFields fields, Derivatives &d) noexcept {
  double *const all = &d.mu2;
  for (int i = computed_fields(fields); i < kFields; ++i)
    all[i] = std::numeric_limits<double>::quiet_NaN();
}

inline double max_abs(Vec3 const &v) noexcept {
  return std::fmax(std::fabs(v[0]), std::fmax(std::fabs(v[1]), std::fabs(v[2])));
}

// Cholesky factor with the reciprocals of its diagonal.
struct Chol : CholInv {
  double kappa_u;  // (max / min diagonal of L)^2 u: lower estimate of cond(Q) u
};

inline bool chol(Sym3 const &a, Chol &c) noexcept {
  if (!chol_inv(a, c)) return false;
  double const dmin = std::fmin(c.l[0], std::fmin(c.l[3], c.l[5]));
  double const dmax = std::fmax(c.l[0], std::fmax(c.l[3], c.l[5]));
  c.kappa_u = (dmax / dmin) * (dmax / dmin) * kU;
  return std::isfinite(c.i0) && std::isfinite(c.i1) && std::isfinite(c.i2) && c.kappa_u < 0.1;
}

inline Vec3 solve(Chol const &c, Vec3 const &b) noexcept { return chol_solve(c, b); }

// x = Q(lambda)^{-1} b by iterative refinement (E7): returns the unevaluated
// sum x + delta, whose estimated relative error 4 e max(e, kappa_u)
// (e = |delta| / |x|: the last correction, itself computed with relative
// error ~ max(e, cond u)) is below 2^-60. False when it does not converge.
inline bool refined_solve(Chol const &c, double lambda, Vec3 const &b, Sym3 const &q1,
                   Sym3 const &q2, Vec3 &x, Vec3 &delta) noexcept {
  x = solve(c, b);
  for (int k = 0; k < kMaxRefine; ++k) {
    delta = solve(c, residual_dd(lambda, b, q1, q2, x));
    double const xm = max_abs(x);
    double const e = max_abs(delta) / xm;
    if (!(e <= 0.5) || !(xm > 0.0) || !std::isfinite(xm)) return false;
    if (4.0 * e * std::fmax(e, c.kappa_u) <= 0x1p-60) return true;
    for (int i = 0; i < kDim; ++i) x[i] += delta[i];
  }
  return false;
}

// Row i of the symmetric a times x = x_hi + x_lo: compensated dot product
// (dot3_c, f_dd.hpp) plus a x_lo in double.
template <bool F>
PW85_ALWAYS_INLINE dd::DD matvec_dd(Sym3 const &a, int i, Vec3 const &xh, Vec3 const &xl) noexcept {
  static constexpr int kIdx[kDim][kDim] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  int const *k = kIdx[i];
  dd::DD const c = dot3_c<F>(a[k[0]], a[k[1]], a[k[2]], xh[0], xh[1], xh[2]);
  double const l = a[k[0]] * xl[0] + a[k[1]] * xl[1] + a[k[2]] * xl[2];
  return dd::fast_two_sum(c.hi, c.lo + l);
}

// Row i of (a + al) times x (double-double), al the low parts of a.
template <bool F>
PW85_ALWAYS_INLINE dd::DD matvec_dd2(Sym3 const &a, Sym3 const &al, int i, dd::DD const x[kDim]) noexcept {
  static constexpr int kIdx[kDim][kDim] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  int const *k = kIdx[i];
  dd::DD const c = dot3_c<F>(a[k[0]], a[k[1]], a[k[2]], x[0].hi, x[1].hi, x[2].hi);
  double const l = (a[k[0]] * x[0].lo + a[k[1]] * x[1].lo + a[k[2]] * x[2].lo) +
                   (al[k[0]] * x[0].hi + al[k[1]] * x[1].hi + al[k[2]] * x[2].hi);
  return dd::fast_two_sum(c.hi, c.lo + l);
}

template <bool F>
PW85_ALWAYS_INLINE dd::DD dot_dd(dd::DD const a[kDim], dd::DD const b[kDim]) noexcept {
  dd::DD const c = dot3_c<F>(a[0].hi, a[1].hi, a[2].hi, b[0].hi, b[1].hi, b[2].hi);
  double const l = (a[0].hi * b[0].lo + a[1].hi * b[1].lo + a[2].hi * b[2].lo) +
                   (a[0].lo * b[0].hi + a[1].lo * b[1].hi + a[2].lo * b[2].hi);
  return dd::fast_two_sum(c.hi, c.lo + l);
}

inline Vec3 cross(Vec3 const &a, Vec3 const &b) noexcept {
  return Vec3{{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}

// Values at one lambda: Cholesky of Q(lambda), s = s_hi + s_lo (refined),
// f'(lambda) in double-double, x0 = (1 - lambda) Q1 s and Q2 s.
// When Q(lambda) is too ill-conditioned for the refinement to converge
// (cond(Q) u > 0.1, beyond the semi-axis class [0.001, 1000]), or when
// force_dd is set, the solves are in double-double throughout (f_dd.hpp,
// solve_dd_impl) and dd is set.
struct AtLambda {
  Chol c;
  bool dd;
  Vec3 s_hi, s_lo, x0, q2s;
  double fp;
};

// x = Q(lambda)^{-1} b as the double-double x + lo (solve_dd_impl).
template <bool F>
PW85_ALWAYS_INLINE bool solve_dd_pair(double lambda, Vec3 const &b, Sym3 const &q1,
                                      Sym3 const &q2, Vec3 &x, Vec3 &lo) noexcept {
  dd::DD s[kDim], phi;
  if (!solve_dd_impl<F>(lambda, b, q1, q2, s, phi)) return false;
  for (int i = 0; i < kDim; ++i) {
    x[i] = s[i].hi;
    lo[i] = s[i].lo;
  }
  return std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]);
}

template <bool F>
PW85_ALWAYS_INLINE bool at_lambda(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                                  bool force_dd, AtLambda &a) noexcept {
  a.dd = !chol(interpolate(q1, q2, lambda), a.c) || force_dd ||
         !refined_solve(a.c, lambda, r, q1, q2, a.s_hi, a.s_lo);
  if (a.dd && !solve_dd_pair<F>(lambda, r, q1, q2, a.s_hi, a.s_lo)) return false;
  a.fp = refined_point_dd(lambda, q1, q2, a.s_hi, a.s_lo, a.x0, a.q2s);
  return std::isfinite(a.fp);
}

// DEFAULT's solution (status, res) has a maximiser inside (0, 1).
inline bool is_solved(Status status, MethodResult const &res) noexcept {
  return (status == kOk || status == kInaccurate) && res.lambda > 0.0 && res.lambda < 1.0;
}

// The derivatives from DEFAULT's solution (status, res): (E8), otherwise
// (E7); the double-double products of arith/dd.hpp by FMA (F = true) or
// Dekker's product. The fields of fields; the others NaN. (E8) computes the
// Hessian for either fields (its error estimate decides whether (E8) is
// taken) but d_q only for kAll; (E7) computes neither d_q nor the Hessian
// for kForces.
template <bool F>
PW85_ALWAYS_INLINE Status derivatives_from(Status status, MethodResult const &res,
                                           Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                                           DerivativeFields fields, Derivatives &d) noexcept {
  static_assert(sizeof(Derivatives) == 29 * sizeof(double), "plain struct of 29 doubles");
  bool const solved = is_solved(status, res);
  double lambda = res.lambda;
  // (E8): most pairs; otherwise the refined path (E7) below.
  bool const all_fields = fields == DerivativeFields::kAll;
  if (solved && cholesky_path::fast_derivatives<F>(lambda, res.mu2, r, q1, q2, all_fields, d)) {
    drop_unrequested(fields, d);
    return status;
  }
  double const nan = std::numeric_limits<double>::quiet_NaN();
  Derivatives out;
  double *const all = &out.mu2;
  for (int i = 0; i < kFields; ++i) all[i] = nan;
  d = out;
  if (!solved) return kNoConvergence;
  Sym3 const dq = difference(q2, q1);
  // Newton steps on f'(lambda) = 0 (E7), f' in double-double, the slope
  // f'' by (E5) in double-double; usually none is needed: the maximiser is
  // then DEFAULT's lambda plus the first-order step, below.
  // The refined s is accurate to ~2^-60 |s| (normwise), and f' to
  // ~2^-60 |s| |(1 - lambda) Q1 s|: too coarse where s^T Q1 s is far
  // below |s| |Q1 s| (Q1 nearly singular, r along its thin direction, lambda
  // small; likewise Q2 near lambda = 1), where the Newton steps then wander
  // with the noise of f'. When they have not settled after kMaxNewton
  // steps, kMaxNewton more in double-double throughout (force_dd).
  AtLambda a;
  bool force_dd = false;
  int max_newton = kMaxNewton;
  for (int pass = 0;; ++pass) {
    if (!at_lambda<F>(lambda, r, q1, q2, force_dd, a)) return kNoConvergence;
    double nu = 1.0 - lambda;
    if (pass < max_newton && !a.dd) {
      // Cheap test first: the Newton step with f'' (E5) in double (one more
      // solve); far from the maximiser, step without the work below.
      Vec3 q1s;
      for (int i = 0; i < kDim; ++i) q1s[i] = a.x0[i] / nu;
      double const slope = -2.0 * dot(q1s, solve(a.c, a.q2s));
      double const step = -a.fp / slope;
      if (slope < 0.0 && !(std::fabs(step) <= 2.0 * kFirstOrder * std::fmin(lambda, nu))) {
        double const next = lambda + step;
        if (!(next > 0.0 && next < 1.0)) return kNoConvergence;
        lambda = next;
        continue;
      }
    }
    Vec3 s, x0 = a.x0, q2s = a.q2s;
    for (int i = 0; i < kDim; ++i) s[i] = a.s_hi[i] + a.s_lo[i];
    // Q^{-1} = X + Xl, column by column (E7): X_ij, i <= j, from column j.
    Vec3 col[kDim], lo[kDim];
    for (int j = 0; j < kDim; ++j) {
      Vec3 e{{0.0, 0.0, 0.0}};
      e[j] = 1.0;
      if ((a.dd || !refined_solve(a.c, lambda, e, q1, q2, col[j], lo[j])) &&
          !solve_dd_pair<F>(lambda, e, q1, q2, col[j], lo[j]))
        return kNoConvergence;
    }
    Sym3 qi{{col[0][0], col[1][0], col[2][0], col[1][1], col[2][1], col[2][2]}};
    Sym3 ql{{lo[0][0], lo[1][0], lo[2][0], lo[1][1], lo[2][1], lo[2][2]}};
    // Q1 s, Q2 s in double-double from s = s_hi + s_lo (compensated dot
    // products), and w = (1 - lambda)^2 Q1 s - lambda^2 Q2 s, whose terms
    // cancel (s.w = f'(lambda) = 0).
    dd::DD t1[kDim], t2[kDim], wd[kDim];
    dd::DD const om = dd::two_sum(1.0, -lambda);
    dd::DD const nu2 = dd::mul<F>(om, om), la2 = dd::two_prod<F>(lambda, lambda);
    for (int i = 0; i < kDim; ++i) {
      t1[i] = matvec_dd<F>(q1, i, a.s_hi, a.s_lo);
      t2[i] = matvec_dd<F>(q2, i, a.s_hi, a.s_lo);
      wd[i] = dd::sub(dd::mul<F>(nu2, t1[i]), dd::mul<F>(la2, t2[i]));
    }
    // (E5): f'' = -2 (Q1 s)^T Q^{-1} (Q2 s) in double-double (the dot product
    // can cancel: both vectors and Q^{-1} are needed beyond double).
    dd::DD y[kDim];
    for (int i = 0; i < kDim; ++i) y[i] = matvec_dd2<F>(qi, ql, i, t2);
    double const d2f = -2.0 * dd::to_double(dot_dd<F>(t1, y));
    Vec3 q1s, dsv;
    for (int i = 0; i < kDim; ++i) {
      q1s[i] = dd::to_double(t1[i]);
      dsv[i] = q2s[i] - q1s[i];
    }
    Vec3 const v = multiply(qi, dsv);  // -ds/dlambda, for the first-order moves below
    // (E6): h = 2 Q^{-1} w, the same vector as 2 (1 - 2 lambda) s - 2 lambda (1 - lambda) v
    // without the cancellation.
    Vec3 h{{0.0, 0.0, 0.0}};
    if (all_fields)
      for (int i = 0; i < kDim; ++i) h[i] = 2.0 * dd::to_double(matvec_dd2<F>(qi, ql, i, wd));
    // The last Newton step dl, below half an ulp of lambda, is still large
    // relative to 1 - lambda when lambda is near 1 (and to lambda near 0): the
    // maximiser is lambda + dl, with 1 - lambda - dl and lambda + dl rounded
    // once each, and s, x0 = (1 - lambda) Q1 s, Q2 s, Q^{-1} moved to first
    // order (s' = -v, x0' = -Q1 s - (1 - lambda) Q1 v, (Q2 s)' = -Q2 v,
    // (Q^{-1})' = -Q^{-1} (Q2 - Q1) Q^{-1}).
    double const dl = -a.fp / d2f;
    if (!(d2f < 0.0) || !std::isfinite(dl)) return kNoConvergence;
    double const rel = std::fabs(dl) / std::fmin(lambda, nu);
    if (!(rel <= kFirstOrder) && pass == max_newton && !a.dd) {
      // Not settled: the steps again from this lambda in double-double.
      force_dd = true;
      max_newton = pass + kMaxNewton;
      continue;
    }
    if (!(rel <= kFirstOrder) && (pass < max_newton || !(rel <= kFirstOrderLast))) {
      // Too far for the first-order moves: a Newton step, and again; after
      // max_newton steps in double-double (f' at its noise level), the
      // looser bound.
      double const next = lambda + dl;
      if (pass == max_newton || !(next > 0.0 && next < 1.0)) return kNoConvergence;
      lambda = next;
      continue;
    }
    {
      Vec3 const q1v = multiply(q1, v), q2v = multiply(q2, v);
      for (int i = 0; i < kDim; ++i) {
        s[i] -= v[i] * dl;
        x0[i] -= (q1s[i] + nu * q1v[i]) * dl;
        q2s[i] -= q2v[i] * dl;
      }
      if (all_fields) {  // Q^{-1}: the Hessian's only
        Vec3 w[kDim];
        for (int j = 0; j < kDim; ++j) w[j] = multiply(qi, multiply(dq, col[j]));
        Sym3 const xdx{{w[0][0], w[1][0], w[2][0], w[1][1], w[2][1], w[2][2]}};
        for (int k = 0; k < kSym; ++k) qi[k] += (ql[k] - xdx[k] * dl);
      }
      nu = nu - dl;
      lambda = lambda + dl;
    }
    double const p = lambda * nu;
    // (E1), (E3), (E4).
    Vec3 g, xr;
    for (int i = 0; i < kDim; ++i) {
      g[i] = 2.0 * p * s[i];
      xr[i] = -lambda * q2s[i];  // x0 - r, without the subtraction
    }
    Vec3 const c1v = cross(x0, g), c2v = cross(xr, g);
    // (E2).
    static constexpr int kI[kSym] = {0, 0, 0, 1, 1, 2}, kJ[kSym] = {0, 1, 2, 1, 2, 2};
    double const c1 = -p * nu, c2 = -p * lambda;
    if (!(d2f < 0.0)) return kNoConvergence;
    out.mu2 = res.mu2;
    out.lambda = lambda;
    for (int i = 0; i < kDim; ++i) {
      out.d_r12[i] = g[i];
      out.d_theta1[i] = -c1v[i];
      out.d_theta2[i] = c2v[i];
    }
    for (int k = 0; all_fields && k < kSym; ++k) {
      double const w = kI[k] == kJ[k] ? 1.0 : 2.0;
      double const ss = w * s[kI[k]] * s[kJ[k]];
      out.d_q1[k] = c1 * ss;
      out.d_q2[k] = c2 * ss;
      out.hess_r12[k] = 2.0 * p * qi[k] - h[kI[k]] * h[kJ[k]] / d2f;
    }
    for (int i = 0; i < computed_fields(fields); ++i)
      if (!std::isfinite(all[i])) return kNoConvergence;
    d = out;
    return status;
  }
}

}  // namespace derivative_paths
}  // namespace pw85
