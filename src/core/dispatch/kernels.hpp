// The one dispatch point: the table of kernel variants the library calls.
//
// Each concept that has variants declares its sub-table (a struct of
// function pointers) in its folder, and the array <concept>_kernels of one
// sub-table per variant (a variant the concept does not compile holds the
// highest one below it); Kernels gathers them. A call site reads
// kernels().<concept>-><kernel>(...): the table of this CPU. The tables are
// constant data and the choice reads the CPU features libgcc recorded at
// start-up: no lazy initialisation, no guard, no state. Tests run any
// variant through kernels_of(v).
//
// To add a kernel: add its pointer to its concept's sub-table and its
// function to each variant the concept compiles. To add a concept: its
// sub-table here and in dispatch.cpp's rows. To add a variant: a value of
// Variant, its CPU test in cpu_variant(), and its row in each concept's
// array.
#pragma once

#include "dispatch/variant.hpp"
#include "common/orientation.hpp"
#include "contact/default_variants.hpp"
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
  DefaultKernels const *contact_default;
};

// One row per variant (dispatch.cpp); the row of a variant the build lacks
// holds, per concept, the highest variant below it that the build has.
extern const Kernels kernel_table[kVariantCount];

// The table of variant v. Calling into it needs variant_runs(v).
inline Kernels const &kernels_of(Variant v) noexcept {
  return kernel_table[static_cast<int>(v)];
}

// The table of the variant this CPU runs (cpu_variant()).
inline Kernels const &kernels() noexcept { return kernels_of(cpu_variant()); }

}  // namespace pw85
