// Contact function through the rational representation of f (pw85
// documentation, section 4.2): the maximiser lambda of f is the root in
// [0, 1] of the numerator c(lambda) of f' = c / b^2 (eqs. (13)-(15g)),
// c(0) = a0 b0 > 0 > c(1); it is found by bisection on the sign of c, and
// mu^2 = f(lambda) by eq. (10).
#include <cfloat>
#include <cmath>

#include "legacy.hpp"

namespace pw85 {
namespace legacy {

namespace {

// Enough halvings to reach one ulp of any lambda down to DBL_MIN.
constexpr int kMaxIter = 1100;

double horner(double const *c, int degree, double x) noexcept {
  double y = c[degree];
  for (int i = degree - 1; i >= 0; --i) y = y * x + c[i];
  return y;
}

}  // namespace

Status contact_bisection(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                         ContactResult &res) noexcept {
  res.iterations = 0;
  if (r[0] == 0.0 && r[1] == 0.0 && r[2] == 0.0) {
    res.mu2 = 0.0;
    res.lambda = 0.5;
    return kOk;
  }
  Rational rat;
  rational_coefficients(r, q1, q2, rat);
  double c[7];
  numerator_coefficients(rat, c);

  double const c_lo = horner(c, 6, 0.0), c_hi = horner(c, 6, 1.0);
  if (!(c_lo > 0.0) || !(c_hi < 0.0)) {
    // The rounded coefficients lost the sign change: no root is bracketed.
    // The best estimate is the endpoint where the computed f' points to.
    double const lambda = (c_lo <= 0.0) ? 0.0 : 1.0;
    FDerivs fd{};
    res.lambda = lambda;
    res.mu2 = f_rational(rat, lambda, fd) ? fd.f : std::nan("");
    return kNoConvergence;
  }
  double lo = 0.0, hi = 1.0;
  Status status = kNoConvergence;
  for (int it = 1; it <= kMaxIter; ++it) {
    res.iterations = it;
    double const mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) {  // the bracket is two adjacent doubles
      status = kOk;
      break;
    }
    double const cm = horner(c, 6, mid);
    if (cm > 0.0) {
      lo = mid;
    } else if (cm < 0.0) {
      hi = mid;
    } else {
      lo = hi = mid;
      status = kOk;
      break;
    }
    if (hi - lo <= 2.0 * DBL_EPSILON * lo) {
      status = kOk;
      break;
    }
  }
  double const lambda = 0.5 * (lo + hi);
  FDerivs fd{};
  res.lambda = lambda;
  if (!f_rational(rat, lambda, fd)) {
    res.mu2 = std::nan("");
    return kNoConvergence;
  }
  res.mu2 = fd.f;
  if (status != kOk) return status;
  // Error estimate of mu^2 = lambda (1 - lambda) a / b from the errors of
  // the coefficients (the error due to lambda is of second order at the
  // maximum of f).
  double const av = rat.a[0] + lambda * (rat.a[1] + lambda * rat.a[2]);
  double const bv = rat.b[0] + lambda * (rat.b[1] + lambda * (rat.b[2] + lambda * rat.b[3]));
  double const rel_err = rat.a_err / std::fabs(av) + rat.b_err / std::fabs(bv);
  return rel_err > kContactRtol ? kInaccurate : kOk;
}

}  // namespace legacy
}  // namespace pw85
