// Certified conservative advancement for the first contact time
// (docs/contact_time.md (T1)-(T7)).
//
// At each t_k: mu^2(t_k) by PW85_METHOD_DEFAULT, with lambda; contact when
// mu^2(t_k) <= 1, or after one more step when mu^2(t_k) <= 1 + kBand (T6);
// otherwise u = s = Q(lambda)^{-1} r12 gives the
// lower bound g of (T5) and t_{k+1} = t_k + tau, tau the first zero of g:
// mu >= 1 on [t_k, t_{k+1}]. Near a crossing g is the tangent of mu (u is
// the maximiser of (T2), D0' its derivative: envelope theorem), so the
// steps converge as Newton's method from the safe side.
#include "contact_time/contact_time.hpp"

#include <cmath>
#include <limits>

#include "contact/contact.hpp"
#include "contact_time/axes.hpp"
#include "contact_time/minorant.hpp"
#include "contact_time/motion.hpp"
#include "derivatives/derivatives.hpp"

namespace pw85 {

namespace {

// Contact is reported at t_k once mu^2(t_k) <= 1 + kBand: 10 times the
// documented accuracy of PW85_METHOD_DEFAULT (T6).
constexpr double kBand = 1e-13;
// In that band, a certified step shorter than kBandStep t_max ends the
// search at its end: a crossing, where g is the tangent of mu.
constexpr double kBandStep = 1e-6;
// A step below half an ulp of t_k (a crossing steeper than mu^2 changes
// across one ulp of t) ends the search at t_k when mu^2(t_k) <= 1 + kStuck.
constexpr double kStuck = 1e-6;

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

// Step of the Lipschitz bound (T7), used when no direction u gives g(0) > 0
// although mu^2 > 1 + kBand: with mu_lo <= mu(t_k), phi' >= -(|v12| + phi om)
// / rho for the maximiser u at t_k, rho = a_min,1 + a_min,2 <= D.
double lipschitz_step(double mu2, double vn, double om, double rho) noexcept {
  double const mu_lo = std::sqrt(mu2 * (1.0 - 1e-13));
  if (!(mu_lo > 1.0)) return 0.0;
  if (om > 0.0) return rho / om * std::log1p(om * (mu_lo - 1.0) / (om + vn));
  return vn > 0.0 ? rho * (mu_lo - 1.0) / vn : std::numeric_limits<double>::infinity();
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
  Vec3 r0, v;
  Sym3 a1, a2;
  for (int i = 0; i < kDim; ++i) {
    r0[i] = std::ldexp(r12[i], -e);
    v[i] = std::ldexp(v12[i], -e);
  }
  for (int i = 0; i < kSym; ++i) {
    a1[i] = std::ldexp(q1[i], -2 * e);
    a2[i] = std::ldexp(q2[i], -2 * e);
  }
  double const vn = norm(v);
  if (!std::isfinite(norm(r0) + t_max * vn) || !std::isfinite(t_max * (norm(w1) + norm(w2))))
    return kInvalidArgument;
  AxisBounds const ax1 = axis_bounds(a1), ax2 = axis_bounds(a2);
  RateBounds const b = rate_bounds(ax1, w1, ax2, w2);
  double const rho = ax1.a_min + ax2.a_min;

  double t = 0.0;
  for (;;) {
    if (res.evaluations >= kContactTimeMaxEval) {
      res.t = t;
      return kNoConvergence;
    }
    Vec3 const r = position(r0, v, t);
    Sym3 const p1 = rotated(a1, w1, t), p2 = rotated(a2, w2, t);
    MethodResult mr;
    Status const s = contact_method(kMethodDefault, r, p1, p2, mr);
    ++res.evaluations;
    // kRange: mu^2 beyond the double range, written rounded (+inf or tiny),
    // still decides; lambda is that of the rescaled problem.
    if (s != kOk && s != kInaccurate && s != kRange) {
      res.t = t;
      return kNoConvergence;
    }
    if (mr.mu2 <= 1.0) {
      res.t = t;
      return kOk;
    }
    bool const band = mr.mu2 <= 1.0 + kBand;  // (T6)
    Vec3 dir;
    Minorant m;
    bool ok = direction(r, p1, p2, mr.lambda, dir) && minorant(r0, v, t, p1, w1, p2, w2, dir, m) &&
              m.gap > 0.0;
    if (!ok && !band) {
      // s accurate to the last bits: lambda and s of the derivatives (E7).
      Derivatives d;
      ++res.evaluations;
      ok = contact_derivatives(r, p1, p2, d) != kNoConvergence &&
           minorant(r0, v, t, p1, w1, p2, w2, Vec3{{d.d_r12[0], d.d_r12[1], d.d_r12[2]}}, m) &&
           m.gap > 0.0;
    }
    if (!ok && band) {
      res.t = t;
      return kOk;
    }
    double const tau = ok ? safe_step(m, b) : lipschitz_step(mr.mu2, vn, b.om, rho);
    if (!(tau >= 0.0)) {  // NaN: no bound
      res.t = t;
      return kNoConvergence;
    }
    if (tau > t_max - t) {
      res.t = inf;
      return kOk;
    }
    if (band && tau <= kBandStep * t_max) {  // the last, Newton-like, step (T6)
      res.t = t + tau;
      return kOk;
    }
    if (t + tau == t) {  // below the resolution of t (T6)
      res.t = t;
      return mr.mu2 <= 1.0 + kStuck ? kOk : kNoConvergence;
    }
    t += tau;
  }
}

}  // namespace pw85
