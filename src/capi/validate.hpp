// Argument validation shared by the extern "C" entry points.
#pragma once

#include <cmath>

#include "common/magnitude.hpp"
#include "common/screen.hpp"
#include "common/status.hpp"
#include "common/sym3.hpp"
#include "common/scaling.hpp"

namespace pw85 {
namespace capi {

inline void fill_nan(double *p, int n) noexcept {
  for (int i = 0; i < n; ++i) p[i] = std::nan("");
}

// Cholesky test of 2^-e q, e the even exponent nearest above that of
// max |q_ij| (exact scaling, the square roots scale exactly): the decision
// of the unscaled test wherever that neither underflows nor overflows, and
// the right one for matrices of subnormal or huge entries.
inline bool spd_scaled(double const *q) noexcept {
  // Common case first: max |q_ij| in [2^-500, 2^500], tested unscaled.
  double const m = max_abs(q, kSym);
  if (m >= 0x1p-500 && m <= 0x1p500) return is_positive_definite(load_sym3(q));
  int e = max_exponent(q, kSym);
  e += e & 1;
  Sym3 s;
  scale_by_power_of_two(q, s.a, kSym, -e);
  return is_positive_definite(s);
}

// A pair of ellipsoids: r12 finite, q1 and q2 finite and positive definite.
inline Status validate_pair(double const *r12, double const *q1, double const *q2) noexcept {
  if (r12 == nullptr || q1 == nullptr || q2 == nullptr) return kInvalidArgument;
  if (!all_finite(r12, kDim) || !all_finite(q1, kSym) || !all_finite(q2, kSym))
    return kInvalidArgument;
  if (!spd_scaled(q1) || !spd_scaled(q2)) return kNotSpd;
  return kOk;
}

// The contract of validate_pair with ldl_positive for the matrices (the
// entry points on hot paths: pw85_overlap, pw85_contact_function_method).
inline Status validate_pair_ldl(double const *r12, double const *q1, double const *q2) noexcept {
  if (r12 == nullptr || q1 == nullptr || q2 == nullptr) return kInvalidArgument;
  if (!all_finite(r12, kDim) || !all_finite(q1, kSym) || !all_finite(q2, kSym))
    return kInvalidArgument;
  if (!ldl_positive_scaled(q1) || !ldl_positive_scaled(q2)) return kNotSpd;
  return kOk;
}

}  // namespace capi
}  // namespace pw85
