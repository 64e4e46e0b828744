// The extern "C" layer of libpw85: validate every argument, call the C++
// core, turn the outcome into a status code. No logic of its own lives here.
// The core is compiled without exceptions, so none can cross this boundary.
#include <cfloat>
#include <cmath>

#include "pw85.h"
#include "contact/contact.hpp"
#include "common/ellipsoid.hpp"
#include "common/magnitude.hpp"
#include "eval/f_cholesky.hpp"
#include "common/status.hpp"
#include "common/sym3.hpp"
#include "validate.hpp"
#include "common/scaling.hpp"

static_assert(pw85::kOk == PW85_OK, "status codes must match pw85.h");
static_assert(pw85::kInvalidArgument == PW85_ERR_INVALID_ARGUMENT, "");
static_assert(pw85::kNotSpd == PW85_ERR_NOT_SPD, "");
static_assert(pw85::kNoConvergence == PW85_ERR_NO_CONVERGENCE, "");
static_assert(pw85::kNotOrthonormal == PW85_ERR_NOT_ORTHONORMAL, "");
static_assert(pw85::kUnknownMethod == PW85_ERR_UNKNOWN_METHOD, "");
static_assert(pw85::kInaccurate == PW85_ERR_INACCURATE, "");
static_assert(pw85::kRange == PW85_ERR_RANGE, "");
static_assert(pw85::kDim == PW85_DIM && pw85::kSym == PW85_SYM, "");

using pw85::capi::fill_nan;

namespace {

// Exact power-of-two scaling of a pair for the pw85 1.0 evaluations of f:
// when max |r_i| or max |Q_ij| lies outside (kSafeLo, kSafeHi), r' = 2^-er r
// and Q' = 2^-eq Q (common even eq), so that f, g and g' (all of the units of
// r^T Q^{-1} r) are those of the scaled pair times 2^(2 er - eq); returns
// that exponent (0: no scaling).
int scale_pair(pw85::Vec3 &r, pw85::Sym3 &q1, pw85::Sym3 &q2) noexcept {
  double const rm = pw85::max_abs(r.x, pw85::kDim), m1 = pw85::max_abs(q1.a, pw85::kSym),
               m2 = pw85::max_abs(q2.a, pw85::kSym), qm = m1 > m2 ? m1 : m2;
  if (rm > pw85::kSafeLo && rm < pw85::kSafeHi && qm > pw85::kSafeLo && qm < pw85::kSafeHi)
    return 0;
  int er, eq;
  std::frexp(rm, &er);
  std::frexp(qm, &eq);
  eq += eq & 1;  // even: the square roots of the Cholesky factor scale exactly
  pw85::scale_pair(r, q1, q2, -er, -eq, r, q1, q2);
  return 2 * er - eq;
}

}  // namespace

extern "C" {

const char *pw85_version(void) { return PW85_VERSION; }

const char *pw85_strerror(int status) {
  switch (status) {
    case PW85_OK:
      return "success";
    case PW85_ERR_INVALID_ARGUMENT:
      return "invalid argument (NULL pointer, NaN or infinite value)";
    case PW85_ERR_NOT_SPD:
      return "matrix not symmetric positive definite (or radius not > 0)";
    case PW85_ERR_NO_CONVERGENCE:
      return "iteration did not converge to the requested accuracy";
    case PW85_ERR_NOT_ORTHONORMAL:
      return "axes not orthonormal or quaternion not unit";
    case PW85_ERR_UNKNOWN_METHOD:
      return "unknown method";
    case PW85_ERR_INACCURATE:
      return "result less accurate than the method documents";
    case PW85_ERR_RANGE:
      return "result out of the range of double";
    case PW85_ERR_CAPACITY:
      return "output array too small";
    case PW85_ERR_NO_MEMORY:
      return "memory allocation failed";
    default:
      return "unknown status";
  }
}

void pw85__cholesky_decomp(double const a[PW85_SYM], double l[PW85_SYM]) {
  if (a == nullptr || l == nullptr) return;
  pw85::Sym3 factor;
  if (!pw85::cholesky(pw85::load_sym3(a), factor)) {
    fill_nan(l, PW85_SYM);
    return;
  }
  for (int i = 0; i < PW85_SYM; ++i) l[i] = factor[i];
}

void pw85__cholesky_solve(double const l[PW85_SYM], double const b[PW85_DIM],
                          double x[PW85_DIM]) {
  if (l == nullptr || b == nullptr || x == nullptr) return;
  pw85::Vec3 const s = pw85::cholesky_solve(pw85::load_sym3(l), pw85::load_vec3(b));
  for (int i = 0; i < PW85_DIM; ++i) x[i] = s[i];
}

void pw85_spheroid(double a, double c, double const n[PW85_DIM], double q[PW85_SYM]) {
  if (q == nullptr) return;
  if (n == nullptr || !(a > 0.0) || !(c > 0.0) || !std::isfinite(a) ||
      !std::isfinite(c) || !pw85::all_finite(n, PW85_DIM) ||
      (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0)) {
    fill_nan(q, PW85_SYM);
    return;
  }
  pw85::Sym3 const s = pw85::spheroid(a, c, pw85::load_vec3(n));
  // An entry beyond DBL_MAX, or a diagonal entry below the smallest
  // subnormal: Q is not representable (NaN, as for a bad argument).
  if (!pw85::all_finite(s.a, PW85_SYM) || !(s[0] > 0.0 && s[3] > 0.0 && s[5] > 0.0)) {
    fill_nan(q, PW85_SYM);
    return;
  }
  for (int i = 0; i < PW85_SYM; ++i) q[i] = s[i];
}

int pw85_ellipsoid(double const radii[PW85_DIM], double const axes[PW85_DIM * PW85_DIM],
                   double q[PW85_SYM]) {
  if (q == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  if (radii == nullptr || axes == nullptr || !pw85::all_finite(radii, PW85_DIM) ||
      !pw85::all_finite(axes, PW85_DIM * PW85_DIM)) {
    fill_nan(q, PW85_SYM);
    return PW85_ERR_INVALID_ARGUMENT;
  }
  pw85::Sym3 s;
  int const status = pw85::ellipsoid(pw85::load_vec3(radii), axes, 1e-10, s);
  if (status != PW85_OK) {
    fill_nan(q, PW85_SYM);
    return status;
  }
  for (int i = 0; i < PW85_SYM; ++i) q[i] = s[i];
  return PW85_OK;
}

double pw85_f_neg(double lambda, double const *params) {
  if (params == nullptr || !std::isfinite(lambda) ||
      !pw85::all_finite(params, PW85_DIM + 2 * PW85_SYM))
    return std::nan("");
  double f;
  pw85::Vec3 r = pw85::load_vec3(params);
  pw85::Sym3 q1 = pw85::load_sym3(params + 3), q2 = pw85::load_sym3(params + 9);
  int const e = scale_pair(r, q1, q2);
  if (!pw85::f_cholesky(lambda, r, q1, q2, f)) return std::nan("");
  return -std::ldexp(f, e);  // rounded once beyond the double range
}

void pw85__residual(double lambda, double const r12[PW85_DIM], double const q1[PW85_SYM],
                    double const q2[PW85_SYM], double out[3]) {
  if (out == nullptr) return;
  pw85::Residual res;
  if (r12 == nullptr || q1 == nullptr || q2 == nullptr || !std::isfinite(lambda) ||
      !pw85::all_finite(r12, PW85_DIM) || !pw85::all_finite(q1, PW85_SYM) ||
      !pw85::all_finite(q2, PW85_SYM)) {
    fill_nan(out, 3);
    return;
  }
  pw85::Vec3 r = pw85::load_vec3(r12);
  pw85::Sym3 a = pw85::load_sym3(q1), b = pw85::load_sym3(q2);
  int const e = scale_pair(r, a, b);
  if (!pw85::residual_cholesky(lambda, r, a, b, res)) {
    fill_nan(out, 3);
    return;
  }
  out[0] = std::ldexp(res.f, e);
  out[1] = std::ldexp(res.g, e);
  out[2] = std::ldexp(res.dg, e);
}

int pw85_contact_function(double const r12[PW85_DIM], double const q1[PW85_SYM],
                          double const q2[PW85_SYM], double out[2]) {
  int const status = pw85::capi::validate_pair(r12, q1, q2);
  if (out == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  if (status != PW85_OK) {
    fill_nan(out, 2);
    return status;
  }
  pw85::ContactResult res;
  pw85::Vec3 const r = pw85::load_vec3(r12);
  pw85::Sym3 const a = pw85::load_sym3(q1), b = pw85::load_sym3(q2);
  pw85::Status const s = pw85::contact_brent(r, a, b, res);
  out[0] = res.mu2;
  out[1] = res.lambda;
  pw85::Status const checked = pw85::contact_brent_status(r, a, b, res, s);
  // mu^2 out of the range of double (written rounded: +Inf, subnormal or 0;
  // r12 = 0 gives mu^2 = 0 exactly).
  bool const r_zero = r12[0] == 0.0 && r12[1] == 0.0 && r12[2] == 0.0;
  if ((checked == PW85_OK || checked == PW85_ERR_INACCURATE) && !r_zero &&
      !(res.mu2 >= DBL_MIN && res.mu2 <= DBL_MAX))
    return PW85_ERR_RANGE;
  return checked;
}

}  // extern "C"
