// The CPU probe and the table of kernels per variant (kernels.hpp).
#include "dispatch/kernels.hpp"

namespace pw85 {

namespace {

Variant probe_cpu() noexcept {
#if PW85_ISA_FMA || PW85_ISA_LEVELS
  __builtin_cpu_init();  // the probe may run before libgcc's constructor
#endif
#if PW85_ISA_LEVELS
  if (__builtin_cpu_supports("x86-64-v4")) return Variant::v4;
  if (__builtin_cpu_supports("x86-64-v3")) return Variant::v3;
#endif
#if PW85_ISA_FMA
  if (__builtin_cpu_supports("fma")) return Variant::fma;
#endif
  return Variant::portable;
}

Kernels make_kernels(Variant v) noexcept {
  return Kernels{dd_kernels_for(v), overlap_dd_kernels_for(v), orientation_kernels_for(v),
                 overlap_kernels_for(v), derivative_kernels_for(v)};
}

}  // namespace

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

Variant cpu_variant() noexcept {
  static Variant const variant = probe_cpu();
  return variant;
}

bool variant_runs(Variant v) noexcept {
  return variant_built(v) && static_cast<int>(v) <= static_cast<int>(cpu_variant());
}

Kernels const &kernels_of(Variant v) noexcept {
  static Kernels const table[kVariantCount] = {
      make_kernels(Variant::portable), make_kernels(Variant::fma), make_kernels(Variant::v3),
      make_kernels(Variant::v4)};
  int i = static_cast<int>(v);
  if (i < 0 || i >= kVariantCount) i = 0;
  while (i > 0 && !variant_built(static_cast<Variant>(i))) --i;
  return table[i];
}

}  // namespace pw85
