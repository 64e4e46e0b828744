// PW85_METHOD_DEFAULT across pairs on x86-64-v4 (docs/batch.md,
// "Throughput"): the rational step of contact_default_v4 (default.cpp,
// rational_v4) for eight pairs at once, pair l in lane l of each vector:
// the screen of the entry (screen.hpp, screen_contact_lanes), the seven
// coefficients (M12)-(M13) in double-double (f_rational_dd.hpp: rdd::terms
// per adjugate entry, then the sums over the entries; det_precise for d0,
// d3 in lanes where their bound fails), the grid start (M24)
// (start_scan.hpp: the quartics of (M22) by start_lanes.hpp, the coarse and
// fine grids, scan_interpolate; (M22) itself, start.hpp, for a lane whose
// root is off the grid), and the Halley iteration (M8) on f_eval_rational
// with rational_decide (rational_step.hpp) until the quartic model (M18) is
// accepted. Every lane performs the IEEE operations of the one-pair code in
// the same order (this file is compiled without contraction,
// src/meson.build), so a lane carries the bits of
// pw85_contact_function_method. A lane whose rational step declines runs
// the general method alone (contact_default_general_v4), as the one-pair
// call does after that step; a lane that fails the screen, or whose result
// breaks the promise that methods.cpp checks after every method, is
// returned undecided for the caller's one-pair call.
#include "common/fp.hpp"
#include "common/isa.hpp"
#include "common/lanes.hpp"
#include "common/screen.hpp"
#include "contact/contact.hpp"
#include "contact/default_params.hpp"
#include "contact/rational_step.hpp"
#include "contact/start.hpp"
#include "contact/start_lanes.hpp"
#include "contact/start_scan.hpp"
#include "eval/f_rational_dd.hpp"

namespace pw85 {
#if PW85_ISA_LEVELS
namespace {

using namespace lanes;
constexpr int W = kDefaultLanes;
static_assert(W == 8, "one pair per lane of an __m512d");
typedef VecD<W> V8;
typedef MaskD<W> M8;

PW85_V4_INLINE V8 bc(double x) noexcept { return V8{} + x; }

PW85_V4_INLINE M8 from_bits(__mmask8 k) noexcept {
  return reinterpret_cast<M8>(_mm512_movm_epi64(k));
}

PW85_V4_INLINE __mmask8 to_bits(M8 m) noexcept {
  return _mm512_movepi64_mask(reinterpret_cast<__m512i>(m));
}

// The coefficients of rational_coefficients_dd (f_rational_dd.hpp), one
// pair per lane.
struct CoefL {
  V8 c[8];
};

// The permutations of rational_coefficients_dd (ip, iq, is, it), and the
// factors of w_k r_i r_j, per adjugate entry k (storage order 00 01 02 11
// 12 22).
constexpr int kIp[kSym] = {3, 2, 1, 0, 1, 0}, kIq[kSym] = {5, 4, 4, 5, 2, 3};
constexpr int kIs[kSym] = {4, 1, 2, 2, 0, 1}, kIt[kSym] = {4, 5, 3, 2, 4, 1};
constexpr int kRi[kSym] = {0, 0, 0, 1, 1, 2}, kRj[kSym] = {0, 1, 2, 1, 2, 2};
constexpr double kW[kSym] = {1.0, 2.0, 2.0, 1.0, 2.0, 1.0};

// The terms (rdd::terms) of adjugate entries k and k + 1, added: round 1 of
// the tree.
PW85_V4_INLINE void pair_sum(Vec3L<W> const &r, SymL<W> const &a, SymL<W> const &b, int k,
                             rdd::DD v[7], __m512d m[7]) noexcept {
  using namespace rdd;
  Terms t[2];
  for (int i = 0; i < 2; ++i) {
    int const e = k + i;
    V8 const we = bc(kW[e]);
    terms(a[kIp[e]], a[kIq[e]], a[kIs[e]], a[kIt[e]], b[kIp[e]], b[kIq[e]], b[kIs[e]],
          b[kIt[e]], a[e] * we, b[e] * we, r[kRi[e]] * we, r[kRj[e]], t[i]);
  }
  for (int j = 0; j < 7; ++j) {
    v[j] = add(t[0].v[j], t[1].v[j]);
    m[j] = t[0].m[j] + t[1].m[j];
  }
}

// rational_coefficients_dd for the eight pairs: lane k of its vectors
// (entry k) is the vector of entry k here, and its three rounds of
// transposed sums become, per coefficient, the same sums in the same tree,
// ((0 + 1) + (2 + 3)) + ((4 + 5) + (6 + 7)), but for the last term: entries
// 6 and 7 are its padding, +0 in both parts, and adding that +0 pair
// changes nothing but the sign of a zero part; a nonzero sum is the same
// bits without it, and a zero sum fails the test (sum > 0) in both.
// Returns the lanes where every coefficient passes its test.
PW85_V4_INLINE M8 coefficients(Vec3L<W> const &r, SymL<W> const &a, SymL<W> const &b,
                              CoefL &out) noexcept {
  using namespace rdd;
  // Rounds 2 and 3, entry pair by entry pair.
  DD s0123[7], v[7];
  __m512d m0123[7], m[7];
  pair_sum(r, a, b, 0, s0123, m0123);
  pair_sum(r, a, b, 2, v, m);
  for (int j = 0; j < 7; ++j) {
    s0123[j] = add(s0123[j], v[j]);
    m0123[j] = m0123[j] + m[j];
  }
  pair_sum(r, a, b, 4, v, m);
  // The scale, as in rational_coefficients_dd.
  V8 const tr = ((a[0] + a[3]) + a[5]) + ((b[0] + b[3]) + b[5]);
  M8 const bits = reinterpret_cast<M8>(tr);
  M8 const e = ((bits >> 52) & 0x7FF) - 1023;
  V8 const scale = reinterpret_cast<V8>((1023 - 3 * e) << 52);
  __mmask8 ok = 0xFF, okd[2] = {0xFF, 0xFF};
  for (int j = 0; j < 7; ++j) {
    double const third = j == 3 || j == 6 ? kThird : 1.0;
    __mmask8 okj;
    out.c[j] = finish(add(s0123[j], v[j]), m0123[j] + m[j], bc(third) * scale, okj);
    if (j == 3 || j == 6)
      okd[j == 6] = okj;
    else
      ok &= okj;
  }
  // d0 and d3 where their bound fails: det_precise, as in
  // rational_dets_precise (all eight lanes, when one needs it).
  SymL<W> const *const qs[2] = {&a, &b};
  for (int mat = 0; mat < 2; ++mat) {
    if (okd[mat] != 0xFF) {
      __m512d q[kSym], det;
      for (int i = 0; i < kSym; ++i) q[i] = (*qs[mat])[i];
      __mmask8 const take = static_cast<__mmask8>(~okd[mat]) & to_bits(det_precise(q, det));
      int const j = mat == 0 ? 3 : 6;
      out.c[j] = _mm512_mask_blend_pd(take, out.c[j], det * scale);
      okd[mat] |= take;
    }
    ok &= okd[mat];
  }
  return from_bits(ok);
}

// scan_start (start_scan.hpp) for the eight pairs; (M22) (start.hpp) in the
// lanes of want where it returns -1.
PW85_V4_INLINE V8 grid_start(Vec3L<W> const &r, SymL<W> const &q1, SymL<W> const &q2, M8 want,
                            double const *const rp[W], double const *const q1p[W],
                            double const *const q2p[W]) noexcept {
  using namespace default_params;
  StartQuarticsOf<VecD<W>> sq;
  start_quartics<false>(r, q1, q2, sq);
  V8 pn[7], pdn[7];
  scan_sextics(sq, pn, pdn);
  // Coarse grid: k = the first point where a1 - x^2 a2 is not positive;
  // xa = point k - 1 (k = 0, or none: off the grid). Lanes outside want
  // count as found from the start (their values are not used).
  __mmask8 const wanted = to_bits(want);
  __mmask8 found = static_cast<__mmask8>(~wanted), first = 0;
  V8 xa{};
  // The points in groups of kCoarseGroup, evaluated before their masks
  // are taken in order (a lane found at a point ignores the later ones, so
  // k and xa are those of the point-by-point scan). Groups of 4 against one
  // point per test of found: 2.2 / 3.7 / 3.9 / 1.3 % less time per pair in
  // classes 0-3; groups of 2: 0-0.8 %; of 8: 3-5 % more, of 16: 4-6 % more
  // (pw85_contact_function_pairs over the one-pair loop, medians of 6 runs
  // alternating the builds, build/bench/bench_batch --n 100000 --reps 5).
  constexpr int kCoarseGroup = 4;
  static_assert(32 % kCoarseGroup == 0, "whole groups");
  for (int i0 = 0; i0 < 32 && found != 0xFF; i0 += kCoarseGroup) {
    unsigned pos[kCoarseGroup];
    for (int u = 0; u < kCoarseGroup; ++u)
      pos[u] = scan::positive_mask(scan::sextic(pn, bc(kScanCoarse[i0 + u])));
    for (int u = 0; u < kCoarseGroup; ++u) {
      int const i = i0 + u;
      __mmask8 const nonpos = static_cast<__mmask8>(~pos[u] & ~found);
      if (i == 0)
        first = nonpos;
      else
        xa = _mm512_mask_blend_pd(nonpos, xa, bc(kScanCoarse[i - 1]));
      found |= nonpos;
    }
  }
  __mmask8 const on_grid = found & wanted & static_cast<__mmask8>(~first);
  // Fine grid: x_j = xa exp(j h / 15); the first non-positive j, clamped
  // to 1..15 (none: 15), per lane in jv. Point j = 0 is not evaluated: x_0
  // = xa * 1 is the coarse point k - 1, whose value, the same operations
  // on the same x, was positive. Then x1 = x_(j-1), x2 = x_j and n1, n2
  // there, the same products and the same sextic as at the grid points.
  // Against carrying n1, n2, x1, x2 through the loop by four blends per
  // point and evaluating points 0 and 15: 1.8 / 2.6 / 2.6 / 1.7 % less time
  // per pair in classes 0-3 (pw85_contact_function_pairs over the one-pair
  // loop, medians of 7 runs alternating the builds,
  // build/bench/bench_batch --n 100000 --reps 5).
  __m512i jv = _mm512_set1_epi64(15);
  found = static_cast<__mmask8>(~on_grid);
  for (int j = 1; j < 15 && found != 0xFF; ++j) {
    __mmask8 const nonpos = static_cast<__mmask8>(
        ~scan::positive_mask(scan::sextic(pn, xa * bc(kScanFine[j]))) & ~found);
    found |= nonpos;
    jv = _mm512_mask_blend_epi64(nonpos, jv, _mm512_set1_epi64(j));
  }
  __m512d const f0 = _mm512_load_pd(kScanFine), f1 = _mm512_load_pd(kScanFine + 8);
  V8 const x1v = xa * V8(_mm512_permutex2var_pd(f0, jv - _mm512_set1_epi64(1), f1));
  V8 const x2v = xa * V8(_mm512_permutex2var_pd(f0, jv, f1));
  V8 const n1 = scan::sextic(pn, x1v), n2 = scan::sextic(pn, x2v);
  V8 const e1 = scan::sextic(pdn, x1v), e2 = scan::sextic(pdn, x2v);
  V8 const lam = scan_interpolate(n1, e1, n2, e2, x1v);
  M8 const ok = from_bits(on_grid) & (lam > 0.0) & (lam < 1.0);
  M8 const m22 = want & ~ok;
  if (!any(m22)) return lam;
  V8 out = lam;
  for (int l = 0; l < W; ++l)
    if (m22[l] != 0)
      out[l] = log_newton_start<kStartMin, kStartMax>(view_vec3(rp[l]), view_sym3(q1p[l]),
                                                      view_sym3(q2p[l]), kStartTol);
  return out;
}

}  // namespace

PW85_TARGET_V4 void rational_lanes_v4(double const *const rp[W], double const *const q1p[W],
                                      double const *const q2p[W], MethodResult res[W],
                                      int status[W]) noexcept {
  Vec3L<W> r;
  SymL<W> q1, q2;
  for (int l = 0; l < W; ++l) {
    for (int i = 0; i < kDim; ++i) r[i][l] = rp[l][i];
    for (int i = 0; i < kSym; ++i) {
      q1[i][l] = q1p[l][i];
      q2[i][l] = q2p[l][i];
    }
  }
  M8 const screen = screen_contact_lanes<V8>(r, q1, q2, kSafeLo, kSafeHi);
  M8 accepted{};
  V8 mu2{}, lam{}, err{};
  M8 iters{};
  if (any(screen)) {
    // rational_v4: the coefficients, the start, rational_iterate.
    CoefL k;
    M8 active = screen & coefficients(r, q1, q2, k);
    V8 lambda{};
    if (any(active)) lambda = grid_start(r, q1, q2, active, rp, q1p, q2p);
    accepted = rational_iterate(k, lambda, active, mu2, lam, err, iters);
  }
  // The promise checked after every method (methods.cpp, checked).
  M8 const kept = (mu2 >= 0.0) & (lam >= 0.0) & (lam <= 1.0) & (err == err);
  for (int l = 0; l < W; ++l) {
    MethodResult &o = res[l];
    o.method = kMethodDefault;
    if (accepted[l] != 0) {
      o.mu2 = mu2[l];
      o.lambda = lam[l];
      o.mu2_error = err[l];
      o.iterations = static_cast<int>(iters[l]);
      status[l] = kept[l] != 0 ? kOk : kLaneUndecided;
    } else if (screen[l] != 0) {
      // The rational step declined: the general method, as in
      // contact_default_v4.
      Status const s = contact_default_general_v4(view_vec3(rp[l]), view_sym3(q1p[l]),
                                                  view_sym3(q2p[l]), o);
      bool const ok = o.mu2 >= 0.0 && o.lambda >= 0.0 && o.lambda <= 1.0 &&
                      o.mu2_error == o.mu2_error;
      status[l] = ok ? s : kLaneUndecided;
    } else {
      status[l] = kLaneUndecided;
    }
  }
}
#endif

}  // namespace pw85
