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

#include <cmath>

#include "arith/dd.hpp"
#include "common/fp.hpp"
#include "common/isa.hpp"
#include "common/lanes.hpp"
#include "common/sym3.hpp"
#include "derivatives/derivatives.hpp"
#include "derivatives/fast.hpp"
#include "eval/f_coefficients_dd.hpp"

namespace pw85 {
// The adjugate path (E9), x86-64-v4.
namespace adjugate_path {

using lanes::broadcast;
using lanes::broadcast_index;
using lanes::LaneBits8;
using lanes::LaneIndex8;
using lanes::Lanes8;

// The kernel's results rounded to double, in the lanes of AVX-512 vectors,
// with bounds on their errors.
struct Values {
  Lanes8 c;      // C = adj Q(lambda), lanes 0-5 (storage order of Sym3)
  Lanes8 ub;     // U = C r in lanes 0-2, B = det Q(lambda) in lane 3
  Lanes8 t;      // T1 = Q1 U in lanes 0-2, T2 = Q2 U in lanes 3-5
  Lanes8 cw;     // C W in lanes 0-2
  Lanes8 dots;   // F = U.W (= f' B^2) in lane 0, A = T1.(C T2) (= a2 B^3) in lane 3
  double f_err;  // bound on the error of F
  bool ok;       // C, U and B within kMaxRelS, T1 and T2 within kMaxRelT (max norm)
  double rel_h;  // relative error bound (max norm) of C W and of A
};

// Bound on the error of the double-double evaluation, in units of the
// polynomial of absolute values: 12 dependent operations (products without
// the low-times-low term, sums of unnormalised pairs), each within a few
// u^2 of the absolute values of its operands; 128 u^2 with margin.
constexpr double kGammaDD = 128.0 * kU * kU;

PW85_V4_INLINE Lanes8 idx_perm(Lanes8 v, LaneIndex8 i) { return dd_lanes::perm(v, i); }

PW85_V4_INLINE dd_lanes::DD perm_dd(dd_lanes::DD x, LaneIndex8 i) {
  return dd_lanes::DD{dd_lanes::perm(x.h, i), dd_lanes::perm(x.l, i)};
}

PW85_V4_INLINE dd_lanes::DD bcast_dd(dd_lanes::DD x, int j) {
  return perm_dd(x, broadcast_index(j));
}

PW85_V4_INLINE dd_lanes::DD set1_dd(dd::DD x) {
  return dd_lanes::DD{broadcast(x.hi), broadcast(x.lo)};
}

// Lane by lane, the largest |v| over the lane's triple (lanes 0-2, 3-5;
// lanes 6, 7 with themselves).
PW85_V4_INLINE Lanes8 triple_max(Lanes8 v) {
  Lanes8 const a = lanes::vabs(v);
  Lanes8 const b = idx_perm(a, LaneIndex8{1, 2, 0, 4, 5, 3, 6, 7});
  Lanes8 const c = idx_perm(a, LaneIndex8{2, 0, 1, 5, 3, 4, 6, 7});
  return lanes::vmax(a, lanes::vmax(b, c));
}

// Column j of a symmetric matrix in lanes 0-5 (Sym3 order), in lanes 0-2
// (lanes 3-5: the same again, for two products at once).
PW85_V4_INLINE LaneIndex8 sym_column(int j) {
  return j == 0 ? LaneIndex8{0, 1, 2, 0, 1, 2, 6, 6}
                : j == 1 ? LaneIndex8{1, 3, 4, 1, 3, 4, 6, 6}
                         : LaneIndex8{2, 4, 5, 2, 4, 5, 6, 6};
}

PW85_V4_INLINE Lanes8 bcast(Lanes8 v, int j) { return idx_perm(v, broadcast_index(j)); }

// Column j of Q1 (lanes 0-2) and of Q2 (lanes 3-5), from a = Q1, b = Q2 in
// Sym3 order.
PW85_V4_INLINE Lanes8 q_columns(Lanes8 a, Lanes8 b, int j) {
  LaneIndex8 const i0{0, 1, 2, 8, 9, 10, 6, 6};
  LaneIndex8 const i1{1, 3, 4, 9, 11, 12, 6, 6};
  LaneIndex8 const i2{2, 4, 5, 10, 12, 13, 6, 6};
  return lanes::permute(a, j == 0 ? i0 : j == 1 ? i1 : i2, b);
}

// Symmetric 3x3 matrix (lanes 0-5) times the vector in lanes 0-2 of v
// (result in lanes 0-2, and again in 3-5).
PW85_V4_INLINE Lanes8 sym_mul(Lanes8 m, Lanes8 v) {
  Lanes8 acc = idx_perm(m, sym_column(0)) * bcast(v, 0);
  acc = lanes::fma(idx_perm(m, sym_column(1)), bcast(v, 1), acc);
  return lanes::fma(idx_perm(m, sym_column(2)), bcast(v, 2), acc);
}

// Sum of lanes 0-2 of v.
PW85_V4_INLINE double sum3(Lanes8 v) { return (v[0] + v[1]) + v[2]; }

// The largest |v| over lanes 0-5.
PW85_V4_INLINE double max6(Lanes8 v) {
  Lanes8 const m = triple_max(v);
  return cholesky_path::max2(m[0], m[3]);
}

// Largest relative error bounds of the kernel's values accepted: C, U and B
// (s and X: far below u), T1 and T2 (x0 and Q2 s: the torques), C W and A
// (h and a2: the Hessian). Each is counted in the estimates below.
constexpr double kMaxRelS = 0x1p-57, kMaxRelT = 0x1p-50, kMaxRelH = 0x1p-26;

// The kernel at lambda = lh + ll (a double-double, 0 < lambda < 1).
PW85_V4_INLINE void kernel(double lh, double ll, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                           Values &out) {
  using namespace dd_lanes;
  using lanes::blend;
  using lanes::fma;
  using lanes::keep;
  using lanes::permute_into;
  Lanes8 const a = lanes::load_first(q1.a, kSym);
  Lanes8 const b = lanes::load_first(q2.a, kSym);
  // 1 - lambda as nh + nl.
  dd::DD const om = dd::two_sum(1.0, -lh);
  dd::DD const nu{om.hi, om.lo - ll}, la{lh, ll};
  // Q(lambda) = (1 - lambda) Q1 + lambda Q2, lanes 0-5 (Sym3 order).
  DD const pa = two_prod(broadcast(nu.hi), a), pb = two_prod(broadcast(lh), b);
  DD q = two_sum(pa.h, pb.h);
  q.l = q.l + ((pa.l + pb.l) + fma(broadcast(nu.lo), a, broadcast(ll) * b));
  Lanes8 const qa = fma(broadcast(nu.hi), vabs(a), broadcast(lh) * vabs(b));
  // C = adj Q(lambda): entry k = P_k Q_k - S_k T_k (adj_index,
  // f_coefficients_dd.hpp; lanes 6, 7 read the zero padding).
  AdjIndex const ix = adj_index();
  LaneIndex8 const ip = ix.p, iq = ix.q, is = ix.s, it = ix.t;
  DD const c = sub(mul_dd(perm_dd(q, ip), perm_dd(q, iq)), mul_dd(perm_dd(q, is), perm_dd(q, it)));
  Lanes8 const ca = fma(idx_perm(qa, ip), idx_perm(qa, iq), idx_perm(qa, is) * idx_perm(qa, it));
  // U = C r (lanes 0-2) and B = sum_j Q_0j C_0j (lane 3): column j of C
  // (sym_column: C_0j in lane 3) times r_j, and times Q_0j in lane 3.
  DD ub{Lanes8{}, Lanes8{}};
  Lanes8 uba = Lanes8{};
  for (int j = 0; j < 3; ++j) {
    LaneIndex8 const ij = broadcast_index(j);
    Lanes8 const rj = keep(0x07, broadcast(r[j]));
    DD const m{permute_into(rj, 0x08, q.h, ij), permute_into(Lanes8{}, 0x08, q.l, ij)};
    DD const p = mul_dd(perm_dd(c, sym_column(j)), m);
    Lanes8 const pm = idx_perm(ca, sym_column(j)) * permute_into(vabs(rj), 0x08, qa, ij);
    ub = j == 0 ? p : add(ub, p);
    uba = uba + pm;
  }
  // T1 = Q1 U (lanes 0-2), T2 = Q2 U (lanes 3-5): columns of Q1 and Q2
  // times U_j; and (1 - lambda) B U (lanes 0-2), for C W below.
  DD t{Lanes8{}, Lanes8{}};
  Lanes8 ta = Lanes8{};
  for (int j = 0; j < 3; ++j) {
    Lanes8 const g = q_columns(a, b, j);
    DD const p = mul_d(bcast_dd(ub, j), g);
    Lanes8 const pm = vabs(g) * idx_perm(uba, broadcast_index(j));
    t = j == 0 ? p : add(t, p);
    ta = ta + pm;
  }
  DD const nub = mul_dd(bcast_dd(ub, 3), set1_dd(nu));
  DD const nubu = mul_dd(nub, ub);
  Lanes8 const nubua = (broadcast(nu.hi) * uba) * idx_perm(uba, broadcast_index(3));
  // Y = C T2 (lanes 0-2): column j of C times T2_j. With Q = (1 - lambda) Q1
  // + lambda Q2 and C Q = B I,
  //   C W = (1 - lambda)^2 C Q1 U - lambda^2 C Q2 U = (1 - lambda) B U - lambda Y.
  DD y{Lanes8{}, Lanes8{}};
  Lanes8 ya = Lanes8{};
  for (int j = 0; j < 3; ++j) {
    DD const p = mul_dd(perm_dd(c, sym_column(j)), bcast_dd(t, 3 + j));
    Lanes8 const pm = idx_perm(ca, sym_column(j)) * bcast(ta, 3 + j);
    y = j == 0 ? p : add(y, p);
    ya = ya + pm;
  }
  DD const cw = sub(nubu, mul_dd(y, set1_dd(la)));
  Lanes8 const cwa = fma(broadcast(lh), ya, nubua);
  // W = (1 - lambda)^2 T1 - lambda^2 T2 (lanes 0-2).
  dd::DD const nu2 = dd::mul<true>(nu, nu), la2 = dd::mul<true>(la, la);
  LaneIndex8 const hi3{3, 4, 5, 6, 6, 6, 6, 6};
  DD const w = sub(mul_dd(t, set1_dd(nu2)), mul_dd(perm_dd(t, hi3), set1_dd(la2)));
  Lanes8 const wa = fma(broadcast(nu2.hi), ta, broadcast(la2.hi) * idx_perm(ta, hi3));
  // F = U.W (lane 0) and A = T1.Y (lane 3): products lane by lane, then
  // the sums of lanes 0-2 and 3-5.
  LaneIndex8 const lo3{6, 6, 6, 0, 1, 2, 6, 6};
  DD const x1{blend(0x38, idx_perm(t.h, lo3), ub.h), blend(0x38, idx_perm(t.l, lo3), ub.l)};
  DD const x2{blend(0x38, idx_perm(y.h, lo3), w.h), blend(0x38, idx_perm(y.l, lo3), w.l)};
  // The products with their low-times-low terms (mul_dd drops them: below
  // u^2 x1a x2a, but not below the bound used here), so that the bound of
  // the two dot products follows from those of their factors: the error of
  // x1 (x1a, its absolute-value polynomial, times gamma u^2) times |x2|, and
  // the other way round; the products' own roundings are within it.
  // (x1a x2a, the polynomial of the dot product itself, can be far larger:
  // both factors' cancellations multiplied.)
  DD const p0 = two_prod(x1.h, x2.h);
  DD const pr{p0.h, fma(x1.h, x2.l, fma(x1.l, x2.h, fma(x1.l, x2.l, p0.l)))};
  Lanes8 const x1a = blend(0x38, idx_perm(ta, lo3), uba);
  Lanes8 const x2a = blend(0x38, idx_perm(ya, lo3), wa);
  Lanes8 const pra = fma(x1a, vabs(x2.h), vabs(x1.h) * x2a);
  LaneIndex8 const n1{1, 6, 6, 4, 6, 6, 6, 6};
  LaneIndex8 const n2{2, 6, 6, 5, 6, 6, 6, 6};
  DD const dots = add(add(pr, perm_dd(pr, n1)), perm_dd(pr, n2));
  Lanes8 const dotsa = (pra + idx_perm(pra, n1)) + idx_perm(pra, n2);
  // Rounded values.
  Lanes8 const cv = c.h + c.l, ubv = ub.h + ub.l;
  Lanes8 const tv = t.h + t.l, cwv = cw.h + cw.l;
  Lanes8 const dv = dots.h + dots.l;
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
  LaneIndex8 const swap{3, 4, 5, 0, 1, 2, 6, 7};
  Lanes8 const cm = triple_max(cv), cam = triple_max(ca);
  Lanes8 const num_c = lanes::vmax(cam, idx_perm(cam, swap));
  Lanes8 const den_c = lanes::vmax(cm, idx_perm(cm, swap));
  Lanes8 const gamma = broadcast(kGammaDD);
  Lanes8 const max_s = broadcast(kMaxRelS), max_t = broadcast(kMaxRelT);
  LaneBits8 const ok_c = lanes::le_bits(gamma * num_c, max_s * den_c);
  LaneBits8 const ok_ub = lanes::le_bits(gamma * triple_max(uba), max_s * triple_max(ubv));
  LaneBits8 const ok_t = lanes::le_bits(gamma * triple_max(ta), max_t * triple_max(tv));
  Lanes8 const cwm = triple_max(cwv), cwam = triple_max(cwa);
  out.f_err = kGammaDD * dotsa[0];
  out.ok = (ok_c & ok_ub & ok_t & 0x09) == 0x09;  // lane 0: C, U, T1; lane 3: B, T2
  out.rel_h = kGammaDD * cholesky_path::max2(cwam[0] / cwm[0], dotsa[3] / std::fabs(dv[3]));
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
  Lanes8 const qa = lanes::load_first(q1.a, kSym), qb = lanes::load_first(q2.a, kSym);
  double const mq1 = max6(qa), mq2 = max6(qb);
  Lanes8 const g[3] = {q_columns(qa, qb, 0), q_columns(qa, qb, 1), q_columns(qa, qb, 2)};
  LaneIndex8 const hi3{3, 4, 5, 6, 6, 6, 6, 6};
  // Index vectors of the products s_i s_j, h_i h_j over the stored entries,
  // and the weights of the stored entries (1 on the diagonal, 2 off it).
  LaneIndex8 const ki{0, 0, 0, 1, 1, 2, 6, 6};
  LaneIndex8 const kj{0, 1, 2, 1, 2, 2, 6, 6};
  Lanes8 const wk{1.0, 2.0, 2.0, 1.0, 2.0, 1.0, 0.0, 0.0};
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
    Lanes8 const vib = broadcast(ib);
    Lanes8 const sv = k.ub * vib, pv = k.t * vib;
    Lanes8 const xv = k.c * vib;
    Lanes8 const hv = k.cw * broadcast(2.0 * ib2);
    double const a2 = ((aa * ib) * ib) * ib, iha = 0.5 * (((bb * ia) * bb) * bb);
    double const fp = ff * ib2;
    Lanes8 const pm = triple_max(pv);
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
    Lanes8 const v = sym_mul(xv, idx_perm(pv, hi3) - pv);
    Lanes8 qv = g[0] * bcast(v, 0);  // [Q1 v, Q2 v]
    qv = lanes::fma(g[1], bcast(v, 1), qv);
    qv = lanes::fma(g[2], bcast(v, 2), qv);
    double const mv = triple_max(v)[0];
    Lanes8 const vdl = broadcast(dl);
    Lanes8 const sm = lanes::fnma(v, vdl, sv);
    Lanes8 const mnu{nu, nu, nu, 1.0, 1.0, 1.0, 0.0, 0.0};
    Lanes8 const xq =  // [x0, Q2 s] moved
        lanes::fnma(lanes::fma(mnu, qv, lanes::keep(0x07, pv)), vdl, mnu * pv);
    double const lam = lh + (ll + dl), nus = om.hi + ((om.lo - ll) - dl), p = lam * nus;
    double const p2 = 2.0 * p;
    // Outputs (E1)-(E4): g; -x0 x g and (x0 - r) x g, x0 - r = -lambda Q2 s,
    // as one cross product of [x0, x0 - r] with [g, g]; (E2).
    out.mu2 = mu2;
    out.lambda = lam;
    Lanes8 const gv = sm * broadcast(p2);
    lanes::store_first(out.d_r12, kDim, gv);
    Lanes8 const av = xq * Lanes8{1.0, 1.0, 1.0, -lam, -lam, -lam, 0.0, 0.0};
    LaneIndex8 const yzx{1, 2, 0, 4, 5, 3, 6, 6};
    LaneIndex8 const zxy{2, 0, 1, 5, 3, 4, 6, 6};
    LaneIndex8 const gyzx{1, 2, 0, 1, 2, 0, 6, 6};
    LaneIndex8 const gzxy{2, 0, 1, 2, 0, 1, 6, 6};
    Lanes8 const cr = lanes::fms(idx_perm(av, yzx), idx_perm(gv, gzxy),
                                 idx_perm(av, zxy) * idx_perm(gv, gyzx));
    Lanes8 const th = cr * Lanes8{-1.0, -1.0, -1.0, 1.0, 1.0, 1.0, 0.0, 0.0};
    lanes::store_first(out.d_theta1, 2 * kDim, th);  // d_theta1, d_theta2
    Lanes8 const ss = (idx_perm(sm, ki) * idx_perm(sm, kj)) * wk;
    Lanes8 const dq1 = ss * broadcast(-p * nus);
    Lanes8 const dq2 = ss * broadcast(-p * lam);
    lanes::store_first(out.d_q1, kSym, dq1);
    lanes::store_first(out.d_q2, kSym, dq2);
    // Finiteness of the outputs from the registers (x - x: 0 for finite x,
    // NaN otherwise): reloading the struct just written by masked stores
    // measured 2-5 ns per call slower (scratch loop over bench_derivatives'
    // pairs, classes 0 and 2).
    Lanes8 const fin = (lanes::keep(0x07, gv - gv) + lanes::keep(0x3F, th - th)) +
                       (lanes::keep(0x3F, dq1 - dq1) + lanes::keep(0x3F, dq2 - dq2));
    // Hessian (E6) from X, h and a2 at lambda (not moved: their relative
    // change along dl is below t2, counted in err_t).
    Lanes8 hess =
        lanes::fma(idx_perm(hv, ki) * idx_perm(hv, kj), broadcast(iha), xv * broadcast(p2));
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
    bool const grad_ok = 3.0 * err_g2p <= cholesky_path::kAcceptG * ms * p2;
    bool hess_ok = err_eps + err_t <= cholesky_path::kAcceptH * mhess;
    if (grad_ok && !hess_ok && t2 <= kMaxMove) {
      // X, h and a2 moved to lambda + dl to first order:
      //   X' = -X D X, D = Q2 - Q1, (Q1 s)' = -Q1 v, (Q2 s)' = -Q2 v,
      //   a2' = -((Q1 v).X Q2 s + (X Q1 s).D (X Q2 s) + (X Q1 s).Q2 v),
      //   w' = -2 r - (1 - lambda)^2 Q1 v + lambda^2 Q2 v (Q s = r),
      //   h' = 2 X' w + 2 X w' = X (2 w' - D h);
      // their second-order terms are below ~t2^2 relative, the rounding of
      // the first-order terms ~u times them.
      using lanes::fma;
      Lanes8 const dm = qb - qa;
      // Columns j of X D X (lanes 0-2), then its stored entries.
      Lanes8 w[3];
      for (int j = 0; j < 3; ++j) w[j] = sym_mul(xv, sym_mul(dm, idx_perm(xv, sym_column(j))));
      Lanes8 const w01 = lanes::permute(w[0], LaneIndex8{0, 8, 6, 9, 6, 6, 6, 6}, w[1]);
      Lanes8 const xdx = lanes::permute(w01, LaneIndex8{0, 1, 8, 3, 9, 10, 6, 6}, w[2]);
      Lanes8 const xm = lanes::fnma(xdx, vdl, xv);
      // [X Q1 s, X Q2 s], D X Q2 s.
      Lanes8 y = idx_perm(xv, sym_column(0)) * idx_perm(pv, LaneIndex8{0, 0, 0, 3, 3, 3, 6, 6});
      y = fma(idx_perm(xv, sym_column(1)), idx_perm(pv, LaneIndex8{1, 1, 1, 4, 4, 4, 6, 6}), y);
      y = fma(idx_perm(xv, sym_column(2)), idx_perm(pv, LaneIndex8{2, 2, 2, 5, 5, 5, 6, 6}), y);
      Lanes8 const y2 = idx_perm(y, hi3), dy2 = sym_mul(dm, y2);
      Lanes8 const qv2 = idx_perm(qv, hi3);
      double const da2 = -sum3(fma(qv, y2, fma(y, dy2, y * qv2)));
      double const a2m = a2 + da2 * dl, iham = 0.5 / a2m;
      Lanes8 const rv = lanes::load_first(r.x, kDim);
      Lanes8 const wp =
          broadcast(2.0) *
              fma(broadcast(lh * lh), qv2, fma(broadcast(-nu * nu), qv, broadcast(-2.0) * rv)) -
          sym_mul(dm, hv);
      Lanes8 const hm = fma(sym_mul(xv, wp), vdl, hv);
      Lanes8 const hessm =
          fma(idx_perm(hm, ki) * idx_perm(hm, kj), broadcast(iham), xm * broadcast(p2));
      double const mhm = triple_max(hm)[0], mhessm = max6(hessm);
      Lanes8 const ym = triple_max(y), qm = triple_max(qv);
      double const md = max6(dm), my1 = ym[0], my2 = ym[3];
      double const second = 4.0 * t2 * t2;
      double const err_hm = 24.0 * kU * adl * mx * (triple_max(wp)[0] + 3.0 * md * mh) + second * mhm;
      double const err_am =
          18.0 * kU * adl * (qm[0] * my2 + 3.0 * my1 * md * my2 + my1 * qm[3]) + second * a2m;
      double const err_m =
          3.0 * (p2 * mx * (eps_x + 2.0 * kU + 2.0 * kU * t2 + second) +
                 (2.0 * mhm * (e_h * mhm + err_hm) + mhm * mhm * (eps2 + 3.0 * kU) +
                  mhm * mhm * err_am * 2.0 * iham) * iham);
      hess_ok = err_m <= cholesky_path::kAcceptH * mhessm && a2m > 0.0;
      if (hess_ok) hess = hessm;
    }
    lanes::store_first(out.hess_r12, kSym, hess);
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
    Lanes8 const z = fin + lanes::keep(0x3F, hess - hess);
    return lanes::eq_bits(z, Lanes8{}) == 0xFF && (mu2 - mu2) == 0.0 && (lam - lam) == 0.0;
  }
  return false;
}

}  // namespace adjugate_path
}  // namespace pw85
