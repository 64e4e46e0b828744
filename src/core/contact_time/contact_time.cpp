// Certified conservative advancement for the first contact time, then a
// safeguarded Newton refinement of the crossing (docs/contact_time.md
// (T1)-(T8)).
//
// At each t_k: mu^2(t_k) by PW85_METHOD_DEFAULT, with lambda and an error
// bound e_k. Contact is confirmed at t_k when mu^2(t_k) + e_k <= 1 (T6).
// Otherwise u = s = Q(lambda)^{-1} r12 gives the lower bound g of (T5) at
// the level m = kLevel < 1 and t_{k+1} = t_k + tau, tau the first zero of g:
// mu >= kLevel on [t_k, t_{k+1}]. Near a crossing g is the tangent of mu - m
// (u is the maximiser of (T2), D0' its derivative: envelope theorem), so the
// steps converge as Newton's method from the safe side; near a minimum of
// mu^2 above kLevel^2 the gap g(0) stays away from 0 and so do the steps.
// Once confirmed, the crossing of mu^2 = 1 is refined inside the bracket
// left by the advancement (T8).
#include "contact_time/contact_time.hpp"

#include <cmath>
#include <limits>

#include "contact/contact.hpp"
#include "contact_time/axes.hpp"
#include "contact_time/minorant.hpp"
#include "contact_time/motion.hpp"
#include "derivatives/derivatives.hpp"
#include "eval/f_dd.hpp"
#include "common/scaling.hpp"

namespace pw85 {

namespace {

// Level of the advancement (T6): the steps certify mu >= kLevel, i.e.
// mu^2 >= kLevel^2 = 1 - 2.27e-13, 22 times DEFAULT's documented accuracy
// (1e-14) below 1. Where contact is not confirmed (mu^2 > 1 - 2e-14), the
// gap N0 - kLevel D0 >= ~1e-13 D0 is 75 times its rounding margin (12 u D0,
// minorant.hpp): the steps never shrink to zero at a minimum of mu^2.
constexpr double kLevel = 1.0 - 0x1p-43;
// The refinement (T8) stops when its Newton step or its bracket is below
// kRefineTol t_max, and after kRefineMaxIter evaluations (bisection halves
// the bracket at least every second one).
constexpr double kRefineTol = 1e-12;
constexpr int kRefineMaxIter = 100;

RateBounds rate_bounds(AxisBounds const &a1, Vec3 const &w1, AxisBounds const &a2,
                       Vec3 const &w2) noexcept {
  RateBounds b{0.0, 0.0, {0.0, 0.0}, {0.0, 0.0}, {a1.a_min, a2.a_min}};
  AxisBounds const *a[2] = {&a1, &a2};
  Vec3 const *w[2] = {&w1, &w2};
  for (int i = 0; i < 2; ++i) {
    double const wn = norm(*w[i]);
    if (wn == 0.0) continue;
    double const hi = a[i]->a_max, lo = a[i]->a_min;
    b.om_i[i] = wn * (hi - lo) * (1.0 + 1e-12);          // (T3)
    b.c_i[i] = wn * wn * ((hi - lo) * (hi + lo)) * (1.0 + 1e-12);
    b.om += b.om_i[i];
    b.Om += b.c_i[i] / lo;                                // (T4)
  }
  b.om *= 1.0 + 1e-12;
  b.Om *= 1.0 + 1e-12;
  return b;
}

// s = Q(lambda)^{-1} r12 by a Cholesky solve in double.
bool direction(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, double lambda, Vec3 &s) noexcept {
  CholInv c;
  if (!chol_inv(interpolate(q1, q2, lambda), c)) return false;
  s = chol_solve(c, r);
  return true;
}

// Step of the Lipschitz bound (T7), used when no direction u gives g(0) > 0:
// with mu_lo <= mu(t_k), phi' >= -(|v12| + phi om) / rho for the maximiser u
// at t_k, rho = a_min,1 + a_min,2 <= D, so phi >= level for
// tau <= (rho / om) ln((|v12| + mu_lo om) / (|v12| + level om)).
double lipschitz_step(double mu_lo, double level, double vn, double om, double rho) noexcept {
  if (!(mu_lo > level)) return 0.0;
  if (om > 0.0) return rho / om * std::log1p(om * (mu_lo - level) / (om * level + vn));
  return vn > 0.0 ? rho * (mu_lo - level) / vn : std::numeric_limits<double>::infinity();
}

// The motion of the pair in the rescaled lengths (T1).
struct Motion {
  Vec3 r0, v, w1, w2;
  Sym3 a1, a2;
};

// One evaluation at t: f = mu^2 - 1 of DEFAULT, [lo2, hi2] the bounds of the
// exact mu^2 from its error bound (documented accuracy 1e-14 relative, or the
// method's estimate when larger), the direction and minorant of (T5) at the
// level kLevel, and df = dmu^2/dt = 2 mu (v12.u - mu D0') / D0 (T8; envelope
// theorem, u the maximiser of (T2)), NaN when no minorant.
struct Sample {
  double t, f, lo2, hi2, df;
  bool ok;  // m holds a minorant with g(0) > 0
  Minorant m;
  MethodResult mr;
};

// Returns false when DEFAULT fails; counts its evaluations.
bool sample(Motion const &mo, double t, Sample &p, int &evaluations) noexcept {
  Vec3 const r = position(mo.r0, mo.v, t);
  Sym3 const p1 = rotated(mo.a1, mo.w1, t), p2 = rotated(mo.a2, mo.w2, t);
  Status const s = contact_method(kMethodDefault, r, p1, p2, p.mr);
  ++evaluations;
  // kRange: mu^2 beyond the double range, written rounded (+inf or tiny),
  // still decides; lambda is that of the rescaled problem.
  if (s != kOk && s != kInaccurate && s != kRange) return false;
  double const mu2 = p.mr.mu2;
  p.t = t;
  p.f = mu2 - 1.0;
  p.lo2 = std::fmin(mu2 * (1.0 - kDefaultRelAccuracy), mu2 - p.mr.mu2_error);
  p.hi2 = std::fmax(mu2 * (1.0 + kDefaultRelAccuracy), mu2 + p.mr.mu2_error);
  Vec3 dir;
  p.ok = direction(r, p1, p2, p.mr.lambda, dir) &&
         minorant(mo.r0, mo.v, t, p1, mo.w1, p2, mo.w2, dir, kLevel, p.m);
  if (!(p.ok && p.m.gap > 0.0) && p.hi2 > 1.0) {
    // s accurate to the last bits: lambda and s of the derivatives (E7).
    Derivatives d;
    ++evaluations;
    p.ok = contact_derivatives(r, p1, p2, d) != kNoConvergence &&
           minorant(mo.r0, mo.v, t, p1, mo.w1, p2, mo.w2,
                    Vec3{{d.d_r12[0], d.d_r12[1], d.d_r12[2]}}, kLevel, p.m);
  }
  p.df = std::numeric_limits<double>::quiet_NaN();
  if (p.ok) {
    double const mu = std::sqrt(mu2), d0 = p.m.h[0] + p.m.h[1];
    p.df = 2.0 * mu * (p.m.n1 - mu * p.m.d1) / d0;
    p.ok = p.m.gap > 0.0;
  }
  return true;
}

// Newton's step on mu(t) - 1 = f / (1 + mu) from f = mu^2 - 1 and
// df = dmu^2/dt (T8). Without rotation mu(t) is convex (a gauge along a
// line; linear when the line passes through 0): from the side where mu > 1
// the steps do not overshoot.
double newton_step(double f, double df) noexcept {
  double const mu = std::sqrt(1.0 + f);
  return -2.0 * mu * f / ((1.0 + mu) * df);
}

// mu^2(t) - 1 beyond double precision (T8), for the last steps of the
// refinement: lambda refined by pw85_contact_derivatives' Newton steps on
// f' = 0 in double-double (E7), then f(lambda) = lambda (1 - lambda) r^T s
// with s = Q(lambda)^{-1} r solved in double-double (f_dd.hpp) at
// r = r_hi + r_lo, the position in double-double (r^T Q^{-1} r gains
// 2 r_lo.s to first order). Its error is that of Q_i(t) (exact without
// rotation) and a few u^2 cond(Q(lambda)), where DEFAULT's value is only
// good to ~ulp(1) = 2.2e-16, i.e. a time error ulp(1) / |dmu^2/dt|. df =
// dmu^2/dt = d_r12.v12 + d_theta1.w1 + d_theta2.w2 (derivatives.md).
bool precise(Motion const &mo, double t, double &f, double &df, int &evaluations) noexcept {
  using namespace dd;
  Vec3 rh, rl;
  for (int i = 0; i < kDim; ++i) {
    DD const x = add(two_prod<false>(t, mo.v[i]), mo.r0[i]);
    rh[i] = x.hi;
    rl[i] = x.lo;
  }
  Sym3 const p1 = rotated(mo.a1, mo.w1, t), p2 = rotated(mo.a2, mo.w2, t);
  Derivatives d;
  ++evaluations;
  if (contact_derivatives(rh, p1, p2, d) == kNoConvergence) return false;
  DD s[kDim], phi;
  if (!solve_dd_impl<isa::kStaticFma>(d.lambda, rh, p1, p2, s, phi)) return false;
  DD const p = mul<false>(two_sum(1.0, -d.lambda), d.lambda);
  double const lo = 2.0 * (rl[0] * s[0].hi + rl[1] * s[1].hi + rl[2] * s[2].hi);
  f = to_double(add(add(mul<false>(p, phi), -1.0), p.hi * lo));
  df = dot(Vec3{{d.d_r12[0], d.d_r12[1], d.d_r12[2]}}, mo.v) +
       dot(Vec3{{d.d_theta1[0], d.d_theta1[1], d.d_theta1[2]}}, mo.w1) +
       dot(Vec3{{d.d_theta2[0], d.d_theta2[1], d.d_theta2[2]}}, mo.w2);
  return std::isfinite(f) && std::isfinite(df);
}

// The crossing of mu^2 = 1 in [a, b], f(a) > 0 >= f(b) (T8). First on
// DEFAULT's values: Newton's step from the last sample when it stays inside
// the bracket, else regula falsi, else (or when the bracket did not halve)
// bisection, until the step or the bracket is below tol: c. Then, where
// DEFAULT's error e bounds the time only to e / |dmu^2/dt| > tol, Newton
// steps on precise() (at most kPreciseSteps) from c, kept within
// 4 e / |dmu^2/dt| of c and in [0, t_k] (t_k, the time contact was
// confirmed, is before any time with mu^2 < kLevel^2); c stands when such
// an evaluation fails. Writes the crossing to t; false when a DEFAULT
// evaluation fails or the budget runs out in the first part.
constexpr int kPreciseSteps = 4;

bool refine(Motion const &mo, double tol, double t_k, Sample a, Sample b, double &t,
            int &evaluations) noexcept {
  Sample x = a;
  double width = b.t - a.t, c = b.t;
  for (int it = 0;; ++it) {
    double const secant = a.t + (b.t - a.t) * (a.f / (a.f - b.f));
    if (!(b.t - a.t > tol) || it == kRefineMaxIter) {
      c = std::fmin(std::fmax(secant, a.t), b.t);
      break;
    }
    c = x.t + newton_step(x.f, x.df);
    bool const newton = c > a.t && c < b.t;
    if (newton && std::fabs(c - x.t) <= tol) break;
    if (!newton) c = secant;
    if (!(c > a.t && c < b.t) || (it % 2 == 1 && b.t - a.t > 0.5 * width))
      c = a.t + 0.5 * (b.t - a.t);
    if (it % 2 == 1) width = b.t - a.t;
    if (evaluations >= kContactTimeMaxEval || !sample(mo, c, x, evaluations)) return false;
    if (x.f > 0.0) a = x;
    else b = x;
  }
  double const e = std::fmax(x.hi2 - 1.0 - x.f, 1.0 + x.f - x.lo2);
  if (!(e > tol * std::fabs(x.df))) {  // DEFAULT resolves the crossing to tol
    t = c;
    return true;
  }
  double const w = 4.0 * e / std::fabs(x.df);
  double const lo = std::fmax(c - w, 0.0), hi = std::fmin(c + w, t_k);
  t = c;
  for (int k = 0; k < kPreciseSteps; ++k) {
    double f, df;
    if (evaluations >= kContactTimeMaxEval || !precise(mo, c, f, df, evaluations)) break;
    double const next = std::fmin(std::fmax(c + newton_step(f, df), lo), hi);
    if (std::isnan(next)) break;
    bool const done = !(std::fabs(next - c) > tol);
    t = c = next;
    if (done) break;
  }
  return true;
}

}  // namespace

Status contact_time(Vec3 const &r12, Vec3 const &v12, Sym3 const &q1, Vec3 const &w1,
                    Sym3 const &q2, Vec3 const &w2, double t_max,
                    ContactTimeResult &res) noexcept {
  double const inf = std::numeric_limits<double>::infinity();
  res.t = 0.0;
  res.evaluations = 0;
  // Lengths in units of 2^e, 2^e near the largest semi-axis: mu and t are
  // unchanged by r -> 2^-e r, v -> 2^-e v, Q -> 2^-2e Q (exact).
  double qmax = 0.0;
  for (int i = 0; i < kSym; ++i) qmax = std::fmax(qmax, std::fmax(std::fabs(q1[i]), std::fabs(q2[i])));
  int const eq = std::ilogb(qmax);
  int const e = (eq - (eq & 1)) / 2;  // floor(eq / 2): inputs scaled by 2^k give 2^(e + k)
  Motion mo;
  mo.w1 = w1;
  mo.w2 = w2;
  scale_pair(r12, q1, q2, -e, -2 * e, mo.r0, mo.a1, mo.a2);
  scale_by_power_of_two(v12.x, mo.v.x, kDim, -e);
  double const vn = norm(mo.v);
  if (!std::isfinite(norm(mo.r0) + t_max * vn) || !std::isfinite(t_max * (norm(w1) + norm(w2))))
    return kInvalidArgument;
  AxisBounds const ax1 = axis_bounds(mo.a1), ax2 = axis_bounds(mo.a2);
  RateBounds const b = rate_bounds(ax1, w1, ax2, w2);
  double const rho = ax1.a_min + ax2.a_min;

  // above: the last sample with mu^2 > 1; below: the first one after it
  // (has_below), the bracket of (T8).
  Sample p{}, above{}, below{};
  bool has_below = false;
  double t = 0.0;
  for (;;) {
    if (res.evaluations >= kContactTimeMaxEval || !sample(mo, t, p, res.evaluations)) {
      res.t = t;
      return kNoConvergence;
    }
    if (t == 0.0 && p.f <= 0.0) {  // overlapping or touching at t = 0
      res.t = 0.0;
      return kOk;
    }
    if (p.f > 0.0) {
      above = p;
      has_below = false;
    } else if (!has_below) {
      below = p;
      has_below = true;
    }
    if (p.hi2 <= 1.0) {  // contact confirmed (T6)
      if (!refine(mo, kRefineTol * t_max, t, above, below, res.t, res.evaluations)) {
        res.t = t;  // [0, t_k] is certified
        return kNoConvergence;
      }
      return kOk;
    }
    double const tau = p.ok ? safe_step(p.m, b)
                            : lipschitz_step(std::sqrt(p.lo2), kLevel, vn, b.om, rho);
    if (!(tau > 0.0)) {  // NaN or 0: no bound
      res.t = t;
      return kNoConvergence;
    }
    if (tau > t_max - t) {
      res.t = inf;
      return kOk;
    }
    double next = t + tau;
    if (next - t > tau) next = std::nextafter(next, 0.0);  // rounded past the certified step
    // A step below the resolution of t (a crossing steeper than mu^2 changes
    // across one ulp of t): the next double, evaluated in turn (T6).
    if (next == t) next = std::nextafter(t, inf);
    t = next;
  }
}

}  // namespace pw85
