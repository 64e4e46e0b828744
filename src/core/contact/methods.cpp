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

#include "contact/contact.hpp"
#include "dca/dca.hpp"
#include "common/magnitude.hpp"
#include "contact/newton.hpp"

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

// ZHENG (dca_3d.cpp) with the same independent check as BRENT: its own
// estimate (D13) compares mu2 with a double f at its lambda, which can agree
// with it while both are wrong when Q(lambda) is ill-conditioned (127 silent
// failures in 20000 pairs of the last class of bench_contact before).
Status contact_zheng_checked(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                             MethodResult &res) noexcept {
  Status const s = contact_zheng_method(r, q1, q2, res);
  double f;
  double const err = error_at(res.mu2, res.lambda, r, q1, q2, f);
  if (!(err <= res.mu2_error)) res.mu2_error = err;  // also replaces a NaN
  if (s != kOk) return s;
  return res.mu2_error <= kZhengRelAccuracy * res.mu2 ? kOk : kInaccurate;
}

}  // namespace

Status contact_method_in_range(int method, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                               MethodResult &res) noexcept {
  res.method = method;
  res.iterations = 0;
  Status s;
  switch (method) {
    case kMethodBrent:
      s = contact_brent_checked(r, q1, q2, res);
      break;
    case kMethodNewton:
      s = contact_newton(r, q1, q2, res);
      break;
    case kMethodRational:
      s = contact_rational(r, q1, q2, res);
      break;
    case kMethodZheng:  // dca_3d.cpp (issue 5)
      s = contact_zheng_checked(r, q1, q2, res);
      break;
    default:
      res.method = kMethodDefault;
      s = contact_default(r, q1, q2, res);
      break;
  }
  return s;
}

Status contact_method(int method, Vec3 const &r_in, Sym3 const &q1_in, Sym3 const &q2_in,
                      MethodResult &res) noexcept {
  res.method = method;
  res.iterations = 0;
  if (method < kMethodDefault || method > kMethodZheng) {
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
    for (int i = 0; i < kDim; ++i) r[i] = std::ldexp(r[i], -er);
    for (int i = 0; i < kSym; ++i) {
      q1[i] = std::ldexp(q1[i], -eq);
      q2[i] = std::ldexp(q2[i], -eq);
    }
  }
  Status const s = contact_method_in_range(method, r, q1, q2, res);
  if (scale) {
    res.mu2 = std::ldexp(res.mu2, 2 * er - eq);
    res.mu2_error = std::ldexp(res.mu2_error, 2 * er - eq);
  }
  return s;
}

}  // namespace pw85
