// The instruction-set variants of the kernels (dispatch/kernels.hpp) and the
// target attributes that compile a body for one of them.
//
// A kernel is written once, as an always-inline body (a template on the lane
// type or on the operations it may use), and compiled into one function per
// variant by its folder's *_variants.cpp with the attributes below. Which
// variant runs is decided once, in dispatch/dispatch.cpp; no kernel queries
// the CPU.
//
// The variants:
//  - portable: the code for any CPU the build targets;
//  - fma:      the fused multiply-add (double-double error-free products);
//  - v3:       x86-64-v3 (AVX2 and FMA);
//  - v4:       x86-64-v4 (AVX-512 F/BW/CD/DQ/VL).
// fma exists with GCC or Clang on x86 when the build does not already target
// FMA (then the portable body is the FMA body: kStaticFma); v3 and v4 exist
// with GCC >= 12 on x86-64 when the build does not already target AVX2
// (-march=haswell, -march=native, ...: a body compiled for such a target
// cannot be inlined into a function whose arch= attribute lacks some of
// its features, and the portable body is then compiled for that target). The meson option isa_dispatch=false
// (PW85_NO_ISA_DISPATCH) builds the portable variant only.
#pragma once

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
    !defined(__clang__) && __GNUC__ >= 12 && !defined(__AVX2__)
#define PW85_ISA_LEVELS 1
#define PW85_TARGET_V3 __attribute__((target("arch=x86-64-v3")))
#define PW85_TARGET_V4 __attribute__((target("arch=x86-64-v4")))
// An always-inline helper compiled for x86-64-v4 (AVX-512 intrinsics), to
// be inlined into a PW85_TARGET_V4 function.
#define PW85_V4_INLINE __attribute__((target("arch=x86-64-v4"), always_inline)) inline
#else
#define PW85_ISA_LEVELS 0
#endif

// Rows of a concept's table of variants (dispatch/kernels.hpp): the table
// of a variant where the build compiles it, else the fallback.
#if PW85_ISA_FMA
#define PW85_IF_FMA(table, fallback) table
#else
#define PW85_IF_FMA(table, fallback) fallback
#endif
#if PW85_ISA_LEVELS
#define PW85_IF_LEVELS(table, fallback) table
#else
#define PW85_IF_LEVELS(table, fallback) fallback
#endif

namespace pw85 {

enum class Variant : unsigned char { portable, fma, v3, v4 };
constexpr int kVariantCount = 4;

// The FMA body when the whole build targets FMA (-mfma, -march=...), else
// the portable one: the body of the portable variant.
constexpr bool kStaticFma = PW85_ISA_STATIC_FMA;

// "portable", "fma", "x86-64-v3", "x86-64-v4".
char const *variant_name(Variant v) noexcept;

// Whether this build compiled the variant.
bool variant_built(Variant v) noexcept;

// Whether this build compiled the variant and this CPU can run it.
bool variant_runs(Variant v) noexcept;

// The variant the library runs on this CPU: the highest that runs. The CPU
// is probed once, by libgcc's constructor (__cpu_indicator_init) when the
// program starts; __builtin_cpu_supports reads the features it recorded.
inline Variant cpu_variant() noexcept {
#if PW85_ISA_LEVELS
  if (__builtin_cpu_supports("x86-64-v4")) return Variant::v4;
  if (__builtin_cpu_supports("x86-64-v3")) return Variant::v3;
#endif
#if PW85_ISA_FMA
  if (__builtin_cpu_supports("fma")) return Variant::fma;
#endif
  return Variant::portable;
}

}  // namespace pw85
