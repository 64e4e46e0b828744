// Overlap predicate: floating-point filters with rigorous error bounds, then
// the exact stage (overlap_exact.cpp) for the pairs they cannot decide.
// The argument that each verdict is certain is in docs/overlap.md; the
// equation numbers below refer to it.
//
// Notation (after an exact power-of-two scaling): E1 = {x : x^T Q1^{-1} x <= 1},
// E2 = {x : (x - r)^T Q2^{-1} (x - r) <= 1}, Q(l) = (1 - l) Q1 + l Q2,
// f(l) = l (1 - l) r^T Q(l)^{-1} r, mu^2 = max f (pw85 documentation,
// chapter 3, eqs. (6), (10), (11)).
#include <cmath>

#include "overlap.hpp"

namespace pw85 {

namespace {

constexpr double kU = 0x1p-53;  // unit roundoff
// Error bound of an expression of at most 16 rounded operations on any path
// (docs/overlap.md, eq. (O3)): |fl(E) - E| <= kC * fl(|E|) + kAbs.
constexpr double kC = 32 * kU;
// Absolute term covering gradual underflow for inputs in the safe range
// |Q_ij| <= 2^60, |r_i| <= 2^60 (eq. (O3), (O9)).
constexpr double kAbs = 0x1p-800;
constexpr double kRangeHi = kOverlapRangeHi, kRangeLo = kOverlapRangeLo;

struct Bounded {
  double v;     // computed value
  double perm;  // computed value of the same expression on absolute values
  double err() const noexcept { return kC * perm + kAbs; }
};

// det Q and its permanent-like bound; m[] receives the adjugate entries
// {adj00, adj01, adj02, adj11, adj12, adj22} and ma[] their bounds.
inline Bounded det_adj(Sym3 const &q, Sym3 const &qa, double m[6], double ma[6]) noexcept {
  m[0] = q[3] * q[5] - q[4] * q[4];
  m[1] = q[2] * q[4] - q[1] * q[5];
  m[2] = q[1] * q[4] - q[2] * q[3];
  m[3] = q[0] * q[5] - q[2] * q[2];
  m[4] = q[1] * q[2] - q[0] * q[4];
  m[5] = q[0] * q[3] - q[1] * q[1];
  ma[0] = qa[3] * qa[5] + qa[4] * qa[4];
  ma[1] = qa[2] * qa[4] + qa[1] * qa[5];
  ma[2] = qa[1] * qa[4] + qa[2] * qa[3];
  ma[3] = qa[0] * qa[5] + qa[2] * qa[2];
  ma[4] = qa[1] * qa[2] + qa[0] * qa[4];
  ma[5] = qa[0] * qa[3] + qa[1] * qa[1];
  Bounded d;
  d.v = q[0] * m[0] + q[1] * m[1] + q[2] * m[2];
  d.perm = qa[0] * ma[0] + qa[1] * ma[1] + qa[2] * ma[2];
  return d;
}

// y^T adj y and its bound; ya = |y| bound (componentwise).
inline Bounded quad_adj(double const m[6], double const ma[6], Vec3 const &y,
                        Vec3 const &ya) noexcept {
  Bounded b;
  b.v = m[0] * (y[0] * y[0]) + m[3] * (y[1] * y[1]) + m[5] * (y[2] * y[2]) +
        2.0 * (m[1] * (y[0] * y[1]) + m[2] * (y[0] * y[2]) + m[4] * (y[1] * y[2]));
  b.perm = ma[0] * (ya[0] * ya[0]) + ma[3] * (ya[1] * ya[1]) + ma[5] * (ya[2] * ya[2]) +
           2.0 * (ma[1] * (ya[0] * ya[1]) + ma[2] * (ya[0] * ya[2]) +
                  ma[4] * (ya[1] * ya[2]));
  return b;
}

inline Sym3 abs3(Sym3 const &q) noexcept {
  Sym3 a;
  for (int i = 0; i < kSym; ++i) a[i] = std::fabs(q[i]);
  return a;
}

// p(l) = det Q(l) - l (1 - l) r^T adj Q(l) r at l on the grid 2^-52 Z, so
// that nu = 1 - l is exact (eq. (O4)).
inline Bounded p_at(double l, Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept {
  double const nu = 1.0 - l;
  Sym3 q, qa;
  for (int i = 0; i < kSym; ++i) {
    q[i] = nu * q1[i] + l * q2[i];
    qa[i] = nu * std::fabs(q1[i]) + l * std::fabs(q2[i]);
  }
  double m[6], ma[6];
  Bounded const d = det_adj(q, qa, m, ma);
  Vec3 const ra{{std::fabs(r[0]), std::fabs(r[1]), std::fabs(r[2])}};
  Bounded const a = quad_adj(m, ma, r, ra);
  double const w = l * nu;
  return Bounded{d.v - w * a.v, d.perm + w * a.perm};
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

// Rounds l in [0, 1] to the grid 2^-52 Z (exact: (l + 1) - 1).
inline double to_grid(double l) noexcept {
  return (l + 1.0) - 1.0;
}

// Witness certificate (eq. (O6)): x strictly inside E1 and E2.
inline bool witness_inside(Vec3 const &x, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                           Bounded const &det1, double const m1[6], double const ma1[6],
                           Bounded const &det2, double const m2[6],
                           double const ma2[6]) noexcept {
  Vec3 const xa{{std::fabs(x[0]), std::fabs(x[1]), std::fabs(x[2])}};
  // The error bound (O3) with kAbs needs |x_i| (and so |x_i - r_i|) in the
  // safe range (eq. (O9)); NaN fails the test too.
  if (!(xa[0] <= kRangeHi && xa[1] <= kRangeHi && xa[2] <= kRangeHi)) return false;
  Bounded const a1 = quad_adj(m1, ma1, x, xa);
  double const g1 = det1.v - a1.v;
  if (!(g1 > kC * (det1.perm + a1.perm) + kAbs)) return false;
  Vec3 const y{{x[0] - r[0], x[1] - r[1], x[2] - r[2]}};
  Vec3 const ya{{std::fabs(x[0]) + std::fabs(r[0]), std::fabs(x[1]) + std::fabs(r[1]),
                 std::fabs(x[2]) + std::fabs(r[2])}};
  Bounded const a2 = quad_adj(m2, ma2, y, ya);
  double const g2 = det2.v - a2.v;
  (void)q1;
  (void)q2;
  return g2 > kC * (det2.perm + a2.perm) + kAbs;
}

inline double max_abs(double const *x, int n) noexcept {
  double m = 0.0;
  for (int i = 0; i < n; ++i) {
    double const a = std::fabs(x[i]);
    m = a > m ? a : m;  // inputs are finite: no NaN semantics needed
  }
  return m;
}

// r^T Q r with its bound (the support function of {x : x^T Q^{-1} x <= 1}
// along r is sqrt(r^T Q r)); rr[] = {r0 r0, r1 r1, r2 r2, r0 r1, r0 r2, r1 r2}.
inline Bounded quad_q(Sym3 const &q, double const rr[6], double const rra[6]) noexcept {
  Bounded b;
  b.v = q[0] * rr[0] + q[3] * rr[1] + q[5] * rr[2] +
        2.0 * (q[1] * rr[3] + q[2] * rr[4] + q[4] * rr[5]);
  b.perm = std::fabs(q[0]) * rr[0] + std::fabs(q[3]) * rr[1] + std::fabs(q[5]) * rr[2] +
           2.0 * (std::fabs(q[1]) * rra[3] + std::fabs(q[2]) * rra[4] +
                  std::fabs(q[4]) * rra[5]);
  return b;
}

// Same as quad_adj, from the products rr[] (entries of r r^T).
inline Bounded quad_m(double const m[6], double const ma[6], double const rr[6],
                      double const rra[6]) noexcept {
  Bounded b;
  b.v = m[0] * rr[0] + m[3] * rr[1] + m[5] * rr[2] +
        2.0 * (m[1] * rr[3] + m[2] * rr[4] + m[4] * rr[5]);
  b.perm = ma[0] * rr[0] + ma[3] * rr[1] + ma[5] * rr[2] +
           2.0 * (ma[1] * rra[3] + ma[2] * rra[4] + ma[4] * rra[5]);
  return b;
}

// tr(adj(A) B) = sum_ij adj(A)_ij B_ij (eq. (O10)).
inline Bounded trace_adj(double const m[6], double const ma[6], Sym3 const &b,
                         Sym3 const &ba) noexcept {
  Bounded t;
  t.v = m[0] * b[0] + m[3] * b[3] + m[5] * b[5] + 2.0 * (m[1] * b[1] + m[2] * b[2] + m[4] * b[4]);
  t.perm = ma[0] * ba[0] + ma[3] * ba[3] + ma[5] * ba[5] +
           2.0 * (ma[1] * ba[1] + ma[2] * ba[2] + ma[4] * ba[4]);
  return t;
}

// Mixed adjugate M = adj(A + B) - adj(A) - adj(B), bilinear in (A, B),
// entries in the order of Sym3 (eq. (O10)); ma[] the same on |A|, |B|.
inline void mixed_adj(Sym3 const &a, Sym3 const &b, Sym3 const &aa, Sym3 const &ba,
                      double m[6], double ma[6]) noexcept {
  m[0] = (a[3] * b[5] + b[3] * a[5]) - 2.0 * (a[4] * b[4]);
  m[1] = (a[2] * b[4] + b[2] * a[4]) - (a[1] * b[5] + b[1] * a[5]);
  m[2] = (a[1] * b[4] + b[1] * a[4]) - (a[2] * b[3] + b[2] * a[3]);
  m[3] = (a[0] * b[5] + b[0] * a[5]) - 2.0 * (a[2] * b[2]);
  m[4] = (a[1] * b[2] + b[1] * a[2]) - (a[0] * b[4] + b[0] * a[4]);
  m[5] = (a[0] * b[3] + b[0] * a[3]) - 2.0 * (a[1] * b[1]);
  ma[0] = (aa[3] * ba[5] + ba[3] * aa[5]) + 2.0 * (aa[4] * ba[4]);
  ma[1] = (aa[2] * ba[4] + ba[2] * aa[4]) + (aa[1] * ba[5] + ba[1] * aa[5]);
  ma[2] = (aa[1] * ba[4] + ba[1] * aa[4]) + (aa[2] * ba[3] + ba[2] * aa[3]);
  ma[3] = (aa[0] * ba[5] + ba[0] * aa[5]) + 2.0 * (aa[2] * ba[2]);
  ma[4] = (aa[1] * ba[2] + ba[1] * aa[2]) + (aa[0] * ba[4] + ba[0] * aa[4]);
  ma[5] = (aa[0] * ba[3] + ba[0] * aa[3]) + 2.0 * (aa[1] * ba[1]);
}

// p(l) from its coefficients P_j in the basis s^(4-j) t^j (eq. (O14)),
// s = 1 - l exact (l on the grid 2^-52 Z), with the bound of (O14) from the
// rounding of the sum and the bounds E_j of the coefficients.
inline Bounded p_bernstein(double l, double const P[5], double const E[5]) noexcept {
  double const sv = 1.0 - l, t = l;
  double const s2 = sv * sv, t2 = t * t;
  double const w0 = s2 * s2, w1 = (s2 * sv) * t, w2 = s2 * t2, w3 = sv * (t2 * t), w4 = t2 * t2;
  Bounded p;
  p.v = (P[0] * w0 + P[1] * w1) + (P[2] * w2 + (P[3] * w3 + P[4] * w4));
  double const s1a = (std::fabs(P[0]) * w0 + std::fabs(P[1]) * w1) +
                     (std::fabs(P[2]) * w2 + (std::fabs(P[3]) * w3 + std::fabs(P[4]) * w4));
  double const s2a = (E[0] * w0 + E[1] * w1) + (E[2] * w2 + (E[3] * w3 + E[4] * w4));
  // Stored so that p.err() = kC * perm + kAbs is the bound of (O14).
  p.perm = (16 * kU * s1a + s2a) * (1.0 + 32 * kU) / kC;
  return p;
}

// Decided verdict (0 or 1) or kUndecided.
constexpr int kUndecided = -1;

// The floating-point filters on inputs in the safe range (eq. (O9)):
// |Q_ij| <= 2^60, |r_i| <= 2^60, r != 0. Returns 0, 1 or kUndecided.
int filters(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, int &st) noexcept {
  double const rr[6] = {r[0] * r[0], r[1] * r[1], r[2] * r[2],
                        r[0] * r[1], r[0] * r[2], r[1] * r[2]};
  double const rra[6] = {rr[0], rr[1], rr[2], std::fabs(rr[3]), std::fabs(rr[4]),
                         std::fabs(rr[5])};
  // --- Separating plane orthogonal to r (eq. (O11)). ---
  // h_i^2 = r^T Q_i r: E1 lies in {x : r.x <= h1}, E2 in {x : r.x >= r.r - h2}.
  Bounded const a1 = quad_q(q1, rr, rra), a2 = quad_q(q2, rr, rra);
  double const h1 = std::sqrt(a1.v + a1.err()), h2 = std::sqrt(a2.v + a2.err());
  double const rdr = rr[0] + rr[1] + rr[2];
  if (rdr >= (h1 + h2) * (1.0 + 32 * kU)) {
    st = kStageSpheres;
    return 0;
  }
  // --- Determinants and adjugates (eq. (O3)). ---
  Sym3 const qa1 = abs3(q1), qa2 = abs3(q2);
  double m1[6], ma1[6], m2[6], ma2[6];
  Bounded const det1 = det_adj(q1, qa1, m1, ma1);
  Bounded const det2 = det_adj(q2, qa2, m2, ma2);
  // c0 = r^T adj Q1 r, c2 = r^T adj Q2 r (eq. (O10)).
  Bounded const c0 = quad_m(m1, ma1, rr, rra), c2 = quad_m(m2, ma2, rr, rra);
  // --- Segment (eq. (O12)): the ray t r leaves E1 at t = s1 = sqrt(det Q1 / c0)
  // and E2 covers t in (1 - s2, 1], s2 = sqrt(det Q2 / c2); s1 + s2 > 1 means
  // a point of the segment lies in both interiors. Certified with lower
  // bounds of the determinants and upper bounds of c0, c2. ---
  {
    double const lo1 = det1.v - det1.err(), lo2 = det2.v - det2.err();
    double const hi1 = c0.v + c0.err(), hi2 = c2.v + c2.err();
    if (lo1 > 0.0 && lo2 > 0.0) {
      double const ssum = std::sqrt(lo1 / hi1) + std::sqrt(lo2 / hi2);
      if (ssum * (1.0 - 16 * kU) > 1.0) {
        st = kStageSpheres;
        return 1;
      }
    }
  }
  // --- Coefficients of p in the basis s^(4-j) t^j, s = 1 - l, t = l
  // (eq. (O10)): P0 = b0, P1 = b0 + b1 - c0, P2 = b1 + b2 - c1,
  // P3 = b2 + b3 - c2, P4 = b3. ---
  Bounded const b1 = trace_adj(m1, ma1, q2, qa2), b2 = trace_adj(m2, ma2, q1, qa1);
  double mm[6], mma[6];
  mixed_adj(q1, q2, qa1, qa2, mm, mma);
  Bounded const c1 = quad_m(mm, mma, rr, rra);
  Bounded const p1{(det1.v + b1.v) - c0.v, (det1.perm + b1.perm) + c0.perm};
  Bounded const p2{(b1.v + b2.v) - c1.v, (b1.perm + b2.perm) + c1.perm};
  Bounded const p3{(b2.v + det2.v) - c2.v, (b2.perm + det2.perm) + c2.perm};
  if (p1.v > p1.err() && p2.v > p2.err() && p3.v > p3.err()) {
    st = kStageFilter;  // (O13): all coefficients positive, p > 0 on [0, 1]
    return 1;
  }
  // --- Minimum of the quartic p (not certified: only chooses l), then
  // p(l) <= -err certifies separation (O4), or a witness at l overlap (O6).
  double const P0 = det1.v, P1 = p1.v, P2 = p2.v, P3 = p3.v, P4 = det2.v;
  // Power basis p(l) = a0 + a1 l + ... + a4 l^4.
  double const k1 = -4.0 * P0 + P1, k2 = 6.0 * P0 - 3.0 * P1 + P2;
  double const k3 = -4.0 * P0 + 3.0 * P1 - 2.0 * P2 + P3;
  double const k4 = P0 - P1 + P2 - P3 + P4;
  double const Pc[5] = {P0, P1, P2, P3, P4};
  double const Ec[5] = {det1.err(), p1.err(), p2.err(), p3.err(), det2.err()};
  double l = to_grid(h1 / (h1 + h2));
  if (!(l > 0.0 && l < 1.0)) l = 0.5;
  double lo = 0.0, hi = 1.0;
  Bounded p = p_bernstein(l, Pc, Ec);
  // Every iterate is a candidate for (O14): a well-separated pair stops at
  // the first l where p <= -bound, long before the minimum is found.
  for (int it = 0; it < 6 && !(p.v <= -p.err()); ++it) {
    double const dp = k1 + l * (2.0 * k2 + l * (3.0 * k3 + l * (4.0 * k4)));
    double const d2p = 2.0 * k2 + l * (6.0 * k3 + l * (12.0 * k4));
    if (dp > 0.0)
      hi = l;
    else
      lo = l;
    double next = l - dp / d2p;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    next = to_grid(next);
    if (!(next > 0.0 && next < 1.0) || next == l) break;
    bool const done = std::fabs(next - l) <= 0x1p-27;  // p(l) within ~u of min
    l = next;
    p = p_bernstein(l, Pc, Ec);
    if (done) break;
  }
  if (p.v <= -p.err()) {
    st = kStageFilter;
    return 0;
  }
  if (p.v > p.err()) {
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
    if (witness_inside(x, r, q1, q2, det1, m1, ma1, det2, m2, ma2)) {
      st = kStageFilter;
      return 1;
    }
  }

  // --- Newton for lambda* with Cholesky, then one certificate. ---
  Sym3 const d = difference(q2, q1);
  l = to_grid(h1 / (h1 + h2));
  if (!(l > 0.0 && l < 1.0)) l = 0.5;
  lo = 0.0;
  hi = 1.0;
  Newton nv;
  for (int it = 0; it < 40; ++it) {
    if (!newton_values(l, r, q1, q2, d, nv)) break;
    // Early separation: f(l) >= 1 at a grid point, certified by p(l) <= 0.
    if (nv.f >= 1.0) {
      Bounded const pl = p_at(l, r, q1, q2);
      if (pl.v <= -pl.err()) {
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
    // Early overlap: well below 1, witness at the current point (eq. (O6)).
    double const est = nv.f + 0.5 * nv.df * (nv.df / -nv.d2f);
    if (est < 0.95 || step <= 0x1p-52) {
      double const nu = 1.0 - l;
      Vec3 x = multiply(q1, nv.s);
      for (int i = 0; i < kDim; ++i) x[i] *= nu;
      if (est < 1.0 && witness_inside(x, r, q1, q2, det1, m1, ma1, det2, m2, ma2)) {
        st = kStageFilter;
        return 1;
      }
      if (step <= 0x1p-52) break;
    }
    if (next == l || hi - lo <= 0x1p-52) break;
    l = next;
  }
  return kUndecided;
}

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
      exact_scale = exact_scale && (q1[i] == 0.0 || std::fabs(q1[i]) >= 0x1p-1022) &&
                    (q2[i] == 0.0 || std::fabs(q2[i]) >= 0x1p-1022);
    }
    for (int i = 0; i < kDim; ++i) {
      r[i] = r_in[i] * sr;
      exact_scale = exact_scale && (r[i] == 0.0 || std::fabs(r[i]) >= 0x1p-1022) &&
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
  // --- Exact stage. ---
  st = kStageExact;
  return overlap_exact(r_in, q1_in, q2_in, verdict);
}

Status overlap_in_range(double const *rp, double const *q1p, double const *q2p,
                        int &verdict) noexcept {
  Vec3 const r = load_vec3(rp);
  Sym3 const q1 = load_sym3(q1p), q2 = load_sym3(q2p);
  if (r[0] == 0.0 && r[1] == 0.0 && r[2] == 0.0) {
    verdict = 1;
    return kOk;
  }
  int st;
  int const v = filters(r, q1, q2, st);
  if (v != kUndecided) {
    verdict = v;
    return kOk;
  }
  return overlap_exact(r, q1, q2, verdict);
}

}  // namespace pw85
