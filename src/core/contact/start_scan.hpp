// DEFAULT's start on x86-64-v4 (docs/methods.md, eq. (M24)), in place of the
// Newton iteration of (M22) on the coefficient step's path (default.hpp,
// coefficient_step). lambda* is the root of a1(x) = x^2 a2(x), x = lambda /
// (1 - lambda), with the quartics a_i of (M22) (start.hpp); in t = log x,
// y(t) = (a1 - x^2 a2) / (a1 + x^2 a2) = tanh((log a1 - log a2) / 2 - t)
// is positive below the root and negative above it. The root is located
//  1. on a coarse grid of 32 points, t = (k - 15.5) h, h = 3/4, covering
//     |t| <= 11.6 (|lambda - 1/2| < 0.5 - 1e-5), by the first grid point
//     where a1 - x^2 a2 is not positive;
//  2. on 16 points (step h / 15) from coarse point k - 1 to coarse point k
//     of that interval, the same way;
//  3. by linear interpolation of y in t between the two points that bracket
//     it (the error is second order in the step, docs/methods.md).
// Each grid is evaluated in AVX-512 vectors, a1 - x^2 a2 and a1 + x^2 a2
// as sextics (Estrin's scheme): no division, no branch per point, and a
// dependency chain of two polynomial evaluations instead of one Newton
// step after another; the two bracketing values are taken from the
// registers by permutes. A root outside the coarse grid returns -1
// (the caller then runs (M22)). The quartics are used unscaled (the scaling
// of (M22) protects its products of three a_i; here none is formed). Only
// the start depends on this; the coefficient step that follows certifies its
// own result.
#pragma once

#include "contact/start.hpp"

#if PW85_ISA_LEVELS

namespace pw85 {

namespace scan {

using lanes::Lanes8;
using lanes::LaneIndex8;

// The sextic sum_n c_n x^n, lane by lane (Estrin's scheme: four levels of
// FMA after x): at eight points x for one pair (the c_n broadcast,
// scan_start), or at one point x (broadcast) for one pair per lane
// (contact/default.hpp, coefficient_step_lanes), the same IEEE operations in each lane.
PW85_V4_INLINE Lanes8 sextic(Lanes8 const c[7], Lanes8 x) {
  using lanes::fma;
  Lanes8 const x2 = x * x, x4 = x2 * x2;
  Lanes8 const lo = fma(x2, fma(x, c[3], c[2]), fma(x, c[1], c[0]));
  Lanes8 const hi = fma(x2, c[6], fma(x, c[5], c[4]));
  return fma(x4, hi, lo);
}

PW85_V4_INLINE unsigned positive_mask(Lanes8 v) {
  return lanes::gt_bits(v, Lanes8{});
}

// Index of the first lane (0-15, or 0-31) whose value is not positive (16,
// or 32, when all are).
PW85_V4_INLINE unsigned first_nonpositive16(Lanes8 v0, Lanes8 v1) {
  unsigned const pos = positive_mask(v0) | (positive_mask(v1) << 8);
  return (unsigned)__builtin_ctz(~pos);  // ~pos has bit 16 and up set
}
PW85_V4_INLINE unsigned first_nonpositive(Lanes8 v0, Lanes8 v1, Lanes8 v2, Lanes8 v3) {
  unsigned long long const pos = (unsigned long long)(positive_mask(v0) | (positive_mask(v1) << 8) |
                                                      (positive_mask(v2) << 16) |
                                                      (positive_mask(v3) << 24));
  return (unsigned)__builtin_ctzll(~pos);  // ~pos has bit 32 and up set
}


}  // namespace scan

// The grids: x = exp((k - 15.5) h), k = 0..31, and the factors exp(l h / 15),
// l = 0..15, h = 3 / 4.
constexpr double kScanStep = 0.75;
alignas(64) constexpr double kScanCoarse[32] = {
    8.93977622368364048e-06, 1.89255064140518597e-05, 4.00652973929510687e-05,
    8.48182352464691553e-05, 1.79560205425832969e-04, 3.80128957869463682e-04,
    8.04733010124613246e-04, 1.70361979580257398e-03, 3.60656313601573049e-03,
    7.63509421885996166e-03, 1.61634945881658741e-02, 3.42181183116660320e-02,
    7.24397570342514563e-02, 1.53354966844928470e-01, 3.24652467358349739e-01,
    6.87289278790972236e-01, 1.45499141461820125e+00, 3.08021684891803105e+00,
    6.52081912033011246e+00, 1.38045741860670947e+01, 2.92242837812349414e+01,
    6.18678092503678840e+01, 1.30974153210818599e+02, 2.77272284523133976e+02,
    5.86985430941708842e+02, 1.24264816705499584e+03, 2.63068619029913589e+03,
    5.56916270856600386e+03, 1.17899175465529188e+04, 2.49592556419145949e+04,
    5.28387446085731863e+04, 1.11859623214142310e+05};
alignas(64) constexpr double kScanFine[16] = {
    1.00000000000000000e+00, 1.05127109637602412e+00, 1.10517091807564771e+00,
    1.16183424272828306e+00, 1.22140275816016985e+00, 1.28402541668774139e+00,
    1.34985880757600318e+00, 1.41906754859325712e+00, 1.49182469764127035e+00,
    1.56831218549016893e+00, 1.64872127070012819e+00, 1.73325301786739527e+00,
    1.82211880039050889e+00, 1.91554082901389622e+00, 2.01375270747047663e+00,
    2.11700001661267478e+00};

// The sextics a1 - x^2 a2 (pn) and a1 + x^2 a2 (pdn) from the quartics of
// (M22) (start.hpp, start_quartics<false>), for one pair (T = double) or one
// pair per lane.
template <class T, class Q>
PW85_ALWAYS_INLINE void scan_sextics(Q const &sq, T pn[7], T pdn[7]) noexcept {
  pn[0] = sq.a1[0];
  pn[1] = sq.a1[1];
  pn[2] = sq.a1[2] - sq.a2[0];
  pn[3] = sq.a1[3] - sq.a2[1];
  pn[4] = sq.a1[4] - sq.a2[2];
  pn[5] = -sq.a2[3];
  pn[6] = -sq.a2[4];
  pdn[0] = sq.a1[0];
  pdn[1] = sq.a1[1];
  pdn[2] = sq.a1[2] + sq.a2[0];
  pdn[3] = sq.a1[3] + sq.a2[1];
  pdn[4] = sq.a1[4] + sq.a2[2];
  pdn[5] = sq.a2[3];
  pdn[6] = sq.a2[4];
}

// Step 3: lambda from the values n1, n2 of a1 - x^2 a2 and e1, e2 of
// a1 + x^2 a2 at the fine points x1 and x1 exp(h / 15) that bracket the
// root (y = n / e). Linear interpolation in t: x = x1 exp(v), v = (h / 15)
// w, w = y1 / (y1 - y2) in [0, 1]; exp(v) by its [2/2] Pade form (relative
// error below v^5 / 720 < 5e-10), written in y1 and y1 - y2 so that lambda
// = x / (1 + x) takes one division. One pair (T = double) or one pair per
// lane.
template <class T>
PW85_ALWAYS_INLINE T scan_interpolate(T n1, T e1, T n2, T e2, T x1) noexcept {
  T const y1 = n1 / e1, y2 = n2 / e2;
  T const a = y1 * (kScanStep / 15.0), b = y1 - y2;
  T const b2 = 12.0 * (b * b), ab = 6.0 * (a * b), aa = a * a;
  T const en = (b2 + aa) + ab, ed = (b2 + aa) - ab;
  T const xn = x1 * en;
  return xn / (ed + xn);
}

// Returns lambda, or -1 when the root is outside the coarse grid (or the
// interpolated lambda is not in (0, 1)).
PW85_V4_INLINE double scan_start(
    Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept {
  StartQuartics sq;
  start_quartics<false>(r, q1, q2, sq);
  double pn_s[7], pdn_s[7];
  scan_sextics(sq, pn_s, pdn_s);
  scan::Lanes8 pn[7], pdn[7];
  for (int i = 0; i < 7; ++i) {
    pn[i] = lanes::broadcast(pn_s[i]);
    pdn[i] = lanes::broadcast(pdn_s[i]);
  }
  scan::Lanes8 c_num[4];
  for (int v = 0; v < 4; ++v) c_num[v] = scan::sextic(pn, lanes::load(kScanCoarse + 8 * v));
  unsigned const k = scan::first_nonpositive(c_num[0], c_num[1], c_num[2], c_num[3]);
  if (__builtin_expect(k == 0 || k == 32, 0)) return -1.0;
  double const xa = kScanCoarse[k - 1];
  scan::Lanes8 const xav = lanes::broadcast(xa);
  scan::Lanes8 f_num[2], f_den[2];
  for (int v = 0; v < 2; ++v) {
    scan::Lanes8 const x = xav * lanes::load(kScanFine + 8 * v);
    f_num[v] = scan::sextic(pn, x);
    f_den[v] = scan::sextic(pdn, x);
  }
  // Fine point 0 is the coarse point k - 1 (y > 0), point 15 the coarse
  // point k (y <= 0): the first non-positive j is in 1..15.
  unsigned j = scan::first_nonpositive16(f_num[0], f_num[1]);
  j = j < 1 ? 1 : (j > 15 ? 15 : j);  // (rounding at the shared points)
  scan::LaneIndex8 const i1 = lanes::broadcast_index(j - 1), i2 = lanes::broadcast_index(j);
  double const n1 = lanes::lane0(lanes::permute(f_num[0], i1, f_num[1]));
  double const e1 = lanes::lane0(lanes::permute(f_den[0], i1, f_den[1]));
  double const n2 = lanes::lane0(lanes::permute(f_num[0], i2, f_num[1]));
  double const e2 = lanes::lane0(lanes::permute(f_den[0], i2, f_den[1]));
  double const l = scan_interpolate(n1, e1, n2, e2, xa * kScanFine[j - 1]);
  return l > 0.0 && l < 1.0 ? l : -1.0;
}

}  // namespace pw85
#endif
