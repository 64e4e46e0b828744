// The variants of the derivatives from DEFAULT's solution
// (derivatives_variants.cpp).
#pragma once

#include "common/status.hpp"
#include "common/sym3.hpp"
#include "contact/contact.hpp"
#include "dispatch/variant.hpp"

namespace pw85 {

struct Derivatives;
enum class DerivativeFields;

struct DerivativeKernels {
  // The derivatives of the pair from DEFAULT's solution (status, res):
  // (E9) first on x86-64-v4, then (E8), then (E7) (docs/derivatives.md);
  // the fields of fields (derivatives.hpp), the others NaN.
  Status (*from_solution)(Status status, MethodResult const &res, Vec3 const &r,
                          Sym3 const &q1, Sym3 const &q2, DerivativeFields fields,
                          Derivatives &d) noexcept;
};

// The kernels of variant v: x86-64-v4 (with (E9)), else the fused
// multiply-add in the double-double products (fma and x86-64-v3) where
// built, else the portable code.
extern const DerivativeKernels derivative_kernels[kVariantCount];

}  // namespace pw85
