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
constexpr double kAbs = 0x1p-900;

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
  for (int i = 0; i < n; ++i) m = std::fmax(m, std::fabs(x[i]));
  return m;
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
  // Exact scaling (eq. (O1)): Q -> 2^-2k Q, r -> 2^-k r leaves mu^2 unchanged;
  // chosen so that max |Q_ij| < 1. Every scaled value must stay normal (or
  // zero) for the scaling to be exact; otherwise go to the exact stage.
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
  if (exact_scale) {
    // --- Stage 1: spheres (eqs. (O7), (O8)). ---
    double const rr = dot(r, r);
    auto gersh = [](Sym3 const &q) {
      double const a0 = std::fabs(q[0]) + std::fabs(q[1]) + std::fabs(q[2]);
      double const a1 = std::fabs(q[1]) + std::fabs(q[3]) + std::fabs(q[4]);
      double const a2 = std::fabs(q[2]) + std::fabs(q[4]) + std::fabs(q[5]);
      return std::fmax(a0, std::fmax(a1, a2));
    };
    double const big = std::sqrt(gersh(q1)) + std::sqrt(gersh(q2));
    if (rr >= (big * big) * (1.0 + 32 * kU)) {
      st = kStageSpheres;
      verdict = 0;
      return kOk;
    }
    Sym3 const qa1 = abs3(q1), qa2 = abs3(q2);
    double m1[6], ma1[6], m2[6], ma2[6];
    Bounded const det1 = det_adj(q1, qa1, m1, ma1);
    Bounded const det2 = det_adj(q2, qa2, m2, ma2);
    double const lo1 = det1.v - det1.err(), lo2 = det2.v - det2.err();
    if (lo1 > 0.0 && lo2 > 0.0) {
      // lambda_min >= det / (sum of principal 2x2 minors) >= det / (q0 q3 + q0 q5 + q3 q5).
      double const s1 = (q1[0] * q1[3] + q1[0] * q1[5] + q1[3] * q1[5]) * (1.0 + 8 * kU);
      double const s2 = (q2[0] * q2[3] + q2[0] * q2[5] + q2[3] * q2[5]) * (1.0 + 8 * kU);
      double const small = std::sqrt(lo1 / s1) + std::sqrt(lo2 / s2);
      if (rr * (1.0 + 32 * kU) < (small * small) * (1.0 - 32 * kU)) {
        st = kStageSpheres;
        verdict = 1;
        return kOk;
      }
    }

    // --- Stage 2: Newton for lambda*, then one certificate. ---
    Sym3 const d = difference(q2, q1);
    double const h1 = std::sqrt(dot(r, multiply(q1, r)));
    double const h2 = std::sqrt(dot(r, multiply(q2, r)));
    double l = to_grid(h1 / (h1 + h2));
    if (!(l > 0.0 && l < 1.0)) l = 0.5;
    double lo = 0.0, hi = 1.0;
    Newton nv;
    bool ok = true;
    for (int it = 0; it < 40; ++it) {
      if (!newton_values(l, r, q1, q2, d, nv)) {
        ok = false;
        break;
      }
      // Early separation: f(l) >= 1 at a grid point, certified by p(l) <= 0.
      if (nv.f >= 1.0) {
        Bounded const p = p_at(l, r, q1, q2);
        if (p.v <= -p.err()) {
          st = kStageFilter;
          verdict = 0;
          return kOk;
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
        if (est < 1.0 &&
            witness_inside(x, r, q1, q2, det1, m1, ma1, det2, m2, ma2)) {
          st = kStageFilter;
          verdict = 1;
          return kOk;
        }
        if (step <= 0x1p-52) break;
      }
      if (next == l || hi - lo <= 0x1p-52) break;
      l = next;
    }
    (void)ok;
  }
  // --- Stage 3: exact. ---
  st = kStageExact;
  return overlap_exact(r_in, q1_in, q2_in, verdict);
}

}  // namespace pw85
