// extern "C" entry point of the method-selecting contact function: checks
// the pointers, calls pw85::contact_method_entry (src/core/contact/methods.cpp,
// which screens the values and dispatches), copies the result out.
#include <cmath>

#include "pw85.h"
#include "contact/contact.hpp"

static_assert(pw85::kMethodDefault == PW85_METHOD_DEFAULT, "method ids must match pw85.h");
static_assert(pw85::kMethodBrent == PW85_METHOD_BRENT, "");
static_assert(pw85::kMethodNewton == PW85_METHOD_NEWTON, "");
static_assert(pw85::kMethodRational == PW85_METHOD_RATIONAL, "");
static_assert(pw85::kMethodZheng == PW85_METHOD_ZHENG, "");
static_assert(pw85::kMethodCount == PW85_METHOD_ZHENG + 1, "a method of the core missing in pw85.h");

extern "C" int pw85_contact_function_method(double const r12[PW85_DIM],
                                            double const q1[PW85_SYM],
                                            double const q2[PW85_SYM], int method,
                                            pw85_result *res) {
  if (res == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  // Every input is read before *res is written (res may alias them).
  pw85::MethodResult m;
  int const s = r12 == nullptr || q1 == nullptr || q2 == nullptr
                    ? PW85_ERR_INVALID_ARGUMENT
                    : pw85::contact_method_entry(r12, q1, q2, method, m);
  if (s == PW85_ERR_UNKNOWN_METHOD || s == PW85_ERR_INVALID_ARGUMENT || s == PW85_ERR_NOT_SPD) {
    double const nan = std::nan("");
    res->mu2 = nan;
    res->lambda = nan;
    res->mu2_error = nan;
    res->iterations = 0;
    res->method = method;
    return s;
  }
  res->mu2 = m.mu2;
  res->lambda = m.lambda;
  res->mu2_error = m.mu2_error;
  res->iterations = m.iterations;
  res->method = m.method;
  return s;
}
