// Overlap predicate: floating-point filters with rigorous error bounds, then
// the exact stage (overlap_exact.cpp) for the pairs they cannot decide.
// The argument that each verdict is certain is in docs/overlap.md; the
// equation numbers below refer to it.
// The first certificates, written once for one pair and for W pairs, and
// the notation are in filters.hpp; this file holds the later stages of one
// pair's filters and the entry of the general path.
#include <cmath>
#include <cstdint>
#include <cstring>

#include "common/fp.hpp"
#include "common/magnitude.hpp"
#include "overlap/bounded.hpp"
#include "overlap/filters.hpp"
#include "overlap/overlap.hpp"
#include "overlap/overlap_dd.hpp"

namespace pw85 {

namespace {

using namespace overlap_filters;

// Error bound (eq. (O3), overlap.hpp): |fl(E) - E| <= kC * fl(P) + kAbs.
constexpr double kC = kOverlapFilterC, kAbs = kOverlapFilterAbs;
constexpr double kRangeHi = kOverlapRangeHi, kRangeLo = kOverlapRangeLo;

// The bounded values of one pair (bounded.hpp): {fl(E), fl(P)} in one
// vector of 2 doubles.
using bounded::Pair;
using PairSym = bounded::Sym<Pair>;

// g = det Q - y^T adj(Q) y > 0 certified: y = x - c strictly inside
// {y : y^T Q^{-1} y < 1} (eq. (O6)); yb[] is y bounded (lane 1 >= |y_i|),
// |y_i| <= 2^60 required by the caller. When the double bound leaves the
// sign open, the same expression in double-double decides (eq. (O15)).
inline bool inside(Pair det, Pair const m[kSym], Pair const yb[kDim], Sym3 const &q,
                   Vec3 const &x, Vec3 const &c) noexcept {
  Pair yy[kSym];
  outer(yb, yy);
  Pair const g = det - flip(quad(m, yy));
  if (g[0] > err(g)) return true;
  if (!(g[0] > -err(g))) return false;  // certainly outside (or NaN)
  return witness_g_dd(q, x, c) > kDDRel * g[1] + kAbs;
}

// p(l) = det Q(l) - l (1 - l) r^T adj Q(l) r at l on the grid 2^-52 Z, so
// that nu = 1 - l is exact (eq. (O4)).
inline Pair p_at(double l, Pair const rr[kSym], PairSym const &q1, PairSym const &q2) noexcept {
  double const nu = 1.0 - l;
  PairSym q;
  for (int i = 0; i < kSym; ++i) {
    q.p[i] = nu * q1.p[i] + l * q2.p[i];  // lane 1: nu |q1| + l |q2| >= |q(l)|
    q.n[i] = flip(q.p[i]);
  }
  Pair m[kSym];
  Pair const d = det_adj(q, m);
  return d - flip((l * nu) * quad(m, rr));
}

// Cholesky-based f, f', f'' and s = Q(l)^{-1} r (pw85 documentation,
// chapter 4, eqs. (4), (6), (9)); not certified, only used to find lambda*.
struct Newton {
  double f, df, d2f;
  Vec3 s;
};

inline bool newton_values(double l, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                          Sym3 const &d, Newton &out) noexcept {
  Sym3 lo;
  if (!cholesky(interpolate(q1, q2, l), lo)) return false;
  Vec3 const s = cholesky_solve(lo, r);
  Vec3 const u = multiply(d, s);
  Vec3 const v = cholesky_solve(lo, u);
  double const rs = dot(r, s), su = dot(s, u), uv = dot(u, v);
  double const w = l * (1.0 - l);
  out.f = w * rs;
  out.df = (1.0 - 2.0 * l) * rs - w * su;
  out.d2f = -2.0 * rs - 2.0 * (1.0 - 2.0 * l) * su + 2.0 * w * uv;
  out.s = s;
  return std::isfinite(out.f) && std::isfinite(out.df) && std::isfinite(out.d2f);
}

// p(l) from its coefficients P_j in the basis s^(4-j) t^j (eq. (O14)),
// s = 1 - l exact (l on the grid 2^-52 Z), with the bound of (O14) from the
// rounding of the sum and the bounds E_j of the coefficients.
inline Pair p_bernstein(double l, double const P[5], double const E[5]) noexcept {
  double const sv = 1.0 - l, t = l;
  double const s2 = sv * sv, t2 = t * t;
  double const w0 = s2 * s2, w1 = (s2 * sv) * t, w2 = s2 * t2, w3 = sv * (t2 * t), w4 = t2 * t2;
  double const v = (P[0] * w0 + P[1] * w1) + (P[2] * w2 + (P[3] * w3 + P[4] * w4));
  double const s1a = (std::fabs(P[0]) * w0 + std::fabs(P[1]) * w1) +
                     (std::fabs(P[2]) * w2 + (std::fabs(P[3]) * w3 + std::fabs(P[4]) * w4));
  double const s2a = (E[0] * w0 + E[1] * w1) + (E[2] * w2 + (E[3] * w3 + E[4] * w4));
  // Lane 1 stored so that err() = kC * lane 1 + kAbs is the bound of (O14).
  return Pair{v, (16 * kU * s1a + s2a) * (1.0 + 32 * kU) / kC};
}

// Witness certificate (eq. (O6)): x strictly inside E1 and E2.
inline bool witness_inside(Vec3 const &x, Vec3 const &r, Pair const rb[kDim], Sym3 const &q1,
                           Sym3 const &q2, Pair det1, Pair const m1[kSym], Pair det2,
                           Pair const m2[kSym]) noexcept {
  // The error bound (O3) with kAbs needs |x_i| (and so |x_i - r_i|) in the
  // safe range (eq. (O9)); NaN fails the test too.
  if (!(std::fabs(x[0]) <= kRangeHi && std::fabs(x[1]) <= kRangeHi &&
        std::fabs(x[2]) <= kRangeHi))
    return false;
  Pair const xb[kDim] = {pos(x[0]), pos(x[1]), pos(x[2])};
  Vec3 const zero{{0.0, 0.0, 0.0}};
  if (!inside(det1, m1, xb, q1, x, zero)) return false;
  Pair const y[kDim] = {xb[0] - flip(rb[0]), xb[1] - flip(rb[1]), xb[2] - flip(rb[2])};
  return inside(det2, m2, y, q2, x, r);
}

// Witness certificate (eq. (O17)) at the point P = c + hi + lo given in
// double-double, c = 0 (from_c2 false) or r: g_k > kDDRel P_k + kAbs for
// both ellipsoids, P_k the bound expression of g_k (eq. (O15)) with the
// offsets y bounded by |hi| + |lo| and |hi -+ r| (1 + 2^-50) + |lo|.
inline bool witness_dd_inside(Vec3 const &hi, Vec3 const &lo, bool from_c2, Vec3 const &r,
                              Sym3 const &q1, Sym3 const &q2, Pair det1, Pair const m1[kSym],
                              Pair det2, Pair const m2[kSym]) noexcept {
  if (!(std::fabs(hi[0]) <= kRangeHi && std::fabs(hi[1]) <= kRangeHi &&
        std::fabs(hi[2]) <= kRangeHi))
    return false;
  Pair e[kDim], o[kDim];  // lane 1: bounds of the offsets from c and from the other centre
  double const sgn = from_c2 ? 1.0 : -1.0;
  for (int i = 0; i < kDim; ++i) {
    e[i] = pos(hi[i]) + pos(lo[i]);
    o[i] = pos(std::fabs(hi[i] + sgn * r[i]) * (1.0 + 0x1p-50) + std::fabs(lo[i]));
  }
  Pair ee[kSym], oo[kSym];
  outer(e, ee);
  outer(o, oo);
  Pair const *mc = from_c2 ? m2 : m1, *mo = from_c2 ? m1 : m2;
  double const pc = (from_c2 ? det2 : det1)[1] + quad(mc, ee)[1];
  double const po = (from_c2 ? det1 : det2)[1] + quad(mo, oo)[1];
  double g[2];
  witness_pair_dd(q1, q2, r, hi, lo, from_c2, g);
  double const p1 = from_c2 ? po : pc, p2 = from_c2 ? pc : po;
  return g[0] > kDDRel * p1 + kAbs && g[1] > kDDRel * p2 + kAbs;
}

// p(l) <= 0 certified (separation, eq. (O4)): in double, and in
// double-double (eq. (O15)) when the double bound leaves the sign open.
inline bool p_negative(double l, Vec3 const &r, Pair const rr[kSym], Sym3 const &q1,
                       Sym3 const &q2, PairSym const &b1q, PairSym const &b2q) noexcept {
  Pair const pl = p_at(l, rr, b1q, b2q);
  if (pl[0] <= -err(pl)) return true;
  if (!(pl[0] <= err(pl))) return false;  // certainly positive (or NaN)
  return p_dd(l, r, q1, q2) <= -(kDDRel * pl[1] + kAbs);
}

[[gnu::noinline]] int filters(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, int &st) noexcept {
  return filters_inline(r, q1, q2, st);
}

}  // namespace

// The pairs that (O18) leaves open (near contact, or coefficients whose
// bounds are too loose): Newton on log f from l, p(l) from Q(l), witnesses.
// Rare (the first certificates decide almost every pair: docs/overlap.md),
// so it recomputes the coefficients rather than receive them: the hot path
// then keeps them in registers.
[[gnu::noinline]] int overlap_filters::filters_slow(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                                                    double l, int &st) noexcept {
  Pair const rb[kDim] = {pos(r[0]), pos(r[1]), pos(r[2])};
  Pair rr[kSym];
  outer(rb, rr);
  PairSym const b1q = bound_sym(q1.a), b2q = bound_sym(q2.a);
  Coefs<double> c;
  coefficients<double>(rr, b1q, b2q, c);
  Pair const &det1 = c.det1, &det2 = c.det2, &c0 = c.c0, &c1 = c.c1, &c2 = c.c2, &b1 = c.b1,
           &b2 = c.b2, &p1 = c.p1, &p2 = c.p2, &p3 = c.p3;
  Pair const *m1 = c.m1, *m2 = c.m2;
  // --- Maximiser of f = l (1 - l) N / D (not certified: only chooses l),
  // N = c0 s^2 + c1 s t + c2 t^2 = r^T adj Q(l) r, D = det Q(l) (eq. (O10)),
  // by safeguarded Newton steps on phi = log f (concave on (0, 1): f is
  // concave and positive). At every iterate p(l) <= -err certifies
  // separation (O14); after the last one a witness at l may certify overlap
  // (O6). (Minimising the quartic p itself is not the same: p = D (1 - f)
  // is dominated by D and often has its minimum near l = 0 or 1, far from
  // where f > 1.)
  double const P0 = det1[0], P1 = p1[0], P2 = p2[0], P3 = p3[0], P4 = det2[0];
  double const Pc[5] = {P0, P1, P2, P3, P4};
  double const Ec[5] = {err(det1), err(p1), err(p2), err(p3), err(det2)};
  // Power bases N = n0 + n1 l + n2 l^2, D = d0 + d1 l + d2 l^2 + d3 l^3.
  double const n0 = c0[0], n1 = c1[0] - 2.0 * c0[0], n2 = (c0[0] - c1[0]) + c2[0];
  double const d0 = det1[0], d1 = b1[0] - 3.0 * d0, d2 = (3.0 * d0 - 2.0 * b1[0]) + b2[0];
  double const d3 = ((b1[0] - d0) - b2[0]) + det2[0];
  double lo = 0.0, hi = 1.0;
  Pair p = p_bernstein(l, Pc, Ec);
  for (int it = 0; it < 8 && !(p[0] <= -err(p)); ++it) {
    double const nv = n0 + l * (n1 + l * n2), dn = n1 + 2.0 * n2 * l;
    double const dv = d0 + l * (d1 + l * (d2 + l * d3));
    double const dd = d1 + l * (2.0 * d2 + 3.0 * d3 * l), d2d = 2.0 * d2 + 6.0 * d3 * l;
    double const il = 1.0 / l, im = 1.0 / (1.0 - l), a = dn / nv, b = dd / dv;
    double const g1 = (il - im) + (a - b);
    double const g2 = -(il * il + im * im) + (2.0 * n2 / nv - a * a) - (d2d / dv - b * b);
    if (g1 > 0.0)
      lo = l;
    else
      hi = l;
    double next = l - g1 / g2;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    next = to_grid(next);
    if (!(next > 0.0 && next < 1.0) || next == l) break;
    bool const done = std::fabs(next - l) <= 0x1p-27 * l * (1.0 - l);
    l = next;
    p = p_bernstein(l, Pc, Ec);
    if (done) break;
  }
  if (p[0] <= -err(p)) {
    st = kStageFilter;
    return 0;
  }
  // The coefficients P_j carry bounds of the size of their terms; p formed
  // from Q(l) directly (O4) has a bound relative to Q(l), often far tighter,
  // and double-double (O15) tighter still.
  if (p[0] <= err(p) && p_negative(l, r, rr, q1, q2, b1q, b2q)) {
    st = kStageFilter;
    return 0;
  }
  {
    // x = (1 - l) Q1 adj(Q(l)) r / det Q(l): the point of E1 where the
    // ellipsoids would touch if f(l) were mu^2 (pw85 documentation, ch. 3).
    double const nu = 1.0 - l;
    Sym3 q;
    for (int i = 0; i < kSym; ++i) q[i] = nu * q1[i] + l * q2[i];
    Sym3 const adj = adjugate3(q);
    double const dq = q[0] * adj[0] + q[1] * adj[1] + q[2] * adj[2];
    Vec3 const s = multiply(adj, r);
    Vec3 x = multiply(q1, s);
    double const w = nu / dq;
    for (int i = 0; i < kDim; ++i) x[i] *= w;
    if (witness_inside(x, r, rb, q1, q2, det1, m1, det2, m2)) {
      st = kStageFilter;
      return 1;
    }
  }

  // --- Newton for lambda* with Cholesky, then one certificate; from the
  // l of the coefficient stage (usually close to lambda*). ---
  Sym3 const d = difference(q2, q1);
  if (!(l > 0.0 && l < 1.0)) l = 0.5;
  lo = 0.0;
  hi = 1.0;
  Newton nv;
  // Last evaluated point, for the refined witness below.
  double lw = -1.0, d2w = 0.0, estw = 2.0;
  // Newton converges quadratically until the steps reach the rounding noise
  // of the double f'(l) (about kappa(Q) u / |f''|, far above 2^-52 for
  // ill-conditioned Q(l)); from then on they no longer shrink, and the
  // double-double loop below refines l. Stalled: a step of at most 2^-26
  // l (1 - l) not below a quarter of the previous one.
  double prev_step = 1.0;
  for (int it = 0; it < 40; ++it) {
    if (!newton_values(l, r, q1, q2, d, nv)) break;
    // Early separation: f(l) >= 1 at a grid point, certified by p(l) <= 0.
    if (nv.f >= 1.0) {
      if (p_negative(l, r, rr, q1, q2, b1q, b2q)) {
        st = kStageFilter;
        return 0;
      }
    }
    if (nv.df > 0.0)
      lo = l;
    else
      hi = l;
    double next = l - nv.df / nv.d2f;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    next = to_grid(next);
    double const step = std::fabs(next - l);
    bool const stalled = step <= 0x1p-26 * std::fmin(l, 1.0 - l) && step >= 0.25 * prev_step;
    bool const converged = step <= 0x1p-52 || stalled;
    prev_step = step;
    // Early overlap: well below 1, witness at the current point (eq. (O6)).
    double const est = nv.f + 0.5 * nv.df * (nv.df / -nv.d2f);
    lw = l;
    d2w = nv.d2f;
    estw = est;
    if (est < 0.95 || converged) {
      double const nu = 1.0 - l;
      Vec3 x = multiply(q1, nv.s);
      for (int i = 0; i < kDim; ++i) x[i] *= nu;
      if (est < 1.0 && witness_inside(x, r, rb, q1, q2, det1, m1, det2, m2)) {
        st = kStageFilter;
        return 1;
      }
      if (converged) break;
    }
    if (next == l || hi - lo <= 0x1p-52) break;
    l = next;
  }
  // --- Witness from a double-double solve (eq. (O17)): near contact
  // (1 - mu^2 below about kappa(Q) u) the witness above fails: the double s,
  // hence f'(l) and the balance of the two margins of x, carry an error of
  // about kappa(Q) u, and rounding x to double moves it by u |x|, which can
  // be large on the scale of the smaller ellipsoid. witness_point_dd gives
  // the point as a double-double offset from the centre of the smaller
  // ellipsoid and f'(l), both from s in double-double; a few Newton steps
  // (slope: the double f'') balance the margins, and the witness is tried
  // once the step is small. ---
  if (lw > 0.0 && lw < 1.0 && estw < 1.0 + 0x1p-20 && d2w < 0.0) {
    l = lw;
    for (int k = 0; k < 6; ++k) {
      bool const from_c2 = l > 0.5;
      Vec3 hi, lo;
      double df;
      if (!witness_point_dd(l, r, q1, q2, from_c2, hi, lo, df)) break;
      double const next = l - df / d2w;
      // The margins differ by about f'(l): no witness while the step is
      // large (Newton on the double-double f' converges quadratically).
      bool const near = std::fabs(next - l) <= 0x1p-30 * std::fmin(l, 1.0 - l);
      if ((near || k == 5) &&
          witness_dd_inside(hi, lo, from_c2, r, q1, q2, det1, m1, det2, m2)) {
        st = kStageFilter;
        return 1;
      }
      if (!(next > 0.0 && next < 1.0) || next == l) break;
      l = next;
    }
  }
  return kUndecided;
}

namespace {

inline bool in_range(Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept {
  double const qm1 = max_abs(q1.a, kSym), qm2 = max_abs(q2.a, kSym);
  double const qm = qm1 > qm2 ? qm1 : qm2;
  double const rm = max_abs(r.x, kDim);
  return qm >= kRangeLo && qm <= kRangeHi && rm <= kRangeHi;
}

}  // namespace

Status overlap(Vec3 const &r_in, Sym3 const &q1_in, Sym3 const &q2_in, int &verdict,
               int *stage) noexcept {
  int st_dummy;
  int &st = stage ? *stage : st_dummy;
  if (r_in[0] == 0.0 && r_in[1] == 0.0 && r_in[2] == 0.0) {
    st = kStageTrivial;
    verdict = 1;
    return kOk;
  }
  if (in_range(r_in, q1_in, q2_in)) {
    int const v = filters(r_in, q1_in, q2_in, st);
    if (v != kUndecided) {
      verdict = v;
      return kOk;
    }
  } else {
    // Exact scaling (eq. (O1)), only outside the safe range: Q -> 2^-2k Q,
    // r -> 2^-k r leaves mu^2 unchanged; chosen so that max |Q_ij| < 1.
    // Every scaled value must stay normal (or zero) for the scaling to be
    // exact; otherwise go to the exact stage.
    int e;
    std::frexp(std::fmax(max_abs(q1_in.a, kSym), max_abs(q2_in.a, kSym)), &e);
    int const k = e >= 0 ? (e + 1) / 2 : -((-e) / 2);  // 2k >= e: max |Q| 2^-2k < 1
    double const sq = std::ldexp(1.0, -2 * k), sr = std::ldexp(1.0, -k);
    Sym3 q1, q2;
    Vec3 r;
    bool exact_scale = sq != 0.0 && sr != 0.0 && std::isfinite(sq) && std::isfinite(sr);
    for (int i = 0; i < kSym; ++i) {
      q1[i] = q1_in[i] * sq;
      q2[i] = q2_in[i] * sq;
      exact_scale = exact_scale && (q1[i] == 0.0 || std::fabs(q1[i]) >= kMinNormal) &&
                    (q2[i] == 0.0 || std::fabs(q2[i]) >= kMinNormal);
    }
    for (int i = 0; i < kDim; ++i) {
      r[i] = r_in[i] * sr;
      exact_scale = exact_scale && (r[i] == 0.0 || std::fabs(r[i]) >= kMinNormal) &&
                    std::isfinite(r[i]);
    }
    if (exact_scale && in_range(r, q1, q2)) {
      int const v = filters(r, q1, q2, st);
      if (v != kUndecided) {
        verdict = v;
        return kOk;
      }
    }
  }
  // Separation by size (eq. (O19)): each ellipsoid lies in the ball of
  // radius sqrt(lambda_max(Q_k)) <= sqrt(3 max |Q_ij|) about its centre
  // (Gershgorin), so |r| > 2 sqrt(3 qmax) separates them (mu^2 > 1). With
  // r_max = max |r_i| >= 2^(er - 1) and qmax < 2^eq, 2 er >= eq + 6 gives
  // r_max^2 >= 16 qmax: an integer test, exact at any magnitude.
  {
    int er, eq;
    std::frexp(max_abs(r_in.x, kDim), &er);
    std::frexp(std::fmax(max_abs(q1_in.a, kSym), max_abs(q2_in.a, kSym)), &eq);
    if (2 * er >= eq + 6) {
      st = kStageFilter;
      verdict = 0;
      return kOk;
    }
  }
  // --- Exact stage. ---
  st = kStageExact;
  return overlap_exact(r_in, q1_in, q2_in, verdict);
}

}  // namespace pw85
