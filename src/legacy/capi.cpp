// The extern "C" layer of libpw85_legacy: validate, call the core of
// src/legacy/, map to a status code of pw85.h. No logic of its own.
#include <cmath>

#include "pw85_legacy.h"
#include "../capi/validate.hpp"
#include "legacy.hpp"

static_assert(pw85::kOk == PW85_OK, "status codes must match pw85.h");
static_assert(pw85::kNoConvergence == PW85_ERR_NO_CONVERGENCE, "");
static_assert(pw85::kInaccurate == PW85_ERR_INACCURATE, "");

using pw85::load_sym3;
using pw85::load_vec3;
using pw85::capi::fill_nan;

namespace {

double f_common(double lambda, double const *r12, double const *q1, double const *q2,
                double *out, bool rational) {
  pw85::legacy::FDerivs fd{};
  bool ok = std::isfinite(lambda) && pw85::capi::validate_pair(r12, q1, q2) == pw85::kOk;
  if (ok) {
    if (rational) {
      pw85::legacy::Rational rat;
      pw85::legacy::rational_coefficients(load_vec3(r12), load_sym3(q1), load_sym3(q2), rat);
      ok = pw85::legacy::f_rational(rat, lambda, fd);
    } else {
      ok = pw85::legacy::f_cholesky(lambda, load_vec3(r12), load_sym3(q1), load_sym3(q2),
                                    fd, nullptr);
    }
  }
  if (!ok) {
    if (out != nullptr) fill_nan(out, 3);
    return std::nan("");
  }
  if (out != nullptr) {
    out[0] = fd.f;
    out[1] = fd.df;
    out[2] = fd.d2f;
  }
  return fd.f;
}

using ContactMethod = pw85::Status (*)(pw85::Vec3 const &, pw85::Sym3 const &,
                                       pw85::Sym3 const &, pw85::ContactResult &) noexcept;

int contact_common(double const *r12, double const *q1, double const *q2, double *out,
                   ContactMethod method) {
  if (out == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  int const status = pw85::capi::validate_pair(r12, q1, q2);
  if (status != PW85_OK) {
    fill_nan(out, 2);
    return status;
  }
  pw85::ContactResult res;
  int const s = method(load_vec3(r12), load_sym3(q1), load_sym3(q2), res);
  out[0] = res.mu2;
  out[1] = res.lambda;
  return s;
}

}  // namespace

extern "C" {

double pw85_legacy__det_sym(double const a[PW85_SYM]) {
  if (a == nullptr) return std::nan("");
  return pw85::legacy::det_sym(load_sym3(a));
}

double pw85_legacy__xT_adjA_x(double const x[PW85_DIM], double const a[PW85_SYM]) {
  if (x == nullptr || a == nullptr) return std::nan("");
  return pw85::legacy::xT_adjA_x(load_vec3(x), load_sym3(a));
}

void pw85_legacy__rT_adjQ_r_as_poly(double const r[PW85_DIM], double const q1[PW85_SYM],
                                    double const q2[PW85_SYM], double const q3[PW85_SYM],
                                    double a[PW85_DIM]) {
  if (a == nullptr) return;
  if (r == nullptr || q1 == nullptr || q2 == nullptr || q3 == nullptr) {
    fill_nan(a, PW85_DIM);
    return;
  }
  pw85::legacy::rT_adjQ_r_as_poly(load_vec3(r), load_sym3(q1), load_sym3(q2),
                                  load_sym3(q3), a);
}

void pw85_legacy__detQ_as_poly(double const q1[PW85_SYM], double const q2[PW85_SYM],
                               double const q3[PW85_SYM], double const q4[PW85_SYM],
                               double b[PW85_DIM + 1]) {
  if (b == nullptr) return;
  if (q1 == nullptr || q2 == nullptr || q3 == nullptr || q4 == nullptr) {
    fill_nan(b, PW85_DIM + 1);
    return;
  }
  pw85::legacy::detQ_as_poly(load_sym3(q1), load_sym3(q2), load_sym3(q3), load_sym3(q4), b);
}

double pw85_legacy_f1(double lambda, double const r12[PW85_DIM], double const q1[PW85_SYM],
                      double const q2[PW85_SYM], double *out) {
  return f_common(lambda, r12, q1, q2, out, false);
}

double pw85_legacy_f2(double lambda, double const r12[PW85_DIM], double const q1[PW85_SYM],
                      double const q2[PW85_SYM], double *out) {
  return f_common(lambda, r12, q1, q2, out, true);
}

int pw85_legacy_contact_function1(double const r12[PW85_DIM], double const q1[PW85_SYM],
                                  double const q2[PW85_SYM], double out[2]) {
  return contact_common(r12, q1, q2, out, pw85::legacy::contact_newton);
}

int pw85_legacy_contact_function2(double const r12[PW85_DIM], double const q1[PW85_SYM],
                                  double const q2[PW85_SYM], double out[2]) {
  return contact_common(r12, q1, q2, out, pw85::legacy::contact_bisection);
}

}  // extern "C"
