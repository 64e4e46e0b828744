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
// double), so the relative error of each group is known from that ratio;
// a group beyond its bound (kMaxRelS, kMaxRelT, kMaxRelH below) declines to
// (E8). Where the Hessian's estimate fails because X, h and a2 were not
// moved along dl, they are moved to first order; where the move is too
// large for that, the whole runs again at lambda + dl, with lambda given as
// a double-double (Q(lambda) is formed from it), where the move is ~u^2
// relative.
#pragma once

#include <immintrin.h>

#include <cmath>

#include "arith/dd.hpp"
#include "common/fp.hpp"
#include "common/isa.hpp"
#include "common/sym3.hpp"
#include "derivatives/derivatives.hpp"
#include "derivatives/fast.hpp"
#include "eval/f_coefficients_dd.hpp"

namespace pw85 {
namespace adjd {

// The kernel's results rounded to double, in the lanes of AVX-512 vectors,
// with bounds on their errors.
struct Values {
  __m512d c;     // C = adj Q(lambda), lanes 0-5 (storage order of Sym3)
  __m512d ub;    // U = C r in lanes 0-2, B = det Q(lambda) in lane 3
  __m512d t;     // T1 = Q1 U in lanes 0-2, T2 = Q2 U in lanes 3-5
  __m512d cw;    // C W in lanes 0-2
  __m512d dots;  // F = U.W (= f' B^2) in lane 0, A = T1.(C T2) (= a2 B^3) in lane 3
  double f_err;  // bound on the error of F
  bool ok;       // C, U and B within kMaxRelS, T1 and T2 within kMaxRelT (max norm)
  double rel_h;  // relative error bound (max norm) of C W and of A
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

// Column j of a symmetric matrix in lanes 0-5 (Sym3 order), in lanes 0-2
// (lanes 3-5: the same again, for two products at once).
PW85_V4_INLINE __m512i sym_column(int j) {
  return j == 0 ? _mm512_setr_epi64(0, 1, 2, 0, 1, 2, 6, 6)
                : j == 1 ? _mm512_setr_epi64(1, 3, 4, 1, 3, 4, 6, 6)
                         : _mm512_setr_epi64(2, 4, 5, 2, 4, 5, 6, 6);
}

PW85_V4_INLINE __m512d bcast(__m512d v, int j) { return idx_perm(v, _mm512_set1_epi64(j)); }

// Column j of Q1 (lanes 0-2) and of Q2 (lanes 3-5), from a = Q1, b = Q2 in
// Sym3 order.
PW85_V4_INLINE __m512d q_columns(__m512d a, __m512d b, int j) {
  __m512i const i0 = _mm512_setr_epi64(0, 1, 2, 8, 9, 10, 6, 6);
  __m512i const i1 = _mm512_setr_epi64(1, 3, 4, 9, 11, 12, 6, 6);
  __m512i const i2 = _mm512_setr_epi64(2, 4, 5, 10, 12, 13, 6, 6);
  return _mm512_permutex2var_pd(a, j == 0 ? i0 : j == 1 ? i1 : i2, b);
}

// Symmetric 3x3 matrix (lanes 0-5) times the vector in lanes 0-2 of v
// (result in lanes 0-2, and again in 3-5).
PW85_V4_INLINE __m512d sym_mul(__m512d m, __m512d v) {
  __m512d acc = _mm512_mul_pd(idx_perm(m, sym_column(0)), bcast(v, 0));
  acc = _mm512_fmadd_pd(idx_perm(m, sym_column(1)), bcast(v, 1), acc);
  return _mm512_fmadd_pd(idx_perm(m, sym_column(2)), bcast(v, 2), acc);
}

// Sum of lanes 0-2 of v.
PW85_V4_INLINE double sum3(__m512d v) { return (v[0] + v[1]) + v[2]; }

// The largest |v| over lanes 0-5.
PW85_V4_INLINE double max6(__m512d v) {
  __m512d const m = triple_max(v);
  return fastd::max2(m[0], m[3]);
}

// Largest relative error bounds of the kernel's values accepted: C, U and B
// (s and X: far below u), T1 and T2 (x0 and Q2 s: the torques), C W and A
// (h and a2: the Hessian). Each is counted in the estimates below.
constexpr double kMaxRelS = 0x1p-57, kMaxRelT = 0x1p-50, kMaxRelH = 0x1p-26;

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
  // C = adj Q(lambda): entry k = P_k Q_k - S_k T_k (adj_index,
  // f_coefficients_dd.hpp; lanes 6, 7 read the zero padding).
  AdjIndex const ix = adj_index();
  __m512i const ip = ix.p, iq = ix.q, is = ix.s, it = ix.t;
  DD const c = sub(mul_dd(perm_dd(q, ip), perm_dd(q, iq)), mul_dd(perm_dd(q, is), perm_dd(q, it)));
  __m512d const ca = _mm512_fmadd_pd(idx_perm(qa, ip), idx_perm(qa, iq),
                                     _mm512_mul_pd(idx_perm(qa, is), idx_perm(qa, it)));
  // U = C r (lanes 0-2) and B = sum_j Q_0j C_0j (lane 3): column j of C
  // (sym_column: C_0j in lane 3) times r_j, and times Q_0j in lane 3.
  DD ub{_mm512_setzero_pd(), _mm512_setzero_pd()};
  __m512d uba = _mm512_setzero_pd();
  for (int j = 0; j < 3; ++j) {
    __m512i const ij = _mm512_set1_epi64(j);
    __m512d const rj = _mm512_maskz_mov_pd(0x07, _mm512_set1_pd(r[j]));
    DD const m{_mm512_mask_permutexvar_pd(rj, 0x08, ij, q.h),
               _mm512_maskz_permutexvar_pd(0x08, ij, q.l)};
    DD const p = mul_dd(perm_dd(c, sym_column(j)), m);
    __m512d const pm = _mm512_mul_pd(idx_perm(ca, sym_column(j)),
                                     _mm512_mask_permutexvar_pd(vabs(rj), 0x08, ij, qa));
    ub = j == 0 ? p : add(ub, p);
    uba = _mm512_add_pd(uba, pm);
  }
  // T1 = Q1 U (lanes 0-2), T2 = Q2 U (lanes 3-5): columns of Q1 and Q2
  // times U_j; and (1 - lambda) B U (lanes 0-2), for C W below.
  DD t{_mm512_setzero_pd(), _mm512_setzero_pd()};
  __m512d ta = _mm512_setzero_pd();
  for (int j = 0; j < 3; ++j) {
    __m512d const g = q_columns(a, b, j);
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
    DD const p = mul_dd(perm_dd(c, sym_column(j)), bcast_dd(t, 3 + j));
    __m512d const pm = _mm512_mul_pd(idx_perm(ca, sym_column(j)), bcast(ta, 3 + j));
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
  // The products with their low-times-low terms (mul_dd drops them: below
  // u^2 x1a x2a, but not below the bound used here), so that the bound of
  // the two dot products follows from those of their factors: the error of
  // x1 (x1a, its absolute-value polynomial, times gamma u^2) times |x2|, and
  // the other way round; the products' own roundings are within it.
  // (x1a x2a, the polynomial of the dot product itself, can be far larger:
  // both factors' cancellations multiplied.)
  DD const p0 = two_prod(x1.h, x2.h);
  DD const pr{p0.h, _mm512_fmadd_pd(x1.h, x2.l,
                                    _mm512_fmadd_pd(x1.l, x2.h, _mm512_fmadd_pd(x1.l, x2.l, p0.l)))};
  __m512d const x1a = _mm512_mask_blend_pd(0x38, uba, idx_perm(ta, lo3));
  __m512d const x2a = _mm512_mask_blend_pd(0x38, wa, idx_perm(ya, lo3));
  __m512d const pra = _mm512_fmadd_pd(x1a, vabs(x2.h), _mm512_mul_pd(vabs(x1.h), x2a));
  __m512i const n1 = _mm512_setr_epi64(1, 6, 6, 4, 6, 6, 6, 6);
  __m512i const n2 = _mm512_setr_epi64(2, 6, 6, 5, 6, 6, 6, 6);
  DD const dots = add(add(pr, perm_dd(pr, n1)), perm_dd(pr, n2));
  __m512d const dotsa = _mm512_add_pd(_mm512_add_pd(pra, idx_perm(pra, n1)), idx_perm(pra, n2));
  // Rounded values.
  __m512d const cv = _mm512_add_pd(c.h, c.l), ubv = _mm512_add_pd(ub.h, ub.l);
  __m512d const tv = _mm512_add_pd(t.h, t.l), cwv = _mm512_add_pd(cw.h, cw.l);
  __m512d const dv = _mm512_add_pd(dots.h, dots.l);
  out.c = cv;
  out.ub = ubv;
  out.t = tv;
  out.cw = cwv;
  out.dots = dv;
  // The groups' bounds, each in the max norm (lane by lane over the
  // triples, C over both triples): gamma u^2 times the largest
  // absolute-value polynomial against the group's bound (kMaxRelS,
  // kMaxRelT) times the largest value, as products; the estimates use those
  // bounds. For C W and A, the ratio itself (rel_h): the Hessian's estimate
  // uses it.
  __m512i const swap = _mm512_setr_epi64(3, 4, 5, 0, 1, 2, 6, 7);
  __m512d const cm = triple_max(cv), cam = triple_max(ca);
  __m512d const num_c = _mm512_maskz_max_pd(0xFF, cam, idx_perm(cam, swap));
  __m512d const den_c = _mm512_maskz_max_pd(0xFF, cm, idx_perm(cm, swap));
  __m512d const gamma = _mm512_set1_pd(kGammaDD);
  __m512d const max_s = _mm512_set1_pd(kMaxRelS), max_t = _mm512_set1_pd(kMaxRelT);
  unsigned const ok_c = _mm512_cmp_pd_mask(_mm512_mul_pd(gamma, num_c),
                                           _mm512_mul_pd(max_s, den_c), _CMP_LE_OQ);
  unsigned const ok_ub = _mm512_cmp_pd_mask(_mm512_mul_pd(gamma, triple_max(uba)),
                                            _mm512_mul_pd(max_s, triple_max(ubv)), _CMP_LE_OQ);
  unsigned const ok_t = _mm512_cmp_pd_mask(_mm512_mul_pd(gamma, triple_max(ta)),
                                           _mm512_mul_pd(max_t, triple_max(tv)), _CMP_LE_OQ);
  __m512d const cwm = triple_max(cwv), cwam = triple_max(cwa);
  out.f_err = kGammaDD * dotsa[0];
  out.ok = (ok_c & ok_ub & ok_t & 0x09) == 0x09;  // lane 0: C, U, T1; lane 3: B, T2
  out.rel_h = kGammaDD * fastd::max2(cwam[0] / cwm[0], dotsa[3] / std::fabs(dv[3]));
}

// Largest t2 (relative change of X along dl) for the first-order move of
// X, h and a2; beyond it, the second pass.
constexpr double kMaxMove = 0x1p-24;

// The derivatives at DEFAULT's maximiser lambda, mu2 its value, as
// fast_derivatives (fast.hpp), in the lanes of AVX-512 vectors (3-vectors
// in lanes 0-2, pairs of them in lanes 0-2 and 3-5, symmetric matrices in
// lanes 0-5). Writes out; returns false when an estimate exceeds its bound
// or a value is not finite (the caller then writes out by other means).
PW85_V4_INLINE bool adjugate_derivatives(double lambda, double mu2, Vec3 const &r,
                                         Sym3 const &q1, Sym3 const &q2,
                                         Derivatives &out) noexcept {
  __m512d const qa = _mm512_maskz_loadu_pd(0x3F, q1.a), qb = _mm512_maskz_loadu_pd(0x3F, q2.a);
  double const mq1 = max6(qa), mq2 = max6(qb);
  __m512d const g[3] = {q_columns(qa, qb, 0), q_columns(qa, qb, 1), q_columns(qa, qb, 2)};
  __m512i const hi3 = _mm512_setr_epi64(3, 4, 5, 6, 6, 6, 6, 6);
  // Index vectors of the products s_i s_j, h_i h_j over the stored entries,
  // and the weights of the stored entries (1 on the diagonal, 2 off it).
  __m512i const ki = _mm512_setr_epi64(0, 0, 0, 1, 1, 2, 6, 6);
  __m512i const kj = _mm512_setr_epi64(0, 1, 2, 1, 2, 2, 6, 6);
  __m512d const wk = _mm512_setr_pd(1.0, 2.0, 2.0, 1.0, 2.0, 1.0, 0.0, 0.0);
  double lh = lambda, ll = 0.0;
  for (int pass = 0; pass < 2; ++pass) {
    Values k;
    kernel(lh, ll, r, q1, q2, k);
    if (!(k.ok && k.rel_h <= kMaxRelH)) return false;
    dd::DD const om = dd::two_sum(1.0, -lh);
    double const nu = om.hi + (om.lo - ll);
    double const bb = k.ub[3], ib = 1.0 / bb, ib2 = ib * ib;
    double const aa = k.dots[3], ia = 1.0 / aa, ff = k.dots[0];
    // Values at lambda: s, [Q1 s, Q2 s], X, h = 2 X w; a2 = -f''/2,
    // 1 / (2 a2), f'.
    __m512d const vib = _mm512_set1_pd(ib);
    __m512d const sv = _mm512_mul_pd(k.ub, vib), pv = _mm512_mul_pd(k.t, vib);
    __m512d const xv = _mm512_mul_pd(k.c, vib);
    __m512d const hv = _mm512_mul_pd(k.cw, _mm512_set1_pd(2.0 * ib2));
    double const a2 = ((aa * ib) * ib) * ib, iha = 0.5 * (((bb * ia) * bb) * bb);
    double const fp = ff * ib2;
    __m512d const pm = triple_max(pv);
    double const mx = max6(xv), ms = triple_max(sv)[0], mh = triple_max(hv)[0];
    double const mq1s = pm[0], mq2s = pm[3];
    // Relative errors of s and X (rounding of the kernel's value, of 1 / B,
    // the product), of h and of a2; absolute error of f'.
    double const es = 3.0 * kU + 2.0 * kMaxRelS, eps_x = es;
    double const e_h = 5.0 * kU + kMaxRelS + k.rel_h, eps2 = 6.0 * kU + kMaxRelS + k.rel_h;
    double const err_fp = (k.f_err + 2.0 * kU * std::fabs(ff)) * ib2 + 4.0 * kU * std::fabs(fp);
    // The step to the root of f' (Newton, (E7)), dl = f' / (2 a2), and the
    // first-order moves along it, as fast_derivatives: v = X (Q2 s - Q1 s),
    // s' = -v, x0' = -Q1 s - (1 - lambda) Q1 v, (Q2 s)' = -Q2 v.
    double const dl = 0.5 * ((ff * bb) * ia);
    double const adl = std::fabs(dl);
    double const t2 = 9.0 * adl * mx * (mq1 + mq2);
    __m512d const v = sym_mul(xv, _mm512_sub_pd(idx_perm(pv, hi3), pv));
    __m512d qv = _mm512_mul_pd(g[0], bcast(v, 0));  // [Q1 v, Q2 v]
    qv = _mm512_fmadd_pd(g[1], bcast(v, 1), qv);
    qv = _mm512_fmadd_pd(g[2], bcast(v, 2), qv);
    double const mv = triple_max(v)[0];
    __m512d const vdl = _mm512_set1_pd(dl);
    __m512d const sm = _mm512_fnmadd_pd(v, vdl, sv);
    __m512d const mnu = _mm512_setr_pd(nu, nu, nu, 1.0, 1.0, 1.0, 0.0, 0.0);
    __m512d const xq =  // [x0, Q2 s] moved
        _mm512_fnmadd_pd(_mm512_fmadd_pd(mnu, qv, _mm512_maskz_mov_pd(0x07, pv)), vdl,
                         _mm512_mul_pd(mnu, pv));
    double const lam = lh + (ll + dl), nus = om.hi + ((om.lo - ll) - dl), p = lam * nus;
    double const p2 = 2.0 * p;
    // Outputs (E1)-(E4): g; -x0 x g and (x0 - r) x g, x0 - r = -lambda Q2 s,
    // as one cross product of [x0, x0 - r] with [g, g]; (E2).
    out.mu2 = mu2;
    out.lambda = lam;
    __m512d const gv = _mm512_mul_pd(sm, _mm512_set1_pd(p2));
    _mm512_mask_storeu_pd(out.d_r12, 0x07, gv);
    __m512d const av = _mm512_mul_pd(xq, _mm512_setr_pd(1.0, 1.0, 1.0, -lam, -lam, -lam, 0.0, 0.0));
    __m512i const yzx = _mm512_setr_epi64(1, 2, 0, 4, 5, 3, 6, 6);
    __m512i const zxy = _mm512_setr_epi64(2, 0, 1, 5, 3, 4, 6, 6);
    __m512i const gyzx = _mm512_setr_epi64(1, 2, 0, 1, 2, 0, 6, 6);
    __m512i const gzxy = _mm512_setr_epi64(2, 0, 1, 2, 0, 1, 6, 6);
    __m512d const cr = _mm512_fmsub_pd(idx_perm(av, yzx), idx_perm(gv, gzxy),
                                       _mm512_mul_pd(idx_perm(av, zxy), idx_perm(gv, gyzx)));
    __m512d const th = _mm512_mul_pd(cr, _mm512_setr_pd(-1.0, -1.0, -1.0, 1.0, 1.0, 1.0, 0.0, 0.0));
    _mm512_mask_storeu_pd(out.d_theta1, 0x3F, th);
    __m512d const ss = _mm512_mul_pd(_mm512_mul_pd(idx_perm(sm, ki), idx_perm(sm, kj)), wk);
    __m512d const dq1 = _mm512_mul_pd(ss, _mm512_set1_pd(-p * nus));
    __m512d const dq2 = _mm512_mul_pd(ss, _mm512_set1_pd(-p * lam));
    _mm512_mask_storeu_pd(out.d_q1, 0x3F, dq1);
    _mm512_mask_storeu_pd(out.d_q2, 0x3F, dq2);
    // Finiteness of the outputs from the registers (x - x: 0 for finite x,
    // NaN otherwise): reloading the struct just written by masked stores
    // measured 2-5 ns per call slower (scratch loop over bench_derivatives'
    // pairs, classes 0 and 2).
    __m512d const fin = _mm512_add_pd(
        _mm512_add_pd(_mm512_maskz_sub_pd(0x07, gv, gv), _mm512_maskz_sub_pd(0x3F, th, th)),
        _mm512_add_pd(_mm512_maskz_sub_pd(0x3F, dq1, dq1), _mm512_maskz_sub_pd(0x3F, dq2, dq2)));
    // Hessian (E6) from X, h and a2 at lambda (not moved: their relative
    // change along dl is below t2, counted in err_t).
    __m512d hess = _mm512_fmadd_pd(_mm512_mul_pd(idx_perm(hv, ki), idx_perm(hv, kj)),
                                   _mm512_set1_pd(iha), _mm512_mul_pd(xv, _mm512_set1_pd(p2)));
    double mhess = max6(hess);
    // Error estimates of fast_derivatives (max norms; a factor 3 converts
    // to 2-norms), multiplied through by |s| and 2 p: the gradient's and
    // s's, from s, from the move (adl mv / |s| relative, its second-order
    // term times t2, v's error) and from the error of dl (times |h| for g,
    // |v| for s, which d_q and the torques need on its own); the Hessian's,
    // from X, h, a2 and from not moving them (t2).
    // dl's error: from f', from a2 and from the step itself (Newton's
    // truncation, f'' changing along dl by ~t2 relative).
    double const err_dl = err_fp * iha + adl * (eps2 + t2);
    double const err_g2p = p2 * ((es + 4.0 * kU) * ms + adl * mv * t2 +
                                 3.0 * adl * mx * (eps_x + 2.0 * kU) * (mq1s + mq2s) +
                                 err_dl * mv) +
                           err_dl * mh;
    double const err_eps = 3.0 * (p2 * mx * (eps_x + 2.0 * kU) +
                                  mh * mh * (2.0 * e_h + eps2 + 3.0 * kU) * iha);
    double const err_t = 3.0 * (p2 * mx * t2 + 3.0 * mh * mh * t2 * iha);
    bool const grad_ok = 3.0 * err_g2p <= fastd::kAcceptG * ms * p2;
    bool hess_ok = err_eps + err_t <= fastd::kAcceptH * mhess;
    if (grad_ok && !hess_ok && t2 <= kMaxMove) {
      // X, h and a2 moved to lambda + dl to first order:
      //   X' = -X D X, D = Q2 - Q1, (Q1 s)' = -Q1 v, (Q2 s)' = -Q2 v,
      //   a2' = -((Q1 v).X Q2 s + (X Q1 s).D (X Q2 s) + (X Q1 s).Q2 v),
      //   w' = -2 r - (1 - lambda)^2 Q1 v + lambda^2 Q2 v (Q s = r),
      //   h' = 2 X' w + 2 X w' = X (2 w' - D h);
      // their second-order terms are below ~t2^2 relative, the rounding of
      // the first-order terms ~u times them.
      __m512d const dm = _mm512_sub_pd(qb, qa);
      // Columns j of X D X (lanes 0-2), then its stored entries.
      __m512d w[3];
      for (int j = 0; j < 3; ++j) w[j] = sym_mul(xv, sym_mul(dm, idx_perm(xv, sym_column(j))));
      __m512d const w01 =
          _mm512_permutex2var_pd(w[0], _mm512_setr_epi64(0, 8, 6, 9, 6, 6, 6, 6), w[1]);
      __m512d const xdx =
          _mm512_permutex2var_pd(w01, _mm512_setr_epi64(0, 1, 8, 3, 9, 10, 6, 6), w[2]);
      __m512d const xm = _mm512_fnmadd_pd(xdx, vdl, xv);
      // [X Q1 s, X Q2 s], D X Q2 s.
      __m512d y = _mm512_mul_pd(idx_perm(xv, sym_column(0)),
                                idx_perm(pv, _mm512_setr_epi64(0, 0, 0, 3, 3, 3, 6, 6)));
      y = _mm512_fmadd_pd(idx_perm(xv, sym_column(1)),
                          idx_perm(pv, _mm512_setr_epi64(1, 1, 1, 4, 4, 4, 6, 6)), y);
      y = _mm512_fmadd_pd(idx_perm(xv, sym_column(2)),
                          idx_perm(pv, _mm512_setr_epi64(2, 2, 2, 5, 5, 5, 6, 6)), y);
      __m512d const y2 = idx_perm(y, hi3), dy2 = sym_mul(dm, y2);
      __m512d const qv2 = idx_perm(qv, hi3);
      double const da2 = -sum3(_mm512_fmadd_pd(
          qv, y2, _mm512_fmadd_pd(y, dy2, _mm512_mul_pd(y, qv2))));
      double const a2m = a2 + da2 * dl, iham = 0.5 / a2m;
      __m512d const rv = _mm512_maskz_loadu_pd(0x07, r.x);
      __m512d const wp = _mm512_sub_pd(
          _mm512_mul_pd(_mm512_set1_pd(2.0),
                        _mm512_fmadd_pd(_mm512_set1_pd(lh * lh), qv2,
                                        _mm512_fmadd_pd(_mm512_set1_pd(-nu * nu), qv,
                                                        _mm512_mul_pd(_mm512_set1_pd(-2.0), rv)))),
          sym_mul(dm, hv));
      __m512d const hm = _mm512_fmadd_pd(sym_mul(xv, wp), vdl, hv);
      __m512d const hessm = _mm512_fmadd_pd(_mm512_mul_pd(idx_perm(hm, ki), idx_perm(hm, kj)),
                                            _mm512_set1_pd(iham), _mm512_mul_pd(xm, _mm512_set1_pd(p2)));
      double const mhm = triple_max(hm)[0], mhessm = max6(hessm);
      __m512d const ym = triple_max(y), qm = triple_max(qv);
      double const md = max6(dm), my1 = ym[0], my2 = ym[3];
      double const second = 4.0 * t2 * t2;
      double const err_hm = 24.0 * kU * adl * mx * (triple_max(wp)[0] + 3.0 * md * mh) + second * mhm;
      double const err_am =
          18.0 * kU * adl * (qm[0] * my2 + 3.0 * my1 * md * my2 + my1 * qm[3]) + second * a2m;
      double const err_m =
          3.0 * (p2 * mx * (eps_x + 2.0 * kU + 2.0 * kU * t2 + second) +
                 (2.0 * mhm * (e_h * mhm + err_hm) + mhm * mhm * (eps2 + 3.0 * kU) +
                  mhm * mhm * err_am * 2.0 * iham) * iham);
      hess_ok = err_m <= fastd::kAcceptH * mhessm && a2m > 0.0;
      if (hess_ok) hess = hessm;
    }
    _mm512_mask_storeu_pd(out.hess_r12, 0x3F, hess);
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
    __m512d const z = _mm512_add_pd(fin, _mm512_maskz_sub_pd(0x3F, hess, hess));
    return _mm512_cmp_pd_mask(z, _mm512_setzero_pd(), _CMP_EQ_OQ) == 0xFF && (mu2 - mu2) == 0.0 &&
           (lam - lam) == 0.0;
  }
  return false;
}

}  // namespace adjd
}  // namespace pw85
