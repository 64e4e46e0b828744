// The double-double kernels of f_dd.hpp, compiled for any CPU (Dekker's
// product) and with the FMA instruction, chosen at run time
// (common/isa.hpp). std::fma without hardware FMA is a library call, ten
// times slower than either.
#include "eval/f_dd.hpp"

namespace pw85 {

namespace {
#if PW85_ISA_FMA
PW85_TARGET_FMA bool f_eval_dd_fma(double lambda, Vec3 const &r,
                                                  Sym3 const &q1, Sym3 const &q2,
                                                  FEvalDD &out) noexcept {
  return f_eval_dd_impl<true>(lambda, r, q1, q2, out);
}
PW85_TARGET_FMA double f_stationary_fma(double lambda, Vec3 const &r,
                                                      Sym3 const &q1, Sym3 const &q2,
                                                      Vec3 const &s) noexcept {
  return f_stationary_avx(lambda, r, q1, q2, s);
}
PW85_TARGET_FMA Vec3 residual_dd_fma(double lambda, Vec3 const &r,
                                                   Sym3 const &q1, Sym3 const &q2,
                                                   Vec3 const &s) noexcept {
  return residual_dd_impl<true>(lambda, r, q1, q2, s);
}
PW85_TARGET_FMA bool contact_point_dd_fma(double lambda, Vec3 const &r,
                                                        Sym3 const &q1, Sym3 const &q2,
                                                        Vec3 &x0, Vec3 &n,
                                                        double &df) noexcept {
  return contact_point_dd_impl<true>(lambda, r, q1, q2, x0, n, df);
}
PW85_TARGET_FMA double refined_point_dd_fma(double lambda, Sym3 const &q1,
                                                         Sym3 const &q2, Vec3 const &s,
                                                         Vec3 const &delta, Vec3 &x0,
                                                         Vec3 &q2s) noexcept {
  return refined_point_impl<true>(lambda, q1, q2, s, delta, x0, q2s);
}
#endif
}  // namespace

bool f_eval_dd(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
               FEvalDD &out) noexcept {
#if PW85_ISA_FMA
  if (isa::has_fma()) return f_eval_dd_fma(lambda, r, q1, q2, out);
#endif
  return f_eval_dd_impl<isa::kStaticFma>(lambda, r, q1, q2, out);
}

double f_stationary(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                    Vec3 const &s) noexcept {
#if PW85_ISA_STATIC_FMA
  return f_stationary_avx(lambda, r, q1, q2, s);
#else
#if PW85_ISA_FMA
  if (isa::has_fma()) return f_stationary_fma(lambda, r, q1, q2, s);
#endif
  return f_stationary_impl<false>(lambda, r, q1, q2, s);
#endif
}

Vec3 residual_dd(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                 Vec3 const &s) noexcept {
#if PW85_ISA_FMA
  if (isa::has_fma()) return residual_dd_fma(lambda, r, q1, q2, s);
#endif
  return residual_dd_impl<isa::kStaticFma>(lambda, r, q1, q2, s);
}

bool contact_point_dd(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                      Vec3 &x0, Vec3 &n, double &df) noexcept {
#if PW85_ISA_FMA
  if (isa::has_fma()) return contact_point_dd_fma(lambda, r, q1, q2, x0, n, df);
#endif
  return contact_point_dd_impl<isa::kStaticFma>(lambda, r, q1, q2, x0, n, df);
}

double refined_point_dd(double lambda, Sym3 const &q1, Sym3 const &q2, Vec3 const &s,
                        Vec3 const &delta, Vec3 &x0, Vec3 &q2s) noexcept {
#if PW85_ISA_FMA
  if (isa::has_fma()) return refined_point_dd_fma(lambda, q1, q2, s, delta, x0, q2s);
#endif
  return refined_point_impl<isa::kStaticFma>(lambda, q1, q2, s, delta, x0, q2s);
}

}  // namespace pw85
