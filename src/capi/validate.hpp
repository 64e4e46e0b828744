// Argument validation shared by the extern "C" entry points.
#pragma once

#include <cmath>

#include "common/screen.hpp"
#include "common/status.hpp"
#include "common/sym3.hpp"

namespace pw85 {
namespace capi {

inline void fill_nan(double *p, int n) noexcept {
  for (int i = 0; i < n; ++i) p[i] = std::nan("");
}

// A pair of ellipsoids: r12 finite, q1 and q2 finite and positive definite.
inline Status validate_pair(double const *r12, double const *q1, double const *q2) noexcept {
  if (r12 == nullptr || q1 == nullptr || q2 == nullptr) return kInvalidArgument;
  if (!all_finite(r12, kDim) || !all_finite(q1, kSym) || !all_finite(q2, kSym))
    return kInvalidArgument;
  if (!is_positive_definite(load_sym3(q1)) || !is_positive_definite(load_sym3(q2)))
    return kNotSpd;
  return kOk;
}

// The contract of validate_pair with ldl_positive for the matrices (the
// entry points on hot paths: pw85_overlap, pw85_contact_function_method).
inline Status validate_pair_ldl(double const *r12, double const *q1, double const *q2) noexcept {
  if (r12 == nullptr || q1 == nullptr || q2 == nullptr) return kInvalidArgument;
  if (!all_finite(r12, kDim) || !all_finite(q1, kSym) || !all_finite(q2, kSym))
    return kInvalidArgument;
  if (!ldl_positive(q1) || !ldl_positive(q2)) return kNotSpd;
  return kOk;
}

}  // namespace capi
}  // namespace pw85
