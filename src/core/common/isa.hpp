// Helpers for kernel bodies: forced inlining and opaque values. The
// instruction-set variants and their target attributes are in
// dispatch/variant.hpp.
#pragma once

#include <type_traits>

#if defined(__GNUC__)
#define PW85_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define PW85_ALWAYS_INLINE inline
#endif

#include "dispatch/variant.hpp"

namespace pw85 {

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
