// extern "C" layer of the distance-of-closest-approach functions
// (include/pw85.h; core in src/core/dca/ and src/core/contact/contact_2d.cpp):
// validate, normalise the direction, call the core, map to a status code.
#include <cfloat>
#include <cmath>

#include "pw85.h"
#include "contact/contact.hpp"
#include "dca/dca.hpp"
#include "common/magnitude.hpp"
#include "common/status.hpp"
#include "common/sym2.hpp"
#include "common/sym3.hpp"
#include "validate.hpp"
#include "common/scaling.hpp"

static_assert(pw85::kDcaMaxEval == PW85_DCA_MAX_EVAL, "must match pw85.h");
static_assert(pw85::kDcaThetaTol == PW85_DCA_THETA_TOL, "must match pw85.h");

namespace {

using pw85::capi::fill_nan;

// Finite, non-zero direction: writes u / |u| (scaled first by a power of two
// so that |u| neither overflows nor underflows).
template <int N>
bool normalise(double const *u, double *out) noexcept {
  double m = 0.0;
  for (int i = 0; i < N; ++i) m = std::fmax(m, std::fabs(u[i]));
  if (!(m > 0.0)) return false;
  int e;
  std::frexp(m, &e);
  double n2 = 0.0;
  pw85::scale_by_power_of_two(u, out, N, -e);
  for (int i = 0; i < N; ++i) n2 += out[i] * out[i];
  double const inv = 1.0 / std::sqrt(n2);
  for (int i = 0; i < N; ++i) out[i] *= inv;
  return true;
}

// Positive definiteness of 2^-e q, e the even exponent at or above that of
// max |q_ij| (exact): det = q00 q11 - q01^2 neither underflows nor
// overflows (1e-300 I is accepted).
bool spd_scaled_2d(double const *q) noexcept {
  int e = pw85::max_exponent(q, 3);
  e += e & 1;
  pw85::Sym2 s;
  pw85::scale_by_power_of_two(q, s.a, 3, -e);
  return pw85::is_positive_definite(s);
}

// A pair of ellipses: r finite, q1 and q2 finite and positive definite.
pw85::Status validate_pair_2d(double const *r, double const *q1, double const *q2) noexcept {
  if (r == nullptr || q1 == nullptr || q2 == nullptr) return pw85::kInvalidArgument;
  if (!pw85::all_finite(r, 2) || !pw85::all_finite(q1, 3) || !pw85::all_finite(q2, 3))
    return pw85::kInvalidArgument;
  if (!spd_scaled_2d(q1) || !spd_scaled_2d(q2)) return pw85::kNotSpd;
  return pw85::kOk;
}

// The entry points compute into locals (d NaN, evaluations 0 until a result
// exists) and write the outputs last: outputs may alias the inputs.
int dca_zheng_checked(double const u[3], double const q1[6], double const q2[6],
                      double theta_tol, double &d, int &evaluations) {
  int const status = pw85::capi::validate_pair(u, q1, q2);
  if (status != PW85_OK) return status;
  if (!std::isfinite(theta_tol) || theta_tol < 0.0) return PW85_ERR_INVALID_ARGUMENT;
  pw85::Vec3 un;
  if (!normalise<3>(u, un.x)) return PW85_ERR_INVALID_ARGUMENT;
  if (theta_tol == 0.0) theta_tol = PW85_DCA_THETA_TOL;
  pw85::DcaResult res;
  int const s = pw85::dca_zheng(un, pw85::load_sym3(q1), pw85::load_sym3(q2), theta_tol,
                                PW85_DCA_MAX_EVAL, res);
  evaluations = res.evaluations;
  d = res.d;
  return s;
}

int dca_2d_checked(double const u[2], double const q1[3], double const q2[3], double &d) {
  int const status = validate_pair_2d(u, q1, q2);
  if (status != PW85_OK) return status;
  pw85::Vec2 un;
  if (!normalise<2>(u, un.x)) return PW85_ERR_INVALID_ARGUMENT;
  pw85::Dca2dResult res;
  int const s = pw85::dca_2d(un, pw85::load_sym2(q1), pw85::load_sym2(q2), res);
  if (s != PW85_OK && s != PW85_ERR_NO_CONVERGENCE) return s;
  d = res.d;
  return s;
}

int dca_checked(double const u[3], double const q1[6], double const q2[6], int method,
                double &d) {
  int const status = pw85::capi::validate_pair(u, q1, q2);
  if (status != PW85_OK) return status;
  if (u[0] == 0.0 && u[1] == 0.0 && u[2] == 0.0) return PW85_ERR_INVALID_ARGUMENT;
  double dd = std::nan("");
  int const s = pw85::dca_by_contact_function(pw85::load_vec3(u), pw85::load_sym3(q1),
                                              pw85::load_sym3(q2), method, dd);
  d = dd;
  return s;
}

}  // namespace

extern "C" {

int pw85_dca_2d(double const u[2], double const q1[3], double const q2[3], double *d) {
  if (d == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  double dd = std::nan("");
  int const s = dca_2d_checked(u, q1, q2, dd);
  *d = dd;
  return s;
}

int pw85_contact_function_2d(double const r12[2], double const q1[3], double const q2[3],
                             double out[2]) {
  if (out == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  int const status = validate_pair_2d(r12, q1, q2);
  if (status != PW85_OK) {
    fill_nan(out, 2);
    return status;
  }
  int iterations;
  int const s = pw85::contact_function_2d(pw85::load_vec2(r12), pw85::load_sym2(q1),
                                          pw85::load_sym2(q2), out[0], out[1], iterations);
  // mu^2 out of the range of double (written rounded: +Inf, subnormal or 0;
  // r12 = 0 gives mu^2 = 0 exactly).
  bool const r_zero = r12[0] == 0.0 && r12[1] == 0.0;
  if (s == PW85_OK && !r_zero && !(out[0] >= DBL_MIN && out[0] <= DBL_MAX)) return PW85_ERR_RANGE;
  return s;
}

int pw85_dca(double const u[3], double const q1[6], double const q2[6], int method,
             double *d) {
  if (d == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  double dd = std::nan("");
  int evaluations = 0;
  int const s = method == PW85_METHOD_ZHENG
                    ? dca_zheng_checked(u, q1, q2, 0.0, dd, evaluations)
                    : dca_checked(u, q1, q2, method, dd);
  *d = dd;
  return s;
}

int pw85_dca_ex(double const u[3], double const q1[6], double const q2[6], double theta_tol,
                double *d, int *evaluations) {
  double dd = std::nan("");
  int ev = 0;
  int const s = d == nullptr ? PW85_ERR_INVALID_ARGUMENT
                             : dca_zheng_checked(u, q1, q2, theta_tol, dd, ev);
  if (evaluations != nullptr) *evaluations = ev;
  if (d != nullptr) *d = dd;
  return s;
}

}  // extern "C"
