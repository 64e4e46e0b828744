// Derivatives of the contact function (docs/derivatives.md).
//
// With lambda the maximiser of f(lambda) = lambda (1 - lambda) r^T Q^{-1} r,
// Q = (1 - lambda) Q1 + lambda Q2, s = Q^{-1} r, the envelope theorem
// (f'(lambda) = 0) gives
//   d mu^2 / d r   = 2 lambda (1 - lambda) s                         (E1)
//   d mu^2 / d Q1  = -lambda (1 - lambda)^2 s s^T,
//   d mu^2 / d Q2  = -lambda^2 (1 - lambda) s s^T                    (E2)
// (stored entry k = (i, j): times 2 when i != j, where q[k] is both Q_ij and
// Q_ji); with x0 = (1 - lambda) Q1 s and x0 - r = -lambda Q2 s    (E3)
// the rotations Q_i -> R Q_i R^T, R = I + [dtheta]_x, give
//   d mu^2 / d theta1 = -x0 x g,  d mu^2 / d theta2 = (x0 - r) x g    (E4)
// and differentiating f'(lambda(r), r) = 0,
//   f''(lambda) = -2 (Q2 s)^T Q^{-1} (Q1 s)  (< 0)                  (E5)
//   d^2 mu^2 / d r^2 = 2 lambda (1 - lambda) Q^{-1} - h h^T / f'',
//   h = d g / d lambda = 2 (1 - 2 lambda) s - 2 lambda (1 - lambda) Q^{-1} (Q2 - Q1) s.  (E6)
//
// On x86-64-v4 the adjugate path of adjugate.hpp (E9) is tried first;
// elsewhere, and where it declines, the fast path of fast.hpp (E8); the
// others take the refined path (E7) of paths.hpp (the variants:
// derivatives_variants.cpp).
//
// Accuracy (E7): g depends on lambda to first order, so lambda from
// PW85_METHOD_DEFAULT is refined by Newton steps on f'(lambda) = 0 with f' in
// double-double (f_dd.hpp, refined_point_dd); s and the columns of Q^{-1} are
// Cholesky solves in double with iterative refinement, the residual
// b - Q(lambda) x in double-double (f_dd.hpp, residual_dd), until the
// correction's estimated error is below 2^-60 of the solution; a double solve
// alone errs by up to cond(Q(lambda)) u.
#include "derivatives/derivatives.hpp"

#include <cmath>
#include <initializer_list>

#include "common/scaling.hpp"
#include "contact/contact.hpp"
#include "derivatives/fast.hpp"
#include "derivatives/paths.hpp"
#include "dispatch/kernels.hpp"

namespace pw85 {

namespace {

using derivative_paths::is_solved;
using derivative_paths::kFields;

// DEFAULT's solution; in_range: every magnitude inside (kSafeLo, kSafeHi)
// and r != 0, so that DEFAULT is called without the dispatcher's checks
// (contact.hpp).
inline Status solve_default(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, bool in_range,
                            MethodResult &res) noexcept {
  return in_range ? contact_method_in_range(kMethodDefault, r, q1, q2, res)
                  : contact_method(kMethodDefault, r, q1, q2, res);
}

// The derivatives from DEFAULT's solution, by the variant of this CPU
// (derivatives_variants.cpp).
inline Status derivatives_variant(Status status, MethodResult const &res, Vec3 const &r,
                                  Sym3 const &q1, Sym3 const &q2, DerivativeFields fields,
                                  Derivatives &d) noexcept {
  return kernels().derivatives->from_solution(status, res, r, q1, q2, fields, d);
}

// derivatives_variant; with the maximiser lambda above 1 - 2^-10, or
// where it gives up with lambda > 1/2, for the swapped pair (-r, Q2, Q1)
// instead, whose maximiser 1 - lambda (exact) is near 0, where a double
// resolves it relative to itself (near 1, 1 - lambda is resolved only to
// 2^-53 absolutely: too coarse for the Newton steps of (E7), and for the
// first-order terms of (E8) and (E9), when 1 - lambda is small, i.e. Q1
// much larger than Q2).
// mu^2(r, Q1, Q2) = mu^2(-r, Q2, Q1): mu2 and the Hessian are the same,
// g changes sign, d_q1 and d_q2 swap, and so do the torques (rotating
// ellipsoid 1 about its centre is rotating the swapped pair's ellipsoid 2;
// x0' = x0 - r, g' = -g in (E4)).
inline Status derivatives_dispatch(Status status, MethodResult const &res, Vec3 const &r,
                                   Sym3 const &q1, Sym3 const &q2, DerivativeFields fields,
                                   Derivatives &d) noexcept {
  bool const near_one = is_solved(status, res) && res.lambda > 1.0 - 0x1p-10;
  Status const first = near_one ? kNoConvergence : derivatives_variant(status, res, r, q1, q2, fields, d);
  if (first != kNoConvergence || !is_solved(status, res) || !(res.lambda > 0.5)) return first;
  MethodResult swapped = res;
  swapped.lambda = 1.0 - res.lambda;
  Vec3 const nr{{-r[0], -r[1], -r[2]}};
  Derivatives e;
  Status const second = derivatives_variant(status, swapped, nr, q2, q1, fields, e);
  if (second != kOk && second != kInaccurate) {
    if (near_one) d = e;  // all NaN
    return second;
  }
  d.mu2 = e.mu2;
  d.lambda = 1.0 - e.lambda;
  for (int i = 0; i < kDim; ++i) {
    d.d_r12[i] = -e.d_r12[i];
    d.d_theta1[i] = e.d_theta2[i];
    d.d_theta2[i] = e.d_theta1[i];
  }
  for (int k = 0; k < kSym; ++k) {
    d.d_q1[k] = e.d_q2[k];
    d.d_q2[k] = e.d_q1[k];
    d.hess_r12[k] = e.hess_r12[k];
  }
  return second;
}

// A largest |r12 component| that contact_derivatives takes as it is.
inline bool moderate_r(double mr) noexcept { return mr > 0x1p-30 && mr < 0x1p30; }

// Magnitudes that contact_derivatives takes as they are (no rescaling).
inline bool unscaled(double mq, double mr) noexcept {
  return mq > 0x1p-60 && mq < 0x1p60 && moderate_r(mr);
}

}  // namespace

bool derivatives_from_default_ok(Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept {
  return unscaled(cholesky_path::max2(cholesky_path::max_abs6(q1), cholesky_path::max_abs6(q2)), cholesky_path::max_abs3(r));
}

Status contact_derivatives_from_default(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                                        Status status, MethodResult const &res,
                                        Derivatives &d, DerivativeFields fields) noexcept {
  return derivatives_dispatch(status, res, r, q1, q2, fields, d);
}

namespace {

// The derivatives of (r, Q1, Q2) from those of the pair scaled as
// mu^2(2^e r, 2^2e Q1, 2^2e Q2) = mu^2(r, Q1, Q2): g scales back by 2^e, d_q
// and the Hessian by 2^2e; mu2, lambda and the torques are invariant. An r
// still far from 1 after that (a far or a very close pair) is scaled alone
// to [0.5, 1) by 2^-t, unless scale_r is false: mu^2 is homogeneous of
// degree 2 in r, so mu2, the torques and d_q scale back by 2^2t, g by 2^t,
// the Hessian not at all, lambda is invariant. NaN fields and
// kNoConvergence where a field leaves the range of double.
Status scaled_derivatives(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, int e, bool scale_r,
                          DerivativeFields fields, Derivatives &d) noexcept {
  // t from the exponent of max |r| (frexp: in [2^(er - 1), 2^er)), so that
  // r is scaled once, by 2^(e - t), with no intermediate overflow.
  int er;
  double const mr = cholesky_path::max_abs3(r);
  std::frexp(mr, &er);
  int const t = scale_r && !moderate_r(std::ldexp(mr, e)) ? er + e : 0;
  Vec3 rs;
  Sym3 a, b;
  scale_pair(r, q1, q2, e - t, 2 * e, rs, a, b);
  Derivatives s;
  MethodResult res;
  Status const status =
      derivatives_dispatch(solve_default(rs, a, b, false, res), res, rs, a, b, fields, s);
  if (status != kOk && status != kInaccurate) {
    d = s;  // all NaN
    return status;
  }
  s.mu2 = std::ldexp(s.mu2, 2 * t);
  scale_by_power_of_two(s.d_r12, kDim, e + t);
  scale_by_power_of_two(s.d_theta1, kDim, 2 * t);
  scale_by_power_of_two(s.d_theta2, kDim, 2 * t);
  scale_by_power_of_two(s.d_q1, kSym, 2 * e + 2 * t);
  scale_by_power_of_two(s.d_q2, kSym, 2 * e + 2 * t);
  scale_by_power_of_two(s.hess_r12, kSym, 2 * e);
  double const *all = &s.mu2;
  for (int i = 0; i < derivative_paths::computed_fields(fields); ++i) {
    if (!std::isfinite(all[i])) {
      double const nan = std::nan("");
      d = Derivatives{nan, nan, {nan, nan, nan}, {nan, nan, nan}, {nan, nan, nan},
                      {nan, nan, nan, nan, nan, nan}, {nan, nan, nan, nan, nan, nan},
                      {nan, nan, nan, nan, nan, nan}};
      return kNoConvergence;  // a field out of the range of double
    }
  }
  d = s;
  return status;
}

}  // namespace

// Magnitudes far from 1: the pair is solved scaled (scaled_derivatives),
// first with the larger matrix entry scaled to [1, 4) and r to [0.5, 1).
// Where the matrices' entries span a wide range (an ellipsoid far longer
// than the other, or than r12), a field of the scaled problem can leave the
// range of double although the pair's own fields are moderate: then r is
// left with the matrices' scale, then the smallest diagonal entry is scaled
// to [1, 4) instead, with and without r.
Status contact_derivatives(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, Derivatives &d,
                           DerivativeFields fields) noexcept {
  double const mq1 = cholesky_path::max_abs6(q1), mq2 = cholesky_path::max_abs6(q2);
  double const mq = cholesky_path::max2(mq1, mq2);
  double const mr = cholesky_path::max_abs3(r);
  if (unscaled(mq, mr)) {
    bool const in_range = mq1 > kSafeLo && mq1 < kSafeHi && mq2 > kSafeLo && mq2 < kSafeHi;
    MethodResult res;
    Status const status = solve_default(r, q1, q2, in_range, res);
    return derivatives_dispatch(status, res, r, q1, q2, fields, d);
  }
  double min_diagonal = HUGE_VAL;
  for (Sym3 const *q : {&q1, &q2})
    for (int k : {0, 3, 5}) min_diagonal = std::fmin(min_diagonal, std::fabs(q->a[k]));
  int ex_max, ex_min;
  std::frexp(mq, &ex_max);
  std::frexp(min_diagonal, &ex_min);
  int const exponents[2] = {-(ex_max / 2), -(ex_min / 2)};
  Status status = kNoConvergence;
  for (int k = 0; k < 4 && status == kNoConvergence; ++k) {
    int const e = exponents[k / 2];
    bool const scale_r = k % 2 == 0;
    if (k >= 2 && e == exponents[0]) break;                      // tried already
    if (!scale_r && moderate_r(std::ldexp(mr, e))) continue;  // r was not scaled alone
    // The smallest diagonal entry's scale can push the largest entry, or
    // r12 left unscaled, out of the range of double: not tried there.
    if (!(std::ldexp(mq, 2 * e) < 0x1p1000 && (scale_r || std::ldexp(mr, e) < 0x1p1000)))
      continue;
    status = scaled_derivatives(r, q1, q2, e, scale_r, fields, d);
  }
  return status;
}

}  // namespace pw85
