// The double-double kernels of f_dd.hpp, compiled twice on x86: once for
// any CPU (Dekker's product) and once with the FMA instruction (target
// attribute), chosen at run time with __builtin_cpu_supports. std::fma
// without hardware FMA is a library call, ten times slower than either.
#include "eval/f_dd.hpp"

namespace pw85 {

namespace {
#ifdef PW85_DD_DISPATCH
__attribute__((target("fma"))) bool f_eval_dd_fma(double lambda, Vec3 const &r,
                                                  Sym3 const &q1, Sym3 const &q2,
                                                  FEvalDD &out) noexcept {
  return f_eval_dd_impl<true>(lambda, r, q1, q2, out);
}
__attribute__((target("fma"))) double f_stationary_fma(double lambda, Vec3 const &r,
                                                      Sym3 const &q1, Sym3 const &q2,
                                                      Vec3 const &s) noexcept {
  return f_stationary_avx(lambda, r, q1, q2, s);
}
__attribute__((target("fma"))) Vec3 residual_dd_fma(double lambda, Vec3 const &r,
                                                   Sym3 const &q1, Sym3 const &q2,
                                                   Vec3 const &s) noexcept {
  return residual_dd_impl<true>(lambda, r, q1, q2, s);
}
__attribute__((target("fma"))) bool contact_point_dd_fma(double lambda, Vec3 const &r,
                                                        Sym3 const &q1, Sym3 const &q2,
                                                        Vec3 &x0, Vec3 &n,
                                                        double &df) noexcept {
  return contact_point_dd_impl<true>(lambda, r, q1, q2, x0, n, df);
}
__attribute__((target("fma"))) double refined_point_dd_fma(double lambda, Sym3 const &q1,
                                                         Sym3 const &q2, Vec3 const &s,
                                                         Vec3 const &delta, Vec3 &x0,
                                                         Vec3 &q2s) noexcept {
  return refined_point_impl<true>(lambda, q1, q2, s, delta, x0, q2s);
}
using dd::cpu_has_fma;
#endif
}  // namespace

bool f_eval_dd(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
               FEvalDD &out) noexcept {
#if defined(PW85_DD_STATIC_FMA)
  return f_eval_dd_impl<true>(lambda, r, q1, q2, out);
#else
#if defined(PW85_DD_DISPATCH)
  if (cpu_has_fma()) return f_eval_dd_fma(lambda, r, q1, q2, out);
#endif
  return f_eval_dd_impl<false>(lambda, r, q1, q2, out);
#endif
}

double f_stationary(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                    Vec3 const &s) noexcept {
#if defined(PW85_DD_STATIC_FMA)
  return f_stationary_avx(lambda, r, q1, q2, s);
#else
#if defined(PW85_DD_DISPATCH)
  if (cpu_has_fma()) return f_stationary_fma(lambda, r, q1, q2, s);
#endif
  return f_stationary_impl<false>(lambda, r, q1, q2, s);
#endif
}

Vec3 residual_dd(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                 Vec3 const &s) noexcept {
#if defined(PW85_DD_STATIC_FMA)
  return residual_dd_impl<true>(lambda, r, q1, q2, s);
#else
#if defined(PW85_DD_DISPATCH)
  if (cpu_has_fma()) return residual_dd_fma(lambda, r, q1, q2, s);
#endif
  return residual_dd_impl<false>(lambda, r, q1, q2, s);
#endif
}

bool contact_point_dd(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                      Vec3 &x0, Vec3 &n, double &df) noexcept {
#if defined(PW85_DD_STATIC_FMA)
  return contact_point_dd_impl<true>(lambda, r, q1, q2, x0, n, df);
#else
#if defined(PW85_DD_DISPATCH)
  if (cpu_has_fma()) return contact_point_dd_fma(lambda, r, q1, q2, x0, n, df);
#endif
  return contact_point_dd_impl<false>(lambda, r, q1, q2, x0, n, df);
#endif
}

double refined_point_dd(double lambda, Sym3 const &q1, Sym3 const &q2, Vec3 const &s,
                        Vec3 const &delta, Vec3 &x0, Vec3 &q2s) noexcept {
#if defined(PW85_DD_STATIC_FMA)
  return refined_point_impl<true>(lambda, q1, q2, s, delta, x0, q2s);
#else
#if defined(PW85_DD_DISPATCH)
  if (cpu_has_fma()) return refined_point_dd_fma(lambda, q1, q2, s, delta, x0, q2s);
#endif
  return refined_point_impl<false>(lambda, q1, q2, s, delta, x0, q2s);
#endif
}

}  // namespace pw85
