// Argument validation shared by the extern "C" entry points.
#pragma once

#include <cmath>

#include "../core/status.hpp"
#include "../core/sym3.hpp"

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

}  // namespace capi
}  // namespace pw85
