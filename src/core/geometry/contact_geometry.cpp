// Contact geometry (docs/contact_geometry.md, eqs. (G1)-(G10)).
//
// From the maximiser lambda of f (pw85 documentation, chapter 3, eqs. (9a),
// (11), (13)-(14)): with Q = (1 - lambda) Q1 + lambda Q2 and s = Q^{-1} r,
//   x0 = (1 - lambda) Q1 s                     (G1, contact point - c1)
//   n  = s / |s|                               (G2, normal, since the
//        gradient of x^T Q1^{-1} x at x0 is 2 (1 - lambda) s)
//   dca = |r| / mu                             (G4)
//   depth = dca - |r| = |r| (1 - mu^2) / (mu (1 + mu))   (G5)
//   depth_n = depth (r/|r|) . n                (G6)
//
// Accuracy (docs/contact_geometry.md, section "Algorithm"):
//  fast path: s by Cholesky in double, one step of iterative refinement with
//    the residual r - Q s in double-double (G8); the size of the correction
//    estimates the error of the double solve, and with the amplification of
//    that error by Q1 in x0 (G1) and f'(lambda) = (1 - lambda)^2 s^T Q1 s -
//    lambda^2 s^T Q2 s (G9: zero at the exact maximiser) it decides whether
//    x0 and n are accurate to kTol; most pairs stop here;
//  slow path: Newton steps on f'(lambda) = 0 with f' in double-double and
//    the double f'' as slope (G10), then s, x0, n in double-double
//    (f_dd.hpp, contact_point_dd_impl).
#include <cmath>

#include "common/fp.hpp"
#include "common/magnitude.hpp"
#include "contact/contact.hpp"
#include "geometry/contact_geometry.hpp"
#include "eval/f_dd.hpp"
#include "eval/f_ldl.hpp"
#include "common/scaling.hpp"

namespace pw85 {

namespace {
// Target relative accuracy of x0 and n (and of |f'(lambda)| / mu^2) on the
// fast path; the slow path is taken when the estimate exceeds it.
constexpr double kTol = 0x1p-43;  // 1.1e-13
constexpr int kMaxNewton = 6;

inline double max_abs(Vec3 const &v) noexcept {
  return std::fmax(std::fabs(v[0]), std::fmax(std::fabs(v[1]), std::fabs(v[2])));
}

inline Vec3 abs_multiply(Sym3 const &a, Vec3 const &x) noexcept {
  Sym3 b;
  for (int i = 0; i < kSym; ++i) b[i] = std::fabs(a[i]);
  Vec3 y;
  for (int i = 0; i < kDim; ++i) y[i] = std::fabs(x[i]);
  return multiply(b, y);
}

// What the fast path learnt, for the slow path: the Newton-corrected lambda
// (start), the slope f'' (0 if unknown) and the rates |x0'| / |x0|,
// |s'| / |s| that turn a step in lambda into relative changes of x0 and n.
struct FastInfo {
  double start, slope = 0.0, rate = 0.0;
};

// Fast path (G8, G9, G11): s by Cholesky in double refined once with the
// double-double residual, kept as the unevaluated sum s0 + delta; x0 and
// f'(lambda) from it in double-double (refined_point_impl, f_dd.hpp); then
// lambda is corrected to first order by one Newton step on f' = 0 and x0, s
// moved along their derivatives (G11). Returns true, with lambda, x0 and n,
// when the estimated relative errors of x0 and n are below kTol; false sends
// the pair to the slow path.
bool fast_point(double &lambda_io, Vec3 const &r, Sym3 const &q1, Sym3 const &q2, Vec3 &x0,
                Vec3 &n, FastInfo &info) noexcept {
  double const lambda = lambda_io;
  double const nu = 1.0 - lambda;
  info.start = lambda;
  if (!(lambda > 0.0 && nu > 0.0)) return false;
  CholInv c;
  if (!chol_inv(interpolate(q1, q2, lambda), c)) return false;
  Sym3 const &l = c.l;
  Vec3 const s0 = chol_solve(c, r);
  Vec3 const delta = chol_solve(c, residual_dd(lambda, r, q1, q2, s0));
  double const smax = max_abs(s0);
  // Relative error of the double solve, estimated by the correction (G8),
  // and of s0 + delta: the correction's own relative error (~es, or the
  // condition estimate from the Cholesky diagonal times u if larger) times es.
  double const es = max_abs(delta) / smax;
  if (!(es <= 1e-6)) return false;
  double const dmin = std::fmin(l[0], std::fmin(l[3], l[5]));
  double const dmax = std::fmax(l[0], std::fmax(l[3], l[5]));
  double const kappa_u = (dmax / dmin) * (dmax / dmin) * kU;
  double const es1 = 4.0 * es * std::fmax(es, kappa_u) + 0x1p-100;
  Vec3 xb, t2;  // (1 - lambda) Q1 (s0 + delta), Q2 (s0 + delta)
  double const fp = refined_point_dd(lambda, q1, q2, s0, delta, xb, t2);
  Vec3 s, t1;
  for (int i = 0; i < kDim; ++i) {
    s[i] = s0[i] + delta[i];
    t1[i] = xb[i] / nu;
  }
  Vec3 const sa{{std::fabs(s[0]), std::fabs(s[1]), std::fabs(s[2])}};
  Vec3 const a1 = abs_multiply(q1, s), a2 = abs_multiply(q2, s);
  // Error bound of f'(lambda) (G9): error of s0 + delta (first order), the
  // double-double evaluation, the final rounding.
  double const big = nu * nu * dot(a1, sa) + lambda * lambda * dot(a2, sa);
  double const efp = (6.0 * es1 + 0x1p-100) * big + 2.0 * kU * std::fabs(fp);
  // Derivatives (G11): s' = -v with v = Q^{-1} D s, D = Q2 - Q1;
  // f'' = -2 phi + 2 (1 - 2 lambda) phi' + lambda (1 - lambda) phi'',
  // phi = r.s, phi' = -s.D s, phi'' = 2 (D s).v; x0' = -Q1 s - (1 - lambda) Q1 v.
  Vec3 ds;
  for (int i = 0; i < kDim; ++i) ds[i] = t2[i] - t1[i];
  Vec3 const v = chol_solve(c, ds);
  double const d2f = -2.0 * dot(r, s) - 2.0 * (1.0 - 2.0 * lambda) * dot(s, ds) +
                     2.0 * lambda * nu * dot(ds, v);
  if (!(d2f < 0.0)) return false;
  double const dl = -fp / d2f;
  double const edl = efp / -d2f;
  if (!(std::fabs(dl) <= 1e-3 * (lambda < nu ? lambda : nu))) return false;
  Vec3 const q1v = multiply(q1, v);
  info.slope = d2f;
  Vec3 xd;
  for (int i = 0; i < kDim; ++i) xd[i] = -t1[i] - nu * q1v[i];
  double const xmax = max_abs(xb), xdmax = max_abs(xd), vrel = max_abs(v) / smax;
  info.start = lambda + dl;
  info.rate = std::fmax(xdmax / xmax, vrel);
  // x0: error of s0 + delta amplified by Q1 (|Q1||s| / |Q1 s|), roundings,
  // error of the step dl, second-order term of the step (|x0''| ~
  // 2 |x0'| |v| / |s|), first-order error of v (relative es) times the step.
  double const step = edl + 2.0 * vrel * dl * dl + es * std::fabs(dl);
  double const ex = (nu * max_abs(a1) / xmax) * es1 + 3.0 * kU + xdmax * step / xmax;
  double const en = es1 + 4.0 * kU + vrel * step;
  if (!(ex <= kTol && en <= kTol)) return false;
  for (int i = 0; i < kDim; ++i) {
    x0[i] = xb[i] + xd[i] * dl;
    s[i] -= v[i] * dl;
  }
  double const ns = std::sqrt(dot(s, s));
  for (int i = 0; i < kDim; ++i) n[i] = s[i] / ns;
  lambda_io = lambda + dl;
  return true;
}

// mu2, lambda, x0 and n for r and Q1, Q2 in the range of contact_geometry's
// scaling (below); g's other fields untouched.
Status contact_point(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                     ContactGeometry &g) noexcept {
  // PW85_METHOD_DEFAULT (src/core/contact/default.hpp, docs/methods.md).
  MethodResult res;
  Status status = contact_method(kMethodDefault, r, q1, q2, res);
  double lambda = res.lambda;
  if (!(lambda >= 0.0 && lambda <= 1.0)) return kNoConvergence;
  double const mu2 = res.mu2;  // the method's value (accurate to its documented tolerance)
  Vec3 x0, n;
  FastInfo info;
  if (!fast_point(lambda, r, q1, q2, x0, n, info)) {
    // Slow path (G10): Newton steps on f' = 0 with f' in double-double and
    // the slope f'' in double (its relative error only slows convergence),
    // from the fast path's first-order lambda; stop when the next step would
    // move x0 and n by less than kTol / 1024 relative.
    lambda = info.start;
    double slope = info.slope, rate = info.rate;
    FEval e;
    if (!(slope < 0.0) || !(rate > 0.0)) {
      if (f_eval(lambda, r, q1, q2, difference(q2, q1), e) && e.d2f < 0.0) {
        slope = e.d2f;
        rate = HUGE_VAL;  // unknown: iterate until lambda stops moving
      }
    }
    double df = 0.0;
    if (!contact_point_dd(lambda, r, q1, q2, x0, n, df)) {
      lambda = res.lambda;
      if (!contact_point_dd(lambda, r, q1, q2, x0, n, df)) return kNoConvergence;
    }
    if (!(slope < 0.0)) {
      // No usable double f'': secant of the double-double f' over a short step.
      double const h = 0x1p-20 * (lambda < 0.5 ? lambda : 1.0 - lambda);
      Vec3 x1, n1;
      double df1;
      if (h > 0.0 && contact_point_dd(lambda + h, r, q1, q2, x1, n1, df1)) {
        double const secant = (df1 - df) / h;
        if (secant < 0.0) slope = secant;
      }
      rate = HUGE_VAL;
    }
    for (int k = 0; k < kMaxNewton && slope < 0.0; ++k) {
      double const step = -df / slope;
      if (std::fabs(step) * rate <= 0x1p-10 * kTol) break;
      double const next = lambda + step;
      if (!(next > 0.0 && next < 1.0) || next == lambda) break;
      Vec3 x1, n1;
      double df1;
      if (!contact_point_dd(next, r, q1, q2, x1, n1, df1)) break;
      // The secant slope of the double-double f' corrects an inaccurate
      // double f'' (Q(lambda) too ill-conditioned for the double solve).
      double const secant = (df1 - df) / (next - lambda);
      if (secant < 0.0) slope = secant;
      if (std::fabs(df1) >= std::fabs(df)) continue;  // no progress: keep the better point
      lambda = next;
      x0 = x1;
      n = n1;
      df = df1;
    }
  }
  g.mu2 = mu2;
  g.lambda = lambda;
  for (int i = 0; i < kDim; ++i) {
    g.x0[i] = x0[i];
    g.n[i] = n[i];
  }
  return status;
}

}  // namespace

Status contact_geometry(Vec3 const &r_in, Sym3 const &q1_in, Sym3 const &q2_in,
                        ContactGeometry &g) noexcept {
  // NaN until computed: an early kNoConvergence leaves no garbage.
  double const nan = std::nan("");
  g = ContactGeometry{nan, nan, {nan, nan, nan}, {nan, nan, nan}, nan, nan, nan};
  // Exact rescaling by powers of two (G12): r' = 2^-er r, Q' = 2^-eq Q with
  // eq even leave lambda and n unchanged and give mu2 = 2^(2 er - eq) mu2',
  // x0 = 2^er x0' (G1), dca = 2^(eq/2) dca' (G4). Done when r or the
  // matrices lie outside (kSafeLo, kSafeHi), where the intermediate s^T Q s
  // ~ |r|^2 / |Q| could overflow or underflow.
  double const rmax = max_abs(r_in.x, kDim), qm1 = max_abs(q1_in.a, kSym),
               qm2 = max_abs(q2_in.a, kSym), qmax = qm1 > qm2 ? qm1 : qm2;
  bool const scale = !(rmax > kSafeLo && rmax < kSafeHi && qmax > kSafeLo && qmax < kSafeHi);
  int er = 0, eq = 0;
  Vec3 r = r_in;
  Sym3 q1 = q1_in, q2 = q2_in;
  if (scale) {
    std::frexp(rmax, &er);
    std::frexp(qmax, &eq);
    eq += eq & 1;  // even (also for negative eq: two's complement)
    scale_pair(r, q1, q2, -er, -eq, r, q1, q2);
  }
  Status status = contact_point(r, q1, q2, g);
  if (!(g.lambda >= 0.0 && g.lambda <= 1.0)) return status;
  // In the scaled frame: |r'|, mu' and dca' = |r'| / mu' (G4).
  double const nr = std::sqrt(dot(r, r));
  double const mu_s = std::sqrt(g.mu2);
  double const dca_s = nr / mu_s;
  // r'.n / |r'|: the cosine of (G6), scale-free.
  double const cosine = (r[0] * g.n[0] + r[1] * g.n[1] + r[2] * g.n[2]) / nr;
  int const emu = er - eq / 2;  // mu = 2^emu mu'
  double const mu2 = scale ? std::ldexp(g.mu2, 2 * emu) : g.mu2;
  double const mu = scale ? std::ldexp(mu_s, emu) : mu_s;
  g.mu2 = mu2;
  if (scale)
    scale_by_power_of_two(g.x0, kDim, er);
  g.dca = scale ? std::ldexp(dca_s, eq / 2) : dca_s;
  // depth = dca - |r| = dca (1 - mu) (G5): as dca (1 - mu^2) / (1 + mu)
  // without cancellation near tangency; for mu >= 2, where mu^2 may
  // overflow, as dca - |r| (no cancellation there).
  if (mu < 2.0)
    g.depth = g.dca * ((1.0 - mu2) / (1.0 + mu));
  else
    g.depth = g.dca - (scale ? std::ldexp(nr, er) : nr);
  g.depth_n = g.depth * cosine;
  // A result out of the range of double (status.hpp kRange): mu2, dca or
  // the largest |x0_i| above DBL_MAX or below DBL_MIN, or |depth| above
  // DBL_MAX.
  double const xmax = max_abs(Vec3{{g.x0[0], g.x0[1], g.x0[2]}});
  auto out = [](double v) { return !(v >= kMinNormal && v <= kMaxDouble); };
  if (status == kOk && (out(mu2) || out(g.dca) || out(xmax) || !(std::fabs(g.depth) <= kMaxDouble)))
    status = kRange;
  return status;
}

}  // namespace pw85
