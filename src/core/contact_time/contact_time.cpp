// Certified conservative advancement for the first contact time, then a
// refinement of the crossing on a certified bracket (docs/contact_time.md
// (T1)-(T10)).
//
// At each t_k: mu^2(t_k) by PW85_METHOD_DEFAULT on r12(t_k), Q_i(t_k)
// rounded to double, with lambda and bounds [lo, hi] on the exact mu^2:
// DEFAULT's error bound plus the first-order effect of the rounding of its
// inputs, or the enclosure of the exact motion (enclosure.hpp, (T9), (T10))
// where those do not decide. Contact is confirmed at t_k when hi <= 1 (T6).
// Otherwise u = s = Q(lambda)^{-1} r12 gives the lower bound g of (T5) at
// the level m = kLevel < 1, formed for the exact Q_i(t_k) (minorant.hpp),
// and t_{k+1} = t_k + tau, tau the first zero of g: mu >= kLevel on
// [t_k, t_{k+1}]. Near a crossing g is the tangent of mu - m (u is the
// maximiser of (T2), D0' its derivative: envelope theorem), so the steps
// converge as Newton's method from the safe side; near a minimum of mu^2
// above kLevel^2 the gap g(0) stays away from 0 and so do the steps. Once
// confirmed, the crossing of mu^2 = 1 is refined inside the bracket left by
// the advancement (T8).
#include "contact_time/contact_time.hpp"

#include <cmath>
#include <limits>

#include "contact/contact.hpp"
#include "contact_time/axes.hpp"
#include "contact_time/minorant.hpp"
#include "contact_time/enclosure.hpp"
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
// The refinement (T8) stops on a certified bracket of width kRefineTol t_max.
// Newton's steps must halve, else regula falsi keeping a tenth of the
// bracket on each side, else bisection; kRefineMaxIter is a safeguard.
constexpr double kRefineTol = 1e-10;
constexpr int kRefineMaxIter = 400;
// DEFAULT's value on the rounded inputs decides the sign of mu^2 - 1 only
// where the first-order bound of the input perturbation (T9) stays below
// this relative size; elsewhere the enclosure decides.
constexpr double kFirstOrderTrust = 1e-8;
// Largest semi-axis ratio (bounds of axes.hpp) of either ellipsoid: the
// enclosure's relative floor 64 u^2 (k1 + k2), k_i the squared ratios, is
// then below 6.3e-16, its width at mu^2 ~ 1 (8 times the floor) below
// 5e-15, a 45th of the band 1 - kLevel^2 = 2.27e-13 it must resolve.
constexpr double kMaxAxisRatio = 1e7;

// Constants of (T3), (T4), (T3') for the pair.
RateBounds rate_bounds(AxisBounds const &a1, Vec3 const &w1, double cn1, AxisBounds const &a2,
                       Vec3 const &w2, double cn2) noexcept {
  RateBounds b{0.0, 0.0, {0.0, 0.0}, {0.0, 0.0}, {a1.a_min, a2.a_min}};
  AxisBounds const *a[2] = {&a1, &a2};
  Vec3 const *w[2] = {&w1, &w2};
  double const cn[2] = {cn1, cn2};
  for (int i = 0; i < 2; ++i) {
    double const wn = norm(*w[i]);
    if (wn == 0.0) continue;
    double const hi = a[i]->a_max, lo = a[i]->a_min;
    // (T3), (T3'): |dh/dt| <= min(|w| (a_max - a_min), ||[W, Q]|| / (2 a_min))
    b.om_i[i] = std::fmin(wn * (hi - lo), cn[i] / (2.0 * lo)) * (1.0 + 1e-12);
    // (T4), (T4'): |q''| / 2 <= min(|w|^2 (a_max^2 - a_min^2), |w| ||[W, Q]||)
    b.c_i[i] = std::fmin(wn * wn * ((hi - lo) * (hi + lo)), wn * cn[i]) * (1.0 + 1e-12);
    b.om += b.om_i[i];
    b.Om += b.c_i[i] / lo;
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

// The motion of the pair in the rescaled lengths (T1), with the constants
// of the bounds: semi-axis bounds, Frobenius norms of Q_i and bounds on
// ||[W_i, Q_i]||.
struct Motion {
  Vec3 r0, v, w1, w2;
  Sym3 a1, a2;
  AxisBounds ax1, ax2;
  double qf1, qf2, cn1, cn2;
  bool rotating;  // w1 or w2 nonzero
};

// One evaluation at t: DEFAULT on r(t) and Q_i(t) rounded to double, f its
// mu^2 - 1; [lo, hi] bounds of the exact mu^2(t) - 1: DEFAULT's error bound
// (documented accuracy 1e-14 relative, or the method's estimate when larger)
// plus the first-order effect of the rounding of its inputs (T9), or, when
// those do not decide (decide) or no step can be certified, the enclosure of
// the exact motion (enclosure.hpp). The direction and minorant of (T5) at
// the level kLevel; df = dmu^2/dt = 2 mu (v12.u - mu D0') / D0 (T8; envelope
// theorem, u the maximiser of (T2)), NaN when no minorant; mu_lo a
// certified lower bound of mu(t).
struct Sample {
  double t, f, lo, hi, df, mu_lo;
  bool ok;         // m holds a minorant with g(0) > 0
  bool enclosed;   // [lo, hi] from the enclosure
  Minorant m;
};

bool minorant_at(Motion const &mo, ExactPose const *pose, double t, Vec3 const &s, Minorant &m) noexcept {
  if (pose == nullptr) return minorant(mo.r0, mo.v, t, mo.a1, mo.w1, mo.a2, mo.w2, s, kLevel, m);
  return minorant_rotating(*pose, mo.v, mo.a1, mo.w1, mo.a2, mo.w2, mo.ax1, mo.ax2, s, kLevel, m);
}

// Whether r0 + t v is a double in every component (no rounding by
// position()).
bool r_is_exact(Vec3 const &r0, Vec3 const &v, double t) noexcept {
  for (int i = 0; i < kDim; ++i)
    if (dd::add(dd::two_prod<false>(t, v[i]), r0[i]).lo != 0.0) return false;
  return true;
}

// Returns false when DEFAULT fails; counts its evaluations (the enclosure
// counts as one more).
bool sample(Motion const &mo, double t, bool decide, Sample &p, int &evaluations) noexcept {
  double const inf = std::numeric_limits<double>::infinity();
  Vec3 const r = position(mo.r0, mo.v, t);
  Sym3 const p1 = rotated(mo.a1, mo.w1, t), p2 = rotated(mo.a2, mo.w2, t);
  MethodResult mr;
  Status const s = contact_method(kMethodDefault, r, p1, p2, mr);
  ++evaluations;
  // kRange: mu^2 beyond the double range, written rounded (+inf or tiny),
  // still decides; lambda is that of the rescaled problem.
  if (s != kOk && s != kInaccurate && s != kRange) return false;
  double const mu2 = mr.mu2, lam = mr.lambda;
  p.t = t;
  p.f = mu2 - 1.0;
  p.enclosed = false;
  Vec3 dir;
  bool const have_dir = direction(r, p1, p2, lam, dir);
  // (T9) first-order effect of the rounding of DEFAULT's inputs: r(t) to u
  // per component, Q_i(t) by 16 u ||Q_i||_F (products) and by the angle
  // t |w_i| rounded (3 u t ||[W_i, Q_i]||); doubled.
  // At t = 0, and without rotation where r(t) is a double, DEFAULT's inputs
  // are exact: no such term.
  bool const exact_inputs = t == 0.0 || (!mo.rotating && r_is_exact(mo.r0, mo.v, t));
  double e_in = exact_inputs ? 0.0 : inf;
  if (!exact_inputs && have_dir) {
    double const sn = std::sqrt(dot(dir, dir));  // inf or NaN: e_in not trusted
    double const dq1 = mo.rotating ? 16 * kU * mo.qf1 + 3 * kU * t * mo.cn1 : 0.0;
    double const dq2 = mo.rotating ? 16 * kU * mo.qf2 + 3 * kU * t * mo.cn2 : 0.0;
    e_in = 2.0 * lam * (1.0 - lam) *
           (2.0 * sn * kU * std::sqrt(dot(r, r)) + sn * sn * ((1.0 - lam) * dq1 + lam * dq2));
  }
  double const e = std::fmax(mu2 * kDefaultRelAccuracy, mr.mu2_error) + e_in;
  if (mu2 == inf) {  // kRange: mu^2 above DBL_MAX
    p.lo = p.hi = inf;
  } else if (e_in <= kFirstOrderTrust * mu2) {
    p.lo = p.f - e;
    p.hi = p.f + e;
  } else {
    p.lo = -inf;
    p.hi = inf;
  }
  ExactPose pose;
  ExactPose const *pp = nullptr;
  if (!mo.rotating) {
    p.ok = have_dir && minorant_at(mo, nullptr, t, dir, p.m);
  } else if (have_dir) {
    // First the minorant of the rounded Q_i(t), lowered by the effect of
    // their rounding (|dh_i| <= dQ_i / (2 h_i), |d(h_i')| <= |w_i| dQ_i / h_i,
    // dQ_i as for e_in): certified where the gap is wide; else the exact one.
    double const dq1 = 16 * kU * mo.qf1 + 3 * kU * t * mo.cn1;
    double const dq2 = 16 * kU * mo.qf2 + 3 * kU * t * mo.cn2;
    p.ok = minorant(mo.r0, mo.v, t, p1, mo.w1, p2, mo.w2, dir, kLevel, p.m);
    double margin = 0.0;
    if (p.ok) {
      margin = 0.5 * (dq1 / p.m.h[0] + dq2 / p.m.h[1]) * (1.0 + 1e-12);
      p.m.gap -= margin;
      p.m.slope -= (norm(mo.w1) * dq1 / p.m.h[0] + norm(mo.w2) * dq2 / p.m.h[1]) * (1.0 + 1e-12);
    }
    // the exact minorant where the margin would cost more than a tenth of the gap
    if (!(p.ok && p.m.gap > 9.0 * margin)) {
      pose = exact_pose(mo.r0, mo.v, t, mo.w1, mo.w2);
      pp = &pose;
      p.ok = minorant_at(mo, pp, t, dir, p.m);
    }
  } else {
    p.ok = false;
  }
  bool const undecided = !(p.lo > 0.0) && !(p.hi <= 0.0);
  bool const stuck = !(p.ok && p.m.gap > 0.0) && !(p.hi <= 0.0);
  if ((decide && undecided) || stuck) {
    if (pp == nullptr) {
      pose = exact_pose(mo.r0, mo.v, t, mo.w1, mo.w2);
      pp = &pose;
    }
    ++evaluations;
    Mu2Bounds b;
    if (enclose_mu2(pose, mo.a1, mo.a2, p1, p2, mo.ax1, mo.ax2, lam, b)) {
      p.lo = b.lo;
      p.hi = b.hi;
      p.f = 0.5 * (b.lo + b.hi);
      p.enclosed = true;
      Minorant m2;
      if (minorant_at(mo, pp, t, b.s, m2) && (!p.ok || m2.gap > p.m.gap)) {
        p.m = m2;
        p.ok = true;
      }
    }
  }
  if (!(p.ok && p.m.gap > 0.0) && !(p.hi <= 0.0)) {
    // Neither direction gives a step (Q(lambda) too ill-conditioned for
    // the Cholesky solves at DEFAULT's lambda): the direction of the
    // derivatives, whose lambda is refined by Newton steps in double-double
    // (E7); any direction gives a valid minorant.
    if (pp == nullptr && mo.rotating) {
      pose = exact_pose(mo.r0, mo.v, t, mo.w1, mo.w2);
      pp = &pose;
    }
    Derivatives d;
    ++evaluations;
    Minorant m3;
    if (contact_derivatives(r, p1, p2, d) != kNoConvergence &&
        minorant_at(mo, pp, t, Vec3{{d.d_r12[0], d.d_r12[1], d.d_r12[2]}}, m3) &&
        (!p.ok || m3.gap > p.m.gap)) {
      p.m = m3;
      p.ok = true;
    }
  }
  p.df = std::numeric_limits<double>::quiet_NaN();
  // mu_lo from the bounds (DEFAULT's or the enclosure's), else 0
  p.mu_lo = p.lo > -1.0 ? std::sqrt(1.0 + p.lo) : 0.0;
  if (p.ok) {
    double const mu = std::sqrt(std::fmax(1.0 + p.f, 0.0)), d0 = p.m.h[0] + p.m.h[1];
    p.df = 2.0 * mu * (p.m.n1 - mu * p.m.d1) / d0;
    p.mu_lo = std::fmax(p.mu_lo, kLevel + p.m.gap / d0);
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

double secant(Sample const &a, Sample const &b) noexcept {
  double const c = a.t + (b.t - a.t) * (a.f / (a.f - b.f));
  return std::fmin(std::fmax(c, a.t), b.t);
}

// The crossing of mu^2 = 1 in [a, b], mu^2(a) > 1 and mu^2(b) <= 1
// certified (T8). The bracket shrinks on certified signs only. Newton's
// steps from the last sample, while they stay inside the bracket and at
// least halve, are evaluated tol / 3 short of their root by DEFAULT alone
// (their sign is used where its bound decides it; at a transversal
// crossing it does, and the bracket often closes there); once a step is
// below tol / 2, the next evaluation is
// placed tol / 3 beyond its root, across the crossing, with its sign
// decided (by the enclosure where DEFAULT's bound does not), so that the
// bracket closes to below tol in one or two such probes. Otherwise regula
// falsi or bisection, with decided signs. Stops on a bracket below tol
// (writes Newton's root from its end nearer the crossing, else the last
// prediction or the secant, inside it), on two consecutive doubles, or on a
// decided sample whose enclosure contains 1 (|mu^2 - 1| within its width:
// that time). Returns false when an evaluation fails or the budget runs
// out.
bool refine(Motion const &mo, double tol, Sample a, Sample b, double &t,
            int &evaluations) noexcept {
  double const inf = std::numeric_limits<double>::infinity();
  Sample x = a;
  double pred = std::numeric_limits<double>::quiet_NaN(), last_step = inf;
  for (int it = 0;; ++it) {
    if (!(b.t - a.t > tol) || it == kRefineMaxIter) break;
    double const step = newton_step(x.f, x.df), newton = x.t + step;
    bool decide = true;
    double c;
    if (newton > a.t && newton < b.t && std::fabs(step) <= 0.5 * last_step) {
      pred = c = newton;
      last_step = std::fabs(step);
      if (std::fabs(step) <= 0.5 * tol) {  // probe across the predicted root
        last_step = inf;  // Newton from the probe is taken
        c = step >= 0.0 ? newton + tol / 3.0 : newton - tol / 3.0;
        if (!(c > a.t && c < b.t)) c = step >= 0.0 ? 0.5 * (newton + b.t) : 0.5 * (a.t + newton);
        // the root within an ulp of the end (a crossing steeper than the
        // resolution of t): the probe tol / 3 on the near side instead
        if (!(c > a.t && c < b.t)) c = step >= 0.0 ? newton - tol / 3.0 : newton + tol / 3.0;
        if (!(c > a.t && c < b.t)) c = a.t + 0.5 * (b.t - a.t);
      } else {  // short of the root by tol / 3: a sample DEFAULT can place
        decide = false;
        c = step >= 0.0 ? newton - tol / 3.0 : newton + tol / 3.0;
      }
    } else {
      last_step = inf;
      pred = c = secant(a, b);
      if (!(c > a.t && c < b.t) || !(std::fmin(c - a.t, b.t - c) > 0.1 * (b.t - a.t)))
        c = a.t + 0.5 * (b.t - a.t);
    }
    if (!(c > a.t && c < b.t)) break;  // a and b are consecutive doubles
    if (evaluations >= kContactTimeMaxEval || !sample(mo, c, decide, x, evaluations)) return false;
    if (x.lo > 0.0) {
      a = x;
    } else if (x.hi <= 0.0) {
      b = x;
    } else if (decide) {  // |mu^2 - 1| below the enclosure's resolution
      t = c;
      return true;
    }
  }
  if (!(b.t - a.t <= tol) && b.t != std::nextafter(a.t, b.t)) return false;
  // Inside the bracket: Newton's root from the end nearer the crossing, or
  // the last prediction, or the secant.
  Sample const &near = std::fabs(a.f) <= std::fabs(b.f) ? a : b;
  double const last = near.t + newton_step(near.f, near.df);
  if (last >= a.t && last <= b.t) t = last;
  else t = pred >= a.t && pred <= b.t ? pred : secant(a, b);
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
  mo.rotating = norm(w1) > 0.0 || norm(w2) > 0.0;
  mo.ax1 = axis_bounds(mo.a1);
  mo.ax2 = axis_bounds(mo.a2);
  // The domain of the certificate, decided before any evaluation from the
  // inputs alone, so the same on every CPU: semi-axis ratios up to
  // kMaxAxisRatio (the enclosure's floor below the band), angles up to
  // 2^50 rad (the reduction modulo pi of spin.hpp).
  if (!(mo.ax1.a_max <= kMaxAxisRatio * mo.ax1.a_min) ||
      !(mo.ax2.a_max <= kMaxAxisRatio * mo.ax2.a_min) ||
      !(t_max * std::fmax(norm(w1), norm(w2)) <= 0x1p50))
    return kInaccurate;
  mo.cn1 = commutator_norm(mo.a1, w1);
  mo.cn2 = commutator_norm(mo.a2, w2);
  mo.qf1 = mo.qf2 = 0.0;
  for (int i = 0; i < kSym; ++i) {
    double const k = i == 0 || i == 3 || i == 5 ? 1.0 : 2.0;
    mo.qf1 += k * mo.a1[i] * mo.a1[i];
    mo.qf2 += k * mo.a2[i] * mo.a2[i];
  }
  mo.qf1 = std::sqrt(mo.qf1);
  mo.qf2 = std::sqrt(mo.qf2);
  RateBounds const b = rate_bounds(mo.ax1, w1, mo.cn1, mo.ax2, w2, mo.cn2);
  double const rho = mo.ax1.a_min + mo.ax2.a_min;

  // above: the last sample with mu^2 > 1 certified, the left end of the
  // bracket of (T8).
  Sample p{}, above{};
  double t = 0.0;
  for (;;) {
    if (res.evaluations >= kContactTimeMaxEval || !sample(mo, t, t == 0.0, p, res.evaluations)) {
      res.t = t;
      return kNoConvergence;
    }
    // Overlapping or touching at t = 0 (static inputs, exact): certified
    // when the bounds decide, else DEFAULT's value decides (|mu^2(0) - 1|
    // then within its error bound).
    if (t == 0.0 && (p.hi <= 0.0 || (!(p.lo > 0.0) && !(p.f > 0.0)))) {
      res.t = 0.0;
      return kOk;
    }
    if (p.lo > 0.0 || t == 0.0) above = p;
    if (p.hi <= 0.0) {  // contact confirmed (T6)
      if (!refine(mo, kRefineTol * t_max, above, p, res.t, res.evaluations)) {
        res.t = t;  // [0, t_k] is certified
        return kNoConvergence;
      }
      return kOk;
    }
    double const tau = p.ok ? safe_step(p.m, b) : lipschitz_step(p.mu_lo, kLevel, vn, b.om, rho);
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
