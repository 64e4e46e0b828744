// Contact function by Newton iterations on f' (pw85 documentation, chapter
// "Optimization of the function f": f' = 0 at the maximiser), with f' and f''
// of section 4.1, eqs. (6) and (9). Plain Newton iterations are not robust
// (f varies sharply near lambda = 0 and 1), so they are safeguarded: the root
// is kept bracketed in [lo, hi] (f'(lo) > 0 > f'(hi); f'(0) = r^T Q1^{-1} r > 0
// and f'(1) = -r^T Q2^{-1} r < 0), and a Newton step that leaves the bracket,
// or is taken where f'' >= 0, is replaced by bisection.
#include <cfloat>
#include <cmath>

#include "legacy.hpp"

namespace pw85 {
namespace legacy {

namespace {
constexpr int kMaxIter = 200;
}

Status contact_newton(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                      ContactResult &res) noexcept {
  res.iterations = 0;
  if (r[0] == 0.0 && r[1] == 0.0 && r[2] == 0.0) {
    res.mu2 = 0.0;
    res.lambda = 0.5;
    return kOk;
  }
  double lo = 0.0, hi = 1.0;
  double lambda = 0.5;
  FDerivs fd{};
  double rel_err = 0.0;
  for (int it = 1; it <= kMaxIter; ++it) {
    res.iterations = it;
    if (!f_cholesky(lambda, r, q1, q2, fd, &rel_err)) {
      // Q(lambda) is a convex combination of positive definite matrices, so
      // this only happens when rounding destroys positive definiteness.
      res.mu2 = std::nan("");
      res.lambda = lambda;
      return kNoConvergence;
    }
    if (fd.df > 0.0) {
      lo = lambda;
    } else if (fd.df < 0.0) {
      hi = lambda;
    } else {
      lo = hi = lambda;  // exact root
    }
    double next = lambda - fd.df / fd.d2f;
    if (!(fd.d2f < 0.0) || !(next > lo && next < hi)) next = 0.5 * (lo + hi);
    // Converged when the correction is below a few ulps of lambda (lambda
    // near 1: of 1 - lambda is not representable better than 1 ulp of 1).
    double const tol = 2.0 * DBL_EPSILON * std::fmin(lambda, 1.0 - lambda) +
                       DBL_MIN;
    if (std::fabs(next - lambda) <= tol || hi - lo <= tol || next == lambda) {
      res.mu2 = fd.f;
      res.lambda = lambda;
      return rel_err > kContactRtol ? kInaccurate : kOk;
    }
    lambda = next;
  }
  res.mu2 = fd.f;
  res.lambda = lambda;
  return kNoConvergence;
}

}  // namespace legacy
}  // namespace pw85
