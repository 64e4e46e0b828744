// Instruction-set dispatch: the one scheme of every kernel that has
// variants. A kernel is written once, as an always-inline body (a template
// on the operations it may use, or plain code that inlines what it calls),
// wrapped by functions compiled for each instruction set with a target
// attribute, and chosen at run time by the CPU queries below:
//
//   PW85_TARGET_FMA Result kernel_fma(args) { return kernel_body<true>(args); }
//   Result kernel(args) {
//   #if PW85_ISA_FMA
//     if (isa::has_fma()) return kernel_fma(args);
//   #endif
//     return kernel_body<kStaticFma>(args);
//   }
//
// The variants that exist:
//  - PW85_ISA_FMA: the double-double kernels with a fused multiply-add in
//    their error-free products (eval/dd_kernels.cpp, overlap/overlap_dd.cpp,
//    common/orientation.cpp; x86 with GCC or Clang);
//  - PW85_ISA_LEVELS: code compiled for x86-64-v3 (AVX2) and x86-64-v4
//    (AVX-512): the filters of pw85_overlap (overlap/overlap.cpp), DEFAULT's
//    rational step and general method (contact/default.cpp), the entry of
//    pw85_contact_function_method (contact/methods.cpp) and the adjugate
//    path of the derivatives (derivatives/adjugate.hpp); GCC >= 12 on x86-64.
// The meson option isa_dispatch=false (PW85_NO_ISA_DISPATCH) turns both off:
// every kernel then runs its portable code. kStaticFma is true when the
// whole build targets FMA (-mfma, -march=...): the FMA body is then the only
// one and needs no dispatch.
//
// Where results depend on the variant: DEFAULT and the derivatives on
// x86-64-v4 run a different algorithm first (docs/methods.md,
// docs/derivatives.md), so their results may differ in the last bits from
// the portable code, within their documented accuracy; the FMA
// double-double kernels may differ from their portable twins by an ulp. The
// verdicts of pw85_overlap are identical for every variant.
#pragma once

#include <type_traits>

#if defined(__GNUC__)
#define PW85_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define PW85_ALWAYS_INLINE inline
#endif

#if defined(__FMA__)
#define PW85_ISA_STATIC_FMA 1
#define PW85_TARGET_FMA
#else
#define PW85_ISA_STATIC_FMA 0
#endif

#if !defined(PW85_NO_ISA_DISPATCH) && !PW85_ISA_STATIC_FMA && \
    (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
#define PW85_ISA_FMA 1
#define PW85_TARGET_FMA __attribute__((target("fma")))
#else
#define PW85_ISA_FMA 0
#endif

#if !defined(PW85_NO_ISA_DISPATCH) && defined(__x86_64__) && defined(__GNUC__) && \
    !defined(__clang__) && __GNUC__ >= 12
#define PW85_ISA_LEVELS 1
#define PW85_TARGET_V3 __attribute__((target("arch=x86-64-v3")))
#define PW85_TARGET_V4 __attribute__((target("arch=x86-64-v4")))
// An always-inline helper compiled for x86-64-v4 (AVX-512 intrinsics), to
// be inlined into a PW85_TARGET_V4 function.
#define PW85_V4_INLINE __attribute__((target("arch=x86-64-v4"), always_inline)) inline
#else
#define PW85_ISA_LEVELS 0
#endif

namespace pw85 {
namespace isa {

// The FMA body when the build targets FMA, else the portable one: the body
// a kernel runs when no variant is chosen at run time.
constexpr bool kStaticFma = PW85_ISA_STATIC_FMA;

#if PW85_ISA_FMA
inline bool has_fma() noexcept { return __builtin_cpu_supports("fma"); }
#endif
#if PW85_ISA_LEVELS
inline bool has_v3() noexcept { return __builtin_cpu_supports("x86-64-v3"); }
inline bool has_v4() noexcept { return __builtin_cpu_supports("x86-64-v4"); }
#endif

}  // namespace isa

// Makes x opaque to the optimiser (it must be materialised, and may have
// changed): a combined condition such as (a > b) & (c > d) is then tested by
// one branch instead of being split into one branch per comparison, and
// code whose result passes through it is not sunk into the branch that
// uses it. For the unpredictable branches of the overlap filters and of
// DEFAULT's acceptance tests. No effect on the value.
template <class T>
PW85_ALWAYS_INLINE void opaque(T &x) noexcept {
  static_assert(std::is_integral<T>::value, "opaque: a general-purpose register value");
#if defined(__GNUC__)
  asm("" : "+r"(x));
#else
  (void)x;
#endif
}

}  // namespace pw85
