// extern "C" entry point of the method-selecting contact function (issue 7):
// validate, call pw85::contact_method (src/core/methods.cpp), copy out. Valid
// arguments of moderate magnitude (nearly all calls) are recognised by one
// screening pass and go to contact_method_in_range directly (DEFAULT on
// x86-64-v4: to contact_default_v4), skipping the separate finiteness loops
// and the dispatcher's range test, with the caller's arrays passed as views
// (no copy; docs/methods.md, "The C entry (thirteenth session)").
#include <cmath>

#include "pw85.h"
#include "contact/contact.hpp"
#include "common/isa.hpp"
#include "common/sym3.hpp"
#include "validate.hpp"

static_assert(pw85::kMethodDefault == PW85_METHOD_DEFAULT, "method ids must match pw85.h");
static_assert(pw85::kMethodBrent == PW85_METHOD_BRENT, "");
static_assert(pw85::kMethodNewton == PW85_METHOD_NEWTON, "");
static_assert(pw85::kMethodRational == PW85_METHOD_RATIONAL, "");
static_assert(pw85::kMethodZheng == PW85_METHOD_ZHENG, "");

namespace {

// kV4: compiled into entry_v4 below, which calls DEFAULT's v4 variant
// directly (no dispatcher switch, no second CPU check).
template <bool kV4>
PW85_ALWAYS_INLINE int entry_body(double const *r12, double const *q1, double const *q2,
                                  int method, pw85_result *res) noexcept {
  if (res == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  double const nan = std::nan("");
  res->mu2 = nan;
  res->lambda = nan;
  res->mu2_error = nan;
  res->iterations = 0;
  res->method = method;
  if (r12 == nullptr || q1 == nullptr || q2 == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  pw85::MethodResult m;
  int s;
  if (method >= PW85_METHOD_DEFAULT && method <= PW85_METHOD_ZHENG &&
      pw85::capi::screen_contact_pair(r12, q1, q2, pw85::kSafeLo, pw85::kSafeHi)) {
    // Common case: valid arguments of moderate magnitude, checked in one pass.
#if PW85_ISA_DISPATCH
    if (kV4 && method == PW85_METHOD_DEFAULT)
      s = pw85::contact_default_v4(pw85::view_vec3(r12), pw85::view_sym3(q1),
                                   pw85::view_sym3(q2), m);
    else
#endif
      s = pw85::contact_method_in_range(method, pw85::view_vec3(r12), pw85::view_sym3(q1),
                                        pw85::view_sym3(q2), m);
  } else {
    int const status = pw85::capi::validate_pair_ldl(r12, q1, q2);
    if (status != PW85_OK) return status;
    s = pw85::contact_method(method, pw85::load_vec3(r12), pw85::load_sym3(q1),
                             pw85::load_sym3(q2), m);
  }
  if (s == PW85_ERR_UNKNOWN_METHOD) return s;
  res->mu2 = m.mu2;
  res->lambda = m.lambda;
  res->mu2_error = m.mu2_error;
  res->iterations = m.iterations;
  res->method = m.method;
  return s;
}

#if PW85_ISA_DISPATCH
// The entry compiled for x86-64-v4 as well (docs/methods.md, "Instruction
// sets"): together with the v4 variant of DEFAULT (default.cpp) 8-13 ns
// per DEFAULT call faster on this machine (neither alone measured faster),
// with identical results (-ffp-contract=off, src/meson.build).
__attribute__((target("arch=x86-64-v4"))) int entry_v4(double const *r12, double const *q1,
                                                        double const *q2, int method,
                                                        pw85_result *res) noexcept {
  return entry_body<true>(r12, q1, q2, method, res);
}
#endif

}  // namespace

extern "C" int pw85_contact_function_method(double const r12[PW85_DIM],
                                            double const q1[PW85_SYM],
                                            double const q2[PW85_SYM], int method,
                                            pw85_result *res) {
#if PW85_ISA_DISPATCH
  if (__builtin_cpu_supports("x86-64-v4")) return entry_v4(r12, q1, q2, method, res);
#endif
  return entry_body<false>(r12, q1, q2, method, res);
}
