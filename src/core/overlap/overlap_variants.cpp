// The compiled variants of the overlap filters' first certificates
// (overlap/filters.hpp, one body): pw85_overlap's hot path for one pair
// (screen -> filters -> exact stage, inlined whole) and the W-pair lanes of
// the batch calls (overlap_lanes, W = kOverlapLanesV4 = 8 in the x86-64-v4
// variant, one AVX-512 register; kOverlapLanes = 4 in the others), each for
// the x86-64 levels v4 (AVX-512: 32 vector registers, fewer spills of the
// bounded values), v3 (AVX2) and the portable code; the table of this CPU
// (dispatch/kernels.hpp) chooses among them (docs/overlap.md, "Instruction
// sets and reproducibility").
//
// Compiled with GCC's default contraction (src/meson.build), like
// overlap.cpp: the v3 and v4 variants fuse some a * b + c into FMAs; every
// bound of the filters holds for a fused operation too (the product's
// rounding error is then 0), so the verdicts do not depend on the variant.
#include "common/isa.hpp"
#include "common/lanes.hpp"
#include "common/screen.hpp"
#include "common/spd.hpp"
#include "overlap/filters.hpp"
#include "overlap/overlap.hpp"
#include "overlap/overlap_variants.hpp"

namespace pw85 {

namespace {

using overlap_filters::first_certificates;
using overlap_filters::FirstDecision;
using overlap_filters::kUndecided;

// One pair. False: not screened, nothing written.
PW85_ALWAYS_INLINE bool screened_body(double const *rp, double const *q1p, double const *q2p,
                                      int &verdict, Status &status) noexcept {
  if (!screen_overlap_pair(rp, q1p, q2p, kOverlapRangeLo, kOverlapRangeHi)) return false;
  Vec3 const r = load_vec3(rp);
  Sym3 const q1 = load_sym3(q1p), q2 = load_sym3(q2p);
  status = kOk;
  if (r[0] == 0.0 && r[1] == 0.0 && r[2] == 0.0) {
    verdict = 1;
    return true;
  }
  int stage;
  int const v = overlap_filters::filters_inline(r, q1, q2, stage);
  if (v != kUndecided)
    verdict = v;
  else
    status = overlap_exact(r, q1, q2, verdict);
  return true;
}

// The positive-definiteness certificate of spd.hpp (certain_spd) in every
// lane: the same operations, so the same decision as the one-pair screen.
template <class Lane>
PW85_ALWAYS_INLINE lanes::UMaskOf<Lane> certain_spd_lanes(Lane const x[kSym]) noexcept {
  using lanes::gt;
  using lanes::le;
  Lane d0, d1, d2;
  spd_shifted_pivots(x[0], x[1], x[2], x[3], x[4], x[5], d0, d1, d2);
  return gt(d0, 0.0) & gt(d1, 0.0) & gt(d2, 0.0) & le(d2, kMaxDouble);
}

// W pairs, pair l = (rp[l], q1p[l], q2p[l]) in lane l: verdict[l] = 1, 0, or
// -1 when the lane fails the screen (that of screen.hpp's
// screen_overlap_pair, and r != 0) or the first certificates leave it open.
template <int W>
PW85_ALWAYS_INLINE void lanes_body(double const *const rp[W], double const *const q1p[W],
                                   double const *const q2p[W], int verdict[W]) noexcept {
  using Lane = lanes::VecD<W>;
  using lanes::ge;
  using lanes::le;
  using lanes::ne;
  using lanes::vabs;
  using lanes::vmax;
  Lane r[kDim], a[kSym], b[kSym];
  lanes::gather<kDim, W>(rp, r);
  lanes::gather<kSym, W>(q1p, a);
  lanes::gather<kSym, W>(q2p, b);
  Lane qm = vabs(a[0]);
  for (int i = 1; i < kSym; ++i) qm = vmax(qm, vabs(a[i]));
  for (int i = 0; i < kSym; ++i) qm = vmax(qm, vabs(b[i]));
  lanes::UMaskOf<Lane> const screened =
      le(vabs(r[0]), kOverlapRangeHi) & le(vabs(r[1]), kOverlapRangeHi) &
      le(vabs(r[2]), kOverlapRangeHi) & ge(qm, kOverlapRangeLo) & le(qm, kOverlapRangeHi) &
      certain_spd_lanes(a) & certain_spd_lanes(b) &
      (ne(r[0], 0.0) | ne(r[1], 0.0) | ne(r[2], 0.0));
  FirstDecision<Lane> const d = first_certificates<Lane>(r, a, b, screened);
  using Signed = lanes::MaskOf<Lane>;
  Signed const v = -1 - 2 * reinterpret_cast<Signed>(d.one) - reinterpret_cast<Signed>(d.zero);
  for (int l = 0; l < W; ++l) verdict[l] = static_cast<int>(v[l]);
}

// The kernels of one variant, compiled with the target attribute TARGET;
// WIDE lanes per vector (8 pairs: WIDE lanes at a time).
#define PW85_OVERLAP_VARIANT(name, TARGET, WIDE)                                                \
  [[gnu::noinline]] TARGET bool screened_##name(double const *rp, double const *q1p,            \
                                                double const *q2p, int &verdict,                \
                                                Status &status) noexcept {                      \
    return screened_body(rp, q1p, q2p, verdict, status);                                        \
  }                                                                                             \
  TARGET void lanes4_##name(double const *const rp[4], double const *const q1p[4],              \
                            double const *const q2p[4], int verdict[4]) noexcept {              \
    lanes_body<4>(rp, q1p, q2p, verdict);                                                       \
  }                                                                                             \
  TARGET void lanes8_##name(double const *const rp[8], double const *const q1p[8],              \
                            double const *const q2p[8], int verdict[8]) noexcept {              \
    for (int l = 0; l < 8; l += WIDE) lanes_body<WIDE>(rp + l, q1p + l, q2p + l, verdict + l);  \
  }                                                                                             \
  constexpr OverlapKernels kOverlap_##name = {screened_##name, lanes4_##name, lanes8_##name,    \
                                              WIDE};

static_assert(kOverlapLanes == 4 && kOverlapLanesV4 == 8, "the widths of OverlapKernels");
PW85_OVERLAP_VARIANT(portable, , 4)
#if PW85_ISA_LEVELS
PW85_OVERLAP_VARIANT(v3, PW85_TARGET_V3, 4)
PW85_OVERLAP_VARIANT(v4, PW85_TARGET_V4, 8)
#endif

}  // namespace

const OverlapKernels overlap_kernels[kVariantCount] = {
    kOverlap_portable, kOverlap_portable, PW85_IF_LEVELS(kOverlap_v3, kOverlap_portable),
    PW85_IF_LEVELS(kOverlap_v4, kOverlap_portable)};

}  // namespace pw85
