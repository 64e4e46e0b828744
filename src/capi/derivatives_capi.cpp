// extern "C" layer of pw85_contact_derivatives (docs/derivatives.md):
// validation and status mapping; the work is in src/core/derivatives/.
#include <cmath>
#include <cstring>

#include "pw85.h"
#include "contact/contact.hpp"
#include "derivatives/derivatives.hpp"
#include "common/screen.hpp"
#include "common/sym3.hpp"
#include "validate.hpp"

static_assert(sizeof(pw85_derivatives_t) == sizeof(pw85::Derivatives),
              "pw85_derivatives_t mirrors pw85::Derivatives");

extern "C" {

int pw85_contact_derivatives_ex(double const r12[PW85_DIM], double const q1[PW85_SYM],
                                double const q2[PW85_SYM], unsigned flags,
                                pw85_derivatives_t *d) {
  if (d == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  pw85::Derivatives out;
  pw85::DerivativeFields fields = pw85::DerivativeFields::kAll;
  bool const flags_ok = pw85::capi::derivative_fields(flags, fields);
  // Valid arguments of moderate magnitude (nearly all calls): the one-pass
  // screen of pw85_contact_function_method (common/screen.hpp).
  if (flags_ok && r12 != nullptr && q1 != nullptr && q2 != nullptr &&
      pw85::screen_contact_pair(r12, q1, q2, pw85::kSafeLo, pw85::kSafeHi)) {
    int const status = pw85::contact_derivatives(pw85::load_vec3(r12), pw85::load_sym3(q1),
                                                 pw85::load_sym3(q2), out, fields);
    std::memcpy(d, &out, sizeof out);
    return status;
  }
  pw85::capi::fill_nan(&out.mu2, 29);
  int status = flags_ok ? pw85::capi::validate_pair(r12, q1, q2) : PW85_ERR_INVALID_ARGUMENT;
  if (status == PW85_OK && r12[0] == 0.0 && r12[1] == 0.0 && r12[2] == 0.0)
    status = PW85_ERR_INVALID_ARGUMENT;  // mu^2 = 0 is a cone point: no derivative
  if (status == PW85_OK)
    status = pw85::contact_derivatives(pw85::load_vec3(r12), pw85::load_sym3(q1),
                                       pw85::load_sym3(q2), out, fields);
  std::memcpy(d, &out, sizeof out);
  return status;
}

int pw85_contact_derivatives(double const r12[PW85_DIM], double const q1[PW85_SYM],
                             double const q2[PW85_SYM], pw85_derivatives_t *d) {
  return pw85_contact_derivatives_ex(r12, q1, q2, PW85_DERIVATIVES_ALL, d);
}

}  // extern "C"
