// Fast path of the derivatives on x86-64-v4 (docs/derivatives.md, (E9)):
// the quantities of (E1)-(E6) at lambda from the adjugate of Q(lambda),
// all in double-double across the lanes of AVX-512 vectors, then the
// first-order move to the root of f' and a-posteriori error estimates, as
// in (E8) (fast.hpp). With C = adj Q(lambda), B = det Q(lambda),
// U = C r = B s, T_k = Q_k U = B Q_k s, W = (1 - lambda)^2 T1 - lambda^2 T2
// = B w, every quantity is a polynomial in the inputs, with no division:
//   s = U / B, X = Q^{-1} = C / B, x0 = (1 - lambda) T1 / B, Q2 s = T2 / B,
//   f'(lambda) = U.W / B^2, a2 = -f''/2 = T1.(C T2) / B^3, h = 2 C W / B^2.
// A polynomial evaluated in double-double errs by at most gamma u^2 times
// the same polynomial of the absolute values (computed alongside in
// double), so the relative error of each of them is known from that ratio;
// a ratio beyond 2^-60 / (gamma u^2) (cancellation beyond ~2^40 in one of
// them) declines to (E8). Q(lambda) is formed from lambda given as a
// double-double, so that a second pass at lambda + dl (the root of f' to
// ~u^2) serves the pairs whose first-order move is too large for the
// Hessian (cond(Q(lambda)) u beyond ~1e-7: mostly semi-axis ratios beyond
// 10^4).
#pragma once

#include <immintrin.h>

#include <cmath>

#include "arith/dd.hpp"
#include "common/fp.hpp"
#include "common/isa.hpp"
#include "common/sym3.hpp"
#include "derivatives/derivatives.hpp"
#include "derivatives/fast.hpp"
#include "eval/f_rational_dd.hpp"

namespace pw85 {
namespace adjd {

// The kernel's results rounded to double (lanes of the vectors below),
// with bounds on their errors.
struct Values {
  double c[8];     // C = adj Q(lambda), lanes 0-5 (storage order of Sym3)
  double ub[8];    // U = C r in lanes 0-2, B = det Q(lambda) in lane 3
  double t[8];     // T1 = Q1 U in lanes 0-2, T2 = Q2 U in lanes 3-5
  double cw[8];    // C W in lanes 0-2
  double dots[8];  // F = U.W (= f' B^2) in lane 0, A = T1.(C T2) (= a2 B^3) in lane 3
  double f_err;    // bound on the error of F
  double rel_s;    // relative error bounds (max norm) of C, U, B together,
  double rel_t;    // of T1 and T2,
  double rel_h;    // of C W and of A
};

// Bound on the error of the double-double evaluation, in units of the
// polynomial of absolute values: 12 dependent operations (products without
// the low-times-low term, sums of unnormalised pairs), each within a few
// u^2 of the absolute values of its operands; 128 u^2 with margin.
constexpr double kGammaDD = 128.0 * kU * kU;

PW85_V4_INLINE __m512d idx_perm(__m512d v, __m512i i) { return rdd::perm(v, i); }

PW85_V4_INLINE rdd::DD perm_dd(rdd::DD x, __m512i i) {
  return rdd::DD{rdd::perm(x.h, i), rdd::perm(x.l, i)};
}

PW85_V4_INLINE rdd::DD bcast_dd(rdd::DD x, int j) { return perm_dd(x, _mm512_set1_epi64(j)); }

PW85_V4_INLINE rdd::DD set1_dd(dd::DD x) {
  return rdd::DD{_mm512_set1_pd(x.hi), _mm512_set1_pd(x.lo)};
}

// Lane by lane, the largest |v| over the lane's triple (lanes 0-2, 3-5;
// lanes 6, 7 with themselves).
PW85_V4_INLINE __m512d triple_max(__m512d v) {
  __m512d const a = rdd::vabs(v);
  __m512d const b = idx_perm(a, _mm512_setr_epi64(1, 2, 0, 4, 5, 3, 6, 7));
  __m512d const c = idx_perm(a, _mm512_setr_epi64(2, 0, 1, 5, 3, 4, 6, 7));
  return _mm512_maskz_max_pd(0xFF, a, _mm512_maskz_max_pd(0xFF, b, c));
}

// True when the 29 doubles at p are finite (x - x is 0 for finite x).
PW85_V4_INLINE bool all_finite(double const *p) {
  __m512d const a = _mm512_loadu_pd(p), b = _mm512_loadu_pd(p + 8);
  __m512d const c = _mm512_loadu_pd(p + 16), d = _mm512_maskz_loadu_pd(0x1F, p + 24);
  __m512d const z = _mm512_add_pd(_mm512_add_pd(_mm512_sub_pd(a, a), _mm512_sub_pd(b, b)),
                                  _mm512_add_pd(_mm512_sub_pd(c, c), _mm512_sub_pd(d, d)));
  return _mm512_cmp_pd_mask(z, _mm512_setzero_pd(), _CMP_EQ_OQ) == 0xFF;
}

// The kernel at lambda = lh + ll (a double-double, 0 < lambda < 1).
PW85_V4_INLINE void kernel(double lh, double ll, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                           Values &out) {
  using namespace rdd;
  __m512d const a = _mm512_maskz_loadu_pd(0x3F, q1.a);
  __m512d const b = _mm512_maskz_loadu_pd(0x3F, q2.a);
  // 1 - lambda as nh + nl.
  dd::DD const om = dd::two_sum(1.0, -lh);
  dd::DD const nu{om.hi, om.lo - ll}, la{lh, ll};
  // Q(lambda) = (1 - lambda) Q1 + lambda Q2, lanes 0-5 (Sym3 order).
  DD const pa = two_prod(_mm512_set1_pd(nu.hi), a), pb = two_prod(_mm512_set1_pd(lh), b);
  DD q = two_sum(pa.h, pb.h);
  q.l = _mm512_add_pd(q.l, _mm512_add_pd(_mm512_add_pd(pa.l, pb.l),
                                         _mm512_fmadd_pd(_mm512_set1_pd(nu.lo), a,
                                                         _mm512_mul_pd(_mm512_set1_pd(ll), b))));
  __m512d const qa = _mm512_fmadd_pd(_mm512_set1_pd(nu.hi), vabs(a),
                                     _mm512_mul_pd(_mm512_set1_pd(lh), vabs(b)));
  // C = adj Q(lambda): entry k = P_k Q_k - S_k T_k (f_rational_dd.hpp's
  // index vectors; lanes 6, 7 read the zero padding).
  __m512i const ip = _mm512_setr_epi64(3, 2, 1, 0, 1, 0, 6, 6);
  __m512i const iq = _mm512_setr_epi64(5, 4, 4, 5, 2, 3, 6, 6);
  __m512i const is = _mm512_setr_epi64(4, 1, 2, 2, 0, 1, 6, 6);
  __m512i const it = _mm512_setr_epi64(4, 5, 3, 2, 4, 1, 6, 6);
  DD const c = sub(mul_dd(perm_dd(q, ip), perm_dd(q, iq)), mul_dd(perm_dd(q, is), perm_dd(q, it)));
  __m512d const ca = _mm512_fmadd_pd(idx_perm(qa, ip), idx_perm(qa, iq),
                                     _mm512_mul_pd(idx_perm(qa, is), idx_perm(qa, it)));
  // U = C r (lanes 0-2) and B = sum_j Q_0j C_0j (lane 3): column j of C
  // times r_j, and C_0j times Q_0j in lane 3.
  __m512i const col[3] = {_mm512_setr_epi64(0, 1, 2, 0, 6, 6, 6, 6),
                          _mm512_setr_epi64(1, 3, 4, 1, 6, 6, 6, 6),
                          _mm512_setr_epi64(2, 4, 5, 2, 6, 6, 6, 6)};
  DD ub{_mm512_setzero_pd(), _mm512_setzero_pd()};
  __m512d uba = _mm512_setzero_pd();
  for (int j = 0; j < 3; ++j) {
    __m512i const ij = _mm512_set1_epi64(j);
    __m512d const rj = _mm512_set1_pd(r[j]);
    DD const m{_mm512_mask_permutexvar_pd(rj, 0x08, ij, q.h),
               _mm512_maskz_permutexvar_pd(0x08, ij, q.l)};
    DD const p = mul_dd(perm_dd(c, col[j]), m);
    __m512d const pm = _mm512_mul_pd(idx_perm(ca, col[j]),
                                     _mm512_mask_permutexvar_pd(vabs(rj), 0x08, ij, qa));
    ub = j == 0 ? p : add(ub, p);
    uba = _mm512_add_pd(uba, pm);
  }
  // T1 = Q1 U (lanes 0-2), T2 = Q2 U (lanes 3-5): columns of Q1 and Q2
  // times U_j; and (1 - lambda) B U (lanes 0-2), for C W below.
  __m512i const gcol[3] = {_mm512_setr_epi64(0, 1, 2, 8, 9, 10, 6, 6),
                           _mm512_setr_epi64(1, 3, 4, 9, 11, 12, 6, 6),
                           _mm512_setr_epi64(2, 4, 5, 10, 12, 13, 6, 6)};
  DD t{_mm512_setzero_pd(), _mm512_setzero_pd()};
  __m512d ta = _mm512_setzero_pd();
  for (int j = 0; j < 3; ++j) {
    __m512d const g = _mm512_permutex2var_pd(a, gcol[j], b);
    DD const p = mul_d(bcast_dd(ub, j), g);
    __m512d const pm = _mm512_mul_pd(vabs(g), idx_perm(uba, _mm512_set1_epi64(j)));
    t = j == 0 ? p : add(t, p);
    ta = _mm512_add_pd(ta, pm);
  }
  DD const nub = mul_dd(bcast_dd(ub, 3), set1_dd(nu));
  DD const nubu = mul_dd(nub, ub);
  __m512d const nubua = _mm512_mul_pd(_mm512_mul_pd(_mm512_set1_pd(nu.hi), uba),
                                      idx_perm(uba, _mm512_set1_epi64(3)));
  // Y = C T2 (lanes 0-2): column j of C times T2_j. With Q = (1 - lambda) Q1
  // + lambda Q2 and C Q = B I,
  //   C W = (1 - lambda)^2 C Q1 U - lambda^2 C Q2 U = (1 - lambda) B U - lambda Y.
  DD y{_mm512_setzero_pd(), _mm512_setzero_pd()};
  __m512d ya = _mm512_setzero_pd();
  for (int j = 0; j < 3; ++j) {
    DD const p = mul_dd(perm_dd(c, col[j]), bcast_dd(t, 3 + j));
    __m512d const pm = _mm512_mul_pd(idx_perm(ca, col[j]), idx_perm(ta, _mm512_set1_epi64(3 + j)));
    y = j == 0 ? p : add(y, p);
    ya = _mm512_add_pd(ya, pm);
  }
  DD const cw = sub(nubu, mul_dd(y, set1_dd(la)));
  __m512d const cwa = _mm512_fmadd_pd(_mm512_set1_pd(lh), ya, nubua);
  // W = (1 - lambda)^2 T1 - lambda^2 T2 (lanes 0-2).
  dd::DD const nu2 = dd::mul<true>(nu, nu), la2 = dd::mul<true>(la, la);
  __m512i const hi3 = _mm512_setr_epi64(3, 4, 5, 6, 6, 6, 6, 6);
  DD const w = sub(mul_dd(t, set1_dd(nu2)), mul_dd(perm_dd(t, hi3), set1_dd(la2)));
  __m512d const wa = _mm512_fmadd_pd(_mm512_set1_pd(nu2.hi), ta,
                                     _mm512_mul_pd(_mm512_set1_pd(la2.hi), idx_perm(ta, hi3)));
  // F = U.W (lane 0) and A = T1.Y (lane 3): products lane by lane, then
  // the sums of lanes 0-2 and 3-5.
  __m512i const lo3 = _mm512_setr_epi64(6, 6, 6, 0, 1, 2, 6, 6);
  DD const x1{_mm512_mask_blend_pd(0x38, ub.h, idx_perm(t.h, lo3)),
              _mm512_mask_blend_pd(0x38, ub.l, idx_perm(t.l, lo3))};
  DD const x2{_mm512_mask_blend_pd(0x38, w.h, idx_perm(y.h, lo3)),
              _mm512_mask_blend_pd(0x38, w.l, idx_perm(y.l, lo3))};
  DD const pr = mul_dd(x1, x2);
  __m512d const pra = _mm512_mul_pd(_mm512_mask_blend_pd(0x38, uba, idx_perm(ta, lo3)),
                                    _mm512_mask_blend_pd(0x38, wa, idx_perm(ya, lo3)));
  __m512i const n1 = _mm512_setr_epi64(1, 6, 6, 4, 6, 6, 6, 6);
  __m512i const n2 = _mm512_setr_epi64(2, 6, 6, 5, 6, 6, 6, 6);
  DD const dots = add(add(pr, perm_dd(pr, n1)), perm_dd(pr, n2));
  __m512d const dotsa = _mm512_add_pd(_mm512_add_pd(pra, idx_perm(pra, n1)), idx_perm(pra, n2));
  // Rounded values.
  __m512d const cv = _mm512_add_pd(c.h, c.l), ubv = _mm512_add_pd(ub.h, ub.l);
  __m512d const tv = _mm512_add_pd(t.h, t.l), cwv = _mm512_add_pd(cw.h, cw.l);
  __m512d const dv = _mm512_add_pd(dots.h, dots.l);
  _mm512_storeu_pd(out.c, cv);
  _mm512_storeu_pd(out.ub, ubv);
  _mm512_storeu_pd(out.t, tv);
  _mm512_storeu_pd(out.cw, cwv);
  _mm512_storeu_pd(out.dots, dv);
  // Relative bounds, each group in the max norm: the largest absolute-value
  // polynomial over the largest value (lane by lane over the triples, then
  // C over both triples).
  __m512i const swap = _mm512_setr_epi64(3, 4, 5, 0, 1, 2, 6, 7);
  __m512d const cm = triple_max(cv), cam = triple_max(ca);
  __m512d const num1 = _mm512_maskz_max_pd(0xFF, cam, idx_perm(cam, swap));
  __m512d const den1 = _mm512_maskz_max_pd(0xFF, cm, idx_perm(cm, swap));
  __m512d const r_c = _mm512_div_pd(num1, den1);               // C: every lane
  __m512d const r_ub = _mm512_div_pd(triple_max(uba), triple_max(ubv));  // U: 0-2, B: 3
  __m512d const r_t = _mm512_div_pd(triple_max(ta), triple_max(tv));     // T1: 0-2, T2: 3-5
  __m512d const r_cw = _mm512_div_pd(triple_max(cwa), triple_max(cwv));  // C W: 0-2
  __m512d const r_s = _mm512_maskz_max_pd(0xFF, r_c, r_ub);
  double rs[8], rt[8], rcw[8];
  _mm512_storeu_pd(rs, r_s);
  _mm512_storeu_pd(rt, r_t);
  _mm512_storeu_pd(rcw, r_cw);
  out.f_err = kGammaDD * dotsa[0];
  out.rel_s = kGammaDD * fastd::max2(rs[0], rs[3]);
  out.rel_t = kGammaDD * fastd::max2(rt[0], rt[3]);
  out.rel_h = kGammaDD * fastd::max2(rcw[0], dotsa[3] / std::fabs(out.dots[3]));
}

// Largest relative error bounds of the kernel's values accepted: C, U and B
// (s and X: far below u), T1 and T2 (x0 and Q2 s: the torques), C W and A
// (h and a2: the Hessian). Each is counted in the estimates below.
constexpr double kMaxRelS = 0x1p-57, kMaxRelT = 0x1p-50, kMaxRelH = 0x1p-26;
// Largest t2 (relative change of X along dl) for the first-order move of
// X, h and a2; beyond it, the second pass.
constexpr double kMaxMove = 0x1p-24;
constexpr int kSymIndex[kDim][kDim] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};

// The derivatives at DEFAULT's maximiser lambda, mu2 its value, as
// fast_derivatives (fast.hpp): false, out untouched, when an estimate
// exceeds its bound or a value is not finite.
PW85_V4_INLINE bool adjugate_derivatives(double lambda, double mu2, Vec3 const &r,
                                         Sym3 const &q1, Sym3 const &q2,
                                         Derivatives &out) noexcept {
  using namespace fastd;
  double const mq1 = max_abs6(q1), mq2 = max_abs6(q2);
  double lh = lambda, ll = 0.0;
  for (int pass = 0; pass < 2; ++pass) {
    Values k;
    kernel(lh, ll, r, q1, q2, k);
    if (!(k.rel_s <= kMaxRelS && k.rel_t <= kMaxRelT && k.rel_h <= kMaxRelH)) return false;
    dd::DD const om = dd::two_sum(1.0, -lh);
    double const nu = om.hi + (om.lo - ll);
    double const bb = k.ub[3], ib = 1.0 / bb, ib2 = ib * ib;
    double const aa = k.dots[3], ia = 1.0 / aa, ff = k.dots[0];
    // Values at lambda: s, Q1 s, Q2 s, x0, X, h = 2 X w, a2 = -f''/2 and
    // 1 / (2 a2), f'.
    Vec3 s, q1s, q2s, x0, h;
    for (int i = 0; i < kDim; ++i) {
      s[i] = k.ub[i] * ib;
      q1s[i] = k.t[i] * ib;
      q2s[i] = k.t[3 + i] * ib;
      x0[i] = nu * q1s[i];
      h[i] = 2.0 * (k.cw[i] * ib2);
    }
    Sym3 x;
    for (int i = 0; i < kSym; ++i) x[i] = k.c[i] * ib;
    double const a2 = ((aa * ib) * ib) * ib, iha = 0.5 * (((bb * ia) * bb) * bb);
    double const fp = ff * ib2;
    double const mx = max_abs6(x), ms = max_abs3(s);
    // Relative errors of s and X (rounding of the kernel's value, of 1 / B,
    // the product), of h and of a2; absolute error of f'.
    double const es = 3.0 * kU + 2.0 * k.rel_s, eps_x = es;
    double const e_h = 5.0 * kU + k.rel_s + k.rel_h, eps2 = 6.0 * kU + k.rel_s + k.rel_h;
    double const err_fp = (k.f_err + 2.0 * kU * std::fabs(ff)) * ib2 + 4.0 * kU * std::fabs(fp);
    // The step to the root of f' (Newton, (E7)), dl = f' / (2 a2), and the
    // first-order moves along it, as fast_derivatives.
    double const dl = 0.5 * ((ff * bb) * ia);
    double const adl = std::fabs(dl);
    double const t2 = 9.0 * adl * mx * (mq1 + mq2);
    Vec3 const v = multiply(x, Vec3{{q2s[0] - q1s[0], q2s[1] - q1s[1], q2s[2] - q1s[2]}});
    Vec3 const q1v = multiply(q1, v), q2v = multiply(q2, v);
    double const mq1s = max_abs3(q1s), mq2s = max_abs3(q2s);
    double const mv = max_abs3(v);
    Vec3 const q2s0 = q2s;
    for (int i = 0; i < kDim; ++i) {
      s[i] -= v[i] * dl;
      x0[i] -= (q1s[i] + nu * q1v[i]) * dl;
      q2s[i] -= q2v[i] * dl;
    }
    double const lam = lh + (ll + dl), nus = om.hi + ((om.lo - ll) - dl), p = lam * nus;
    // Written into out directly: when this function returns false, the
    // caller's other paths write every field.
    Derivatives &o = out;
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
    for (int e = 0; e < kSym; ++e) {
      double const ss = (kI[e] == kJ[e] ? 1.0 : 2.0) * s[kI[e]] * s[kJ[e]];
      o.d_q1[e] = c1 * ss;
      o.d_q2[e] = c2 * ss;
    }
    // Hessian (E6) from X, h and a2 at lambda (not moved: their relative
    // change along dl is below t2, counted in err_t).
    double const mh = max_abs3(h);
    double mhess = 0.0;
    for (int e = 0; e < kSym; ++e) {
      o.hess_r12[e] = 2.0 * p * x[e] + h[kI[e]] * h[kJ[e]] * iha;
      mhess = max2(mhess, std::fabs(o.hess_r12[e]));
    }
    // Error estimates of fast_derivatives (max norms; a factor 3 converts
    // to 2-norms), multiplied through by |s| and 2 p: the gradient's, from
    // s, from the move (adl mv / |s| relative, its second-order term times
    // t2, v's error) and from the error of dl (times |h|); the Hessian's,
    // from X, h, a2 and from not moving them (t2).
    double const err_dl = err_fp * iha + adl * eps2;
    double const err_g2p =
        2.0 * p * ((es + 4.0 * kU) * ms + adl * mv * t2 +
                   3.0 * adl * mx * (eps_x + 2.0 * kU) * (mq1s + mq2s)) +
        err_dl * mh;
    double const err_eps = 3.0 * (2.0 * p * mx * (eps_x + 2.0 * kU) +
                                  mh * mh * (2.0 * e_h + eps2 + 3.0 * kU) * iha);
    double const err_t = 3.0 * (2.0 * p * mx * t2 + 3.0 * mh * mh * t2 * iha);
    bool const grad_ok = 3.0 * err_g2p <= kAcceptG * ms * (2.0 * p);
    bool hess_ok = err_eps + err_t <= kAcceptH * mhess;
    if (grad_ok && !hess_ok && t2 <= kMaxMove) {
      // X, h and a2 moved to lambda + dl to first order:
      //   X' = -X D X, D = Q2 - Q1, (Q1 s)' = -Q1 v, (Q2 s)' = -Q2 v,
      //   a2' = -((Q1 v).X Q2 s + (X Q1 s).D (X Q2 s) + (X Q1 s).Q2 v),
      //   w' = -2 r - (1 - lambda)^2 Q1 v + lambda^2 Q2 v (Q s = r),
      //   h' = 2 X' w + 2 X w' = X (2 w' - D h);
      // their second-order terms are below ~t2^2 relative, the rounding of
      // the first-order terms ~u times them.
      Sym3 const dm = difference(q2, q1);
      Sym3 xm;
      for (int j = 0; j < kDim; ++j) {
        Vec3 const cj = multiply(x, multiply(dm, column(x, j)));
        for (int i = 0; i <= j; ++i) xm[kSymIndex[i][j]] = x[kSymIndex[i][j]] - cj[i] * dl;
      }
      Vec3 const y1 = multiply(x, q1s), y2 = multiply(x, q2s0), dy2 = multiply(dm, y2);
      double const da2 = -(dot(q1v, y2) + dot(y1, dy2) + dot(y1, q2v));
      double const a2m = a2 + da2 * dl, iham = 0.5 / a2m;
      double const n2 = nu * nu, l2 = lh * lh;
      Vec3 const dh_in = multiply(dm, h);
      Vec3 wp;
      for (int i = 0; i < kDim; ++i) wp[i] = 2.0 * (-2.0 * r[i] - n2 * q1v[i] + l2 * q2v[i]) - dh_in[i];
      Vec3 const dh = multiply(x, wp);
      Vec3 hm;
      for (int i = 0; i < kDim; ++i) hm[i] = h[i] + dh[i] * dl;
      double const mhm = max_abs3(hm);
      double mhessm = 0.0;
      Sym3 hess;
      for (int e = 0; e < kSym; ++e) {
        hess[e] = 2.0 * p * xm[e] + hm[kI[e]] * hm[kJ[e]] * iham;
        mhessm = max2(mhessm, std::fabs(hess[e]));
      }
      double const md = max_abs6(dm), my1 = max_abs3(y1), my2 = max_abs3(y2);
      double const second = 4.0 * t2 * t2;
      double const err_hm = 24.0 * kU * adl * mx * (max_abs3(wp) + 3.0 * md * mh) + second * mhm;
      double const err_am =
          18.0 * kU * adl * (max_abs3(q1v) * my2 + 3.0 * my1 * md * my2 + my1 * max_abs3(q2v)) +
          second * a2m;
      double const err_m =
          3.0 * (2.0 * p * mx * (eps_x + 2.0 * kU + 2.0 * kU * t2 + second) +
                 (2.0 * mhm * (e_h * mhm + err_hm) + mhm * mhm * (eps2 + 3.0 * kU) +
                  mhm * mhm * err_am * 2.0 * iham) * iham);
      hess_ok = err_m <= kAcceptH * mhessm && a2m > 0.0;
      if (hess_ok)
        for (int e = 0; e < kSym; ++e) o.hess_r12[e] = hess[e];
    }
    bool const ok = grad_ok && hess_ok && a2 > 0.0 && lam > 0.0 && lam < 1.0;
    if (!ok) {
      // Once more at lambda + dl as a double-double, where the move is
      // ~u^2 relative; when the estimates fail there too, decline.
      if (pass == 1 || !(a2 > 0.0) || !(lam > 0.0 && lam < 1.0)) return false;
      dd::DD const n = dd::two_sum(lh, dl);
      lh = n.hi;
      ll = n.lo;
      continue;
    }
    return all_finite(&o.mu2);
  }
  return false;
}

}  // namespace adjd
}  // namespace pw85
