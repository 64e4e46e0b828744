// The seven positive coefficients of f (docs/methods.md, eqs. (M12)-(M13))
// computed in double-double with AVX-512, then f and its derivatives from
// them in double (DEFAULT's fast path on x86-64-v4, default.hpp).
//
// With s = 1 - lambda, t = lambda (Bernstein form, eq. (M13)):
//   f = s t A / B,  A = a0 s^2 + a1 s t + a2 t^2,
//   B = d0 s^3 + d1 s^2 t + d2 s t^2 + d3 t^3,
//   a0 = r^T adj(Q1) r, a1 = r^T M r, a2 = r^T adj(Q2) r,
//   d0 = det Q1, d1 = tr(adj(Q1) Q2), d2 = tr(Q1 adj(Q2)), d3 = det Q2,
// M the mixed adjugate. All seven are positive for positive definite Q1, Q2,
// so A and B are sums of positive terms at every lambda in [0, 1]: with the
// coefficients correct to a few u, f is correct to a few u whatever the
// conditioning of Q(lambda), and so is its maximum. The whole conditioning
// of the problem sits in the coefficients; they are polynomials in the
// inputs, computed here from exact products (two_prod by FMA) and
// compensated sums (two_sum), with an error below 32 u^2 times the sum of
// the absolute values of their terms, which is computed alongside. Where
// that bound fails for d0 or d3 (a nearly singular Q1 or Q2), det_precise
// computes the determinant from its exact terms (compensated summation,
// SumK).
#pragma once

#include <cmath>

#include "common/fp.hpp"
#include "eval/f_derivatives.hpp"
#include "common/isa.hpp"
#include "common/lanes.hpp"
#include "common/sym3.hpp"


namespace pw85 {

// Coefficients, in this order: a0, a1, a2, d0, d1, d2, d3, each times
// scale, a power of two (f = s t A / B does not depend on it).
struct CoefficientsDD {
  double c[8];
  double scale;
  unsigned ok;  // bit j: coefficient j passed its test (coefficients_dd)
};

#if PW85_ISA_LEVELS
// Double-double arithmetic lane by lane on eight-lane vectors (x86-64-v4):
// each lane holds one value h + l (arith/dd.hpp for one double-double), and
// the terms of the coefficients below; also the adjugate kernel of
// derivatives/adjugate.hpp.
namespace dd_lanes {

using lanes::Lanes8;
using lanes::LaneIndex8;

struct DD {
  Lanes8 h, l;
};

// (a + b) exactly as h + e (Knuth's two_sum).
PW85_V4_INLINE DD two_sum(Lanes8 a, Lanes8 b) {
  DD x;
  lanes::two_sum(a, b, x.h, x.l);
  return x;
}

// a b exactly as h + e.
PW85_V4_INLINE DD two_prod(Lanes8 a, Lanes8 b) {
  Lanes8 const p = a * b;
  return DD{p, lanes::fms(a, b, p)};
}

// x + y for unnormalised pairs: the high parts by two_sum, the low parts
// summed in double (error <= u |x.l + y.l + e| + ...: second order).
PW85_V4_INLINE DD add(DD x, DD y) {
  DD const s = two_sum(x.h, y.h);
  return DD{s.h, s.l + (x.l + y.l)};
}

PW85_V4_INLINE DD sub(DD x, DD y) {
  DD const s = two_sum(x.h, Lanes8{} - y.h);
  return DD{s.h, s.l + (x.l - y.l)};
}

// x v, x a pair, v exact: h + l (the l of x times v rounded).
PW85_V4_INLINE DD mul_d(DD x, Lanes8 v) {
  DD const p = two_prod(x.h, v);
  return DD{p.h, lanes::fma(x.l, v, p.l)};
}

// x y for two pairs; x.l y.l (below u^2 |x y|) is left to the error bound.
PW85_V4_INLINE DD mul_dd(DD x, DD y) {
  DD const p = two_prod(x.h, y.h);
  return DD{p.h, lanes::fma(x.h, y.l, lanes::fma(x.l, y.h, p.l))};
}

PW85_V4_INLINE Lanes8 perm(Lanes8 v, LaneIndex8 idx) { return lanes::permute(v, idx, v); }

PW85_V4_INLINE Lanes8 vabs(Lanes8 v) { return lanes::vabs(v); }

// One round of the transposed reduction: lanes of x and y combined by idx_a
// and idx_b (two-source permutes), then added.
PW85_V4_INLINE DD fold(DD x, DD y, LaneIndex8 ia, LaneIndex8 ib) {
  DD const a{lanes::permute(x.h, ia, y.h), lanes::permute(x.l, ia, y.l)};
  DD const b{lanes::permute(x.h, ib, y.h), lanes::permute(x.l, ib, y.l)};
  return add(a, b);
}

PW85_V4_INLINE Lanes8 fold_abs(Lanes8 x, Lanes8 y, LaneIndex8 ia, LaneIndex8 ib) {
  return lanes::permute(x, ia, y) + lanes::permute(x, ib, y);
}

// The terms of the seven contractions (eqs. (M12)-(M13)) for adjugate
// entries C_k = P_k Q_k - S_k T_k: pa, qa, sa, ta the factors P, Q, S, T from
// Q1, pb ... tb from Q2, aw = w_k Q1_k, bw = w_k Q2_k, ri rj = w_k r_i r_j
// (w_k = 1 on the diagonal, 2 off it). Lane by lane: in
// coefficients_dd lane k holds entry k of one pair; in
// contact/default.hpp, coefficient_step_lanes the vectors of one entry k hold one pair per
// lane, and each lane performs the same IEEE operations, so the terms of a
// pair are the same bits in both. v[j] = the term of coefficient j
// (a0, a1, a2, 3 d0, d1, d2, 3 d3; products in double-double), m[j] = the
// sum of the absolute values of its parts (for the error bound).
struct Terms {
  DD v[7];
  Lanes8 m[7];
};

PW85_V4_INLINE void terms(Lanes8 pa, Lanes8 qa, Lanes8 sa, Lanes8 ta, Lanes8 pb, Lanes8 qb,
                          Lanes8 sb, Lanes8 tb, Lanes8 aw, Lanes8 bw, Lanes8 ri, Lanes8 rj,
                          Terms &out) {
  DD const paqa = two_prod(pa, qa), sata = two_prod(sa, ta);
  DD const pbqb = two_prod(pb, qb), sbtb = two_prod(sb, tb);
  DD const paqb = two_prod(pa, qb), pbqa = two_prod(pb, qa);
  DD const satb = two_prod(sa, tb), sbta = two_prod(sb, ta);
  DD const c1 = sub(paqa, sata), c2 = sub(pbqb, sbtb);
  // Mixed adjugate: the polarisation of P Q - S T.
  DD const cm = sub(add(paqb, pbqa), add(satb, sbta));
  // w_k r_i r_j, exactly as a pair.
  DD const rr = two_prod(ri, rj);
  out.v[0] = mul_dd(c1, rr);
  out.v[1] = mul_dd(cm, rr);
  out.v[2] = mul_dd(c2, rr);
  out.v[3] = mul_d(c1, aw);
  out.v[4] = mul_d(c1, bw);
  out.v[5] = mul_d(c2, aw);
  out.v[6] = mul_d(c2, bw);
  Lanes8 const ac1 = vabs(paqa.h) + vabs(sata.h);
  Lanes8 const ac2 = vabs(pbqb.h) + vabs(sbtb.h);
  Lanes8 const acm = (vabs(paqb.h) + vabs(pbqa.h)) + (vabs(satb.h) + vabs(sbta.h));
  Lanes8 const arr = vabs(rr.h), va = vabs(aw), vb = vabs(bw);
  out.m[0] = ac1 * arr;
  out.m[1] = acm * arr;
  out.m[2] = ac2 * arr;
  out.m[3] = ac1 * va;
  out.m[4] = ac1 * vb;
  out.m[5] = ac2 * va;
  out.m[6] = ac2 * vb;
}

// Index vectors of the adjugate entries k (Sym3 storage order 00 01 02 11
// 12 22) as P_k Q_k - S_k T_k, e.g. adj_01 = Q_02 Q_12 - Q_01 Q_22; lanes
// 6, 7 index lane 6 (the zero padding of a masked load of six entries).
struct AdjIndex {
  LaneIndex8 p, q, s, t;
};
PW85_V4_INLINE AdjIndex adj_index() {
  return AdjIndex{LaneIndex8{3, 2, 1, 0, 1, 0, 6, 6}, LaneIndex8{5, 4, 4, 5, 2, 3, 6, 6},
                  LaneIndex8{4, 1, 2, 2, 0, 1, 6, 6}, LaneIndex8{4, 5, 3, 2, 4, 1, 6, 6}};
}

constexpr double kThird = 1.0 / 3.0;

// The bits of the coefficients other than d0 (bit 3) and d3 (bit 6).
constexpr unsigned kCoefficientsNotDet = 0x37;

// A coefficient from its sum over the adjugate entries t (double-double)
// and the sum mt of the absolute values of its terms: (t.h + t.l) times
// ts (the scale, times 1/3 for d0 and d3). ok: 32 u^2 mt <= 2^-56 (the sum),
// and the sum > 0.
PW85_V4_INLINE Lanes8 finish(DD t, Lanes8 mt, Lanes8 ts, lanes::LaneBits8 &ok) {
  Lanes8 const sum = t.h + t.l;
  Lanes8 const bound = mt * (32.0 * 0x1p-106 * 0x1p56);
  ok = lanes::le_bits(bound, sum) & lanes::gt_bits(sum, Lanes8{});
  return sum * ts;
}

// a b - p, one rounding (std::fma: an FMA instruction in the x86-64-v4
// functions that use this file).
PW85_V4_INLINE double fms(double a, double b, double p) { return std::fma(a, b, -p); }
PW85_V4_INLINE Lanes8 fms(Lanes8 a, Lanes8 b, Lanes8 p) { return lanes::fms(a, b, p); }

// Terms of the precise determinant below: n = 20 doubles.
constexpr int kDetTerms = 20;

}  // namespace dd_lanes

// det Q for d0 = det Q1 or d3 = det Q2 (eq. (M13)) where the double-double
// sum fails its bound (cancellation beyond 2^45 of the terms: nearly
// singular matrices, build/tests/test-rational-dd --verbose). By the
// cofactor expansion
//   det Q = q00 q11 q22 - q00 q12^2 - q01^2 q22 + 2 q01 q02 q12 - q02^2 q11,
// each product of three doubles written exactly as four doubles (two_prod
// by FMA, then each part times the third factor), the 20 terms summed by
// SumK with K = 3 (Ogita, Rump and Oishi, "Accurate sum and dot product",
// SIAM J. Sci. Comput. 26(6), 2005: two passes of error-free VecSum, then
// the plain sum), whose result satisfies
//   |res - det| <= (u + 3 gamma_19^2) |det| + gamma_38^3 sum |terms|
// (u = 2^-53, gamma_n = n u / (1 - n u); gamma_38^3 < 2^-143). Accepted
// (mask true) when res > 2^-1000 (the two_prod of terms below 2^-917 may
// lose bits to underflow: at most 2^-1069 in all, below 2^-69 res) and
// 2^-143 mp (1 + 2^-47) <= 2^-56 res, mp the computed sum of |hh| + |ll|
// over the products (ten roundings; the other two parts of each product
// are below u times these, so mp (1 + 2^-47) >= sum |terms|); det is then
// within (2^-53 + 2^-56 + 2^-70) det < 1.13 u. T = double (one pair,
// coefficients_dd) or lanes::Lanes8 (one pair per lane,
// contact/default.hpp, coefficient_step_lanes), the same IEEE operations in each lane.
template <class T>
PW85_V4_INLINE lanes::MaskOf<T> det_precise(T const q[6], T &det) noexcept {
  using dd_lanes::fms;
  using lanes::vabs;
  T p[dd_lanes::kDetTerms];
  // Products x y z with their signs (storage order 00 01 02 11 12 22).
  T const x[5] = {q[0], q[0], q[1], q[1] + q[1], q[2]};
  T const y[5] = {q[3], q[4], q[1], q[2], q[2]};
  T const z[5] = {q[5], -q[4], -q[5], q[4], -q[3]};
  T mp = T{} + 0.0;
  for (int i = 0; i < 5; ++i) {
    T const h = x[i] * y[i], l = fms(x[i], y[i], h);
    T const hh = h * z[i], ll = l * z[i];
    p[4 * i] = hh;
    p[4 * i + 1] = fms(h, z[i], hh);
    p[4 * i + 2] = ll;
    p[4 * i + 3] = fms(l, z[i], ll);
    mp = mp + (vabs(hh) + vabs(ll));
  }
  // SumK, K = 3: two VecSum passes (error-free: the exact sum is kept).
  for (int k = 0; k < 2; ++k)
    for (int i = 1; i < dd_lanes::kDetTerms; ++i) lanes::two_sum(p[i], p[i - 1], p[i], p[i - 1]);
  T s = p[0];
  for (int i = 1; i < dd_lanes::kDetTerms - 1; ++i) s = s + p[i];
  det = s + p[dd_lanes::kDetTerms - 1];
  return (det > 0x1p-1000) & (mp * (0x1p-87 * (1.0 + 0x1p-47)) <= det);
}

// Computes the seven coefficients, times out.scale, into out.c[0..6]
// (out.c[7] = 0), and in out.ok the bits of those that pass their test
// (coefficients_dets_precise below). Returns false when one is not positive or its bound
// 32 u^2 (sum of |terms|) exceeds 2^-56 times it; otherwise each is within
// 2.2 u of its exact value times out.scale (the double-double error, then
// the rounding to double; d0 and d3, formed as tr(adj(Q) Q) / 3, one more
// rounding). out.scale = 2^(-3E), T = tr Q1 + tr Q2 in [2^E, 2^(E+1)), so
// that every d_j times the scale is below 8 (d_j <= T^3): f_eval_coefficients
// forms B^5. T is positive and, for inputs within the range of contact.hpp
// (kSafeLo, kSafeHi), 3E is well inside the exponent range.
PW85_V4_INLINE bool coefficients_dd(
    Vec3 const &r, Sym3 const &q1, Sym3 const &q2, CoefficientsDD &out) noexcept {
  using namespace dd_lanes;
  // The scale, from the inputs (off the dependency chain of the sums).
  double const tr = ((q1[0] + q1[3]) + q1[5]) + ((q2[0] + q2[3]) + q2[5]);
  long long bits;
  __builtin_memcpy(&bits, &tr, sizeof bits);
  long long const e = ((bits >> 52) & 0x7FF) - 1023;
  long long const sbits = (1023 - 3 * e) << 52;
  double scale;
  __builtin_memcpy(&scale, &sbits, sizeof scale);
  Lanes8 const a = lanes::load_first(q1.a, kSym);
  Lanes8 const b = lanes::load_first(q2.a, kSym);
  Lanes8 const rv = lanes::load_first(r.x, kDim);
  // Adjugate entries k as P_k Q_k - S_k T_k (adj_index; lanes 6, 7 are
  // zeroed below by the weights).
  AdjIndex const ix = adj_index();
  Lanes8 const pa = perm(a, ix.p), qa = perm(a, ix.q), sa = perm(a, ix.s), ta = perm(a, ix.t);
  Lanes8 const pb = perm(b, ix.p), qb = perm(b, ix.q), sb = perm(b, ix.s), tb = perm(b, ix.t);
  // Weights of the symmetric contraction sum_ij C_ij X_ij: 1 on the
  // diagonal, 2 off it, 0 in the padding lanes.
  Lanes8 const w{1.0, 2.0, 2.0, 1.0, 2.0, 1.0, 0.0, 0.0};
  Terms v;
  terms(pa, qa, sa, ta, pb, qb, sb, tb, a * w, b * w,
        perm(rv, LaneIndex8{0, 0, 0, 1, 1, 2, 3, 3}) * w,
        perm(rv, LaneIndex8{0, 1, 2, 1, 2, 2, 3, 3}), v);
  DD const zero{Lanes8{}, Lanes8{}};
  // Transposed reduction: three rounds turn the eight vectors into one
  // whose lane j is the sum of the lanes of v[j].
  LaneIndex8 const i1a{0, 8, 2, 10, 4, 12, 6, 14}, i1b{1, 9, 3, 11, 5, 13, 7, 15};
  LaneIndex8 const i2a{0, 1, 8, 9, 4, 5, 12, 13}, i2b{2, 3, 10, 11, 6, 7, 14, 15};
  LaneIndex8 const i3a{0, 1, 2, 3, 8, 9, 10, 11}, i3b{4, 5, 6, 7, 12, 13, 14, 15};
  DD const w01 = fold(v.v[0], v.v[1], i1a, i1b), w23 = fold(v.v[2], v.v[3], i1a, i1b);
  DD const w45 = fold(v.v[4], v.v[5], i1a, i1b), w67 = fold(v.v[6], zero, i1a, i1b);
  DD const z0 = fold(w01, w23, i2a, i2b), z1 = fold(w45, w67, i2a, i2b);
  DD const t = fold(z0, z1, i3a, i3b);
  Lanes8 const m01 = fold_abs(v.m[0], v.m[1], i1a, i1b), m23 = fold_abs(v.m[2], v.m[3], i1a, i1b);
  Lanes8 const m45 = fold_abs(v.m[4], v.m[5], i1a, i1b);
  Lanes8 const m67 = fold_abs(v.m[6], Lanes8{}, i1a, i1b);
  Lanes8 const mt =
      fold_abs(fold_abs(m01, m23, i2a, i2b), fold_abs(m45, m67, i2a, i2b), i3a, i3b);
  // Lanes: a0, a1, a2, 3 d0, d1, d2, 3 d3, 0.
  Lanes8 const third{1.0, 1.0, 1.0, kThird, 1.0, 1.0, kThird, 0.0};
  lanes::LaneBits8 ok;
  Lanes8 const coef = finish(t, mt, third * scale, ok);
  lanes::store(out.c, coef);
  out.scale = scale;
  out.ok = ok & 0x7F;
  return out.ok == 0x7F;
}

// After coefficients_dd declined (out.ok: the coefficients that
// passed): true when a0, a1, a2, d1, d2 passed and det_precise accepts d0
// and d3 where they failed (out.c[3], out.c[6]: det Q1, det Q2 times
// out.scale, within 1.13 u).
PW85_V4_INLINE bool coefficients_dets_precise(Sym3 const &q1, Sym3 const &q2,
                                          CoefficientsDD &out) noexcept {
  if ((out.ok & dd_lanes::kCoefficientsNotDet) != dd_lanes::kCoefficientsNotDet) return false;
  Sym3 const *const qs[2] = {&q1, &q2};
  for (int m = 0; m < 2; ++m) {
    int const j = m == 0 ? 3 : 6;
    if (out.ok & (1u << j)) continue;
    double det;
    if (!det_precise(qs[m]->a, det)) return false;
    out.c[j] = det * out.scale;
  }
  return true;
}

#endif

// f and its first four derivatives at lambda from the coefficients
// (Bernstein form above; phi = A / B, f = s t phi, eq. (M12)), and a bound
// edf on the error of the computed f' (first order in u). f itself is
// within kCoefficientRel f of the exact value (positive terms only).
// One pair (T = double, K = CoefficientsDD: default.hpp) or one pair per lane
// (T a vector type, K its coefficients: contact/default.hpp, coefficient_step_lanes), the same
// IEEE operations in each lane. Returns true (T = double) or the mask of the
// lanes where the evaluation holds.
template <class T>
struct CoefficientEvalOf {
  T lambda, phi, dphi;
  T f, df, d2f, d3f, d4f, edf;
};
typedef CoefficientEvalOf<double> CoefficientEval;

template <class T, class K>
PW85_ALWAYS_INLINE lanes::MaskOf<T> f_eval_coefficients(T lambda, K const &k,
                                                    CoefficientEvalOf<T> &e) noexcept {
  using lanes::vabs;
  using lanes::finite;
  T const a0 = k.c[0], a1 = k.c[1], a2 = k.c[2];
  T const d0 = k.c[3], d1 = k.c[4], d2 = k.c[5], d3 = k.c[6];
  T const s = 1.0 - lambda, t = lambda;
  T const ss = s * s, st = s * t, tt = t * t;
  T const A = (a0 * ss + a2 * tt) + a1 * st;
  T const B = (d0 * ss) * s + (d1 * ss) * t + ((d2 * tt) * s + (d3 * tt) * t);
  // Derivatives with respect to lambda (ds = -dt = -dlambda).
  T const A1 = 2.0 * (a2 * t - a0 * s) + a1 * (s - t);
  T const A2 = 2.0 * ((a0 + a2) - a1);
  T const e0 = d1 - 3.0 * d0, e1 = d2 - d1, e2 = 3.0 * d3 - d2;
  T const B1 = (e0 * ss + e2 * tt) + 2.0 * e1 * st;
  T const B2 = 2.0 * ((e2 * t - e0 * s) + e1 * (s - t));
  T const B3 = 2.0 * ((e0 + e2) - 2.0 * e1);
  // Eq. (M25): phi_k = d^k phi / d lambda^k = N_k / B^(k + 1), from sum_i C(k, i)
  // phi_i B_(k-i) = A_k: the numerators are products and sums only, so
  // they are formed while the division runs (B^5 stays in range: the
  // coefficients are scaled, coefficients_dd).
  T const ib = 1.0 / B;
  T const ib2 = ib * ib, ib3 = ib2 * ib, ib4 = ib2 * ib2, ib5 = ib4 * ib;
  T const N1 = A1 * B - A * B1;
  T const N2 = (A2 * B - A * B2) * B - N1 * (2.0 * B1);
  T const N3 = -(N2 * (3.0 * B1) + (N1 * (3.0 * B2) + (A * B) * B3) * B);
  T const N4 = -(N3 * (4.0 * B1) + (N2 * (6.0 * B2) + (N1 * (4.0 * B3)) * B) * B);
  T const phi = A * ib;
  T const phi1 = N1 * ib2, phi2 = N2 * ib3, phi3 = N3 * ib4, phi4 = N4 * ib5;
  e.lambda = lambda;
  set_f_from_phi(lambda, phi, phi1, phi2, phi3, e);  // f = p phi, eq. (M12)
  T const p = lambda * (1.0 - lambda), p1 = 1.0 - 2.0 * lambda;
  e.d4f = -12.0 * phi2 + 4.0 * p1 * phi3 + p * phi4;
  // Error of f' = p1 phi + p (A1 - phi B1) / B: the terms of A1 and B1 in
  // absolute value, with their few roundings, and the error of phi.
  T const A1a = 2.0 * (a2 * t + a0 * s) + a1 * vabs(s - t);
  T const B1a = (vabs(e0) * ss + vabs(e2) * tt) + 2.0 * vabs(e1) * st;
  e.edf = 16.0 * kU * (vabs(p1) * phi + p * (A1a + phi * B1a) * ib);
  // B >= 2^-150 keeps B^5 phi_4 (N4 and its terms) normal: for inputs
  // within the range of contact.hpp, phi >= |r|^2 / lambda_max(Q) > 2^-183
  // and the scaled B <= 8, so N_k = B^(k+1) phi_k cannot underflow into a
  // finite but wrong phi_k. A smaller B (near an end of [0, 1] where one
  // det Q_i is below 2^-150 times the scale) declines to the general method.
  return (B >= 0x1p-150) & (A > 0.0) & finite(e.f) & finite(e.d4f) & finite(e.edf);
}

}  // namespace pw85
