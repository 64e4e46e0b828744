// Bounds on the exact mu^2(t) of the moving pair (docs/contact_time.md
// (T9)): the rotated forms Q_i(t) = R_i Q_i R_i^T are never rounded; every
// product Q_i(t) x is formed as R_i (Q_i (R_i^T x)) in double-double
// (spin.hpp), from the exact inputs.
//
// For lambda in (0, 1) and any s, with a = s^T Q1(t) s, b = s^T Q2(t) s:
//  - lower: mu >= phi(s) = r.s / (sqrt(a) + sqrt(b))                     (T2)
//  - upper: r = x1 + x2, x1 = (1 - lambda) Q1(t) s, x2 = lambda Q2(t) s + res,
//    res = r - Q(lambda) s; x_i in rho_i E_i gives r in max(rho_1, rho_2) K:
//    mu <= max((1 - lambda) sqrt(a), lambda sqrt(b) + |res| / a_min,2).
// Both equal mu at lambda*, s = Q(lambda*)^{-1} r. s is solved by iterative
// refinement (residual in double-double, corrections by the Cholesky factor
// of the rounded Q(lambda)); lambda, in double-double, by Newton steps on
// f'(lambda) = (1 - lambda)^2 a - lambda^2 b (formed in double-double; f''
// = -2 (Q1 s)^T Q(lambda)^{-1} (Q2 s) in double) until the bounds decide
// the sign of mu^2 - 1 or meet (width ~1e-28).
// Rounding: a, b, r.s carry relative errors below 64 u^2 a_max,i^2 / a_min,i^2
// (the errors of R^T s and of the sums, against the smallest value of the
// form); the bounds are widened by that and by 2^-100 for the remaining
// double-double operations.
#pragma once

#include <cmath>
#include <limits>

#include "common/fp.hpp"
#include "common/sym3.hpp"
#include "contact_time/axes.hpp"
#include "contact_time/spin.hpp"

namespace pw85 {

// The exact motion at one time t: r(t) = r0 + t v and the two rotations, in
// double-double.
struct ExactPose {
  dd::DD r[kDim];
  Spin sp1, sp2;
};

inline ExactPose exact_pose(Vec3 const &r0, Vec3 const &v, double t, Vec3 const &w1,
                            Vec3 const &w2) noexcept {
  ExactPose p;
  for (int i = 0; i < kDim; ++i) p.r[i] = dd::add(dd::two_prod<ddx::kF>(t, v[i]), r0[i]);
  p.sp1 = spin_at(w1, t);
  p.sp2 = spin_at(w2, t);
  return p;
}

// Bounds [lo, hi] on mu^2(t) - 1 (rigorous up to the analysis of the
// header), and the refined direction s.
struct Mu2Bounds {
  double lo, hi;
  Vec3 s;
};

// Relative accuracy floor of the bounds for the pair (semi-axis bounds ax).
inline double enclosure_floor(AxisBounds const &ax1, AxisBounds const &ax2) noexcept {
  double const k1 = (ax1.a_max / ax1.a_min) * (ax1.a_max / ax1.a_min);
  double const k2 = (ax2.a_max / ax2.a_min) * (ax2.a_max / ax2.a_min);
  return 64.0 * kU * kU * (k1 + k2) + 0x1p-100;
}

// p1, p2: Q_i(t) rounded to double (for the Cholesky factors only); lambda
// a starting value (DEFAULT's). Returns false when a factorisation fails or
// the result is not finite.
inline bool enclose_mu2(ExactPose const &pose, Sym3 const &q1, Sym3 const &q2, Sym3 const &p1,
                        Sym3 const &p2, AxisBounds const &ax1, AxisBounds const &ax2,
                        double lambda, Mu2Bounds &out) noexcept {
  using dd::DD;
  double const floor_rel = enclosure_floor(ax1, ax2);
  Vec3 const rd{{to_double(pose.r[0]), to_double(pose.r[1]), to_double(pose.r[2])}};
  double const rn = std::sqrt(dot(rd, rd));
  if (!(lambda > 0.0 && lambda < 1.0)) lambda = 0.5;
  DD lam{lambda, 0.0};  // lambda in double-double: the upper bound is first order in its error
  DD s[kDim];
  bool have_s = false;
  double best_w = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 6; ++it) {
    CholInv c;
    if (!chol_inv(interpolate(p1, p2, lam.hi), c)) return false;
    DD const om = dd::sub(DD{1.0, 0.0}, lam);
    if (!have_s) {
      Vec3 const s0 = chol_solve(c, rd);
      for (int i = 0; i < kDim; ++i) s[i] = DD{s0[i], 0.0};
      have_s = true;
    }
    // iterative refinement of s = Q(lambda)^{-1} r
    double res_n = 0.0, prev = std::numeric_limits<double>::infinity();
    DD a1[kDim], a2[kDim];
    for (int k = 0; k < 12; ++k) {
      rotated_times(pose.sp1, q1, s, a1);
      rotated_times(pose.sp2, q2, s, a2);
      Vec3 res;
      for (int i = 0; i < kDim; ++i)
        res[i] = to_double(dd::sub(dd::sub(pose.r[i], ddx::mul(a1[i], om)), ddx::mul(a2[i], lam)));
      res_n = std::sqrt(dot(res, res));
      if (!std::isfinite(res_n)) return false;
      if (!(res_n > 0x1p-100 * rn) || !(res_n < 0.5 * prev)) break;
      prev = res_n;
      Vec3 const cor = chol_solve(c, res);
      for (int i = 0; i < kDim; ++i) s[i] = dd::add(s[i], cor[i]);
    }
    // bounds at (lambda, s)
    DD const a = dot_dd(s, a1), b = dot_dd(s, a2);  // s^T Q_i(t) s
    DD const rs = dot_dd(pose.r, s);
    if (!(a.hi > 0.0) || !(b.hi > 0.0) || !(rs.hi > 0.0)) return false;
    DD const ha = ddx::sqrt(a), hb = ddx::sqrt(b);
    DD const phi = ddx::mul(rs, dd::recip<ddx::kF>(dd::add(ha, hb)));
    DD const lo2 = ddx::mul(phi, phi);
    DD const up1 = ddx::mul(ha, om);
    DD const up2 = dd::add(ddx::mul(hb, lam), res_n / ax2.a_min * (1.0 + 8 * kU));
    DD const up = up1.hi >= up2.hi ? up1 : up2;
    DD const hi2 = ddx::mul(up, up);
    double const l = to_double(dd::sub(lo2, DD{1.0, 0.0}));
    double const h = to_double(dd::sub(hi2, DD{1.0, 0.0}));
    double const marg = floor_rel * hi2.hi * 4.0 + 0x1p-104 * hi2.hi;
    double const lo = l - marg - kU * std::fabs(l), hi = h + marg + kU * std::fabs(h);
    if (!std::isfinite(lo) || !std::isfinite(hi)) return false;
    if (hi - lo < best_w) {
      best_w = hi - lo;
      out.lo = lo;
      out.hi = hi;
      for (int i = 0; i < kDim; ++i) out.s[i] = to_double(s[i]);
    }
    // the sign of mu^2 - 1 decided, or the bounds at their floor
    if (lo > 0.0 || hi <= 0.0 || !(hi - lo > 8.0 * marg)) break;
    // Newton step on f'(lambda) = (1 - lambda)^2 a - lambda^2 b
    double const fp = to_double(dd::sub(ddx::mul(ddx::mul(a, om), om),
                                        ddx::mul(ddx::mul(b, lam), lam)));
    Vec3 const sd{{s[0].hi, s[1].hi, s[2].hi}};
    Vec3 const q1s = multiply(p1, sd), q2s = multiply(p2, sd);
    double const fpp = -2.0 * dot(q1s, chol_solve(c, q2s));
    if (!(fpp < 0.0)) break;
    DD next = dd::add(lam, -fp / fpp);
    if (!(next.hi > 0.0 && next.hi < 1.0))
      next = DD{fp > 0.0 ? 0.5 * (lam.hi + 1.0) : 0.5 * lam.hi, 0.0};
    if (next.hi == lam.hi && next.lo == lam.lo) break;
    lam = next;
  }
  return best_w < std::numeric_limits<double>::infinity();
}

}  // namespace pw85
