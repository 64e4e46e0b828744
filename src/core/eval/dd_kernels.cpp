// The double-double kernels of f_dd.hpp in their variants (dd_kernels.hpp)
// and the calls that run the variant of this CPU.
#include "eval/dd_kernels.hpp"

#include <cmath>

#include "dispatch/kernels.hpp"
#include "eval/f_dd.hpp"

namespace pw85 {

namespace {

// The kernels with Dekker's product (F false) fall back on the fused
// multiply-add's bodies (std::fma, correctly rounded in software where the
// CPU has no instruction) where they fail (false, or a value not finite).
// Dekker's product splits its factors by a product with 2^27 + 1
// (arith/dd.hpp), which overflows for factors above 2^996, where the fused
// multiply-add's product is still exact. The products s_i s_j and s^T D s
// of f' reach that far where Q(lambda) is tiny beside r (a maximiser near 0
// or 1 of matrices far apart, one 2^-900 of the other). With the fallback,
// an evaluation fails on every CPU where it fails with the fused
// multiply-add (a pivot not positive, a value beyond the range of double),
// with the same result there, and not where only the splitting overflows.
// It runs only on a failure, so its cost (a library call per product)
// never reaches the evaluations that succeed. The fallbacks are out of
// line: inlined, they changed the inlining of the Dekker bodies
// (build/bench/trace_pairs default random 3 in an isa_dispatch=false
// build, callgrind: 1.6% more instructions).
#define PW85_DD_FALLBACK [[maybe_unused]] __attribute__((noinline, cold))

PW85_DD_FALLBACK bool f_eval_fallback(double lambda, Vec3 const &r, Sym3 const &q1,
                                      Sym3 const &q2, FEvalDD &out) noexcept {
  return f_eval_dd_impl<true>(lambda, r, q1, q2, out);
}

PW85_DD_FALLBACK bool contact_point_fallback(double lambda, Vec3 const &r, Sym3 const &q1,
                                             Sym3 const &q2, Vec3 &x0, Vec3 &n,
                                             double &df) noexcept {
  return contact_point_dd_impl<true>(lambda, r, q1, q2, x0, n, df);
}

PW85_DD_FALLBACK Vec3 residual_fallback(double lambda, Vec3 const &r, Sym3 const &q1,
                                        Sym3 const &q2, Vec3 const &s) noexcept {
  return residual_dd_impl<true>(lambda, r, q1, q2, s);
}

PW85_DD_FALLBACK double refined_point_fallback(double lambda, Sym3 const &q1, Sym3 const &q2,
                                               Vec3 const &s, Vec3 const &delta, Vec3 &x0,
                                               Vec3 &q2s) noexcept {
  return refined_point_impl<true>(lambda, q1, q2, s, delta, x0, q2s);
}

PW85_DD_FALLBACK double f_stationary_fallback(double lambda, Vec3 const &r, Sym3 const &q1,
                                              Sym3 const &q2, Vec3 const &s) noexcept {
  return f_stationary_impl<true>(lambda, r, q1, q2, s);
}

#undef PW85_DD_FALLBACK

template <bool F>
PW85_ALWAYS_INLINE bool f_eval_kernel(double lambda, Vec3 const &r, Sym3 const &q1,
                                      Sym3 const &q2, FEvalDD &out) noexcept {
  if constexpr (F)
    return f_eval_dd_impl<true>(lambda, r, q1, q2, out);
  else
    return f_eval_dd_impl<false>(lambda, r, q1, q2, out) ||
           f_eval_fallback(lambda, r, q1, q2, out);
}

template <bool F>
PW85_ALWAYS_INLINE bool contact_point_kernel(double lambda, Vec3 const &r, Sym3 const &q1,
                                             Sym3 const &q2, Vec3 &x0, Vec3 &n,
                                             double &df) noexcept {
  if constexpr (F)
    return contact_point_dd_impl<true>(lambda, r, q1, q2, x0, n, df);
  else
    return contact_point_dd_impl<false>(lambda, r, q1, q2, x0, n, df) ||
           contact_point_fallback(lambda, r, q1, q2, x0, n, df);
}

template <bool F>
PW85_ALWAYS_INLINE Vec3 residual_kernel(double lambda, Vec3 const &r, Sym3 const &q1,
                                        Sym3 const &q2, Vec3 const &s) noexcept {
  Vec3 const rho = residual_dd_impl<F>(lambda, r, q1, q2, s);
  if constexpr (F) return rho;
  if (std::isfinite(rho[0]) && std::isfinite(rho[1]) && std::isfinite(rho[2])) return rho;
  return residual_fallback(lambda, r, q1, q2, s);
}

template <bool F>
PW85_ALWAYS_INLINE double refined_point_kernel(double lambda, Sym3 const &q1, Sym3 const &q2,
                                               Vec3 const &s, Vec3 const &delta, Vec3 &x0,
                                               Vec3 &q2s) noexcept {
  double const df = refined_point_impl<F>(lambda, q1, q2, s, delta, x0, q2s);
  if constexpr (F) return df;
  if (std::isfinite(df) && std::isfinite(x0[0]) && std::isfinite(x0[1]) &&
      std::isfinite(x0[2]) && std::isfinite(q2s[0]) && std::isfinite(q2s[1]) &&
      std::isfinite(q2s[2]))
    return df;
  return refined_point_fallback(lambda, q1, q2, s, delta, x0, q2s);
}

// f_stationary with Dekker's product.
PW85_ALWAYS_INLINE double f_stationary_dekker(double lambda, Vec3 const &r, Sym3 const &q1,
                                              Sym3 const &q2, Vec3 const &s) noexcept {
  double const f = f_stationary_impl<false>(lambda, r, q1, q2, s);
  return std::isfinite(f) ? f : f_stationary_fallback(lambda, r, q1, q2, s);
}

// The kernels of one variant, compiled with the target attribute TARGET from
// the bodies of f_dd.hpp with Dekker's product (FMA false) or the fused
// multiply-add (FMA true); STATIONARY is f_stationary's body.
#define PW85_DD_VARIANT(name, TARGET, FMA, STATIONARY)                                                    \
  TARGET bool f_eval_##name(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,    \
                            FEvalDD &out) noexcept {                                          \
    return f_eval_kernel<FMA>(lambda, r, q1, q2, out);                                        \
  }                                                                                           \
  TARGET double f_stationary_##name(double lambda, Vec3 const &r, Sym3 const &q1,            \
                                    Sym3 const &q2, Vec3 const &s) noexcept {                 \
    return STATIONARY(lambda, r, q1, q2, s);                                                   \
  }                                                                                           \
  TARGET Vec3 residual_##name(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,  \
                              Vec3 const &s) noexcept {                                       \
    return residual_kernel<FMA>(lambda, r, q1, q2, s);                                        \
  }                                                                                           \
  TARGET bool contact_point_##name(double lambda, Vec3 const &r, Sym3 const &q1,             \
                                   Sym3 const &q2, Vec3 &x0, Vec3 &n, double &df) noexcept {  \
    return contact_point_kernel<FMA>(lambda, r, q1, q2, x0, n, df);                           \
  }                                                                                           \
  TARGET double refined_point_##name(double lambda, Sym3 const &q1, Sym3 const &q2,          \
                                     Vec3 const &s, Vec3 const &delta, Vec3 &x0,              \
                                     Vec3 &q2s) noexcept {                                    \
    return refined_point_kernel<FMA>(lambda, q1, q2, s, delta, x0, q2s);                      \
  }                                                                                           \
  constexpr DdKernels kDd_##name = {f_eval_##name, f_stationary_##name, residual_##name,     \
                                    contact_point_##name, refined_point_##name};

#if PW85_ISA_STATIC_FMA
PW85_DD_VARIANT(portable, , true, f_stationary_lanes)
#else
PW85_DD_VARIANT(portable, , false, f_stationary_dekker)
#endif
#if PW85_ISA_FMA
PW85_DD_VARIANT(fma, PW85_TARGET_FMA, true, f_stationary_lanes)
#endif

}  // namespace

const DdKernels dd_kernels[kVariantCount] = {
    kDd_portable, PW85_IF_FMA(kDd_fma, kDd_portable), PW85_IF_FMA(kDd_fma, kDd_portable),
    PW85_IF_FMA(kDd_fma, kDd_portable)};

bool f_eval_dd(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
               FEvalDD &out) noexcept {
  return kernels().dd->f_eval(lambda, r, q1, q2, out);
}

double f_stationary(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                    Vec3 const &s) noexcept {
  return kernels().dd->f_stationary(lambda, r, q1, q2, s);
}

Vec3 residual_dd(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                 Vec3 const &s) noexcept {
  return kernels().dd->residual(lambda, r, q1, q2, s);
}

bool contact_point_dd(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                      Vec3 &x0, Vec3 &n, double &df) noexcept {
  return kernels().dd->contact_point(lambda, r, q1, q2, x0, n, df);
}

double refined_point_dd(double lambda, Sym3 const &q1, Sym3 const &q2, Vec3 const &s,
                        Vec3 const &delta, Vec3 &x0, Vec3 &q2s) noexcept {
  return kernels().dd->refined_point(lambda, q1, q2, s, delta, x0, q2s);
}

}  // namespace pw85
