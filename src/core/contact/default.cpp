// PW85_METHOD_DEFAULT (docs/methods.md, section "DEFAULT"). On x86-64-v4,
// first the rational step
// (rational_iterate below: f from its seven coefficients in double-double,
// f_rational_dd.hpp), from the grid start (M24) (start_scan.hpp); where
// only d0 or d3 failed its bound, the same step again with those two from
// det_precise (declined_v4); when it declines, and on other CPUs:
//  0. from the start (M22) (start.hpp: Newton on the fixed-point equation of
//     (M19) in logarithmic coordinates), a safeguarded
//     Halley iteration as NEWTON's (newton.cpp) but with f and its
//     derivatives from the adjugate of Q(lambda) (f_adj.hpp, eq. (M16)),
//     then f at the final lambda by the stationary form (f_dd.hpp, eq. (M11))
//     whose error is second order in the error of s, bounded componentwise
//     (eq. (M17)); if the total estimate is below kFastRel * mu2 (most pairs)
//     that is the result; otherwise:
//  1. the NEWTON iteration in double (newton.cpp) with its error estimate
//     (eq. (M10));
//  2. f at the final lambda by the stationary form 2 r^T s - s^T Q s with
//     compensated dot products (f_dd.hpp, eq. (M11)), whose error is second
//     order in the error of the double solve; if the estimate is below
//     kFastRel * mu2, that result is returned (the fast path, taken by most
//     pairs);
//  3. otherwise f and f' are re-evaluated in double-double at the current
//     lambda (f_dd.hpp, eq. (M11)) and Newton steps on f' are taken with the
//     double-precision f'' as slope, until the gap f'^2 / (2|f''|) is below
//     2^-60 f. Since mu2 = max f, an error delta on lambda changes mu2 by
//     |f''| delta^2 / 2 only: the accuracy of mu2 is the accuracy of the
//     double-double f, about kappa(Q) 2^-104 relative.
//  4. when the double iteration failed (Q(lambda) not numerically positive
//     definite in double) or its f'' is not accurate to 2^-6 (maximiser
//     very near 0 or 1), dd_bracket (eq. (M26)): double-double f and f'
//     only, with a bound on max f from concavity.
#include <cmath>
#include <limits>

#include "common/fp.hpp"
#include "contact/contact.hpp"
#include "contact/default_params.hpp"
#include "eval/f_adj.hpp"
#include "eval/f_dd.hpp"
#include "eval/f_rational_dd.hpp"
#include "common/isa.hpp"
#include "contact/newton.hpp"
#include "contact/rational_step.hpp"
#include "contact/start_scan.hpp"

namespace pw85 {

namespace {
using namespace default_params;
constexpr int kAdjMaxIter = kHalleyMaxIter;
// The stationary form is tried when the first-order relative error of the
// double phi is below this (its second-order error is then below ~4e-16).
constexpr double kMaxFirstOrderRel = 1e-8;
constexpr double kDDGapTol = 0x1p-60;
constexpr double kDDModelGap = 0x1p-40;
constexpr double kDDSlopeRel = 0x1p-10;
constexpr int kDDMaxNewton = 6;
constexpr double kDDTrustRel = 0x1p-6;
constexpr int kDDMaxBracket = 160;

// DEFAULT's start, eq. (M22) (start.hpp).
PW85_ALWAYS_INLINE double default_start(Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept {
  return log_newton_start<kStartMin, kStartMax>(r, q1, q2, kStartTol);
}

// A double-double evaluation (f_dd.hpp) with bounds on the errors of f and
// f': ef from the bound (M6) of phi plus the rounding of f; edf as in (M10),
// rel (|p'| phi + p |phi'|), times 4 for the error of phi' (first order
// in the error of s, as that of phi), plus the rounding of f'.
struct DDPoint {
  double x, f, df, ef, edf;
};

bool dd_point(double x, Vec3 const &r, Sym3 const &q1, Sym3 const &q2, DDPoint &p) noexcept {
  FEvalDD fd;
  if (!f_eval_dd(x, r, q1, q2, fd) || !std::isfinite(fd.rel)) return false;
  double const pp = x * (1.0 - x), p1 = std::fabs(1.0 - 2.0 * x);
  p = DDPoint{x, fd.f, fd.df, (fd.rel + kU) * fd.f,
              4.0 * fd.rel * (p1 * fd.phi + pp * std::fabs(fd.dphi)) + kU * std::fabs(fd.df)};
  return true;
}

// Bound on max f over [lo, hi] from the tangents at lo and hi (f concave,
// eq. (M3)), their values and slopes widened by their errors:
// f <= fl + sl (x - lo) and f <= fh + sh (x - hi), at their intersection
// (an infinite slope: the other tangent at the far end).
double tangent_bound(DDPoint const &lo, DDPoint const &hi) noexcept {
  double const fl = lo.f + lo.ef, sl = lo.df + lo.edf;
  double const fh = hi.f + hi.ef, sh = hi.df - hi.edf;
  double const w = hi.x - lo.x;
  if (!std::isfinite(sh)) return std::isfinite(sl) ? fl + std::fmax(sl, 0.0) * w : sl;
  if (!std::isfinite(sl)) return fh + std::fmax(-sh, 0.0) * w;
  double const xc = std::fmin(std::fmax((fh - fl + sl * lo.x - sh * hi.x) / (sl - sh), lo.x), hi.x);
  return std::fmax(fl + sl * (xc - lo.x), fh + sh * (xc - hi.x));
}

// Step 4 of DEFAULT (docs/methods.md, eq. (M26)): max f from double-double
// evaluations of f and f' only, with a bound that holds whatever the
// curvature of f (f concave, eq. (M3)). The side of 1/2 holding the
// maximiser is taken from the sign of f'(1/2); a maximiser above 1/2 is
// found as 1 - lambda' with Q1 and Q2 exchanged (f(lambda; Q1, Q2) =
// f(1 - lambda; Q2, Q1)), so that lambda' near 0 is represented to full
// relative precision where 1 - lambda' is not. The bracket [lo, hi] (by the
// sign of the computed f'; lo = 0 at first, where f = 0,
// f' = r^T Q1^{-1} r) shrinks by steps to the intersection of the tangents
// at lo and hi, and by a bisection (geometric while hi / lo > 4: the
// maximiser can lie anywhere down to the smallest double) whenever a step
// did not halve log(hi / lo). Bound: [lo_c, hi_c], the points nearest the
// maximiser where |f'| > edf (its sign certain), bracket the maximiser;
// f* is below tangent_bound(lo_c, hi_c), and below f + ef +
// (|f'| + edf) max(x - lo_c, hi_c - x) at every point x. Ends when the
// smallest such bound is within kDDGapTol of the largest f met, or no
// double lies inside [lo, hi]; mu2 = the largest f met, its error the bound
// minus mu2 plus the error of that f. kNoConvergence when no evaluation
// succeeds.
__attribute__((noinline)) Status dd_bracket(Vec3 const &r, Sym3 const &q1_in,
                                            Sym3 const &q2_in, double hint,
                                            MethodResult &res) noexcept {
  double const inf = std::numeric_limits<double>::infinity();
  DDPoint lo, hi, p;
  ++res.iterations;
  if (!dd_point(0.5, r, q1_in, q2_in, hi)) return kNoConvergence;
  bool const swap = hi.df > 0.0;
  Sym3 const &q1 = swap ? q2_in : q1_in, &q2 = swap ? q1_in : q2_in;
  if (swap) hi.df = -hi.df;  // f' of the exchanged problem
  DDPoint best = hi;
  ++res.iterations;
  if (!dd_point(0.0, r, q1, q2, lo)) lo = DDPoint{0.0, 0.0, inf, 0.0, 0.0};
  DDPoint lo_c = lo, hi_c = hi;
  // f' at 1/2 within its error: the maximiser may lie on either side.
  if (std::fabs(hi.df) <= hi.edf) hi_c = DDPoint{1.0, 0.0, -inf, 0.0, 0.0};
  double upper = inf;  // bound on f*
  // The first point: the hint, when it lies on the side of the maximiser
  // (1 - hint is exact for hint >= 1/2).
  double x = swap ? 1.0 - hint : hint;
  bool take_x = x > 0.0 && x < 0.5;
  double width = inf;  // log(hi / lo) before the last step
  for (int k = 0; k < kDDMaxBracket; ++k) {
    upper = std::fmin(upper, tangent_bound(lo_c, hi_c));
    if (upper - best.f <= kDDGapTol * best.f) break;
    if (!take_x) {
      // The tangents' intersection, or a bisection when the last step did
      // not halve log(hi / lo).
      double const lo_eff = lo.x > 0.0 ? lo.x : 0x1p-1074;
      double const w = std::log1p((hi.x - lo.x) / lo_eff);
      bool const bisect = !(w <= 0.5 * width);
      width = w;
      double const xt = (hi.f - lo.f + lo.df * lo.x - hi.df * hi.x) / (lo.df - hi.df);
      x = !bisect && xt > lo.x && xt < hi.x
              ? xt
              : (hi.x > 4.0 * lo_eff ? std::sqrt(lo_eff) * std::sqrt(hi.x) : 0.5 * (lo.x + hi.x));
    }
    take_x = false;
    if (!(x > lo.x && x < hi.x)) break;  // no double inside [lo, hi]
    ++res.iterations;
    if (!dd_point(x, r, q1, q2, p)) break;
    if (p.f > best.f) best = p;
    if (p.df > p.edf && p.x > lo_c.x)
      lo_c = p;
    else if (p.df < -p.edf && p.x < hi_c.x)
      hi_c = p;
    else if (std::fabs(p.df) <= p.edf)
      upper = std::fmin(upper, p.f + p.ef + (std::fabs(p.df) + p.edf) *
                                                std::fmax(p.x - lo_c.x, hi_c.x - p.x));
    if (p.df > 0.0)
      lo = p;
    else
      hi = p;
  }
  upper = std::fmin(upper, tangent_bound(lo_c, hi_c));
  if (!(best.f > 0.0)) return kNoConvergence;
  res.mu2 = best.f;
  res.lambda = swap ? 1.0 - best.x : best.x;
  res.mu2_error = std::fmax(upper - best.f, 0.0) + best.ef;
  return res.mu2_error <= kDefaultRelAccuracy * res.mu2 ? kOk : kInaccurate;
}

// The whole method, inlined into one function per instruction-set level
// (contact_default below). Its hot part, the start and the adjugate
// iteration of step 1, is inline (start.hpp, f_adj.hpp) and so compiled for
// that level; steps 2-4 call the baseline code of newton.cpp and f_dd.hpp.
PW85_ALWAYS_INLINE Status default_body(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                                       MethodResult &res) noexcept {
  res.iterations = 0;
  Sym3 const d = difference(q2, q1);
  // Step 1: Halley iteration with adjugate evaluations (f_adj.hpp).
  double const lambda0 = default_start(r, q1, q2);
  double start = lambda0;
  {
    double lo = 0.0, hi = 1.0, lambda = lambda0;
    AdjEval e;
    for (int it = 0; it < kAdjMaxIter; ++it) {
      ++res.iterations;
      if (!f_eval_adj(lambda, r, q1, q2, d, e)) break;
      start = lambda;
      HalleyDecision<double> const hd = halley_decide(lambda, e, lo, hi);
      double const a = hd.a, step = hd.step, next = hd.next;
      bool const inside = hd.inside, tiny = hd.tiny;
      if (hd.near) {
        // Error terms (eqs. (M10), (M17)): E bounds the error of s.
        Vec3 const E = adj_error(e, r, q1, q2);
        double const p = lambda * (1.0 - lambda), p1 = std::fabs(1.0 - 2.0 * lambda);
        Vec3 const as{{std::fabs(e.s[0]), std::fabs(e.s[1]), std::fabs(e.s[2])}};
        Sym3 da, qa;
        for (int i = 0; i < kSym; ++i) {
          da[i] = std::fabs(d[i]);
          qa[i] = std::fabs(e.q[i]);
        }
        Vec3 const ar{{std::fabs(r[0]), std::fabs(r[1]), std::fabs(r[2])}};
        double const edf = p1 * dot(ar, E) + 2.0 * p * dot(as, multiply(da, E)) +
                           4.0 * kU * (p1 * e.phi + p * std::fabs(e.dphi));
        // Quartic Taylor model at lambda (eq. (M18)).
        double const h = tiny ? 0.0 : step;
        double const err_l = model_error(edf, h, a, e.d4f);
        bool done = (err_l <= kExtrapBudget * e.f) | (std::fabs(e.df) <= 2.0 * edf) | tiny;
        opaque(done);
        if (done) {
          double const corr = model_increment(h, e);
          // First-order error of the double f: |r|^T E + rounding of r^T s.
          double const err1 =
              p * (dot(ar, E) + 3.0 * kU * dot(ar, as)) + 4.0 * kU * e.f + err_l;
          if (err1 <= kFastRel * e.f) {
            res.mu2 = e.f + corr;
            res.lambda = lambda + h;
            res.mu2_error = err1;
            return kOk;
          }
          // Second-order error of the stationary form: p E^T |Q| E; tested
          // before the form is computed (with f for mu2, 1e-3 margin), so
          // that pairs bound to fail go straight to step 2.
          double const err2 = p * dot(E, multiply(qa, E)) + err_l;
          if (err2 + e.f * kStatRel > 0.999 * kFastRel * e.f) {
            if (!tiny) start = next;
            break;
          }
          double const mu2 = f_stationary(lambda, r, q1, q2, e.s) + corr;
          double const err = mu2 * kStatRel + err2;
          if (err <= kFastRel * mu2) {
            res.mu2 = mu2;
            res.lambda = lambda + h;
            res.mu2_error = err;
            return kOk;
          }
          if (!tiny) start = next;
          break;
        }
      }
      if (tiny) break;
      lambda = inside ? next : 0.5 * (lo + hi);
    }
  }
  // Step 2: LDL^T evaluations (newton.cpp), from the best lambda so far.
  NewtonState st;
  FEval &e = st.e;
  e.f = std::nan("");
  bool const ok = newton_iterate(r, q1, q2, d, start, st, res.iterations);
  double rel_double = 1.0;  // estimated relative error of the double phi
  if (std::isfinite(e.f)) {
    newton_fill_error_terms(st, r, q1, q2);
    rel_double = st.rel;
    double const a = -e.d2f;
    double const err_double = st.rel * std::fabs(st.mu2) + newton_lambda_error(st);
    if (ok && err_double <= kFastRel * st.mu2) {
      // Accurate enough in double: no compensated re-evaluation needed.
      res.mu2 = st.mu2;
      res.lambda = st.lambda;
      res.mu2_error = err_double;
      return kOk;
    }
    if (ok && a > 0.0 && rel_double <= kMaxFirstOrderRel) {
      // f at e.lambda by the stationary form (eq. (M11)), error
      // ~ kStatRel + 4 rel^2 relative; then the Taylor step of the iteration.
      double const h = st.step;
      double const corr = h * (e.df + h * (0.5 * e.d2f + h * e.d3f / 6.0));
      double const mu2 = f_stationary(e.lambda, r, q1, q2, e.s) + corr;
      double const err =
          mu2 * (kStatRel + 4.0 * rel_double * rel_double) + newton_lambda_error(st);
      if (err <= kFastRel * mu2) {
        res.mu2 = mu2;
        res.lambda = st.lambda;
        res.mu2_error = err;
        return kOk;
      }
    }
  }
  // Slow path: double-double.
  // Relative error of the double-double phi: the double estimate with u
  // replaced by u^2 (times 8 for the extra operations of double-double),
  // plus the final rounding to double.
  double const rel_dd = 8.0 * rel_double * kU + 2.0 * kU;
  if (std::isfinite(e.f)) e.lambda = st.lambda > 0.0 && st.lambda < 1.0 ? st.lambda : e.lambda;
  FEvalDD fd;
  double lambda;
  // The double f'' as slope, where the double evaluation has digits
  // (otherwise its f'' can be off by orders of magnitude, and the gap
  // f'^2 / (2 |f''|) with it).
  double a = std::isfinite(e.f) ? -e.d2f : 0.0;  // -f'' > 0
  bool const have_d3f = std::isfinite(e.f) && std::isfinite(e.d3f);
  double const d3f = have_d3f ? e.d3f : 0.0;
  // The first-order error bound of the double f'' below kDDTrustRel of it:
  // rel_double times the sum of its terms |-2 phi| + |2 p' phi'| +
  // |p phi''| <= 4 phi + 4 |p' phi'| + a (eq. (M4)).
  bool const trust_a =
      std::isfinite(e.f) && a > 0.0 &&
      rel_double * (4.0 * e.phi + 4.0 * std::fabs((1.0 - 2.0 * e.lambda) * e.dphi) + a) <=
          kDDTrustRel * a;
  if (trust_a) {
    lambda = e.lambda;
    for (int k = 0; k < kDDMaxNewton; ++k) {
      ++res.iterations;
      if (!f_eval_dd(lambda, r, q1, q2, fd)) break;
      double const gap = fd.df * fd.df / (2.0 * a);
      if (gap <= kDDGapTol * fd.f) {
        res.mu2 = fd.f;
        res.lambda = lambda;
        res.mu2_error = rel_dd * fd.f + gap;
        return res.mu2_error <= kDefaultRelAccuracy * res.mu2 ? kOk : kInaccurate;
      }
      // Small gap: the maximum of the quadratic model, f + gap (h = f'/a),
      // saves the next double-double evaluation. Its error: the slope a
      // from the double evaluation (relative error taken as kDDSlopeRel,
      // far above that of a double f'' where the double iteration
      // converged), and the cubic term |f''' h^3| / 6, counted twice.
      if (have_d3f && gap <= kDDModelGap * fd.f) {
        double const h = fd.df / a;
        double const model_err =
            kDDSlopeRel * gap + std::fabs(d3f * h * h * h) / 3.0;
        if (model_err <= kDDGapTol * fd.f) {
          res.mu2 = fd.f + gap;
          // The maximiser lies in [0, 1] (eq. (M3)); lambda + h, a rounding
          // past 0 or 1 where it is within an ulp of them, is clamped.
          res.lambda = std::fmin(std::fmax(lambda + h, 0.0), 1.0);
          res.mu2_error = rel_dd * res.mu2 + model_err;
          return res.mu2_error <= kDefaultRelAccuracy * res.mu2 ? kOk : kInaccurate;
        }
      }
      double next = lambda + fd.df / a;
      if (!(next > 0.0 && next < 1.0) || next == lambda) break;
      // Refresh the slope where the double evaluation still works.
      FEval e2;
      if (f_eval(next, r, q1, q2, d, e2) && e2.d2f < 0.0) a = -e2.d2f;
      lambda = next;
    }
  }
  // Step 4: the bracketed double-double iteration (dd_bracket).
  double const hint = std::isfinite(e.f) ? e.lambda : start;
  Status const s = dd_bracket(r, q1, q2, hint, res);
  if (s != kNoConvergence) return s;
  res.mu2 = std::isfinite(e.f) ? st.mu2 : std::nan("");
  res.lambda = std::isfinite(e.f) ? st.lambda : std::nan("");
  res.mu2_error = std::isfinite(e.f) ? newton_error(st, r, q1, q2) : std::nan("");
  return kNoConvergence;
}

#if PW85_ISA_LEVELS
// The rational step (docs/methods.md, "PW85_METHOD_DEFAULT"): from the
// start (M24) (or (M22) where (M24) finds no bracket), Halley steps (M8)
// on f evaluated from the seven
// double-double coefficients (f_rational_dd.hpp), whose error does not grow
// with the conditioning of Q(lambda), until the quartic Taylor model (M18)
// at the current lambda is accurate (rational_decide, rational_step.hpp).
// False (the caller then runs the general method) when an evaluation fails
// or the iteration does not settle.
PW85_ALWAYS_INLINE bool rational_iterate(RationalDD const &k, double lambda0,
                                         MethodResult &res) noexcept {
  double lo = 0.0, hi = 1.0, lambda = lambda0;
  RatEval e;
  res.iterations = 0;
  for (int it = 0; it < kAdjMaxIter; ++it) {
    ++res.iterations;
    if (!f_eval_rational(lambda, k, e)) return false;
    RationalDecision<double> const d = rational_decide(lambda, e, lo, hi);
    if (d.done) {
      res.mu2 = d.mu2;
      res.lambda = d.lam;
      res.mu2_error = d.err;
      return true;
    }
    if (d.tiny) return false;
    lambda = d.next;
  }
  return false;
}

// The rational step with its inputs: the seven coefficients, the start
// (M24) ((M22) where (M24) finds no bracket), then rational_iterate. The
// coefficients come first in program order: their independent vector work
// then overlaps with the start's dependency chain (measured: 9-14 ns per
// call less than the other order). Inlined into contact_default_v4, which
// calls the rest out of line (declined_v4): 0.3-2 ns per call
// faster than a separate function (once inlined together with default_body
// it measured 8 ns slower).
PW85_V4_INLINE bool rational_v4(
    Vec3 const &r, Sym3 const &q1, Sym3 const &q2, MethodResult &res) noexcept {
  RationalDD k;
  bool const coef_ok = rational_coefficients_dd(r, q1, q2, k);
  double lambda0 = scan_start(r, q1, q2);
  if (lambda0 < 0.0) lambda0 = default_start(r, q1, q2);
  return coef_ok && rational_iterate(k, lambda0, res);
}

// The rational step again where d0 or d3 failed its bound (cancellation
// beyond 2^45: 18 % of bench_contact's class-3 pairs), with those two from
// det_precise (f_rational_dd.hpp). False where rational_v4 declined for
// another reason.
PW85_V4_INLINE bool rational_precise_v4(
    Vec3 const &r, Sym3 const &q1, Sym3 const &q2, MethodResult &res) noexcept {
  RationalDD k;
  if (rational_coefficients_dd(r, q1, q2, k) || !rational_dets_precise(q1, q2, k))
    return false;
  double lambda0 = scan_start(r, q1, q2);
  if (lambda0 < 0.0) lambda0 = default_start(r, q1, q2);
  return rational_iterate(k, lambda0, res);
}

// The general method compiled for x86-64-v4, from its own start (M22), with
// the same IEEE operations as the baseline (-ffp-contract=off,
// src/meson.build). Out of line: inlined into
// contact_default_v4 below, its register use made every call save and
// restore every callee-saved register, the rational step's calls included.
PW85_TARGET_V4 __attribute__((noinline)) Status default_body_v4(
    Vec3 const &r, Sym3 const &q1, Sym3 const &q2, MethodResult &res) noexcept {
  return default_body(r, q1, q2, res);
}

// After rational_v4 declined: rational_precise_v4, then the general method.
// A separate function that recomputes the coefficients and the start:
// rational_precise_v4 called from rational_v4 with its coefficients (inline
// or not) made the one-pair DEFAULT call 13 ns slower in classes 0-2 of
// bench_batch (87 -> 100 ns), where it never runs.
PW85_TARGET_V4 __attribute__((noinline)) Status declined_v4(
    Vec3 const &r, Sym3 const &q1, Sym3 const &q2, MethodResult &res) noexcept {
  if (rational_precise_v4(r, q1, q2, res)) return kOk;
  return default_body_v4(r, q1, q2, res);
}
#endif

}  // namespace

#if PW85_ISA_LEVELS
// DEFAULT on x86-64-v4 (contact.hpp): the rational step, and the general
// method when it declines.
PW85_TARGET_V4 Status contact_default_v4(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                                         MethodResult &res) noexcept {
  res.method = kMethodDefault;
  if (rational_v4(r, q1, q2, res)) return kOk;
  return declined_v4(r, q1, q2, res);
}

PW85_TARGET_V4 Status contact_default_general_v4(Vec3 const &r, Sym3 const &q1,
                                                 Sym3 const &q2, MethodResult &res) noexcept {
  res.method = kMethodDefault;
  return default_body_v4(r, q1, q2, res);
}
#endif

Status contact_default(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                       MethodResult &res) noexcept {
#if PW85_ISA_LEVELS
  if (isa::has_v4()) return contact_default_v4(r, q1, q2, res);
#endif
  return default_body(r, q1, q2, res);
}

}  // namespace pw85
