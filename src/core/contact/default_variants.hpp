// The variants of PW85_METHOD_DEFAULT (default_variants.cpp), one sub-table
// of the table of kernels (dispatch/kernels.hpp): the one-pair method and
// its lanes, compiled from the bodies of default.hpp for each instruction
// set. docs/methods.md, "Which variant runs where".
#pragma once

#include "common/status.hpp"
#include "common/sym3.hpp"
#include "contact/contact.hpp"
#include "dispatch/variant.hpp"

namespace pw85 {

struct DefaultKernels {
  // DEFAULT for one pair of moderate magnitudes (contact_default,
  // contact.hpp); sets res.method.
  Status (*contact)(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                    MethodResult &res) noexcept;
  // DEFAULT for kDefaultLanes pairs at once (default_lanes, contact.hpp).
  void (*lanes)(double const *const r[kDefaultLanes], double const *const q1[kDefaultLanes],
                double const *const q2[kDefaultLanes], MethodResult res[kDefaultLanes],
                int status[kDefaultLanes]) noexcept;
};

// The kernels of variant v: x86-64-v4 runs the coefficient step first (one
// pair and eight lanes); x86-64-v3 the general method with its first step
// in AVX2 lanes; portable and fma the portable code.
extern const DefaultKernels default_kernels[kVariantCount];

}  // namespace pw85
