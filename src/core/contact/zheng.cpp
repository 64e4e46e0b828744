// PW85_METHOD_ZHENG (docs/dca.md): the contact function through the
// distance of closest approach by plane rotation (dca/dca_3d.cpp,
// dca_zheng): mu^2 = |r|^2 / d(r / |r|)^2, lambda recovered from the
// optimal plane (eq. (D7)) and polished by Newton steps.
#include <cmath>
#include <limits>

#include "common/magnitude.hpp"
#include "common/scaling.hpp"
#include "contact/contact.hpp"
#include "dca/dca.hpp"
#include "eval/f_cholesky.hpp"

namespace pw85 {

namespace {

// Newton steps that polish the recovered lambda (contact_zheng).
constexpr int kLambdaNewton = 3;

}  // namespace

Status contact_zheng(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                     ContactResult &res) noexcept {
  res.iterations = 0;
  if (r[0] == 0.0 && r[1] == 0.0 && r[2] == 0.0) {
    res.mu2 = 0.0;
    res.lambda = 0.5;
    return kOk;
  }
  // |r| without overflow: scale by the largest component (exact power of 2).
  int const er = max_exponent(r.x, kDim);
  Vec3 rs;
  scale_by_power_of_two(r.x, rs.x, kDim, -er);
  double const norm = std::sqrt(dot(rs, rs));
  double const inv_norm = 1.0 / norm;
  Vec3 const u{{rs[0] * inv_norm, rs[1] * inv_norm, rs[2] * inv_norm}};
  DcaResult dr;
  Status const st = dca_zheng(u, q1, q2, kDcaThetaTol, kDcaMaxEval, dr);
  res.iterations = dr.evaluations;
  double const ratio = norm / dr.d;
  res.mu2 = std::ldexp(ratio * ratio, 2 * er);
  // lambda of the optimal plane (D7) depends on theta to first order (d does
  // not), so it is only as accurate as theta; up to kLambdaNewton Newton
  // steps on the residual g = -f' (f_cholesky.hpp) polish it, each kept only
  // if it stays in [0, 1] and decreases |g|. mu2 itself is left as computed
  // by the plane rotation.
  double lambda = dr.lambda;
  Residual cur;
  if (std::isfinite(lambda) && residual_cholesky(lambda, rs, q1, q2, cur)) {
    for (int i = 0; i < kLambdaNewton; ++i) {
      double const next = lambda - cur.g / cur.dg;
      Residual trial;
      if (!(next >= 0.0 && next <= 1.0) || !residual_cholesky(next, rs, q1, q2, trial) ||
          !(std::fabs(trial.g) < std::fabs(cur.g)))
        break;
      lambda = next;
      cur = trial;
    }
  }
  res.lambda = lambda;
  if (!std::isfinite(res.mu2)) return kNoConvergence;
  return st;
}

Status contact_zheng_method(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                            MethodResult &res) noexcept {
  ContactResult cr;
  Status const s = contact_zheng(r, q1, q2, cr);
  res.mu2 = cr.mu2;
  res.lambda = cr.lambda;
  res.iterations = cr.iterations;
  // (D13): f(lambda) <= mu2 for every lambda; at the recovered maximiser the
  // two agree to within the errors of both.
  double f;
  res.mu2_error = f_cholesky(cr.lambda, r, q1, q2, f) ? std::fabs(cr.mu2 - f)
                                                      : std::numeric_limits<double>::quiet_NaN();
  if (s != kOk) return s;
  return res.mu2_error <= kZhengRelAccuracy * res.mu2 ? kOk : kInaccurate;
}

}  // namespace pw85
