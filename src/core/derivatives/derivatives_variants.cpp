// The compiled variants of the derivatives from DEFAULT's solution
// (paths.hpp, one body; adjugate.hpp on x86-64-v4): the double-double
// products by Dekker's product (portable) or the fused multiply-add (fma,
// and x86-64-v3, which runs the fma variant), and on x86-64-v4 the adjugate
// path (E9) first. Compiled without contraction (src/meson.build), like
// derivatives.cpp.
#include "derivatives/derivatives_variants.hpp"

#include "derivatives/derivatives.hpp"
#include "derivatives/paths.hpp"
#include "dispatch/variant.hpp"
#if PW85_ISA_LEVELS
#include "derivatives/adjugate.hpp"
#endif

namespace pw85 {

namespace {

using derivative_paths::derivatives_from;
using derivative_paths::is_solved;

// The kernels of one variant, compiled with the target attribute TARGET,
// the double-double products by the fused multiply-add when FMA is true.
#define PW85_DERIVATIVES_VARIANT(name, TARGET, FMA)                                            \
  TARGET Status from_solution_##name(Status status, MethodResult const &res, Vec3 const &r,    \
                                     Sym3 const &q1, Sym3 const &q2, DerivativeFields fields,  \
                                     Derivatives &d) noexcept {                                \
    return derivatives_from<FMA>(status, res, r, q1, q2, fields, d);                           \
  }                                                                                            \
  constexpr DerivativeKernels kDerivatives_##name = {from_solution_##name};

PW85_DERIVATIVES_VARIANT(portable, , kStaticFma)
#if PW85_ISA_FMA
PW85_DERIVATIVES_VARIANT(fma, PW85_TARGET_FMA, true)
#endif

#if PW85_ISA_LEVELS
// x86-64-v4: (E9) first (adjugate.hpp), then (E8) and (E7). (E9) computes
// every field for either fields: the Hessian's error estimate decides
// whether (E9) is taken, and so which path computes the other fields.
PW85_TARGET_V4 Status from_solution_v4(Status status, MethodResult const &res, Vec3 const &r,
                                       Sym3 const &q1, Sym3 const &q2, DerivativeFields fields,
                                       Derivatives &d) noexcept {
  if (is_solved(status, res) && adjugate_path::adjugate_derivatives(res.lambda, res.mu2, r, q1, q2, d)) {
    derivative_paths::drop_unrequested(fields, d);
    return status;
  }
  return derivatives_from<true>(status, res, r, q1, q2, fields, d);
}
constexpr DerivativeKernels kDerivatives_v4 = {from_solution_v4};
#endif

}  // namespace

const DerivativeKernels derivative_kernels[kVariantCount] = {
    kDerivatives_portable, PW85_IF_FMA(kDerivatives_fma, kDerivatives_portable),
    PW85_IF_FMA(kDerivatives_fma, kDerivatives_portable),
    PW85_IF_LEVELS(kDerivatives_v4, PW85_IF_FMA(kDerivatives_fma, kDerivatives_portable))};

}  // namespace pw85
