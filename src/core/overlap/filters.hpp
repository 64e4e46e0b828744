// The first certificates of the overlap filters (docs/overlap.md): the
// separating plane orthogonal to r (O11), the coefficients of p (O10), the
// coefficients positive (O13), and the subdivision certificate (O18) at
// tau0 and tau1; written once, generic over the lane type Lane: a double
// for one pair (pw85_overlap, whose filters go on in overlap.cpp,
// filters_slow, for the pairs these leave open), a vector of W doubles of
// common/lanes.hpp for W pairs, pair l in lane l (overlap_lanes; no
// operation mixes lanes). A lane is decided only by a certificate whose
// error bound (O3) holds lane by lane, so the verdicts are exact and the
// same for one pair and for W pairs.
//
// The files that include it are compiled with GCC's default contraction
// (src/meson.build): a fused a * b + c satisfies the standard model of (O3)
// with a zero product error, so the bounds hold in every instruction-set
// variant.
//
// Notation (after an exact power-of-two scaling): E1 = {x : x^T Q1^{-1} x <= 1},
// E2 = {x : (x - r)^T Q2^{-1} (x - r) <= 1}, Q(l) = (1 - l) Q1 + l Q2,
// f(l) = l (1 - l) r^T Q(l)^{-1} r, mu^2 = max f (pw85 documentation,
// chapter 3, eqs. (6), (10), (11)).
#pragma once

#include <cstdint>
#include <cstring>

#include "common/fp.hpp"
#include "common/isa.hpp"
#include "common/lanes.hpp"
#include "common/sym3.hpp"
#include "overlap/bounded.hpp"
#include "overlap/overlap.hpp"

namespace pw85 {
namespace overlap_filters {

using bounded::Bounded;
using bounded::bound_sym;
using bounded::det_adj;
using bounded::err;
using bounded::flip;
using bounded::mixed_adj;
using bounded::outer;
using bounded::pos;
using bounded::quad;
using bounded::Sym;
using bounded::trace_adj;
using bounded::value;
using lanes::and_not;
using lanes::ge;
using lanes::gt;
using lanes::le;

// Decided verdict (0 or 1) or kUndecided.
constexpr int kUndecided = -1;

// The mask of the comparisons of Lane: bool for one pair, a vector of
// lane masks for W pairs.
template <class Lane>
using Mask = decltype(lanes::gt(Lane{}, Lane{}));

// For one pair, makes the mask opaque to the optimiser (isa.hpp): a combined
// condition is then tested by one branch instead of one branch per
// comparison, and the code it depends on is not sunk into a branch on one
// of its parts (the branches of the filters are unpredictable:
// docs/overlap.md). Nothing for W pairs, whose masks are not branched on.
PW85_ALWAYS_INLINE void one_branch(bool &m) noexcept { opaque(m); }
template <class LaneMask>
PW85_ALWAYS_INLINE void one_branch(LaneMask &) noexcept {}

// The bounded quantities of eq. (O10) that the later certificates reuse:
// det Q_k and adj Q_k (m1, m2), c0 = r^T adj Q1 r, c1 = r^T M r,
// c2 = r^T adj Q2 r, b1 = tr(adj(Q1) Q2), b2 = tr(adj(Q2) Q1), and the
// inner coefficients P1, P2, P3 of p in the basis s^(4-j) t^j.
template <class Lane>
struct Coefs {
  Bounded<Lane> det1, det2, m1[kSym], m2[kSym], mm[kSym], c0, c1, c2, b1, b2, p1, p2, p3;
};

// Coefficients of p in the basis s^(4-j) t^j, s = 1 - l, t = l (eq. (O10)):
// P0 = b0 = det Q1, P1 = b0 + b1 - c0, P2 = b1 + b2 - c1, P3 = b2 + b3 - c2,
// P4 = b3 = det Q2, with M (mm) the mixed adjugate.
template <class Lane>
PW85_ALWAYS_INLINE void coefficients(Bounded<Lane> const rr[kSym], Sym<Bounded<Lane>> const &b1q,
                                     Sym<Bounded<Lane>> const &b2q, Coefs<Lane> &c) noexcept {
  c.det1 = det_adj(b1q, c.m1);
  c.det2 = det_adj(b2q, c.m2);
  c.c0 = quad(c.m1, rr);
  c.c2 = quad(c.m2, rr);
  c.b1 = trace_adj(c.m1, b2q);
  c.b2 = trace_adj(c.m2, b1q);
  mixed_adj(b1q, b2q, c.mm);
  c.c1 = quad(c.mm, rr);
  c.p1 = (c.det1 + c.b1) - flip(c.c0);
  c.p2 = (c.b1 + c.b2) - flip(c.c1);
  c.p3 = (c.b2 + c.det2) - flip(c.c2);
}

// The power of two 2^-e that brings sum into [0.5, 1), from the exponent
// bits (exact, no libm call): with E the biased exponent of sum,
// 2^-(E - 1022) has biased exponent 2045 - E (normal for 1 <= E <= 2044;
// sum = 0 or subnormal (E = 0): 2^1022 times a value below 2^-1022, still
// < 1).
PW85_ALWAYS_INLINE double binade_scale(double sum) noexcept {
  std::uint64_t bits;
  std::memcpy(&bits, &sum, sizeof bits);
  std::uint64_t const scale_bits = (std::uint64_t{2045} << 52) - (bits & 0x7ff0000000000000u);
  double scale;
  std::memcpy(&scale, &scale_bits, sizeof scale);
  return scale;
}
template <class Lane>
PW85_ALWAYS_INLINE Lane binade_scale(Lane sum) noexcept {
  using Bits = lanes::UMaskOf<Lane>;
  Bits const bits = reinterpret_cast<Bits>(sum);
  Bits const scale_bits = (Bits{} + (2045ULL << 52)) - (bits & 0x7ff0000000000000ULL);
  return reinterpret_cast<Lane>(scale_bits);
}

// The certificate (O18): the Bernstein coefficients x[0..4] of p (scaled
// by 6 so that binom(4, j) divides exactly: 6 P0, 1.5 P1, P2, 1.5 P3, 6 P4)
// subdivided at tau = wt / (ws + wt) by de Casteljau's algorithm in
// homogeneous form (weights ws, wt >= 0 instead of 1 - tau, tau: the results
// are the coefficients on [0, tau] and [tau, 1] times powers of ws + wt > 0,
// same signs, and no division). positive: all of them > err, so p > 0 on
// [0, 1], overlap (1). negative: the one they share, (ws + wt)^4 6 p(tau),
// is <= -err, so f(tau) >= 1, separation (0). Neither: undecided.
// The weights are first scaled by binade_scale(ws + wt) (exact), so that no
// product overflows and an underflow error is never amplified: every value
// of the algorithm is then a combination of the x[j] with nonnegative
// weights summing to less than 1, which keeps the absolute term kAbs of
// (O3) valid. ws and wt must be >= 0 with ws + wt < 2^1000 (here they are
// below 2^220, eq. (O9)); a NaN makes every test false.
template <class Lane>
PW85_ALWAYS_INLINE void subdivide(Bounded<Lane> const x[5], Lane ws, Lane wt, Mask<Lane> &positive,
                                  Mask<Lane> &negative) noexcept {
  using Value = Bounded<Lane>;
  Lane const scale = binade_scale(ws + wt);
  Lane const s = ws * scale, t = wt * scale;
  Value const y0 = s * x[0] + t * x[1], y1 = s * x[1] + t * x[2], y2 = s * x[2] + t * x[3],
              y3 = s * x[3] + t * x[4];
  Value const z0 = s * y0 + t * y1, z1 = s * y1 + t * y2, z2 = s * y2 + t * y3;
  Value const u0 = s * z0 + t * z1, u1 = s * z1 + t * z2;
  Value const pt = s * u0 + t * u1;
  positive = gt(value(y0), err(y0)) & gt(value(z0), err(z0)) & gt(value(u0), err(u0)) &
             gt(value(pt), err(pt)) & gt(value(u1), err(u1)) & gt(value(z2), err(z2)) &
             gt(value(y3), err(y3));
  negative = le(value(pt), -err(pt));
}

// n^T q n, as sym3.hpp's dot(n, multiply(q, n)) computes it.
template <class Lane>
PW85_ALWAYS_INLINE Lane quad_form(Lane const q[kSym], Lane const n[kDim]) noexcept {
  Lane const y0 = q[0] * n[0] + q[1] * n[1] + q[2] * n[2];
  Lane const y1 = q[1] * n[0] + q[3] * n[1] + q[4] * n[2];
  Lane const y2 = q[2] * n[0] + q[4] * n[1] + q[5] * n[2];
  return n[0] * y0 + n[1] * y1 + n[2] * y2;
}

// What the first certificates decided, lane by lane: one (overlap), zero
// (separation; plane: by the plane (O11)), open (neither; the lanes not
// screened included), and the weights
// of the subdivision points tau0 = h1 / (h1 + h2) and tau1 = g1 / (g1 + g2)
// (g = h when tau1 was not tried), where the one-pair filters start their
// next stage.
template <class Lane>
struct FirstDecision {
  Mask<Lane> one, zero, plane, open;
  Lane h1, h2, g1, g2;
};

// Whether the plane (O11) decided every lane still open: for one pair, the
// branch that skips the rest; for W pairs never taken (the plane seldom
// decides every lane of a block, and the test would cost every block).
PW85_ALWAYS_INLINE bool plane_settles_all(bool open) noexcept { return !open; }
template <class LaneMask>
PW85_ALWAYS_INLINE bool plane_settles_all(LaneMask) noexcept { return false; }

// The first certificates for the lanes of screened (the others are left
// open): r, q1, q2 in the safe range (eq. (O9)): |Q_ij| <= 2^60,
// |r_i| <= 2^60, r != 0, Q1 and Q2 positive definite.
template <class Lane>
PW85_ALWAYS_INLINE FirstDecision<Lane> first_certificates(Lane const r[kDim], Lane const q1[kSym],
                                                          Lane const q2[kSym],
                                                          Mask<Lane> screened) noexcept {
  using Value = Bounded<Lane>;
  FirstDecision<Lane> out;
  Value const rb[kDim] = {pos(r[0]), pos(r[1]), pos(r[2])};
  Value rr[kSym];
  outer(rb, rr);
  Sym<Value> const b1q = bound_sym(q1), b2q = bound_sym(q2);
  // --- Separating plane orthogonal to r (eq. (O11)). ---
  // h_k^2 = r^T Q_k r: E1 lies in {x : r.x <= h1}, E2 in {x : r.x >= r.r - h2}.
  Value const a1 = quad(b1q.p, rr), a2 = quad(b2q.p, rr);
  // Tested squared, without square roots (shorter latency to the branch):
  // R = r.r >= sqrt(A1) + sqrt(A2) iff D = R^2 - A1 - A2 >= 0 and
  // D^2 >= 4 A1 A2, with A_k >= h_k^2 and margins for every rounding.
  Lane const A1 = value(a1) + err(a1), A2 = value(a2) + err(a2);
  Lane const rdr = value(rr[0]) + value(rr[1]) + value(rr[2]);
  Lane const d = (rdr * rdr) * (1.0 - 16 * kU) - (A1 + A2) * (1.0 + 16 * kU);
  out.plane = screened & gt(d, 0.0) &
              ge((d * d) * (1.0 - 16 * kU), (4.0 * (A1 * A2)) * (1.0 + 16 * kU) + 0x1p-1000);
  one_branch(out.plane);
  Mask<Lane> const open = and_not(screened, out.plane);
  out.one = Mask<Lane>{};
  out.zero = out.plane;
  out.open = open;
  out.h1 = out.h2 = out.g1 = out.g2 = Lane{};
  if (plane_settles_all(open)) return out;
  Lane const h1 = lanes::vsqrt(A1), h2 = lanes::vsqrt(A2);
  out.h1 = out.g1 = h1;
  out.h2 = out.g2 = h2;
  // --- Coefficients of p (eq. (O10)). ---
  Coefs<Lane> c;
  coefficients<Lane>(rr, b1q, b2q, c);
  Value const x[5] = {6.0 * c.det1, 1.5 * c.p1, c.p2, 1.5 * c.p3, 6.0 * c.det2};
  // (O13): the coefficients themselves positive (also covers the pairs
  // whose weights below underflow, e.g. |r| tiny); and (O18) at tau0 (the
  // start (M7) of docs/methods.md, with the support values of the plane
  // test). Both are computed, and one branch tests whether either decided:
  // a branch on (O13) alone is often mispredicted, and a mispredicted
  // branch costs more than (O18) (docs/overlap.md).
  Mask<Lane> const o13 = gt(value(x[0]), err(x[0])) & gt(value(x[1]), err(x[1])) &
                         gt(value(x[2]), err(x[2])) & gt(value(x[3]), err(x[3])) &
                         gt(value(x[4]), err(x[4]));
  Mask<Lane> positive, negative;
  subdivide<Lane>(x, h2, h1, positive, negative);
  one_branch(positive);
  one_branch(negative);
  out.one = open & (o13 | positive);
  out.zero = out.plane | and_not(and_not(open & negative, o13), positive);
  Mask<Lane> still_open = and_not(open, o13 | positive | negative);
  one_branch(still_open);
  out.open = still_open;
  if (!lanes::any(still_open)) return out;
  // --- (O18) at tau1: one step of the map (M19) of docs/methods.md from
  // l = 1/2, tau1 = g1 / (g1 + g2), g_k^2 = n^T Q_k n along
  // n = adj(Q1 + Q2) r = (adj Q1 + M + adj Q2) r (the normal of the contact
  // for l = 1/2). Not certified: any tau gives a valid certificate. ---
  Lane adj[kSym];
  for (int i = 0; i < kSym; ++i) adj[i] = (value(c.m1[i]) + value(c.mm[i])) + value(c.m2[i]);
  Lane const n[kDim] = {adj[0] * r[0] + adj[1] * r[1] + adj[2] * r[2],
                        adj[1] * r[0] + adj[3] * r[1] + adj[4] * r[2],
                        adj[2] * r[0] + adj[4] * r[1] + adj[5] * r[2]};
  Lane const g1 = lanes::vsqrt(quad_form(q1, n)), g2 = lanes::vsqrt(quad_form(q2, n));
  out.g1 = g1;
  out.g2 = g2;
  subdivide<Lane>(x, g2, g1, positive, negative);
  out.one = out.one | (still_open & positive);
  out.zero = out.zero | and_not(still_open & negative, positive);
  out.open = and_not(still_open, positive | negative);
  return out;
}

// Rounds l in [0, 1] to the grid 2^-52 Z (exact: (l + 1) - 1).
PW85_ALWAYS_INLINE double to_grid(double l) noexcept { return (l + 1.0) - 1.0; }

// The filters' later stages (overlap.cpp): the pairs the first certificates
// leave open, from l in (0, 1) on the grid 2^-52 Z.
int filters_slow(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, double l, int &stage) noexcept;

// The floating-point filters for one pair on inputs in the safe range
// (eq. (O9)): |Q_ij| <= 2^60, |r_i| <= 2^60, r != 0. Returns 0, 1 or
// kUndecided, and the deciding stage.
PW85_ALWAYS_INLINE int filters_inline(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                                      int &stage) noexcept {
  FirstDecision<double> const d = first_certificates<double>(r.x, q1.a, q2.a, true);
  if (d.plane) {
    stage = kStageSpheres;
    return 0;
  }
  if (!d.open) {
    stage = kStageFilter;
    return d.one;
  }
  double l = to_grid(d.g1 / (d.g1 + d.g2));
  if (!(l > 0.0 && l < 1.0)) l = to_grid(d.h1 / (d.h1 + d.h2));
  if (!(l > 0.0 && l < 1.0)) l = 0.5;
  return filters_slow(r, q1, q2, l, stage);
}

}  // namespace overlap_filters
}  // namespace pw85
