// Fast path of the derivatives (docs/derivatives.md, (E8)): (E1)-(E6) in
// double at DEFAULT's lambda from one Cholesky factor of Q(lambda) and its
// inverse X, s refined by residuals in double-double, f'(lambda) in
// double-double, the first-order move to the root of f', and a-posteriori
// error estimates that decide whether the result meets the documented
// accuracy; the Hessian once more with X refined and moved when its
// estimate fails; otherwise the caller takes the refined path (E7).
#pragma once

#include <cmath>

#include "common/fp.hpp"
#include "common/isa.hpp"
#include "common/sym3.hpp"
#include "derivatives/derivatives.hpp"
#include "eval/f_dd.hpp"

namespace pw85 {
// The fast path (E8), from one Cholesky factor of Q(lambda).
namespace cholesky_path {

// Accepted estimated relative errors: a quarter of the documented bounds
// (gradient, torques and d_q 1e-14; Hessian 1e-12).
constexpr double kAcceptG = 2.5e-15, kAcceptH = 2.5e-13;
// Relative error of X = Q^{-1} from a Cholesky factor in the max norm, per
// unit of kappa = 9 max|Q_ij| max|X_ij| (an upper bound of the 1-norm
// condition number): the backward error of the factor and of the
// substitutions, a few u |Q|, times kappa, with margin.
constexpr double kInvErr = 4.0 * kU;
// Largest eps_x for the fast path, and further refinement steps of s.
constexpr double kMaxEpsX = 1e-4;
constexpr int kMaxSteps = 3;

// Maxima of non-negative values (a NaN propagates or is dropped: every
// estimate that uses them is then either NaN, failing its test, or the
// result fails the finiteness test).
PW85_ALWAYS_INLINE double max2(double a, double b) noexcept { return a > b ? a : b; }
PW85_ALWAYS_INLINE double max3(double a, double b, double c) noexcept {
  return max2(a, max2(b, c));
}
PW85_ALWAYS_INLINE double max_abs3(Vec3 const &v) noexcept {
  return max3(std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2]));
}
PW85_ALWAYS_INLINE double max_abs6(Sym3 const &a) noexcept {
  return max2(max3(std::fabs(a[0]), std::fabs(a[1]), std::fabs(a[2])),
              max3(std::fabs(a[3]), std::fabs(a[4]), std::fabs(a[5])));
}
PW85_ALWAYS_INLINE Vec3 abs3(Vec3 const &v) noexcept {
  return Vec3{{std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])}};
}
// Column j of a symmetric matrix.
PW85_ALWAYS_INLINE Vec3 column(Sym3 const &a, int j) noexcept {
  static constexpr int kIdx[kDim][kDim] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  return Vec3{{a[kIdx[j][0]], a[kIdx[j][1]], a[kIdx[j][2]]}};
}
PW85_ALWAYS_INLINE Vec3 cross(Vec3 const &a, Vec3 const &b) noexcept {
  return Vec3{{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}

// One refinement step of X = Q(lambda)^{-1}: X + X R, R = I - Q X with
// each column a residual in double-double (G8); the upper triangle of the
// result. Returns the relative size of the correction, max|X R| / max|X|.
template <bool F>
PW85_ALWAYS_INLINE double refine_inverse(double lambda, Sym3 const &q1, Sym3 const &q2,
                                         double mx, Sym3 &x) noexcept {
  Vec3 c[kDim];
  for (int j = 0; j < kDim; ++j) {
    Vec3 e{{0.0, 0.0, 0.0}};
    e[j] = 1.0;
    c[j] = multiply(x, residual_dd_impl<F>(lambda, e, q1, q2, column(x, j)));
  }
  Sym3 const d{{c[0][0], c[1][0], c[2][0], c[1][1], c[2][1], c[2][2]}};
  for (int k = 0; k < kSym; ++k) x[k] += d[k];
  return max_abs6(d) / mx;
}

// The derivatives at lambda, DEFAULT's maximiser, with mu2 its value.
// Returns false, out untouched, when an estimate exceeds its bound (or a
// value is not finite). d_q1 and d_q2 only when with_dq (otherwise 0); the
// Hessian always (its estimate decides).
template <bool F>
PW85_ALWAYS_INLINE bool fast_derivatives(double lambda, double mu2, Vec3 const &r,
                                         Sym3 const &q1, Sym3 const &q2, bool with_dq,
                                         Derivatives &out) noexcept {
  double const nu = 1.0 - lambda;
  // X = Q(lambda)^{-1} from its Cholesky factor (chol_inverse).
  CholInv c;
  if (!chol_inv(interpolate(q1, q2, lambda), c)) return false;
  Sym3 x = chol_inverse(c);
  double const mx = max_abs6(x);
  double const mq1 = max_abs6(q1), mq2 = max_abs6(q2);
  double eps_x = kInvErr * 9.0 * (nu * mq1 + lambda * mq2) * mx;  // relative error of X
  if (!(eps_x <= kMaxEpsX)) return false;
  // s = X r plus one correction X rho, rho = r - Q s in double-double (G8):
  // the correction's relative error is eps_x, so s + ds errs by e1 eps_x
  // relative (e1 = |ds| / |s|, itself the error of X r: the correction errs
// by max(e1, eps_x) relative, counted 4 times) and by kappa u^2 from rho.
  Vec3 s = multiply(x, r);
  Vec3 ds = multiply(x, residual_dd_impl<F>(lambda, r, q1, q2, s));
  double ims = 1.0 / max_abs3(s);
  double e1 = max_abs3(ds) * ims;
  double es = 4.0 * e1 * max2(e1, eps_x) + eps_x * kU;
  // Further steps while that estimate exceeds 2^-56 (ill-conditioned Q).
  for (int k = 0; k < kMaxSteps && !(es <= 0x1p-56) && e1 <= 1e-3; ++k) {
    for (int i = 0; i < kDim; ++i) s[i] += ds[i];
    ds = multiply(x, residual_dd_impl<F>(lambda, r, q1, q2, s));
    ims = 1.0 / max_abs3(s);
    double const e = max_abs3(ds) * ims;
    es = 4.0 * e * max2(e, e1) + eps_x * kU;  // the last correction errs by <= e1 relative
    e1 = e;
  }
  // f'(lambda) in double-double from s + ds (G9), x0 = (1 - lambda) Q1 s, Q2 s.
  Vec3 x0, q2s;
  double const fp = refined_point_impl<F>(lambda, q1, q2, s, ds, x0, q2s);
  for (int i = 0; i < kDim; ++i) s[i] += ds[i];
  double const inu = 1.0 / nu;
  Vec3 const q1s{{x0[0] * inu, x0[1] * inu, x0[2] * inu}};
  // (E5): a2 = -f''/2 = (Q1 s)^T X (Q2 s); its error from the rounding and
  // from X, relative to |Q1 s|^T |X| |Q2 s|.
  Vec3 const aq1s = abs3(q1s), aq2s = abs3(q2s);
  Sym3 ax;
  for (int k = 0; k < kSym; ++k) ax[k] = std::fabs(x[k]);
  double a2 = dot(q1s, multiply(x, q2s));
  double const ia2 = 1.0 / a2;
  double const a_abs = dot(aq1s, multiply(ax, aq2s));
  double const eps2 = (eps_x + 8.0 * kU) * a_abs * ia2;
  // The step to the root of f' (Newton, (E7)) and v = -ds/dlambda
  // = X (Q2 - Q1) s; the first-order moves of s, x0 = (1 - lambda) Q1 s and
  // Q2 s along dl: s' = -v, x0' = -Q1 s - (1 - lambda) Q1 v, (Q2 s)' = -Q2 v.
  double const dl = 0.5 * fp * ia2;
  Vec3 const v = multiply(x, Vec3{{q2s[0] - q1s[0], q2s[1] - q1s[1], q2s[2] - q1s[2]}});
  Vec3 const q1v = multiply(q1, v), q2v = multiply(q2, v);
  double const mq1s = max3(aq1s[0], aq1s[1], aq1s[2]), mq2s = max3(aq2s[0], aq2s[1], aq2s[2]);
  double const mv = max_abs3(v);
  for (int i = 0; i < kDim; ++i) {
    s[i] -= v[i] * dl;
    x0[i] -= (q1s[i] + nu * q1v[i]) * dl;
    q2s[i] -= q2v[i] * dl;
  }
  double const lam = lambda + dl, nus = nu - dl, p = lam * nus;
  // Outputs (E1)-(E4).
  Derivatives o;
  o.mu2 = mu2;
  o.lambda = lam;
  Vec3 g, xr;
  for (int i = 0; i < kDim; ++i) {
    g[i] = 2.0 * p * s[i];
    xr[i] = -lam * q2s[i];  // x0 - r, without the subtraction
  }
  Vec3 const c1v = cross(x0, g), c2v = cross(xr, g);
  for (int i = 0; i < kDim; ++i) {
    o.d_r12[i] = g[i];
    o.d_theta1[i] = -c1v[i];
    o.d_theta2[i] = c2v[i];
  }
  static constexpr int kI[kSym] = {0, 0, 0, 1, 1, 2}, kJ[kSym] = {0, 1, 2, 1, 2, 2};
  double const c1 = -p * nus, c2 = -p * lam;
  for (int k = 0; k < kSym; ++k) {
    double const ss = (kI[k] == kJ[k] ? 1.0 : 2.0) * s[kI[k]] * s[kJ[k]];
    o.d_q1[k] = with_dq ? c1 * ss : 0.0;
    o.d_q2[k] = with_dq ? c2 * ss : 0.0;
  }
  // w = (1 - lambda)^2 Q1 s - lambda^2 Q2 s, h = 2 X w = dg/dlambda (E6).
  Vec3 w;
  for (int i = 0; i < kDim; ++i) w[i] = nus * x0[i] - (lam * lam) * q2s[i];
  // Error estimates (max norms; a factor 3 converts to 2-norms).
  // t: relative size of the move of s; t2 >= |dl| ||X (Q2 - Q1)||, the
  // relative change of X, f'' and h along dl (not moved) and, times t, the
  // second-order term of s. The error of dl moves g by |h| and s by |v|
  // times it (s on its own: d_q and the torques).
  double const adl = std::fabs(dl);
  double const t = adl * mv * ims;
  double const t2 = 9.0 * adl * mx * (mq1 + mq2);
  double const mw = max_abs3(w), mx0 = max_abs3(x0);
  double const err_fp = 6.0 * mw * (es + 8.0 * kU * kU) / ims;   // of f'
  double const err_dl = 0.5 * err_fp * ia2 + adl * eps2;         // of dl
  Vec3 h = multiply(x, w);
  for (int i = 0; i < kDim; ++i) h[i] *= 2.0;
  double const err_g = es + 4.0 * kU + t * t2 +
                       3.0 * adl * mx * (eps_x + 2.0 * kU) * (mq1s + mq2s) * ims +
                       err_dl * (max_abs3(h) / (2.0 * p) + mv) * ims;
  if (!(3.0 * err_g <= kAcceptG && a2 > 0.0 && lam > 0.0 && lam < 1.0)) return false;
  double const err_w = (2.0 * kU + es) * (nus * mx0 + lam * lam * mq2s);
  // Hessian (E6): 2 p X + h h^T / (2 a2), accepted when its estimated error
  // is below kAcceptH; otherwise once more with X refined (refine_inverse)
  // and moved to lambda + dl to first order, X' = -X (Q2 - Q1) X, and a2, h
  // from the moved Q1 s, Q2 s (their remaining error ~t2^2, negligible).
  double tx = t2;
  Sym3 const x_at = x;  // X at lambda, for refine_inverse
  Sym3 xdx{{0.0, 0.0, 0.0, 0.0, 0.0, 0.0}};
  Vec3 q1sm = q1s;
  bool moved = false, refined = false;
  for (int pass = 0;; ++pass) {
    double const mh = max_abs3(h);
    double const e2 = pass == 0 ? eps2 : (eps_x + 8.0 * kU) * a_abs / a2;
    double const iha = 0.5 / a2;
    double mhess = 0.0;
    for (int k = 0; k < kSym; ++k) {
      o.hess_r12[k] = 2.0 * p * x[k] + h[kI[k]] * h[kJ[k]] * iha;
      mhess = max2(mhess, std::fabs(o.hess_r12[k]));
    }
    // The estimate in two parts: from the error of X (and the rounding),
    // and from lambda + dl (tx).
    double const err_eps = 3.0 * (2.0 * p * mx * (eps_x + 2.0 * kU) +
                                  (12.0 * mh * mx * (eps_x * mw + err_w) +
                                   mh * mh * (e2 + 2.0 * kU)) * iha);
    double const err_t = 3.0 * (2.0 * p * mx * tx + 3.0 * mh * mh * tx * iha);
    if (err_eps + err_t <= kAcceptH * mhess) break;
    if (refined) return false;
    if (!moved) {
      for (int j = 0; j < kDim; ++j) {
        Vec3 const c = multiply(x, multiply(difference(q2, q1), column(x, j)));
        if (j == 0) xdx[0] = c[0];
        if (j == 1) xdx[1] = c[0], xdx[3] = c[1];
        if (j == 2) xdx[2] = c[0], xdx[4] = c[1], xdx[5] = c[2];
      }
      // Second order: dl^2 X D X D X, relative ~ (move) t2.
      tx = t2 * adl * max_abs6(xdx) / mx;
      for (int i = 0; i < kDim; ++i) q1sm[i] = q1s[i] - q1v[i] * dl;
    }
    // Refine when the error of X dominates, or when moving alone failed.
    if (moved || !(err_eps <= 0.5 * kAcceptH * mhess)) {
      x = x_at;
      double const ec = refine_inverse<F>(lambda, q1, q2, mx, x);
      eps_x = 4.0 * ec * max2(ec, eps_x) + 2.0 * kU;
      refined = true;
    }
    moved = true;
    for (int k = 0; k < kSym; ++k) x[k] = (refined ? x[k] : x_at[k]) - xdx[k] * dl;
    a2 = dot(q1sm, multiply(x, q2s));
    h = multiply(x, w);
    for (int i = 0; i < kDim; ++i) h[i] *= 2.0;
  }
  double const *all = &o.mu2;
  bool ok = true;
  for (int i = 0; i < 29; ++i) ok &= std::isfinite(all[i]);
  if (ok) out = o;
  return ok;
}

}  // namespace cholesky_path
}  // namespace pw85
