// The overlap predicate across pairs (docs/batch.md, "Throughput"): the
// screen of pw85_overlap's hot path and the first certificates of its
// filters, (O11), (O13) and (O18) at tau0 and tau1 (docs/overlap.md;
// overlap.cpp, filters_inline), for W pairs at once, pair l in lane l of
// each vector of W doubles (W = kOverlapLanesV4 = 8 in the x86-64-v4
// variant, one AVX-512 register; kOverlapLanes = 4 in the others). Every
// lane performs the operations of the one-pair code on its own pair only
// (no operation mixes lanes), and a lane is decided only by a certificate
// whose error bound (O3) holds lane by lane exactly as in the scalar code: a
// bounded value is the pair of vectors (fl(E), fl(P)) that overlap.cpp keeps
// in the two halves of one SSE2 register, with the same operations in the
// same order. Decided verdicts are therefore exact
// and equal to pw85_overlap's; the lanes that fail the screen (r = 0,
// non-finite, outside the safe range (O9), a non-positive pivot) or that
// these certificates leave open are returned undecided, for the caller's
// one-pair call.
//
// Compiled with GCC's default contraction, like overlap.cpp (src/meson.build):
// a fused a * b + c satisfies the standard model of (O3) with a zero
// product error, so the bounds hold in every variant.
#include <cstdint>

#include "common/fp.hpp"
#include "common/isa.hpp"
#include "common/lanes.hpp"
#include "common/spd.hpp"
#include "overlap/bounded_sym.hpp"
#include "overlap/overlap.hpp"

namespace pw85 {

namespace {

using namespace lanes;

constexpr double kC = kOverlapFilterC, kAbs = kOverlapFilterAbs;

// A bounded value (eq. (O3)): v = fl(E), b = fl(P), as lanes 0 and 1 of
// overlap.cpp's V2, W lanes each.
template <int W>
struct B {
  VecD<W> v, b;
};
template <int W>
PW85_ALWAYS_INLINE B<W> operator+(B<W> x, B<W> y) noexcept { return {x.v + y.v, x.b + y.b}; }
template <int W>
PW85_ALWAYS_INLINE B<W> operator-(B<W> x, B<W> y) noexcept { return {x.v - y.v, x.b - y.b}; }
template <int W>
PW85_ALWAYS_INLINE B<W> operator*(B<W> x, B<W> y) noexcept { return {x.v * y.v, x.b * y.b}; }
template <int W>
PW85_ALWAYS_INLINE B<W> operator*(double c, B<W> x) noexcept { return {c * x.v, c * x.b}; }
// Weight times bounded value (both halves of overlap.cpp's V2 {w, w}).
template <int W>
PW85_ALWAYS_INLINE B<W> operator*(VecD<W> w, B<W> x) noexcept { return {w * x.v, w * x.b}; }

template <int W>
PW85_ALWAYS_INLINE B<W> pos(VecD<W> x) noexcept { return {x, vabs(x)}; }
template <int W>
PW85_ALWAYS_INLINE B<W> flip(B<W> x) noexcept { return {x.v, -x.b}; }
template <int W>
PW85_ALWAYS_INLINE VecD<W> err(B<W> x) noexcept { return kC * x.b + kAbs; }

// The bounded matrix algebra of bounded_sym.hpp on B.
template <int W>
using SymB = bounded::Sym<B<W>>;
using bounded::det_adj;
using bounded::mixed_adj;
using bounded::outer;
using bounded::quad;
using bounded::trace_adj;

template <int W>
PW85_ALWAYS_INLINE SymB<W> bound(VecD<W> const q[kSym]) noexcept {
  SymB<W> b;
  for (int i = 0; i < kSym; ++i) {
    b.p[i] = pos<W>(q[i]);
    b.n[i] = flip(b.p[i]);
  }
  return b;
}

// The positive-definiteness certificate of spd.hpp (certain_spd) in every
// lane: the same operations, so the same decision as the one-pair screen.
template <int W>
PW85_ALWAYS_INLINE UMaskOf<VecD<W>> certain_spd_lanes(VecD<W> const x[kSym]) noexcept {
  VecD<W> d0, d1, d2;
  spd_shifted_pivots(x[0], x[1], x[2], x[3], x[4], x[5], d0, d1, d2);
  return gt(d0, 0.0) & gt(d1, 0.0) & gt(d2, 0.0) & le(d2, kMaxDouble);
}

// The certificate (O18) of overlap.cpp's subdivide at tau = wt / (ws + wt):
// pos_out lanes: p > 0 on [0, 1] (overlap); neg_out lanes: p(tau) <= -err
// (separation).
template <int W>
PW85_ALWAYS_INLINE void subdivide(B<W> const x[5], VecD<W> ws, VecD<W> wt,
                                  UMaskOf<VecD<W>> &pos_out, UMaskOf<VecD<W>> &neg_out) noexcept {
  typedef VecD<W> V;
  typedef UMaskOf<V> M;
  typedef B<W> Bw;
  V const sum = ws + wt;
  M const bits = reinterpret_cast<M>(sum);
  M const scale_bits = (M{} + (0x7fdLL << 52)) - (bits & 0x7ff0000000000000LL);
  V const scale = reinterpret_cast<V>(scale_bits);
  V const s = ws * scale, t = wt * scale;
  Bw const y0 = s * x[0] + t * x[1], y1 = s * x[1] + t * x[2], y2 = s * x[2] + t * x[3],
          y3 = s * x[3] + t * x[4];
  Bw const z0 = s * y0 + t * y1, z1 = s * y1 + t * y2, z2 = s * y2 + t * y3;
  Bw const u0 = s * z0 + t * z1, u1 = s * z1 + t * z2;
  Bw const pt = s * u0 + t * u1;
  pos_out = gt(y0.v, err(y0)) & gt(z0.v, err(z0)) & gt(u0.v, err(u0)) & gt(pt.v, err(pt)) &
            gt(u1.v, err(u1)) & gt(z2.v, err(z2)) & gt(y3.v, err(y3));
  neg_out = le(pt.v, -err(pt));
}

// n^T q n, q as sym3.hpp's multiply and dot compute it.
template <int W>
PW85_ALWAYS_INLINE VecD<W> quad_form(VecD<W> const q[kSym], VecD<W> const n[kDim]) noexcept {
  typedef VecD<W> V;
  V const y0 = q[0] * n[0] + q[1] * n[1] + q[2] * n[2];
  V const y1 = q[1] * n[0] + q[3] * n[1] + q[4] * n[2];
  V const y2 = q[2] * n[0] + q[4] * n[1] + q[5] * n[2];
  return n[0] * y0 + n[1] * y1 + n[2] * y2;
}

// The body, compiled once per width and instruction-set level below.
template <int W>
PW85_ALWAYS_INLINE void lanes_body(double const *const rp[W], double const *const q1p[W],
                                   double const *const q2p[W], int verdict[W]) noexcept {
  typedef VecD<W> V;
  typedef UMaskOf<V> M;  // the masks of the comparisons of lanes.hpp
  typedef B<W> Bw;
  V r[kDim], a[kSym], b[kSym];
  gather<kDim, W>(rp, r);
  gather<kSym, W>(q1p, a);
  gather<kSym, W>(q2p, b);
  // --- Screen (screen.hpp, screen_overlap_pair), and r != 0. ---
  V qm = vabs(a[0]);
  for (int i = 1; i < kSym; ++i) qm = vmax(qm, vabs(a[i]));
  for (int i = 0; i < kSym; ++i) qm = vmax(qm, vabs(b[i]));
  M const screened = le(vabs(r[0]), kOverlapRangeHi) & le(vabs(r[1]), kOverlapRangeHi) &
                     le(vabs(r[2]), kOverlapRangeHi) & ge(qm, kOverlapRangeLo) &
                     le(qm, kOverlapRangeHi) & certain_spd_lanes<W>(a) & certain_spd_lanes<W>(b) &
                     (ne(r[0], 0.0) | ne(r[1], 0.0) | ne(r[2], 0.0));
  // --- filters_inline: separating plane orthogonal to r (O11). ---
  Bw const rb[kDim] = {pos<W>(r[0]), pos<W>(r[1]), pos<W>(r[2])};
  Bw rr[kSym];
  outer(rb, rr);
  SymB<W> const b1q = bound<W>(a), b2q = bound<W>(b);
  Bw const a1 = quad(b1q.p, rr), a2 = quad(b2q.p, rr);
  V const A1 = a1.v + err(a1), A2 = a2.v + err(a2);
  V const rdr = rr[0].v + rr[1].v + rr[2].v;
  V const d = (rdr * rdr) * (1.0 - 16 * kU) - (A1 + A2) * (1.0 + 16 * kU);
  M const plane =
      gt(d, 0.0) & ge((d * d) * (1.0 - 16 * kU), (4.0 * (A1 * A2)) * (1.0 + 16 * kU) + 0x1p-1000);
  V const h1 = vsqrt(A1), h2 = vsqrt(A2);
  // --- Coefficients of p (O10), then (O13) and (O18) at tau0. ---
  Bw m1[kSym], m2[kSym], mm[kSym];
  Bw const det1 = det_adj(b1q, m1), det2 = det_adj(b2q, m2);
  Bw const c0 = quad(m1, rr), c2 = quad(m2, rr);
  Bw const t1 = trace_adj(m1, b2q), t2 = trace_adj(m2, b1q);
  mixed_adj(b1q, b2q, mm);
  Bw const c1 = quad(mm, rr);
  Bw const p1 = (det1 + t1) - flip(c0), p2 = (t1 + t2) - flip(c1), p3 = (t2 + det2) - flip(c2);
  Bw const x[5] = {6.0 * det1, 1.5 * p1, p2, 1.5 * p3, 6.0 * det2};
  M const o13 = gt(x[0].v, err(x[0])) & gt(x[1].v, err(x[1])) & gt(x[2].v, err(x[2])) &
                gt(x[3].v, err(x[3])) & gt(x[4].v, err(x[4]));
  M sub_pos, sub_neg;
  subdivide<W>(x, h2, h1, sub_pos, sub_neg);
  // Verdicts in the order of filters_inline: the plane (0), then (O13) or
  // (O18) all positive (1), then (O18) negative (0).
  M one = screened & ~plane & (o13 | sub_pos);
  M zero = screened & (plane | (~o13 & ~sub_pos & sub_neg));
  M const open = screened & ~one & ~zero;
  if (any(open)) {
    // (O18) at tau1 = g1 / (g1 + g2), g_k^2 = n^T Q_k n, n = adj(Q1 + Q2) r
    // = (adj Q1 + M + adj Q2) r, as filters_inline (not certified: any tau
    // gives a valid certificate), for the lanes still open.
    V adj[kSym];
    for (int i = 0; i < kSym; ++i) adj[i] = (m1[i].v + mm[i].v) + m2[i].v;
    V const n[kDim] = {adj[0] * r[0] + adj[1] * r[1] + adj[2] * r[2],
                       adj[1] * r[0] + adj[3] * r[1] + adj[4] * r[2],
                       adj[2] * r[0] + adj[4] * r[1] + adj[5] * r[2]};
    V const g1 = vsqrt(quad_form<W>(a, n)), g2 = vsqrt(quad_form<W>(b, n));
    subdivide<W>(x, g2, g1, sub_pos, sub_neg);
    one |= open & sub_pos;
    zero |= open & ~sub_pos & sub_neg;
  }
  typedef MaskOf<V> S;
  S const v = -1 - 2 * reinterpret_cast<S>(one) - reinterpret_cast<S>(zero);  // 1, 0 or -1
  for (int l = 0; l < W; ++l) verdict[l] = static_cast<int>(v[l]);
}

#if PW85_ISA_LEVELS
PW85_TARGET_V4 void lanes_v4(double const *const rp[kOverlapLanesV4],
                             double const *const q1p[kOverlapLanesV4],
                             double const *const q2p[kOverlapLanesV4],
                             int verdict[kOverlapLanesV4]) noexcept {
  lanes_body<kOverlapLanesV4>(rp, q1p, q2p, verdict);
}
PW85_TARGET_V3 void lanes_v3(double const *const rp[kOverlapLanes],
                             double const *const q1p[kOverlapLanes],
                             double const *const q2p[kOverlapLanes],
                             int verdict[kOverlapLanes]) noexcept {
  lanes_body<kOverlapLanes>(rp, q1p, q2p, verdict);
}
#endif

}  // namespace

int overlap_lanes_width() noexcept {
#if PW85_ISA_LEVELS
  if (isa::has_v4()) return kOverlapLanesV4;
#endif
  return kOverlapLanes;
}

// Each width runs on every CPU: kOverlapLanesV4 lanes in the x86-64-v4
// variant, else as blocks of kOverlapLanes; kOverlapLanes lanes in the
// x86-64-v3 variant, else in the portable body.
template <int W>
void overlap_lanes(double const *const r[W], double const *const q1[W], double const *const q2[W],
                   int verdict[W]) noexcept {
  static_assert(W == kOverlapLanes || W == kOverlapLanesV4, "the widths of overlap.hpp");
  if constexpr (W == kOverlapLanesV4) {
#if PW85_ISA_LEVELS
    if (isa::has_v4()) return lanes_v4(r, q1, q2, verdict);
#endif
    for (int l = 0; l < W; l += kOverlapLanes)
      overlap_lanes<kOverlapLanes>(r + l, q1 + l, q2 + l, verdict + l);
  } else {
#if PW85_ISA_LEVELS
    if (isa::has_v3()) return lanes_v3(r, q1, q2, verdict);
#endif
    lanes_body<W>(r, q1, q2, verdict);
  }
}

template void overlap_lanes<kOverlapLanes>(double const *const[kOverlapLanes],
                                           double const *const[kOverlapLanes],
                                           double const *const[kOverlapLanes],
                                           int[kOverlapLanes]) noexcept;
template void overlap_lanes<kOverlapLanesV4>(double const *const[kOverlapLanesV4],
                                             double const *const[kOverlapLanesV4],
                                             double const *const[kOverlapLanesV4],
                                             int[kOverlapLanesV4]) noexcept;

}  // namespace pw85
