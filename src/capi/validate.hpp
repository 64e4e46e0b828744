// Argument validation shared by the extern "C" entry points.
#pragma once

#include <cmath>

#include "common/magnitude.hpp"
#include "common/spd.hpp"
#include "common/status.hpp"
#include "common/sym3.hpp"
#include "derivatives/derivatives.hpp"
#include "pw85.h"

namespace pw85 {
namespace capi {

inline void fill_nan(double *p, int n) noexcept {
  for (int i = 0; i < n; ++i) p[i] = std::nan("");
}

// A pair of ellipsoids: r12 finite, q1 and q2 finite and positive definite
// (the one decision of common/spd.hpp).
inline Status validate_pair(double const *r12, double const *q1, double const *q2) noexcept {
  if (r12 == nullptr || q1 == nullptr || q2 == nullptr) return kInvalidArgument;
  if (!all_finite(r12, kDim) || !all_finite(q1, kSym) || !all_finite(q2, kSym))
    return kInvalidArgument;
  if (!positive_definite(q1) || !positive_definite(q2)) return kNotSpd;
  return kOk;
}

// The fields of a flags argument of the derivatives calls; false for
// flags other than PW85_DERIVATIVES_ALL and PW85_DERIVATIVES_FORCES.
inline bool derivative_fields(unsigned flags, DerivativeFields &fields) noexcept {
  if (flags != PW85_DERIVATIVES_ALL && flags != PW85_DERIVATIVES_FORCES) return false;
  fields = flags == PW85_DERIVATIVES_ALL ? DerivativeFields::kAll : DerivativeFields::kForces;
  return true;
}

}  // namespace capi
}  // namespace pw85
