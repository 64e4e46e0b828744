// Helpers for kernel bodies: forced inlining and opaque values. The
// instruction-set variants and their target attributes are in
// dispatch/variant.hpp; the CPU is probed only in dispatch/dispatch.cpp.
#pragma once

#include <type_traits>

#if defined(__GNUC__)
#define PW85_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define PW85_ALWAYS_INLINE inline
#endif

#include "dispatch/variant.hpp"

namespace pw85 {
namespace isa {

// The CPU queries of the kernels that do not read dispatch/kernels.hpp yet.
constexpr bool kStaticFma = pw85::kStaticFma;
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
