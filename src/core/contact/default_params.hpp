// Parameters of step 1 of PW85_METHOD_DEFAULT (docs/methods.md), shared by
// the one-pair code and the vector lanes (default.hpp, first_step),
// which must take the same decisions.
#pragma once

#include "common/fp.hpp"

namespace pw85 {
namespace default_params {

// Fast path when the estimated relative error is below this.
constexpr double kFastRel = 4e-15;
// Rounding error of the stationary form (M11) relative to f: ~7u from its
// last step in double (f_dd.hpp, stationary_combine) and the compensated
// sums, with margin.
constexpr double kStatRel = 10.0 * kU;
constexpr double kExtrapGap = 1e-6;
constexpr double kExtrapBudget = 1e-16;
// Steps of the start (M22) and its stopping test (start.hpp).
constexpr int kStartMin = 1, kStartMax = 6;
constexpr double kStartTol = 3e-2;
// Taylor coefficients 1/3! and 1/4! (rounded): multiplications, since the
// divider is shared by every division and square root of the fast path
// (docs/methods.md, (M21); a division by a constant is not turned into a
// product without -freciprocal-math).
constexpr double kInv6 = 1.0 / 6.0, kInv24 = 1.0 / 24.0;

}  // namespace default_params
}  // namespace pw85
