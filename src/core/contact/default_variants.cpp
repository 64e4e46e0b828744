// The variants of PW85_METHOD_DEFAULT (default_variants.hpp), each compiled
// from the bodies of default.hpp with the target attributes of
// dispatch/variant.hpp, and the calls that read them (contact.hpp:
// contact_default, default_lanes). This file is compiled without
// contraction (src/meson.build): every variant of the general method
// performs the same IEEE operations, and the lanes those of the one-pair
// code.
#include "contact/default.hpp"
#include "contact/default_variants.hpp"
#include "dispatch/kernels.hpp"

namespace pw85 {

namespace {

using namespace default_method;

// Step 1 of the general method in kDefaultLanes / kLanes vectors
// (first_step_lanes).
#define PW85_DEFAULT_LANES_VARIANT(name, TARGET)                                            \
  TARGET void lanes_##name(double const *const r[kDefaultLanes],                            \
                           double const *const q1[kDefaultLanes],                           \
                           double const *const q2[kDefaultLanes],                           \
                           MethodResult res[kDefaultLanes],                                 \
                           int status[kDefaultLanes]) noexcept {                            \
    static_assert(kDefaultLanes % lanes::kLanes == 0, "whole vectors per block");          \
    bool accepted[kDefaultLanes];                                                           \
    for (int b = 0; b < kDefaultLanes; b += lanes::kLanes)                                  \
      first_step_lanes(r + b, q1 + b, q2 + b, res + b, accepted + b);                      \
    for (int l = 0; l < kDefaultLanes; ++l) status[l] = accepted[l] ? kOk : kLaneUndecided; \
  }

// The general method (default_body).
Status contact_portable(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                        MethodResult &res) noexcept {
  res.method = kMethodDefault;
  return default_body(r, q1, q2, res);
}
PW85_DEFAULT_LANES_VARIANT(portable, )

#if PW85_ISA_LEVELS
PW85_DEFAULT_LANES_VARIANT(v3, PW85_TARGET_V3)

// The general method compiled for x86-64-v4, from its own start (M22), with
// the same IEEE operations as the portable one. Out of line: inlined into
// contact_v4 below, its register use made every call save and restore every
// callee-saved register, the coefficient step's calls included.
PW85_TARGET_V4 __attribute__((noinline)) Status general_v4(Vec3 const &r, Sym3 const &q1,
                                                           Sym3 const &q2,
                                                           MethodResult &res) noexcept {
  res.method = kMethodDefault;
  return default_body(r, q1, q2, res);
}

// After coefficient_step declined: coefficient_step_precise, then the general method.
// A separate function that recomputes the coefficients and the start:
// coefficient_step_precise called from coefficient_step with its
// coefficients (inline or not) made the one-pair call slower where it never
// runs (build/bench/bench_batch, classes 0-2).
PW85_TARGET_V4 __attribute__((noinline)) Status declined_v4(Vec3 const &r, Sym3 const &q1,
                                                            Sym3 const &q2,
                                                            MethodResult &res) noexcept {
  if (coefficient_step_precise(r, q1, q2, res)) return kOk;
  return general_v4(r, q1, q2, res);
}

// The coefficient step, and the general method when it declines.
PW85_TARGET_V4 Status contact_v4(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                                 MethodResult &res) noexcept {
  res.method = kMethodDefault;
  if (coefficient_step(r, q1, q2, res)) return kOk;
  return declined_v4(r, q1, q2, res);
}

PW85_TARGET_V4 void lanes_v4(double const *const r[kDefaultLanes],
                             double const *const q1[kDefaultLanes],
                             double const *const q2[kDefaultLanes],
                             MethodResult res[kDefaultLanes],
                             int status[kDefaultLanes]) noexcept {
  lanes8::coefficient_step_lanes<general_v4>(r, q1, q2, res, status);
}
#endif

#undef PW85_DEFAULT_LANES_VARIANT

DefaultKernels const kDefaultPortable = {contact_portable, lanes_portable};
#if PW85_ISA_LEVELS
DefaultKernels const kDefaultV3 = {contact_portable, lanes_v3};
DefaultKernels const kDefaultV4 = {contact_v4, lanes_v4};
#endif

}  // namespace

const DefaultKernels default_kernels[kVariantCount] = {
    kDefaultPortable, kDefaultPortable, PW85_IF_LEVELS(kDefaultV3, kDefaultPortable),
    PW85_IF_LEVELS(kDefaultV4, kDefaultPortable)};

Status contact_default(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                       MethodResult &res) noexcept {
  return kernels().contact_default->contact(r, q1, q2, res);
}

void default_lanes(double const *const r[kDefaultLanes], double const *const q1[kDefaultLanes],
                   double const *const q2[kDefaultLanes], MethodResult res[kDefaultLanes],
                   int status[kDefaultLanes]) noexcept {
  kernels().contact_default->lanes(r, q1, q2, res, status);
}

}  // namespace pw85
