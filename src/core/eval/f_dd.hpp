// f(lambda) and f'(lambda) in double-double arithmetic (arith/dd.hpp),
// for the final steps of PW85_METHOD_DEFAULT (docs/methods.md, eq. (M11)).
// Q(lambda) = (1 - lambda) Q1 + lambda Q2 is formed as double-doubles
// (1 - lambda and the products are error-free transformations of the double
// inputs; the sum errs by a few u^2 of its terms), then
// factored as L D L^T and solved in double-double: the relative error of phi
// is about kappa(Q) 2^-104 instead of kappa(Q) 2^-53.
#pragma once

#include "arith/dd.hpp"
#include "common/isa.hpp"
#include "common/lanes.hpp"
#include "common/sym3.hpp"
#include "eval/f_ldl.hpp"

namespace pw85 {

struct FEvalDD {
  double f;     // f(lambda), rounded to double
  double df;    // f'(lambda), rounded to double
  double phi;   // r^T Q^{-1} r, rounded to double
  double dphi;  // phi' = -s^T D s, rounded to double
  double rel;   // bound on the relative error of phi (eq. (M6), unit kUdd)
};

// Unit of the bound (M6) for the double-double solve, in place of u: the
// operations of arith/dd.hpp err by a few u^2 of their operands, the
// reciprocal by 8 u^2 (arith/dd.hpp); Q(lambda) is formed within u^2 of its
// terms.
constexpr double kUdd = 8.0 * kU * kU;

// Q(lambda) = (1 - lambda) Q1 + lambda Q2 formed as double-doubles,
// factored as L D L^T and s = Q^{-1} r, phi = r^T s solved in double-double
// (shared by f_eval_dd_impl and contact_point_dd_impl). Returns false when a
// pivot is not positive. fac, when not null, receives the high parts of L
// and D (for the bound (M6), phi_error).
template <bool F>
PW85_ALWAYS_INLINE bool solve_dd_impl(double lambda, Vec3 const &r, Sym3 const &q1,
                                      Sym3 const &q2, dd::DD s[kDim], dd::DD &phi,
                                      Ldl *fac = nullptr) noexcept {
  using namespace dd;
  DD const om = two_sum(1.0, -lambda);  // 1 - lambda, exactly
  DD q[kSym];
  for (int i = 0; i < kSym; ++i) {
    // (1 - lambda) q1 exactly as a double-double: om.hi q1 + om.lo q1.
    DD a = two_prod<F>(om.hi, q1[i]);
    a = add(a, om.lo * q1[i]);
    q[i] = add_sloppy(a, two_prod<F>(lambda, q2[i]));
  }
  // L D L^T. The products that do not need a reciprocal (q1^2, q1 q2, q2^2,
  // e^2) are formed while it runs: d1 = q3 - q1^2 / q0, e = q4 - q1 q2 / q0,
  // d2 = q5 - q2^2 / q0 - e^2 / d1, so that each pivot is one product and
  // one difference after the reciprocal before it.
  if (!(q[0].hi > 0.0)) return false;
  DD const id0 = recip<F>(q[0]);
  DD const d1 = sub_sloppy(q[3], mul<F>(mul<F>(q[1], q[1]), id0));
  if (!(d1.hi > 0.0)) return false;
  DD const e = sub_sloppy(q[4], mul<F>(mul<F>(q[1], q[2]), id0));
  DD const d2a = sub_sloppy(q[5], mul<F>(mul<F>(q[2], q[2]), id0));
  DD const id1 = recip<F>(d1);
  DD const d2 = sub_sloppy(d2a, mul<F>(mul<F>(e, e), id1));
  if (!(d2.hi > 0.0)) return false;
  DD const id2 = recip<F>(d2);
  DD const l10 = mul<F>(q[1], id0), l20 = mul<F>(q[2], id0), l21 = mul<F>(e, id1);
  if (fac) *fac = Ldl{l10.hi, l20.hi, l21.hi, q[0].hi, d1.hi, d2.hi, id0.hi, id1.hi, id2.hi};
  // y = L^{-1} r, z = D^{-1} y, s = L^{-T} z with the last row of L^{-T}
  // formed before z2 is known: s0 = z0 - l10 z1 + (l10 l21 - l20) z2.
  DD const y0{r[0], 0.0};
  DD const y1 = sub_sloppy(DD{r[1], 0.0}, mul<F>(l10, r[0]));
  DD const y2 = sub_sloppy(sub_sloppy(DD{r[2], 0.0}, mul<F>(l20, r[0])), mul<F>(l21, y1));
  DD const z0 = mul<F>(y0, id0), z1 = mul<F>(y1, id1), z2 = mul<F>(y2, id2);
  phi = add_sloppy(add_sloppy(mul<F>(y0, z0), mul<F>(y1, z1)), mul<F>(y2, z2));
  DD const c02 = sub_sloppy(mul<F>(l10, l21), l20);
  s[2] = z2;
  s[1] = sub_sloppy(z1, mul<F>(l21, z2));
  s[0] = add_sloppy(sub_sloppy(z0, mul<F>(l10, z1)), mul<F>(c02, z2));
  return true;
}

template <bool F>
PW85_ALWAYS_INLINE bool f_eval_dd_impl(double lambda, Vec3 const &r, Sym3 const &q1,
                                       Sym3 const &q2, FEvalDD &out) noexcept {
  using namespace dd;
  DD const om = two_sum(1.0, -lambda);  // 1 - lambda, exactly
  DD dq[kSym];
  for (int i = 0; i < kSym; ++i) dq[i] = two_sum(q2[i], -q1[i]);  // D = Q2 - Q1, exactly
  DD sv[kDim], phi;
  FEval fac;  // L, D and s in double, for the bound phi_error (eq. (M6))
  if (!solve_dd_impl<F>(lambda, r, q1, q2, sv, phi, &fac.l)) return false;
  DD const s0 = sv[0], s1 = sv[1], s2 = sv[2];
  // s^T D s.
  DD sds = add_sloppy(add_sloppy(mul<F>(dq[0], mul<F>(s0, s0)), mul<F>(dq[3], mul<F>(s1, s1))), mul<F>(dq[5], mul<F>(s2, s2)));
  DD const cross = add_sloppy(add_sloppy(mul<F>(dq[1], mul<F>(s0, s1)), mul<F>(dq[2], mul<F>(s0, s2))),
                       mul<F>(dq[4], mul<F>(s1, s2)));
  sds = add_sloppy(sds, mul<F>(cross, 2.0));
  // p = lambda (1 - lambda), p' = 1 - 2 lambda (exact: 2 lambda is exact).
  DD const p = mul<F>(om, lambda);
  DD const p1 = add(om, -lambda);
  DD const f = mul<F>(p, phi);
  DD const df = sub_sloppy(mul<F>(phi, p1), mul<F>(p, sds));  // f' = p' phi + p phi', phi' = -s^T D s
  out.f = to_double(f);
  out.df = to_double(df);
  out.phi = to_double(phi);
  out.dphi = -to_double(sds);
  fac.lambda = lambda;
  fac.s = Vec3{{to_double(s0), to_double(s1), to_double(s2)}};
  out.rel = phi_error(fac, r, q1, q2) * (kUdd / kU) / out.phi;
  return std::isfinite(out.f) && std::isfinite(out.df);
}

// The last step of (M11): lambda (1 - lambda) (2 r^T s - (1 - lambda)
// s^T Q1 s - lambda s^T Q2 s) in double from the three compensated sums,
// each rounded to double (the unevaluated pair a + c, one rounding). The
// double-double work is in the sums, whose terms cancel; here the terms are
// positive except the one subtraction, and 2 r^T s ~ 2 s^T Q s ~ 2 phi when
// s is close to Q^{-1} r, so the result then errs by at most ~7u relative:
// u/2 for each rounded sum and for 1 - lambda, u/2 per operation, the
// subtraction at most doubling the relative errors of its operands
// (docs/methods.md, (M11)). DEFAULT (default.hpp) uses the form only where
// its bound says s is that close. BRENT (brent.cpp) uses it on its
// Cholesky s, which in the class [0.001, 1000] can be farther; BRENT's
// error estimate (methods.cpp, eq. (M10)) does not rely on this bound.
PW85_ALWAYS_INLINE double stationary_combine(double lambda, double rs, double sq1,
                                             double sq2) noexcept {
  double const om = 1.0 - lambda;
  double const bracket = 2.0 * rs - (om * sq1 + lambda * sq2);
  return (lambda * om) * bracket;
}

// f(lambda) from a double-precision s ~ Q(lambda)^{-1} r by the stationary
// form (docs/methods.md, eq. (M11)):
//   phi = max_x (2 r^T x - x^T Q x) = 2 r^T s - s^T Q s + (s - s*)^T Q (s - s*),
// so that the error of s enters phi only to second order. With
// Q = (1 - lambda) Q1 + lambda Q2,
//   f = lambda (1 - lambda) (2 r^T s - (1 - lambda) s^T Q1 s - lambda s^T Q2 s),
// where r^T s and s^T Qi s are compensated dot products (the products of
// doubles are exact double-doubles) and (1 - lambda) s^T Q1 s + lambda s^T Q2 s
// adds positive numbers. Returns f rounded to double.
template <bool F>
PW85_ALWAYS_INLINE double f_stationary_impl(double lambda, Vec3 const &r, Sym3 const &q1,
                                            Sym3 const &q2, Vec3 const &s) noexcept {
  using namespace dd;
  // Products s_j s_k, exact.
  DD const p[kSym] = {two_prod<F>(s[0], s[0]), two_prod<F>(s[0], s[1]),
                      two_prod<F>(s[0], s[2]), two_prod<F>(s[1], s[1]),
                      two_prod<F>(s[1], s[2]), two_prod<F>(s[2], s[2])};
  // Compensated sums: running sum in double, errors accumulated in c.
  double a = 0.0, ca = 0.0;
  for (int i = 0; i < kDim; ++i) {
    DD const t = two_prod<F>(r[i], s[i]);
    DD const u = two_sum(a, t.hi);
    a = u.hi;
    ca += u.lo + t.lo;
  }
  double b1 = 0.0, c1 = 0.0, b2 = 0.0, c2 = 0.0;
  for (int i = 0; i < kSym; ++i) {
    double const w = (i == 0 || i == 3 || i == 5) ? 1.0 : 2.0;  // exact
    DD const t1 = two_prod<F>(w * q1[i], p[i].hi);
    DD const u1 = two_sum(b1, t1.hi);
    b1 = u1.hi;
    c1 += u1.lo + (t1.lo + w * q1[i] * p[i].lo);
    DD const t2 = two_prod<F>(w * q2[i], p[i].hi);
    DD const u2 = two_sum(b2, t2.hi);
    b2 = u2.hi;
    c2 += u2.lo + (t2.lo + w * q2[i] * p[i].lo);
  }
  return stationary_combine(lambda, a + ca, b1 + c1, b2 + c2);
}

#if PW85_ISA_STATIC_FMA || PW85_ISA_FMA
// f_stationary_impl<true> with 4-lane vectors, for the FMA variant of
// dd_kernels.cpp (eq. (M11), docs/methods.md): the same exact products and
// error-free sums, in another order. Lanes of p hold s_j s_k for the entries
// 0-3 of the symmetric storage, lanes of rr the entries 4-5 and r_0 s_0,
// r_1 s_1; each quadratic form's terms are summed pairwise by two_sum, the
// errors accumulated in double (Ogita, Rump and Oishi's Dot2, as above).
// Same results as the scalar form on random (lambda, s); faster per DEFAULT
// call in classes 1-3 (build/bench/bench_contact).
PW85_ALWAYS_INLINE PW85_TARGET_FMA double f_stationary_lanes(
    double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2, Vec3 const &s) noexcept {
  using namespace dd;
  using lanes::fma;
  using lanes::fms;
  using lanes::Lanes4;
  using lanes::shuffle;
  Lanes4 const sa{s[0], s[0], s[0], s[1]};
  Lanes4 const sb{s[0], s[1], s[2], s[1]};
  Lanes4 const sc{s[1], s[2], r[0], r[1]};
  Lanes4 const sd{s[2], s[2], s[0], s[1]};
  Lanes4 const p = sa * sb, pl = fms(sa, sb, p);
  Lanes4 const rr = sc * sd, rl = fms(sc, sd, rr);
  Lanes4 const w{1.0, 2.0, 2.0, 1.0};  // exact scalings
  Lanes4 const c1a = lanes::load4(q1.a) * w;
  Lanes4 const c2a = lanes::load4(q2.a) * w;
  Lanes4 const c1b{2.0 * q1[4], q1[5], 0.0, 0.0};
  Lanes4 const c2b{2.0 * q2[4], q2[5], 0.0, 0.0};
  // c (p + pl) = h + l exactly up to the rounding of c pl (l = c p - h + c pl).
  Lanes4 const a1 = c1a * p, a1l = fma(c1a, pl, fms(c1a, p, a1));
  Lanes4 const a2 = c2a * p, a2l = fma(c2a, pl, fms(c2a, p, a2));
  Lanes4 const b1 = c1b * rr, b1l = fma(c1b, rl, fms(c1b, rr, b1));
  Lanes4 const b2 = c2b * rr, b2l = fma(c2b, rl, fms(c2b, rr, b2));
  // Lanes {Q1 term, Q1 term, Q2 term, Q2 term}.
  Lanes4 const lo = shuffle<0, 1, 4, 5>(a1, a2), hi = shuffle<2, 3, 6, 7>(a1, a2);
  Lanes4 const x = shuffle<0, 1, 4, 5>(b1, b2);
  Lanes4 err = (shuffle<0, 1, 4, 5>(a1l, a2l) + shuffle<2, 3, 6, 7>(a1l, a2l)) +
               shuffle<0, 1, 4, 5>(b1l, b2l);
  Lanes4 u, e1, v, e2, t, e3;
  lanes::two_sum(lo, hi, u, e1);
  lanes::two_sum(u, x, v, e2);
  lanes::two_sum(v, shuffle<1, 0, 3, 2>(v, v), t, e3);  // lanes 0, 2: the sums
  err = err + (e1 + e2);
  err = (err + shuffle<1, 0, 3, 2>(err, err)) + e3;
  Lanes4 const sq = t + err;  // lanes 0, 2: s^T Q1 s, s^T Q2 s
  double const sq1 = sq[0], sq2 = sq[2];
  // r^T s: lanes 2, 3 of rr and r_2 s_2.
  DD const t2 = two_prod<true>(r[2], s[2]);
  DD const ra = two_sum(rr[2], rr[3]);
  DD const rb = two_sum(ra.hi, t2.hi);
  double const rc = ((rl[2] + rl[3]) + t2.lo) + (ra.lo + rb.lo);
  return stationary_combine(lambda, rb.hi + rc, sq1, sq2);
}
#endif

// Compensated dot product of two 3-vectors (Ogita, Rump and Oishi, SIAM J.
// Sci. Comput. 26(6), 2005, algorithm Dot2): exact products, error-free
// running sum, errors accumulated in double; returns the unevaluated pair
// (sum, correction), accurate as if computed in twice the working precision.
template <bool F>
PW85_ALWAYS_INLINE dd::DD dot3_c(double a0, double a1, double a2, double b0, double b1,
                                 double b2) noexcept {
  using namespace dd;
  DD const p0 = two_prod<F>(a0, b0), p1 = two_prod<F>(a1, b1), p2 = two_prod<F>(a2, b2);
  DD const u = two_sum(p0.hi, p1.hi);
  DD const w = two_sum(u.hi, p2.hi);
  return DD{w.hi, ((p0.lo + p1.lo) + (p2.lo + u.lo)) + w.lo};
}

// Residual rho = r - Q(lambda) s of a double-precision s, with
// Q(lambda) s = (1 - lambda) Q1 s + lambda Q2 s from compensated dot products
// and 1 - lambda exact: accurate to a few ulps of rho plus ~2^-100 |Q||s|
// (iterative refinement, docs/contact_geometry.md, eq. (G8)).
template <bool F>
PW85_ALWAYS_INLINE Vec3 residual_dd_impl(double lambda, Vec3 const &r, Sym3 const &q1,
                                         Sym3 const &q2, Vec3 const &s) noexcept {
  using namespace dd;
  DD const om = two_sum(1.0, -lambda);  // 1 - lambda, exactly
  static constexpr int kIdx[kDim][kDim] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  Vec3 rho;
  for (int i = 0; i < kDim; ++i) {
    int const *k = kIdx[i];
    DD const t1 = dot3_c<F>(q1[k[0]], q1[k[1]], q1[k[2]], s[0], s[1], s[2]);
    DD const t2 = dot3_c<F>(q2[k[0]], q2[k[1]], q2[k[2]], s[0], s[1], s[2]);
    DD const a = two_prod<F>(om.hi, t1.hi);
    DD const b = two_prod<F>(lambda, t2.hi);
    DD const x = two_sum(r[i], -a.hi);
    DD const y = two_sum(x.hi, -b.hi);
    double const low = (om.hi * t1.lo + om.lo * t1.hi) + lambda * t2.lo;
    rho[i] = y.hi + (((x.lo + y.lo) - (a.lo + b.lo)) - low);
  }
  return rho;
}

// From s = Q(lambda)^{-1} r given as double-doubles: Q1 s and Q2 s (t1, t2)
// and f'(lambda) = (1 - lambda)^2 s^T Q1 s - lambda^2 s^T Q2 s
// (docs/contact_geometry.md, eqs. (G1), (G9)), all in double-double.
template <bool F>
PW85_ALWAYS_INLINE dd::DD products_from_s_impl(double lambda, Sym3 const &q1, Sym3 const &q2,
                                               dd::DD const s[kDim], dd::DD t1[kDim],
                                               dd::DD t2[kDim]) noexcept {
  using namespace dd;
  DD const om = two_sum(1.0, -lambda);  // 1 - lambda, exactly
  static constexpr int kIdx[kDim][kDim] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  DD sq1{0.0, 0.0}, sq2{0.0, 0.0};
  for (int i = 0; i < kDim; ++i) {
    t1[i] = DD{0.0, 0.0};
    t2[i] = DD{0.0, 0.0};
    for (int j = 0; j < kDim; ++j) {
      t1[i] = add(t1[i], mul<F>(s[j], q1[kIdx[i][j]]));
      t2[i] = add(t2[i], mul<F>(s[j], q2[kIdx[i][j]]));
    }
    sq1 = add(sq1, mul<F>(s[i], t1[i]));
    sq2 = add(sq2, mul<F>(s[i], t2[i]));
  }
  return sub(mul<F>(mul<F>(sq1, om), om), mul<F>(mul<F>(sq2, lambda), lambda));
}

// The same with x0 = (1 - lambda) Q1 s and Q2 s rounded to double; returns
// f'(lambda) rounded to double.
template <bool F>
PW85_ALWAYS_INLINE double point_from_s_impl(double lambda, Sym3 const &q1, Sym3 const &q2,
                                            dd::DD const s[kDim], Vec3 &x0, Vec3 &q2s) noexcept {
  using namespace dd;
  DD const om = two_sum(1.0, -lambda);  // 1 - lambda, exactly
  DD t1[kDim], t2[kDim];
  DD const df = products_from_s_impl<F>(lambda, q1, q2, s, t1, t2);
  for (int i = 0; i < kDim; ++i) {
    x0[i] = to_double(mul<F>(t1[i], om));
    q2s[i] = to_double(t2[i]);
  }
  return to_double(df);
}

// Contact point, normal and f' at lambda in double-double
// (docs/contact_geometry.md, eqs. (G1), (G2), (G9)): s = Q(lambda)^{-1} r by
// solve_dd_impl, then point_from_s_impl; n = s / |s|. Returns false when
// Q(lambda) is not positive definite in double-double or a value is not
// finite.
template <bool F>
PW85_ALWAYS_INLINE bool contact_point_dd_impl(double lambda, Vec3 const &r, Sym3 const &q1,
                                              Sym3 const &q2, Vec3 &x0, Vec3 &n,
                                              double &df) noexcept {
  using namespace dd;
  DD s[kDim], phi;
  if (!solve_dd_impl<F>(lambda, r, q1, q2, s, phi)) return false;
  Vec3 q2s;
  df = point_from_s_impl<F>(lambda, q1, q2, s, x0, q2s);
  double ss = 0.0;
  for (int i = 0; i < kDim; ++i) {
    n[i] = to_double(s[i]);
    ss += n[i] * n[i];
  }
  double const ns = std::sqrt(ss);
  for (int i = 0; i < kDim; ++i) n[i] /= ns;
  return std::isfinite(df) && std::isfinite(x0[0]) && std::isfinite(x0[1]) &&
         std::isfinite(x0[2]) && ns > 0.0 && std::isfinite(ns);
}

// The same as point_from_s_impl from a refined double solve s + delta
// (unevaluated sum, |delta| <= 1e-6 |s|), for the fast path of
// contact_geometry (eq. (G8)): Qk s = Qk s (compensated dot products) +
// Qk delta (double, its error is ~1e-6 u relative), s^T Qk s likewise;
// returns f'(lambda), x0 and Q2 s rounded to double.
template <bool F>
PW85_ALWAYS_INLINE double refined_point_impl(double lambda, Sym3 const &q1, Sym3 const &q2,
                                             Vec3 const &s, Vec3 const &delta, Vec3 &x0,
                                             Vec3 &q2s) noexcept {
  using namespace dd;
  DD const om = two_sum(1.0, -lambda);  // 1 - lambda, exactly
  static constexpr int kIdx[kDim][kDim] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  DD t1[kDim], t2[kDim];
  for (int i = 0; i < kDim; ++i) {
    int const *k = kIdx[i];
    DD const a = dot3_c<F>(q1[k[0]], q1[k[1]], q1[k[2]], s[0], s[1], s[2]);
    DD const b = dot3_c<F>(q2[k[0]], q2[k[1]], q2[k[2]], s[0], s[1], s[2]);
    double const da = q1[k[0]] * delta[0] + q1[k[1]] * delta[1] + q1[k[2]] * delta[2];
    double const db = q2[k[0]] * delta[0] + q2[k[1]] * delta[1] + q2[k[2]] * delta[2];
    t1[i] = fast_two_sum(a.hi, a.lo + da);
    t2[i] = fast_two_sum(b.hi, b.lo + db);
    DD const x = two_prod<F>(om.hi, t1[i].hi);
    x0[i] = x.hi + (x.lo + (om.hi * t1[i].lo + om.lo * t1[i].hi));
    q2s[i] = t2[i].hi + t2[i].lo;
  }
  // s^T Qk s = s . (Qk s)_hi (compensated) + s . (Qk s)_lo + delta . (Qk s)_hi.
  DD const c1 = dot3_c<F>(s[0], s[1], s[2], t1[0].hi, t1[1].hi, t1[2].hi);
  DD const c2 = dot3_c<F>(s[0], s[1], s[2], t2[0].hi, t2[1].hi, t2[2].hi);
  double const l1 = (s[0] * t1[0].lo + s[1] * t1[1].lo + s[2] * t1[2].lo) +
                    (delta[0] * t1[0].hi + delta[1] * t1[1].hi + delta[2] * t1[2].hi);
  double const l2 = (s[0] * t2[0].lo + s[1] * t2[1].lo + s[2] * t2[2].lo) +
                    (delta[0] * t2[0].hi + delta[1] * t2[1].hi + delta[2] * t2[2].hi);
  DD const sq1 = fast_two_sum(c1.hi, c1.lo + l1), sq2 = fast_two_sum(c2.hi, c2.lo + l2);
  // (1 - lambda)^2 sq1 - lambda^2 sq2 with (1 - lambda)^2, lambda^2 as double-doubles.
  DD const nu2 = mul<F>(om, om), la2 = two_prod<F>(lambda, lambda);
  DD const p1 = mul<F>(nu2, sq1), p2 = mul<F>(la2, sq2);
  return to_double(sub(p1, p2));
}

// The kernels of the variant this CPU runs (dd_kernels.cpp, dispatch/kernels.hpp).
bool f_eval_dd(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
               FEvalDD &out) noexcept;
double f_stationary(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                    Vec3 const &s) noexcept;
Vec3 residual_dd(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                 Vec3 const &s) noexcept;
bool contact_point_dd(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                      Vec3 &x0, Vec3 &n, double &df) noexcept;
double refined_point_dd(double lambda, Sym3 const &q1, Sym3 const &q2, Vec3 const &s,
                        Vec3 const &delta, Vec3 &x0, Vec3 &q2s) noexcept;

}  // namespace pw85
