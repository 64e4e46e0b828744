// Compiler helpers for the hot paths that are compiled for several x86-64
// levels and chosen at run time (docs/overlap.md and docs/methods.md,
// "Instruction sets"): target("arch=x86-64-vN") functions wrap one
// always-inline body, so that everything the body inlines is compiled for
// that level; __builtin_cpu_supports("x86-64-vN") chooses. GCC 12+ on x86-64
// only; the meson option isa_dispatch=false defines PW85_NO_ISA_DISPATCH.
// Floating-point contraction: GCC fuses a * b + c into an FMA by default in
// C++ (also with -std=c++17) where the target has FMA. src/meson.build turns
// it off except in overlap.cpp, overlap_dd.cpp and dd_kernels.cpp, so the
// variants of DEFAULT perform the same IEEE operations as the baseline; the
// overlap variants contract, which its error bounds allow (docs/overlap.md).
#pragma once

#include <type_traits>

#if defined(__GNUC__)
#define PW85_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define PW85_ALWAYS_INLINE inline
#endif

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12 && \
    !defined(PW85_NO_ISA_DISPATCH)
#define PW85_ISA_DISPATCH 1
// An always-inline helper compiled for x86-64-v4 (AVX-512 intrinsics), to
// be inlined into a target("arch=x86-64-v4") function.
#define PW85_V4_INLINE __attribute__((target("arch=x86-64-v4"), always_inline)) inline
#else
#define PW85_ISA_DISPATCH 0
#endif

// Makes x opaque to the optimiser (it must be materialised, and may have
// changed): a combined condition such as (a > b) & (c > d) is then tested by
// one branch instead of being split into one branch per comparison, and
// code whose result passes through it is not sunk into the branch that
// uses it. For the unpredictable branches of the overlap filters and of
// DEFAULT's acceptance tests (docs/overlap.md and docs/methods.md,
// "Branches"). No effect on the value.
template <class T>
PW85_ALWAYS_INLINE void opaque(T &x) noexcept {
  static_assert(std::is_integral<T>::value, "opaque: a general-purpose register value");
#if defined(__GNUC__)
  asm("" : "+r"(x));
#else
  (void)x;
#endif
}
