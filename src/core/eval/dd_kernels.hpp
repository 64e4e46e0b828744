// The variants of the double-double kernels of f_dd.hpp (dd_kernels.cpp):
// Dekker's product on any CPU, the fused multiply-add where the CPU has it.
// std::fma without hardware FMA is a library call, ten times slower than
// either.
#pragma once

#include "common/sym3.hpp"
#include "dispatch/variant.hpp"

namespace pw85 {

struct FEvalDD;

struct DdKernels {
  bool (*f_eval)(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                 FEvalDD &out) noexcept;
  double (*f_stationary)(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                         Vec3 const &s) noexcept;
  Vec3 (*residual)(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                   Vec3 const &s) noexcept;
  bool (*contact_point)(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                        Vec3 &x0, Vec3 &n, double &df) noexcept;
  double (*refined_point)(double lambda, Sym3 const &q1, Sym3 const &q2, Vec3 const &s,
                          Vec3 const &delta, Vec3 &x0, Vec3 &q2s) noexcept;
};

// The kernels of variant v: FMA from the fma variant up, where built.
extern const DdKernels dd_kernels[kVariantCount];

}  // namespace pw85
