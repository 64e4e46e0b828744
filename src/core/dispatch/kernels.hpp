// The one dispatch point: the table of kernel variants the library calls.
//
// Each concept that has variants declares its sub-table (a struct of
// function pointers) in its folder, and the function <concept>_kernels_for(v)
// that returns the sub-table of variant v (the highest variant at most v
// that the concept has); Kernels gathers them. A call site reads
// kernels().<concept>-><kernel>(...): the table of this CPU, chosen once
// (dispatch.cpp). Tests run any variant through kernels_of(v).
//
// To add a kernel: add its pointer to its concept's sub-table and its
// function to each variant the concept compiles. To add a concept: its
// sub-table here and in make_kernels() (dispatch.cpp). To add a variant: a
// value of Variant, its CPU test in cpu_variant(), and its case in the
// concepts' *_kernels_for.
#pragma once

#include "dispatch/variant.hpp"
#include "common/orientation.hpp"
#include "derivatives/derivatives_variants.hpp"
#include "eval/dd_kernels.hpp"
#include "overlap/overlap_dd.hpp"
#include "overlap/overlap_variants.hpp"

namespace pw85 {

struct Kernels {
  DdKernels const *dd;
  OverlapDdKernels const *overlap_dd;
  OrientationKernels const *orientation;
  OverlapKernels const *overlap;
  DerivativeKernels const *derivatives;
};

// The table of variant v if the build has it, else of the highest built
// variant below it. Calling into it needs variant_runs(v).
Kernels const &kernels_of(Variant v) noexcept;

// The table of the variant this CPU runs (cpu_variant()), chosen on the
// first call.
inline Kernels const &kernels() noexcept {
  static Kernels const &table = kernels_of(cpu_variant());
  return table;
}


}  // namespace pw85
