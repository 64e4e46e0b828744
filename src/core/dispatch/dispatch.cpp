// The table of kernels per variant (kernels.hpp), and the variants' names.
#include "dispatch/kernels.hpp"

namespace pw85 {

// Constant-initialised from the concepts' tables: no code runs to build it.
const Kernels kernel_table[kVariantCount] = {
#define PW85_KERNELS_ROW(v)                                                                  \
  Kernels{&dd_kernels[v], &overlap_dd_kernels[v], &orientation_kernels[v], &overlap_kernels[v], \
          &derivative_kernels[v], &default_kernels[v]}
    PW85_KERNELS_ROW(0), PW85_KERNELS_ROW(1), PW85_KERNELS_ROW(2), PW85_KERNELS_ROW(3)
#undef PW85_KERNELS_ROW
};

char const *variant_name(Variant v) noexcept {
  switch (v) {
    case Variant::portable: return "portable";
    case Variant::fma: return "fma";
    case Variant::v3: return "x86-64-v3";
    case Variant::v4: return "x86-64-v4";
  }
  return "unknown";
}

bool variant_built(Variant v) noexcept {
  switch (v) {
    case Variant::portable: return true;
    case Variant::fma: return PW85_ISA_FMA;
    case Variant::v3:
    case Variant::v4: return PW85_ISA_LEVELS;
  }
  return false;
}

bool variant_runs(Variant v) noexcept {
  return variant_built(v) && static_cast<int>(v) <= static_cast<int>(cpu_variant());
}

}  // namespace pw85
