// The decisions of DEFAULT's Halley iterations (docs/methods.md,
// "PW85_METHOD_DEFAULT"), written once for one pair (T = double: step 1 of
// default_body and the coefficient step, default.hpp) and for one pair per
// vector lane (T a vector type: first_step_lanes in contact/default.hpp,
// contact/default.hpp, coefficient_step_lanes). Every lane performs the scalar operations in
// the same order (those files are compiled without contraction,
// src/meson.build), so a lane takes the decisions of the one-pair code and
// computes the same bits.
#pragma once

#include <type_traits>

#include "common/fp.hpp"
#include "common/isa.hpp"
#include "common/lanes.hpp"
#include "contact/default_params.hpp"
#include "eval/f_coefficients_dd.hpp"

namespace pw85 {

// Halley iterations of DEFAULT: at most this many evaluations.
constexpr int kHalleyMaxIter = 30;

// Relative error of f from f_eval_coefficients (f_coefficients_dd.hpp): 2.2 u from
// the coefficients, about 13 u from the evaluation of A / B and s t.
constexpr double kCoefficientRel = 16.0 * kU;

template <class T>
struct HalleyDecision {
  T a, step, next;  // a = -f''; next = lambda + step
  lanes::MaskOf<T> inside, tiny, near;
};

// Narrows [lo, hi] by the sign of f', takes the safeguarded Halley step (M8)
// (Newton where Halley's denominator is not positive, bisection where f is
// not concave), and decides whether lambda is near enough for the quartic
// model (M18): f' small (gap f'^2 / 2a below kExtrapGap f) with the step
// inside the bracket, or the step below rounding. E is an evaluation with
// f, df, d2f, d3f, d4f at lambda.
template <class T, class E>
PW85_ALWAYS_INLINE HalleyDecision<T> halley_decide(T lambda, E const &e, T &lo,
                                                   T &hi) noexcept {
  using namespace default_params;
  using lanes::select;
  using lanes::vabs;
  typedef lanes::MaskOf<T> Mask;
  Mask const up = e.df > 0.0;
  lo = select(up, lambda, lo);
  hi = select(up, hi, lambda);
  T const a = -e.d2f;
  T const den = 2.0 * e.d2f * e.d2f - e.df * e.d3f;
  Mask const apos = a > 0.0;
  Mask const halley = apos & (den > 0.0);
  T const step = select(halley, -2.0 * e.df * e.d2f / den,  // Halley, eq. (M8)
                        select(apos, e.df / a, 0.5 * (lo + hi) - lambda));
  T const next = lambda + step;
  Mask const inside = (next > lo) & (next < hi);
  Mask const tiny = vabs(step) <= 2.0 * kU * lambda;
  Mask near = apos & (tiny | (inside & (e.df * e.df <= 2.0 * a * kExtrapGap * e.f)));
  // One branch per decision (opaque, isa.hpp): without it GCC tests
  // each comparison in turn, and their outcomes vary from pair to pair.
  if constexpr (std::is_same<T, double>::value) opaque(near);
  return HalleyDecision<T>{a, step, next, inside, tiny, near};
}

// Error of the quartic Taylor model (M18) at lambda with increment h: its
// truncation estimated by the last term, counted twice, and the error edf
// of f' (how well the maximiser is known, eq. (M10)).
template <class T>
PW85_ALWAYS_INLINE T model_error(T edf, T h, T a, T d4f) noexcept {
  using lanes::vabs;
  T const h2 = h * h;
  T const trunc = vabs(d4f * h2 * h2) * default_params::kInv24;
  return edf * vabs(h) + edf * edf / (2.0 * a) + 2.0 * trunc;
}

// The model's increment f(lambda + h) - f(lambda).
template <class T, class E>
PW85_ALWAYS_INLINE T model_increment(T h, E const &e) noexcept {
  using namespace default_params;
  return h * (e.df + h * (0.5 * e.d2f + h * (e.d3f * kInv6 + h * e.d4f * kInv24)));
}

// One step of the coefficient iteration (default.hpp, coefficient_iterate) after
// the evaluation e at lambda (f_eval_coefficients): done where the quartic
// model (M18) at lambda is accurate (mu2 = f + the model's increment, at
// lam = lambda + h, error err: kCoefficientRel f plus one rounding, the
// model's error and that of lambda, eq. (M10)); tiny where the step is
// below rounding (the coefficient step declines); next: the next iterate.
template <class T>
struct CoefficientDecision {
  lanes::MaskOf<T> done, tiny;
  T next, mu2, lam, err;
};

template <class T, class E>
PW85_ALWAYS_INLINE CoefficientDecision<T> coefficient_decide(T lambda, E const &e, T &lo,
                                                       T &hi) noexcept {
  using namespace default_params;
  using lanes::select;
  HalleyDecision<T> const hd = halley_decide(lambda, e, lo, hi);
  CoefficientDecision<T> d{};
  d.tiny = hd.tiny;
  d.next = select(hd.inside, hd.next, 0.5 * (lo + hi));
  if (lanes::any(hd.near)) {
    T const h = select(hd.tiny, T{}, hd.step);
    T const err = (kCoefficientRel + kU) * e.f + model_error(e.edf, h, hd.a, e.d4f);
    lanes::MaskOf<T> done = hd.near & (err <= kFastRel * e.f);
    if constexpr (std::is_same<T, double>::value) opaque(done);
    d.done = done;
    if (lanes::any(done)) {
      d.mu2 = e.f + model_increment(h, e);
      d.lam = lambda + h;
      d.err = err;
    }
  }
  return d;
}

// Iterations counted for one pair (an int, active true) or per lane (the
// mask, -1 in the active lanes, subtracted).
PW85_ALWAYS_INLINE void count_active(int &n, bool active) noexcept { n += active; }
template <class Mask>
PW85_ALWAYS_INLINE void count_active(Mask &n, Mask active) noexcept { n -= active; }

// The coefficient iteration (docs/methods.md, "PW85_METHOD_DEFAULT"): from
// lambda, Halley steps (M8) on f evaluated from the seven coefficients
// (f_eval_coefficients, f_coefficients_dd.hpp) until coefficient_decide accepts the
// quartic model (M18), at most kHalleyMaxIter evaluations. One pair
// (Lane = double, coefficients CoefficientsDD) or one pair per lane, the same
// operations in each lane. Returns the pairs (lanes) accepted, with mu2,
// lam, err there; the others declined (an evaluation failed, the step fell
// below rounding, or no convergence). iterations: counted as in
// count_active (default.hpp).
template <class Lane, class Coefficients, class Count>
PW85_ALWAYS_INLINE lanes::MaskOf<Lane> coefficient_iterate(Coefficients const &k, Lane lambda,
                                                        lanes::MaskOf<Lane> active, Lane &mu2,
                                                        Lane &lam, Lane &err,
                                                        Count &iterations) noexcept {
  using lanes::mask_not;
  using lanes::select;
  lanes::MaskOf<Lane> accepted{};
  Lane lo{}, hi = Lane{} + 1.0;
  for (int it = 0; it < kHalleyMaxIter && lanes::any(active); ++it) {
    count_active(iterations, active);
    CoefficientEvalOf<Lane> e;
    active &= f_eval_coefficients(lambda, k, e);
    CoefficientDecision<Lane> const d = coefficient_decide(lambda, e, lo, hi);
    lanes::MaskOf<Lane> const done = active & d.done;
    mu2 = select(done, d.mu2, mu2);
    lam = select(done, d.lam, lam);
    err = select(done, d.err, err);
    accepted |= done;
    active &= mask_not(done) & mask_not(d.tiny);
    lambda = d.next;
  }
  return accepted;
}

}  // namespace pw85
