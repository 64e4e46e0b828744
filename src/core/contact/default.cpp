// PW85_METHOD_DEFAULT (docs/methods.md, section "DEFAULT"). On x86-64-v4,
// first the rational step
// (rational_iterate below: f from its seven coefficients in double-double,
// f_rational_dd.hpp), from the grid start (M24) (start_scan.hpp); when it
// declines, and on other CPUs:
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
//     definite in double), the root of f' is bracketed by bisection on the
//     sign of the double-double f'.
#include <cmath>

#include "common/fp.hpp"
#include "contact/contact.hpp"
#include "contact/default_params.hpp"
#include "eval/f_adj.hpp"
#include "eval/f_dd.hpp"
#include "eval/f_rational_dd.hpp"
#include "common/isa.hpp"
#include "contact/newton.hpp"
#include "contact/start_scan.hpp"

namespace pw85 {

namespace {
using namespace default_params;
constexpr int kAdjMaxIter = 30;
// The stationary form is tried when the first-order relative error of the
// double phi is below this (its second-order error is then below ~4e-16).
constexpr double kMaxFirstOrderRel = 1e-8;
constexpr double kDDGapTol = 0x1p-60;
constexpr double kDDModelGap = 0x1p-40;
constexpr double kDDSlopeRel = 0x1p-10;
constexpr int kDDMaxNewton = 6;
constexpr int kDDMaxBisect = 80;

// DEFAULT's start, eq. (M22) (start.hpp).
PW85_ALWAYS_INLINE double default_start(Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept {
  return log_newton_start<kStartMin, kStartMax>(r, q1, q2, kStartTol);
}

// The parts shared by the two Halley iterations below (step 1 of
// default_body, rational_iterate): E is an evaluation with f, df, d2f, d3f,
// d4f at lambda.
struct HalleyDecision {
  double a, step, next;  // a = -f''; next = lambda + step
  bool inside, tiny, near;
};

// Narrows [lo, hi] by the sign of f', takes the safeguarded Halley step (M8)
// (Newton where Halley's denominator is not positive, bisection where f is
// not concave), and decides whether lambda is near enough for the quartic
// model (M18): f' small (gap f'^2 / 2a below kExtrapGap f) with the step
// inside the bracket, or the step below rounding.
template <class E>
PW85_ALWAYS_INLINE HalleyDecision halley_decide(double lambda, E const &e, double &lo,
                                                double &hi) noexcept {
  if (e.df > 0.0)
    lo = lambda;
  else
    hi = lambda;
  double const a = -e.d2f;
  double step;
  double const den = 2.0 * e.d2f * e.d2f - e.df * e.d3f;
  if (a > 0.0 && den > 0.0)
    step = -2.0 * e.df * e.d2f / den;  // Halley, eq. (M8)
  else if (a > 0.0)
    step = e.df / a;
  else
    step = 0.5 * (lo + hi) - lambda;
  double const next = lambda + step;
  bool const inside = next > lo && next < hi;
  bool const tiny = std::fabs(step) <= 2.0 * kU * lambda;
  // One branch per decision (opaque, isa.hpp): without it GCC tests
  // each comparison in turn, and their outcomes vary from pair to pair.
  bool near = (a > 0.0) & (tiny | (inside & (e.df * e.df <= 2.0 * a * kExtrapGap * e.f)));
  opaque(near);
  return HalleyDecision{a, step, next, inside, tiny, near};
}

// Error of the quartic Taylor model (M18) at lambda with increment h: its
// truncation estimated by the last term, counted twice, and the error edf
// of f' (how well the maximiser is known, eq. (M10)).
PW85_ALWAYS_INLINE double model_error(double edf, double h, double a, double d4f) noexcept {
  double const h2 = h * h;
  double const trunc = std::fabs(d4f * h2 * h2) * kInv24;
  return edf * std::fabs(h) + edf * edf / (2.0 * a) + 2.0 * trunc;
}

// The model's increment f(lambda + h) - f(lambda).
template <class E>
PW85_ALWAYS_INLINE double model_increment(double h, E const &e) noexcept {
  return h * (e.df + h * (0.5 * e.d2f + h * (e.d3f * kInv6 + h * e.d4f * kInv24)));
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
      HalleyDecision const hd = halley_decide(lambda, e, lo, hi);
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
  double a = std::isfinite(e.f) ? -e.d2f : 0.0;  // -f'' > 0
  bool const have_d3f = std::isfinite(e.f) && std::isfinite(e.d3f);
  double const d3f = have_d3f ? e.d3f : 0.0;
  if (std::isfinite(e.f) && a > 0.0) {
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
  // Fallback: bisection on the sign of the double-double f'.
  double lo = 0.0, hi = 1.0;
  lambda = 0.5;
  bool have = false;
  FEvalDD best{};
  double best_lambda = 0.5;
  for (int k = 0; k < kDDMaxBisect && hi - lo > 4.0 * kU * hi; ++k) {
    ++res.iterations;
    lambda = 0.5 * (lo + hi);
    if (!f_eval_dd(lambda, r, q1, q2, fd)) break;
    if (!have || fd.f > best.f) {
      best = fd;
      best_lambda = lambda;
      have = true;
    }
    if (fd.df > 0.0)
      lo = lambda;
    else
      hi = lambda;
  }
  if (!have) {
    res.mu2 = std::isfinite(e.f) ? st.mu2 : std::nan("");
    res.lambda = std::isfinite(e.f) ? st.lambda : std::nan("");
    res.mu2_error = std::isfinite(e.f) ? newton_error(st, r, q1, q2) : std::nan("");
    return kNoConvergence;
  }
  res.mu2 = best.f;
  res.lambda = best_lambda;
  // Gap bound (f concave): f* - f(last) <= |f'(last)| (hi - lo), last = the
  // last bisection point, an end of [lo, hi]; f(best) >= f(last).
  res.mu2_error = rel_dd * best.f + std::fabs(fd.df) * (hi - lo);
  return res.mu2_error <= kDefaultRelAccuracy * res.mu2 ? kOk : kInaccurate;
}

#if PW85_ISA_LEVELS
// Relative error of f from f_eval_rational (f_rational_dd.hpp): 2.2 u from
// the coefficients, about 13 u from the evaluation of A / B and s t.
constexpr double kRationalRel = 16.0 * kU;

// The rational step (docs/methods.md, "PW85_METHOD_DEFAULT"): from the
// start (M24) (or (M22) where (M24) finds no bracket), Halley steps (M8)
// on f evaluated from the seven
// double-double coefficients (f_rational_dd.hpp), whose error does not grow
// with the conditioning of Q(lambda), until the quartic Taylor model (M18)
// at the current lambda is accurate: then mu2 = f + the model's increment,
// with error kRationalRel f (plus one rounding) and the error of the model
// and of lambda (M10). False (the caller then runs the general method) when
// an evaluation fails or the iteration does not settle.
PW85_ALWAYS_INLINE bool rational_iterate(RationalDD const &k, double lambda0,
                                         MethodResult &res) noexcept {
  double lo = 0.0, hi = 1.0, lambda = lambda0;
  RatEval e;
  res.iterations = 0;
  for (int it = 0; it < kAdjMaxIter; ++it) {
    ++res.iterations;
    if (!f_eval_rational(lambda, k, e)) return false;
    HalleyDecision const hd = halley_decide(lambda, e, lo, hi);
    if (hd.near) {
      // As in step 1 of default_body, with the error edf of the rational f'.
      double const h = hd.tiny ? 0.0 : hd.step;
      double const err = (kRationalRel + kU) * e.f + model_error(e.edf, h, hd.a, e.d4f);
      bool done = err <= kFastRel * e.f;
      opaque(done);
      if (done) {
        double const corr = model_increment(h, e);
        res.mu2 = e.f + corr;
        res.lambda = lambda + h;
        res.mu2_error = err;
        return true;
      }
    }
    if (hd.tiny) return false;
    lambda = hd.inside ? hd.next : 0.5 * (lo + hi);
  }
  return false;
}

// The rational step with its inputs: the seven coefficients, the start
// (M24) ((M22) where (M24) finds no bracket), then rational_iterate. The
// coefficients come first in program order: their independent vector work
// then overlaps with the start's dependency chain (measured: 9-14 ns per
// call less than the other order). Inlined into contact_default_v4, which
// calls the general method out of line (default_body_v4): 0.3-2 ns per call
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

// The general method compiled for x86-64-v4, from its own start (M22), with
// the same IEEE operations as the baseline (-ffp-contract=off,
// src/meson.build). Out of line: inlined into
// contact_default_v4 below, its register use made every call save and
// restore every callee-saved register, the rational step's calls included.
PW85_TARGET_V4 __attribute__((noinline)) Status default_body_v4(
    Vec3 const &r, Sym3 const &q1, Sym3 const &q2, MethodResult &res) noexcept {
  return default_body(r, q1, q2, res);
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
