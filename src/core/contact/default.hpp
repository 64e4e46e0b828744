// PW85_METHOD_DEFAULT (docs/methods.md, section "PW85_METHOD_DEFAULT"):
// the bodies, each written once for one pair and, where the batch calls
// run it in vector lanes, for one pair per lane; default_variants.cpp
// compiles them for each instruction set. On x86-64-v4, first the
// coefficient step (coefficient_step below: f from its seven coefficients in
// double-double, f_coefficients_dd.hpp, from the grid start (M24),
// start_scan.hpp; where only d0 or d3 failed its bound, the same step again
// with those two from det_precise, coefficient_step_precise); when it
// declines, and on other CPUs, the general method (default_body), steps
// numbered as in docs/methods.md:
//  1. from the start (M22) (start.hpp: Newton on the fixed-point equation of
//     (M19) in logarithmic coordinates), a safeguarded Halley iteration as
//     NEWTON's (newton.cpp) but with f and its derivatives from the
//     adjugate of Q(lambda) (f_adj.hpp, eq. (M16)) until the quartic model
//     (M18) is accurate; its result is returned when the first-order error
//     of the double f (eqs. (M10), (M17)), or else that of f by the
//     stationary form (f_dd.hpp, eq. (M11), second order in the error of
//     s), is below kFastRel * mu2 (most pairs) (first_step);
//  2. otherwise the NEWTON iteration in double (newton.cpp) with its error
//     estimate (eq. (M10)), then the stationary form 2 r^T s - s^T Q s with
//     compensated dot products at its final lambda; either result is
//     returned when its estimate is below kFastRel * mu2;
//  3. otherwise f and f' are re-evaluated in double-double at the current
//     lambda (f_dd.hpp, eq. (M11)) and Newton steps on f' are taken with the
//     double-precision f'' as slope, until the gap f'^2 / (2|f''|) is below
//     2^-60 f. Since mu2 = max f, an error delta on lambda changes mu2 by
//     |f''| delta^2 / 2 only: the accuracy of mu2 is the accuracy of the
//     double-double f, about kappa(Q) 2^-104 relative;
//  4. when the double iteration failed (Q(lambda) not numerically positive
//     definite in double) or its f'' is not accurate to 2^-6 (maximiser
//     very near 0 or 1), dd_bracket (eq. (M26)): double-double f and f'
//     only, with a bound on max f from concavity.
#pragma once

#include <cmath>
#include <limits>

#include <type_traits>
#include <utility>

#include "common/fp.hpp"
#include "common/lanes.hpp"
#include "common/screen.hpp"
#include "contact/contact.hpp"
#include "contact/default_params.hpp"
#include "eval/f_adj.hpp"
#include "eval/f_dd.hpp"
#include "eval/f_coefficients_dd.hpp"
#include "common/isa.hpp"
#include "contact/newton.hpp"
#include "contact/halley_step.hpp"
#include "contact/start_lanes.hpp"
#include "contact/start_scan.hpp"

namespace pw85 {
namespace default_method {
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

// DEFAULT's start, eq. (M22) (start.hpp), for one pair or one pair per lane.
template <class Vec, class Sym>
PW85_ALWAYS_INLINE auto default_start(Vec const &r, Sym const &q1, Sym const &q2) noexcept {
  return log_newton_start<kStartMin, kStartMax>(r, q1, q2, kStartTol);
}

// A double-double evaluation (f_dd.hpp) with bounds on the errors of f and
// f': ef from the bound (M6) of phi plus the rounding of f; edf as in (M10),
// rel (|p'| phi + p |phi'|), times 4 for the error of phi' (first order
// in the error of s, as that of phi), plus the rounding of f'.
struct DDPoint {
  double x, f, df, ef, edf;
};

inline bool dd_point(double x, Vec3 const &r, Sym3 const &q1, Sym3 const &q2, DDPoint &p) noexcept {
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
inline double tangent_bound(DDPoint const &lo, DDPoint const &hi) noexcept {
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
inline __attribute__((noinline)) Status dd_bracket(Vec3 const &r, Sym3 const &q1_in,
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

// f by the stationary form (f_dd.hpp, eq. (M11)) at lambda: the one-pair
// call, or that call lane by lane in the lanes of want (0 in the others).
PW85_ALWAYS_INLINE double stationary_form(double lambda, Vec3 const &r, Sym3 const &q1,
                                          Sym3 const &q2, Vec3 const &s, bool) noexcept {
  return f_stationary(lambda, r, q1, q2, s);
}
template <int W>
PW85_ALWAYS_INLINE lanes::VecD<W> stationary_form(lanes::VecD<W> lambda,
                                                  lanes::Vec3L<W> const &r,
                                                  lanes::SymL<W> const &q1,
                                                  lanes::SymL<W> const &q2,
                                                  lanes::Vec3L<W> const &s,
                                                  lanes::MaskD<W> want) noexcept {
  lanes::VecD<W> out{};
  for (int l = 0; l < W; ++l) {
    if (want[l] == 0) continue;
    out[l] = f_stationary(lambda[l], Vec3{{r[0][l], r[1][l], r[2][l]}},
                          Sym3{{q1[0][l], q1[1][l], q1[2][l], q1[3][l], q1[4][l], q1[5][l]}},
                          Sym3{{q2[0][l], q2[1][l], q2[2][l], q2[3][l], q2[4][l], q2[5][l]}},
                          Vec3{{s[0][l], s[1][l], s[2][l]}});
  }
  return out;
}

// What step 1 of DEFAULT leaves: where accepted, mu2, its lambda and error;
// elsewhere the lambda step 2 starts from (the last lambda evaluated, or the
// next iterate where the model was accurate but its error too large).
template <class Lane>
struct FirstStep {
  lanes::MaskOf<Lane> accepted;
  Lane mu2, lambda, err;
  Lane start;
};

// Step 1 of DEFAULT (docs/methods.md): from the start (M22), the
// safeguarded Halley iteration (M8) with adjugate evaluations (f_adj.hpp,
// eq. (M16)) until the quartic model (M18) is accurate; accepted where the
// first-order error of the double f (eqs. (M10), (M17)), or else the error
// of the stationary form (M11), is below kFastRel mu2. Written once for one
// pair (Lane = double, Vec3, Sym3: default_body) and for one pair per lane
// (lanes::VecD, Vec3L, SymL: default_lanes), with the same operations in the
// same order in each lane (this file is compiled without contraction,
// src/meson.build), so a lane computes the one-pair call's bits. active:
// the pairs (lanes) to iterate; at most kMaxIter evaluations.
template <int kMaxIter, class Lane, class Vec, class Sym, class Count>
PW85_ALWAYS_INLINE FirstStep<Lane> first_step(Vec const &r, Sym const &q1, Sym const &q2,
                                              Sym const &d, lanes::MaskOf<Lane> active,
                                              Count &iterations) noexcept {
  using lanes::mask_not;
  using lanes::select;
  using lanes::vabs;
  typedef lanes::MaskOf<Lane> Mask;
  Lane const lambda0 = default_start(r, q1, q2);
  FirstStep<Lane> out{};
  out.start = lambda0;
  Lane lo{}, hi = Lane{} + 1.0, lambda = lambda0;
  AdjEvalOf<Lane, Sym, Vec> e;
  for (int it = 0; it < kMaxIter && lanes::any(active); ++it) {
    count_active(iterations, active);
    active &= f_eval_adj(lambda, r, q1, q2, d, e);
    out.start = select(active, lambda, out.start);
    HalleyDecision<Lane> const hd = halley_decide(lambda, e, lo, hi);
    Mask const near = active & hd.near;
    if (lanes::any(near)) {
      // Error terms (eqs. (M10), (M17)): err_s bounds the error of s.
      Vec const err_s = adj_error(e, r, q1, q2);
      Lane const p = lambda * (1.0 - lambda), p1 = vabs(1.0 - 2.0 * lambda);
      Vec const as{{vabs(e.s[0]), vabs(e.s[1]), vabs(e.s[2])}};
      Sym da;
      for (int i = 0; i < kSym; ++i) da[i] = vabs(d[i]);
      Vec const ar{{vabs(r[0]), vabs(r[1]), vabs(r[2])}};
      Lane const edf = p1 * dot(ar, err_s) + 2.0 * p * dot(as, multiply(da, err_s)) +
                       4.0 * kU * (p1 * e.phi + p * vabs(e.dphi));
      // Quartic Taylor model at lambda (eq. (M18)).
      Lane const h = select(hd.tiny, Lane{}, hd.step);
      Lane const err_l = model_error(edf, h, hd.a, e.d4f);
      Mask done = near & ((err_l <= kExtrapBudget * e.f) | (vabs(e.df) <= 2.0 * edf) | hd.tiny);
      if constexpr (std::is_same<Lane, double>::value) opaque(done);
      if (lanes::any(done)) {
        Lane const corr = model_increment(h, e);
        // First-order error of the double f: |r|^T err_s + rounding of r^T s.
        Lane const err1 =
            p * (dot(ar, err_s) + 3.0 * kU * dot(ar, as)) + 4.0 * kU * e.f + err_l;
        Mask accept = done & (err1 <= kFastRel * e.f);
        Lane m = e.f + corr, em = err1;
        Mask const slow = done & mask_not(accept);
        if (lanes::any(slow)) {
          // Second-order error of the stationary form: p err_s^T |Q| err_s;
          // tested before the form is computed (with f for mu2, 1e-3
          // margin), so that pairs bound to fail go straight to step 2.
          Sym qa;
          for (int i = 0; i < kSym; ++i) qa[i] = vabs(e.q[i]);
          Lane const err2 = p * dot(err_s, multiply(qa, err_s)) + err_l;
          Mask const try_stat =
              slow & mask_not(Mask(err2 + e.f * kStatRel > 0.999 * kFastRel * e.f));
          if (lanes::any(try_stat)) {
            Lane const ms = stationary_form(lambda, r, q1, q2, e.s, try_stat) + corr;
            Lane const es = ms * kStatRel + err2;
            Mask const stat_ok = try_stat & (es <= kFastRel * ms);
            m = select(stat_ok, ms, m);
            em = select(stat_ok, es, em);
            accept |= stat_ok;
          }
        }
        out.mu2 = select(accept, m, out.mu2);
        out.lambda = select(accept, lambda + h, out.lambda);
        out.err = select(accept, em, out.err);
        out.accepted |= accept;
        Mask const to_next = done & mask_not(accept) & mask_not(hd.tiny);
        out.start = select(to_next, hd.next, out.start);
        active &= mask_not(done);  // accepted, or step 2 needed
      }
    }
    active &= mask_not(hd.tiny);  // step 2 needed
    lambda = select(hd.inside, hd.next, 0.5 * (lo + hi));
  }
  return out;
}

// The whole method, inlined into one function per instruction-set level
// (default_variants.cpp). Its hot part, the start and the adjugate
// iteration of step 1, is inline (start.hpp, f_adj.hpp) and so compiled for
// that level; steps 2-4 call the baseline code of newton.cpp and f_dd.hpp.
PW85_ALWAYS_INLINE Status default_body(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                                       MethodResult &res) noexcept {
  res.iterations = 0;
  Sym3 const d = difference(q2, q1);
  // Step 1: Halley iteration with adjugate evaluations (first_step).
  FirstStep<double> const first = first_step<kAdjMaxIter, double>(r, q1, q2, d, true,
                                                                   res.iterations);
  if (first.accepted) {
    res.mu2 = first.mu2;
    res.lambda = first.lambda;
    res.mu2_error = first.err;
    return kOk;
  }
  double const start = first.start;
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
  // Step 3: Newton steps on the double-double f'.
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
      // A slope beyond the bound of (M3), -f'' <= 2 f / min(lambda,
      // 1 - lambda)^2 (times 2 for rounding), is not the curvature but the
      // rounding of a Q(lambda) numerically singular in double, which the
      // first-order rel_double does not see: step 4 instead.
      double const m = std::fmin(lambda, 1.0 - lambda);
      if (!(a * m * m <= 4.0 * fd.f)) break;
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

// The vector of p[l][i] over the lanes l.
template <std::size_t... kLane>
PW85_ALWAYS_INLINE lanes::VecD<sizeof...(kLane)> column(double const *const p[], int i,
                                                       std::index_sequence<kLane...>) noexcept {
  return lanes::VecD<sizeof...(kLane)>{p[kLane][i]...};
}

// Step 1 of DEFAULT for kLanes pairs at once, pair l in lane l of each
// vector (docs/batch.md, "Throughput"): the screen of the entry
// (screen.hpp, screen_contact_lanes), then first_step with at most
// kLaneMaxIter evaluations. accepted[l]: the pair's result is that of the
// one-pair call, bit for bit (first_step accepted it and it keeps the
// promise that methods.cpp checks after every method); otherwise (screen
// failed, a failed evaluation, step 2 needed, more steps needed) the pair is
// left to the caller's one-pair call.
constexpr int kLaneMaxIter = 8;  // the pairs that need more: one-pair call

PW85_ALWAYS_INLINE void first_step_lanes(double const *const rp[lanes::kLanes],
                                         double const *const q1p[lanes::kLanes],
                                         double const *const q2p[lanes::kLanes],
                                         MethodResult res[lanes::kLanes],
                                         bool accepted[lanes::kLanes]) noexcept {
  constexpr int kWidth = lanes::kLanes;
  typedef lanes::VecD<kWidth> Lane;
  lanes::Vec3L<kWidth> r;
  lanes::SymL<kWidth> q1, q2;
  auto const lane_index = std::make_index_sequence<kWidth>();
  for (int i = 0; i < kDim; ++i) r[i] = column(rp, i, lane_index);
  for (int i = 0; i < kSym; ++i) {
    q1[i] = column(q1p, i, lane_index);
    q2[i] = column(q2p, i, lane_index);
  }
  lanes::MaskD<kWidth> const active = screen_contact_lanes<Lane>(r, q1, q2, kSafeLo, kSafeHi);
  lanes::MaskD<kWidth> iterations{};
  FirstStep<Lane> first{};
  if (lanes::any(active)) {
    lanes::SymL<kWidth> d;
    for (int i = 0; i < kSym; ++i) d[i] = q2[i] - q1[i];
    first = first_step<kLaneMaxIter, Lane>(r, q1, q2, d, active, iterations);
  }
  // The promise checked after every method (methods.cpp, checked).
  lanes::MaskD<kWidth> const kept = first.accepted & (first.mu2 >= 0.0) &
                                    (first.lambda >= 0.0) & (first.lambda <= 1.0) &
                                    (first.err == first.err);
  for (int l = 0; l < kWidth; ++l) {
    accepted[l] = kept[l] != 0;
    res[l].mu2 = first.mu2[l];
    res[l].lambda = first.lambda[l];
    res[l].mu2_error = first.err[l];
    res[l].iterations = static_cast<int>(iterations[l]);
    res[l].method = kMethodDefault;
  }
}

#if PW85_ISA_LEVELS
// coefficient_iterate (halley_step.hpp) for one pair from lambda0: true
// with res written when it accepts.
PW85_ALWAYS_INLINE bool coefficient_step_accepted(CoefficientsDD const &k, double lambda0,
                                          MethodResult &res) noexcept {
  double mu2 = 0.0, lam = 0.0, err = 0.0;
  res.iterations = 0;
  if (!coefficient_iterate(k, lambda0, true, mu2, lam, err, res.iterations)) return false;
  res.mu2 = mu2;
  res.lambda = lam;
  res.mu2_error = err;
  return true;
}

// The coefficient step with its inputs: the seven coefficients, the start
// (M24) ((M22) where (M24) finds no bracket), then coefficient_iterate. The
// coefficients come first in program order: their independent vector work
// then overlaps with the start's dependency chain. Inlined into contact_v4
// (default_variants.cpp), which calls the rest out of line (declined_v4);
// inlined together with default_body it was slower. Measured by
// build/bench/bench_batch (one-pair DEFAULT loop).
PW85_V4_INLINE bool coefficient_step(
    Vec3 const &r, Sym3 const &q1, Sym3 const &q2, MethodResult &res) noexcept {
  CoefficientsDD k;
  bool const coef_ok = coefficients_dd(r, q1, q2, k);
  double lambda0 = scan_start(r, q1, q2);
  if (lambda0 < 0.0) lambda0 = default_start(r, q1, q2);
  return coef_ok && coefficient_step_accepted(k, lambda0, res);
}

// The coefficient step again where d0 or d3 failed its bound (cancellation
// beyond 2^45: nearly singular Q1 or Q2), with those two from det_precise
// (f_coefficients_dd.hpp). False where coefficient_step declined for
// another reason.
PW85_V4_INLINE bool coefficient_step_precise(
    Vec3 const &r, Sym3 const &q1, Sym3 const &q2, MethodResult &res) noexcept {
  CoefficientsDD k;
  if (coefficients_dd(r, q1, q2, k) || !coefficients_dets_precise(q1, q2, k))
    return false;
  double lambda0 = scan_start(r, q1, q2);
  if (lambda0 < 0.0) lambda0 = default_start(r, q1, q2);
  return coefficient_step_accepted(k, lambda0, res);
}

#endif

#if PW85_ISA_LEVELS
namespace lanes8 {

using namespace lanes;
constexpr int W = kDefaultLanes;
static_assert(W == 8, "one pair per lane of lanes::Lanes8");
typedef VecD<W> V8;
typedef MaskD<W> M8;

PW85_V4_INLINE V8 bc(double x) noexcept { return V8{} + x; }

PW85_V4_INLINE M8 from_bits(LaneBits8 k) noexcept { return mask_of(k); }

PW85_V4_INLINE LaneBits8 to_bits(M8 m) noexcept { return bits(m); }

// The coefficients of coefficients_dd (f_coefficients_dd.hpp), one
// pair per lane.
struct CoefL {
  V8 c[8];
};

// The permutations of coefficients_dd (ip, iq, is, it), and the
// factors of w_k r_i r_j, per adjugate entry k (storage order 00 01 02 11
// 12 22).
constexpr int kIp[kSym] = {3, 2, 1, 0, 1, 0}, kIq[kSym] = {5, 4, 4, 5, 2, 3};
constexpr int kIs[kSym] = {4, 1, 2, 2, 0, 1}, kIt[kSym] = {4, 5, 3, 2, 4, 1};
constexpr int kRi[kSym] = {0, 0, 0, 1, 1, 2}, kRj[kSym] = {0, 1, 2, 1, 2, 2};
constexpr double kW[kSym] = {1.0, 2.0, 2.0, 1.0, 2.0, 1.0};

// The terms (dd_lanes::terms) of adjugate entries k and k + 1, added: round 1 of
// the tree.
PW85_V4_INLINE void pair_sum(Vec3L<W> const &r, SymL<W> const &a, SymL<W> const &b, int k,
                             dd_lanes::DD v[7], V8 m[7]) noexcept {
  using namespace dd_lanes;
  Terms t[2];
  for (int i = 0; i < 2; ++i) {
    int const e = k + i;
    V8 const we = bc(kW[e]);
    terms(a[kIp[e]], a[kIq[e]], a[kIs[e]], a[kIt[e]], b[kIp[e]], b[kIq[e]], b[kIs[e]],
          b[kIt[e]], a[e] * we, b[e] * we, r[kRi[e]] * we, r[kRj[e]], t[i]);
  }
  for (int j = 0; j < 7; ++j) {
    v[j] = add(t[0].v[j], t[1].v[j]);
    m[j] = t[0].m[j] + t[1].m[j];
  }
}

// coefficients_dd for the eight pairs: lane k of its vectors
// (entry k) is the vector of entry k here, and its three rounds of
// transposed sums become, per coefficient, the same sums in the same tree,
// ((0 + 1) + (2 + 3)) + ((4 + 5) + (6 + 7)), but for the last term: entries
// 6 and 7 are its padding, +0 in both parts, and adding that +0 pair
// changes nothing but the sign of a zero part; a nonzero sum is the same
// bits without it, and a zero sum fails the test (sum > 0) in both.
// Returns the lanes where every coefficient passes its test.
PW85_V4_INLINE M8 coefficients(Vec3L<W> const &r, SymL<W> const &a, SymL<W> const &b,
                              CoefL &out) noexcept {
  using namespace dd_lanes;
  // Rounds 2 and 3, entry pair by entry pair.
  DD s0123[7], v[7];
  V8 m0123[7], m[7];
  pair_sum(r, a, b, 0, s0123, m0123);
  pair_sum(r, a, b, 2, v, m);
  for (int j = 0; j < 7; ++j) {
    s0123[j] = add(s0123[j], v[j]);
    m0123[j] = m0123[j] + m[j];
  }
  pair_sum(r, a, b, 4, v, m);
  // The scale, as in coefficients_dd.
  V8 const tr = ((a[0] + a[3]) + a[5]) + ((b[0] + b[3]) + b[5]);
  M8 const bits = reinterpret_cast<M8>(tr);
  M8 const e = ((bits >> 52) & 0x7FF) - 1023;
  V8 const scale = reinterpret_cast<V8>((1023 - 3 * e) << 52);
  LaneBits8 ok = 0xFF, okd[2] = {0xFF, 0xFF};
  for (int j = 0; j < 7; ++j) {
    double const third = j == 3 || j == 6 ? kThird : 1.0;
    LaneBits8 okj;
    out.c[j] = finish(add(s0123[j], v[j]), m0123[j] + m[j], bc(third) * scale, okj);
    if (j == 3 || j == 6)
      okd[j == 6] = okj;
    else
      ok &= okj;
  }
  // d0 and d3 where their bound fails: det_precise, as in
  // coefficients_dets_precise (all eight lanes, when one needs it).
  SymL<W> const *const qs[2] = {&a, &b};
  for (int mat = 0; mat < 2; ++mat) {
    if (okd[mat] != 0xFF) {
      V8 q[kSym], det;
      for (int i = 0; i < kSym; ++i) q[i] = (*qs[mat])[i];
      LaneBits8 const take = static_cast<LaneBits8>(~okd[mat]) & to_bits(det_precise(q, det));
      int const j = mat == 0 ? 3 : 6;
      out.c[j] = blend(take, det * scale, out.c[j]);
      okd[mat] |= take;
    }
    ok &= okd[mat];
  }
  return from_bits(ok);
}

// scan_start (start_scan.hpp) for the eight pairs; (M22) (start.hpp) in the
// lanes of want where it returns -1.
PW85_V4_INLINE V8 grid_start(Vec3L<W> const &r, SymL<W> const &q1, SymL<W> const &q2, M8 want,
                            double const *const rp[W], double const *const q1p[W],
                            double const *const q2p[W]) noexcept {
  using namespace default_params;
  StartQuarticsOf<VecD<W>> sq;
  start_quartics<false>(r, q1, q2, sq);
  V8 pn[7], pdn[7];
  scan_sextics(sq, pn, pdn);
  // Coarse grid: k = the first point where a1 - x^2 a2 is not positive;
  // xa = point k - 1 (k = 0, or none: off the grid). Lanes outside want
  // count as found from the start (their values are not used).
  LaneBits8 const wanted = to_bits(want);
  LaneBits8 found = static_cast<LaneBits8>(~wanted), first = 0;
  V8 xa{};
  // The points in groups of kCoarseGroup, evaluated before their masks
  // are taken in order (a lane found at a point ignores the later ones, so
  // k and xa are those of the point-by-point scan). Groups of 4 were
  // faster than 1, 2, 8 or 16 points per test of found
  // (pw85_contact_function_pairs, build/bench/bench_batch --n 100000
  // --reps 5, runs alternating the builds).
  constexpr int kCoarseGroup = 4;
  static_assert(32 % kCoarseGroup == 0, "whole groups");
  for (int i0 = 0; i0 < 32 && found != 0xFF; i0 += kCoarseGroup) {
    unsigned pos[kCoarseGroup];
    for (int u = 0; u < kCoarseGroup; ++u)
      pos[u] = scan::positive_mask(scan::sextic(pn, bc(kScanCoarse[i0 + u])));
    for (int u = 0; u < kCoarseGroup; ++u) {
      int const i = i0 + u;
      LaneBits8 const nonpos = static_cast<LaneBits8>(~pos[u] & ~found);
      if (i == 0)
        first = nonpos;
      else
        xa = blend(nonpos, bc(kScanCoarse[i - 1]), xa);
      found |= nonpos;
    }
  }
  LaneBits8 const on_grid = found & wanted & static_cast<LaneBits8>(~first);
  // Fine grid: x_j = xa exp(j h / 15); the first non-positive j, clamped
  // to 1..15 (none: 15), per lane in jv. Point j = 0 is not evaluated: x_0
  // = xa * 1 is the coarse point k - 1, whose value, the same operations
  // on the same x, was positive. Then x1 = x_(j-1), x2 = x_j and n1, n2
  // there, the same products and the same sextic as at the grid points:
  // faster than carrying n1, n2, x1, x2 through the loop by four blends per
  // point (build/bench/bench_batch --n 100000 --reps 5, runs alternating
  // the builds).
  LaneIndex8 jv = LaneIndex8{} + 15;
  found = static_cast<LaneBits8>(~on_grid);
  for (int j = 1; j < 15 && found != 0xFF; ++j) {
    LaneBits8 const nonpos = static_cast<LaneBits8>(
        ~scan::positive_mask(scan::sextic(pn, xa * bc(kScanFine[j]))) & ~found);
    found |= nonpos;
    jv = blend(nonpos, LaneIndex8{} + j, jv);
  }
  V8 const f0 = load(kScanFine), f1 = load(kScanFine + 8);
  V8 const x1v = xa * permute(f0, jv - 1, f1);
  V8 const x2v = xa * permute(f0, jv, f1);
  V8 const n1 = scan::sextic(pn, x1v), n2 = scan::sextic(pn, x2v);
  V8 const e1 = scan::sextic(pdn, x1v), e2 = scan::sextic(pdn, x2v);
  V8 const lam = scan_interpolate(n1, e1, n2, e2, x1v);
  M8 const ok = from_bits(on_grid) & (lam > 0.0) & (lam < 1.0);
  M8 const m22 = want & ~ok;
  if (!any(m22)) return lam;
  V8 out = lam;
  for (int l = 0; l < W; ++l)
    if (m22[l] != 0)
      out[l] = log_newton_start<kStartMin, kStartMax>(view_vec3(rp[l]), view_sym3(q1p[l]),
                                                      view_sym3(q2p[l]), kStartTol);
  return out;
}


// The coefficient step for kDefaultLanes pairs at once (docs/batch.md,
// "Throughput"), pair l in lane l of each vector: the screen of the entry
// (screen.hpp, screen_contact_lanes), the seven coefficients (M12)-(M13)
// in double-double (coefficients below: dd_lanes::terms per adjugate entry, then
// the sums over the entries; det_precise for d0, d3 in lanes where their
// bound fails), the grid start (M24) (grid_start below; (M22) for a lane
// whose root is off the grid), and coefficient_iterate (halley_step.hpp).
// Every lane performs the IEEE operations of the one-pair code (coefficient_step)
// in the same order (no contraction, src/meson.build), so a lane carries
// the bits of pw85_contact_function_method. A lane whose coefficient step
// declines runs general (the general method alone, as the one-pair call
// after that step); a lane that fails the screen, or whose result breaks
// the promise that methods.cpp checks after every method, is returned
// undecided for the caller's one-pair call.
template <Status (*general)(Vec3 const &, Sym3 const &, Sym3 const &, MethodResult &) noexcept>
PW85_V4_INLINE void coefficient_step_lanes(double const *const rp[W], double const *const q1p[W],
                                   double const *const q2p[W], MethodResult res[W],
                                   int status[W]) noexcept {
  Vec3L<W> r;
  SymL<W> q1, q2;
  for (int l = 0; l < W; ++l) {
    for (int i = 0; i < kDim; ++i) r[i][l] = rp[l][i];
    for (int i = 0; i < kSym; ++i) {
      q1[i][l] = q1p[l][i];
      q2[i][l] = q2p[l][i];
    }
  }
  M8 const screen = screen_contact_lanes<V8>(r, q1, q2, kSafeLo, kSafeHi);
  M8 accepted{};
  V8 mu2{}, lam{}, err{};
  M8 iters{};
  if (any(screen)) {
    // coefficient_step: the coefficients, the start, coefficient_iterate.
    CoefL k;
    M8 active = screen & coefficients(r, q1, q2, k);
    V8 lambda{};
    if (any(active)) lambda = grid_start(r, q1, q2, active, rp, q1p, q2p);
    accepted = coefficient_iterate(k, lambda, active, mu2, lam, err, iters);
  }
  // The promise checked after every method (methods.cpp, checked).
  M8 const kept = (mu2 >= 0.0) & (lam >= 0.0) & (lam <= 1.0) & (err == err);
  for (int l = 0; l < W; ++l) {
    MethodResult &o = res[l];
    o.method = kMethodDefault;
    if (accepted[l] != 0) {
      o.mu2 = mu2[l];
      o.lambda = lam[l];
      o.mu2_error = err[l];
      o.iterations = static_cast<int>(iters[l]);
      status[l] = kept[l] != 0 ? kOk : kLaneUndecided;
    } else if (screen[l] != 0) {
      // The coefficient step declined: the general method, as in
      // the one-pair call.
      Status const s = general(view_vec3(rp[l]), view_sym3(q1p[l]),
                                                  view_sym3(q2p[l]), o);
      bool const ok = o.mu2 >= 0.0 && o.lambda >= 0.0 && o.lambda <= 1.0 &&
                      o.mu2_error == o.mu2_error;
      status[l] = ok ? s : kLaneUndecided;
    } else {
      status[l] = kLaneUndecided;
    }
  }
}
}  // namespace lanes8
#endif

}  // namespace default_method
}  // namespace pw85
