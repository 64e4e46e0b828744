// Dispatcher of pw85_contact_function_method (docs/methods.md): the common
// preliminaries of every method, then the method itself.
//  - r = 0: mu2 = 0 exactly (f vanishes identically), lambda = 1/2;
//  - r and Q1, Q2 are rescaled by powers of two (exact) when their magnitudes
//    are extreme, so that no method overflows or underflows:
//    r' = 2^-er r, Q' = 2^-eq Q  =>  mu2 = 2^(2 er - eq) mu2', same lambda;
//  - BRENT is pw85 1.0's algorithm (brent.cpp) plus the error estimate of
//    eq. (M10) at its lambda, compared with kBrentRelAccuracy.
#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/contact.hpp"
#include "dca/dca.hpp"
#include "common/magnitude.hpp"
#include "contact/newton.hpp"
#include "common/screen.hpp"
#include "common/scaling.hpp"
#include "dispatch/kernels.hpp"

namespace pw85 {

namespace {

// Error estimate of a result (mu2, lambda) of a method without its own
// accuracy control: the (M10) estimate of a double L D L^T evaluation at
// lambda plus the distance of mu2 from that f. NaN when f cannot be
// evaluated at lambda; f_at receives that f (NaN if none).
double error_at(double mu2, double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                double &f_at) noexcept {
  NewtonState st;
  FEval &e = st.e;
  f_at = std::nan("");
  st.step = 0.0;
  st.trunc = 0.0;
  st.rel = -1.0;
  if (!(std::isfinite(lambda) && f_eval(lambda, r, q1, q2, difference(q2, q1), e)))
    return std::nan("");
  f_at = e.f;
  st.mu2 = e.f;
  st.lambda = e.lambda;
  return newton_error(st, r, q1, q2) + std::fabs(e.f - mu2);
}

Status contact_brent_checked(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                             MethodResult &res) noexcept {
  ContactResult cr;
  Status const s = contact_brent(r, q1, q2, cr);
  res.mu2 = cr.mu2;
  res.lambda = cr.lambda;
  res.iterations = cr.iterations;
  double f;
  res.mu2_error = error_at(cr.mu2, cr.lambda, r, q1, q2, f);
  if (!std::isfinite(res.mu2)) {
    res.mu2 = std::isfinite(f) ? f : 0.0;
    return kNoConvergence;
  }
  if (s != kOk) return s;
  return res.mu2_error <= kBrentRelAccuracy * res.mu2 ? kOk : kInaccurate;
}

// ZHENG (zheng.cpp) with the same independent check as BRENT: its own
// estimate (D13) compares mu2 with a double f at its lambda, which can agree
// with it while both are wrong when Q(lambda) is ill-conditioned.
Status contact_zheng_checked(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                             MethodResult &res) noexcept {
  Status const s = contact_zheng_method(r, q1, q2, res);
  double f;
  double const err = error_at(res.mu2, res.lambda, r, q1, q2, f);
  if (!(err <= res.mu2_error)) res.mu2_error = err;  // also replaces a NaN
  if (s != kOk) return s;
  return res.mu2_error <= kZhengRelAccuracy * res.mu2 ? kOk : kInaccurate;
}

// The statuses that write an estimate (include/pw85.h).
constexpr bool writes_estimate(Status s) noexcept {
  return s == kOk || s == kInaccurate || s == kNoConvergence;
}

// A best estimate of max f where a method ended without one. f is concave
// on [0, 1] (eq. (M3)): f' decreases, and every evaluated point with f' > 0
// (< 0) lies left (right) of the maximiser. f is evaluated in double
// (L D L^T, eq. (M5)) at lambda = 1/2 and at 2^-k, 1 - 2^-k (k = 2 ... 64,
// then up to 1074),
// so that a maximiser near 0 or 1 is met where Q(lambda) is nearly singular
// elsewhere; then bisection on the sign of f' between the nearest points on
// either side, stopping at the first failed evaluation. mu2 = the largest f
// met, lambda its point. Error (f concave): on [lo, hi], which holds the
// maximiser, f* <= f(x) + |f'(x)| (hi - lo) for an evaluated end x, plus
// the error of that f (eq. (M6)); +inf when no end was evaluated. No
// evaluation at all: mu2 = 0 (f >= 0), lambda = 1/2, error +inf.
void best_estimate(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, MethodResult &res) noexcept {
  Sym3 const d = difference(q2, q1);
  double const inf = std::numeric_limits<double>::infinity();
  FEval best, lo_e, hi_e, e;
  best.f = -1.0;
  double lo = 0.0, hi = 1.0;
  bool have_lo = false, have_hi = false;
  auto take = [&](FEval const &x) {
    if (x.f > best.f) best = x;
    if (x.df > 0.0 && x.lambda >= lo) {
      lo = x.lambda;
      lo_e = x;
      have_lo = true;
    } else if (x.df <= 0.0 && x.lambda <= hi) {
      hi = x.lambda;
      hi_e = x;
      have_hi = true;
    }
  };
  auto probe = [&](int k) {
    double const t = std::ldexp(1.0, -k);
    if (f_eval(t, r, q1, q2, d, e)) take(e);
    if (k <= 53 && f_eval(1.0 - t, r, q1, q2, d, e)) take(e);
  };
  if (f_eval(0.5, r, q1, q2, d, e)) take(e);
  for (int k = 2; k <= 64; ++k) probe(k);
  for (int k : {128, 256, 512, 768, 1022, 1074}) probe(k);
  for (int it = 0; it < 100 && hi - lo > 4.0 * kU * hi; ++it) {
    double const mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi || !f_eval(mid, r, q1, q2, d, e)) break;
    take(e);
  }
  if (!(best.f >= 0.0)) {
    res.mu2 = 0.0;
    res.lambda = 0.5;
    res.mu2_error = inf;
    return;
  }
  res.mu2 = best.f;
  res.lambda = best.lambda;
  double gap = inf;
  if (have_lo) gap = std::fmin(gap, lo_e.f + std::fabs(lo_e.df) * (hi - lo) - best.f);
  if (have_hi) gap = std::fmin(gap, hi_e.f + std::fabs(hi_e.df) * (hi - lo) - best.f);
  res.mu2_error = phi_error(best, r, q1, q2) / best.phi * best.f + 4.0 * kU * best.f +
                  std::fmax(gap, 0.0);
}

// The promise of include/pw85.h for a status that writes an estimate:
// finite mu2 >= 0 (or +inf where mu2 exceeds the range of double), lambda
// in [0, 1], mu2_error not NaN. A lambda that a final Taylor step put
// outside [0, 1] is clamped (the error of the step exceeds the distance);
// a NaN estimate is replaced by best_estimate with kNoConvergence; a NaN
// mu2_error by +inf (the error is unknown), and kOk then by kInaccurate.
__attribute__((noinline, cold)) Status settle(Status s, Vec3 const &r, Sym3 const &q1,
                                             Sym3 const &q2, MethodResult &res) noexcept {
  if (std::isnan(res.mu2) || res.mu2 < 0.0 || std::isnan(res.lambda)) {
    best_estimate(r, q1, q2, res);
    return kNoConvergence;
  }
  if (!(res.lambda >= 0.0 && res.lambda <= 1.0)) {
    double const clamped = std::fmin(std::fmax(res.lambda, 0.0), 1.0);
    if (std::fabs(res.lambda - clamped) > 4.0 * kU && s == kOk) s = kInaccurate;
    res.lambda = clamped;
  }
  if (std::isnan(res.mu2_error)) {
    res.mu2_error = std::numeric_limits<double>::infinity();
    if (s == kOk) s = kInaccurate;
  }
  return s;
}

// Checks the estimate a method wrote against that promise (settle when it
// does not hold).
PW85_ALWAYS_INLINE Status checked(Status s, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                                  MethodResult &res) noexcept {
  bool const ok = res.mu2 >= 0.0 && res.lambda >= 0.0 && res.lambda <= 1.0 &&
                  !std::isnan(res.mu2_error);
  if (!ok && writes_estimate(s)) return settle(s, r, q1, q2, res);
  return s;
}

// The table of methods, indexed by Method.
using MethodFunction = Status (*)(Vec3 const &, Sym3 const &, Sym3 const &,
                                  MethodResult &) noexcept;
constexpr MethodFunction kMethods[] = {
    contact_default,        // kMethodDefault: default.hpp, default_variants.cpp
    contact_brent_checked,  // kMethodBrent: brent.cpp
    contact_newton,         // kMethodNewton: newton.cpp
    contact_rational,       // kMethodRational: rational.cpp
    contact_zheng_checked,  // kMethodZheng: zheng.cpp
};
static_assert(sizeof kMethods / sizeof kMethods[0] == kMethodCount,
              "one row of kMethods per Method");

}  // namespace

Status contact_brent_status(Vec3 const &r_in, Sym3 const &q1_in, Sym3 const &q2_in,
                           ContactResult const &cr, Status s) noexcept {
  if (s != kOk || (r_in[0] == 0.0 && r_in[1] == 0.0 && r_in[2] == 0.0)) return s;
  // The rescaled problem of brent.cpp (exact): r' = 2^-er r, Q' = 2^-eq Q.
  int const er = cr.er, eq = cr.eq;
  Vec3 r;
  Sym3 q1, q2;
  scale_pair(r_in, q1_in, q2_in, -er, -eq, r, q1, q2);
  double const mu2 = cr.mu2_rescaled;
  double f;
  double const err = error_at(mu2, cr.lambda, r, q1, q2, f);
  return err <= kBrentRelAccuracy * mu2 ? kOk : kInaccurate;
}

Status contact_method_in_range(int method, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                               MethodResult &res) noexcept {
  res.method = method;
  res.iterations = 0;
  return checked(kMethods[method](r, q1, q2, res), r, q1, q2, res);
}

Status contact_method(int method, Vec3 const &r_in, Sym3 const &q1_in, Sym3 const &q2_in,
                      MethodResult &res) noexcept {
  res.method = method;
  res.iterations = 0;
  if (!is_method(method)) {
    res.mu2 = res.lambda = res.mu2_error = std::nan("");
    return kUnknownMethod;
  }
  if (r_in[0] == 0.0 && r_in[1] == 0.0 && r_in[2] == 0.0) {
    res.mu2 = 0.0;
    res.lambda = 0.5;
    res.mu2_error = 0.0;
    return kOk;
  }
  Vec3 r = r_in;
  Sym3 q1 = q1_in, q2 = q2_in;
  // Cheap range test first (magnitude.hpp); frexp only for extreme
  // magnitudes. The inputs are finite (checked by the C layer).
  double const rmax = max_abs(r.x, kDim), qmax1 = max_abs(q1.a, kSym),
               qmax2 = max_abs(q2.a, kSym);
  constexpr double kLo = kSafeLo, kHi = kSafeHi;
  bool const scale = !(rmax > kLo && rmax < kHi && qmax1 > kLo && qmax1 < kHi &&
                       qmax2 > kLo && qmax2 < kHi);
  int er = 0, eq = 0;
  if (scale) {
    er = max_exponent(r.x, kDim);
    eq = std::max(max_exponent(q1.a, kSym), max_exponent(q2.a, kSym));
    scale_pair(r, q1, q2, -er, -eq, r, q1, q2);
  }
  Status s = contact_method_in_range(method, r, q1, q2, res);
  if (scale) {
    res.mu2 = std::ldexp(res.mu2, 2 * er - eq);
    res.mu2_error = std::ldexp(res.mu2_error, 2 * er - eq);
    // mu2 above DBL_MAX (written +Inf) or below DBL_MIN (written rounded,
    // subnormal or 0): kRange (status.hpp).
    if (s == kOk && !(res.mu2 >= kMinNormal && res.mu2 <= kMaxDouble)) s = kRange;
  }
  return s;
}

// Checks in the order of the general path: finite values (kInvalidArgument),
// then positive definiteness (kNotSpd; common/spd.hpp), then the method.
// DEFAULT from the table of kernels (default_variants.hpp) directly.
Status contact_method_entry(double const *r12, double const *q1, double const *q2, int method,
                            MethodResult &res) noexcept {
  if (is_method(method) && screen_contact_pair(r12, q1, q2, kSafeLo, kSafeHi)) {
    if (method == kMethodDefault) {
      res.iterations = 0;
      return checked(kernels().contact_default->contact(view_vec3(r12), view_sym3(q1),
                                                        view_sym3(q2), res),
                     view_vec3(r12), view_sym3(q1), view_sym3(q2), res);
    }
    return contact_method_in_range(method, view_vec3(r12), view_sym3(q1), view_sym3(q2), res);
  }
  if (!all_finite(r12, kDim) || !all_finite(q1, kSym) || !all_finite(q2, kSym))
    return kInvalidArgument;
  if (!positive_definite(q1) || !positive_definite(q2)) return kNotSpd;
  return contact_method(method, load_vec3(r12), load_sym3(q1), load_sym3(q2), res);
}

}  // namespace pw85
