// extern "C" entry point of the method-selecting contact function (issue 7):
// validate, call pw85::contact_method (src/core/methods.cpp), copy out.
#include <cmath>

#include "pw85.h"
#include "../core/contact.hpp"
#include "../core/sym3.hpp"

static_assert(pw85::kMethodDefault == PW85_METHOD_DEFAULT, "method ids must match pw85.h");
static_assert(pw85::kMethodBrent == PW85_METHOD_BRENT, "");
static_assert(pw85::kMethodNewton == PW85_METHOD_NEWTON, "");
static_assert(pw85::kMethodRational == PW85_METHOD_RATIONAL, "");
static_assert(pw85::kMethodZheng == PW85_METHOD_ZHENG, "");

namespace {

// The contract of pw85::capi::validate_pair (NULL, finite, positive
// definite), with the pivots of L D L^T instead of a Cholesky factorisation
// (no square roots; same decisions up to rounding).
bool ldl_positive(double const *a) noexcept {
  double const d0 = a[0];
  if (!(d0 > 0.0)) return false;
  double const i0 = 1.0 / d0;
  double const l1 = a[1] * i0, l2 = a[2] * i0;
  double const d1 = a[3] - l1 * a[1];
  if (!(d1 > 0.0)) return false;
  double const e = a[4] - l2 * a[1];
  double const d2 = a[5] - l2 * a[2] - (e / d1) * e;  // no overflow of e * e
  return d2 > 0.0 && std::isfinite(d2);
}

int validate(double const *r12, double const *q1, double const *q2) noexcept {
  if (r12 == nullptr || q1 == nullptr || q2 == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  if (!pw85::all_finite(r12, PW85_DIM) || !pw85::all_finite(q1, PW85_SYM) ||
      !pw85::all_finite(q2, PW85_SYM))
    return PW85_ERR_INVALID_ARGUMENT;
  if (!ldl_positive(q1) || !ldl_positive(q2)) return PW85_ERR_NOT_SPD;
  return PW85_OK;
}

}  // namespace

extern "C" int pw85_contact_function_method(double const r12[PW85_DIM],
                                            double const q1[PW85_SYM],
                                            double const q2[PW85_SYM], int method,
                                            pw85_result *res) {
  if (res == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  double const nan = std::nan("");
  res->mu2 = nan;
  res->lambda = nan;
  res->mu2_error = nan;
  res->iterations = 0;
  res->method = method;
  int const status = validate(r12, q1, q2);
  if (status != PW85_OK) return status;
  pw85::MethodResult m;
  int const s = pw85::contact_method(method, pw85::load_vec3(r12), pw85::load_sym3(q1),
                                     pw85::load_sym3(q2), m);
  if (s == PW85_ERR_UNKNOWN_METHOD) return s;
  res->mu2 = m.mu2;
  res->lambda = m.lambda;
  res->mu2_error = m.mu2_error;
  res->iterations = m.iterations;
  res->method = m.method;
  return s;
}
