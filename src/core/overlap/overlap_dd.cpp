// Double-double sign certificates of the overlap filters (docs/overlap.md,
// eq. (O15)). Products of doubles are exact (two_prod), so the 2x2 minors of
// the input matrices carry one rounding of 2^-106 relative to their own value
// instead of 2^-53 relative to the size of their terms. Every kernel is
// compiled with FMA (two_prod in two operations) and with Dekker's product,
// chosen at run time (common/isa.hpp); the certificates hold for either (the
// bounds of (O15) cover both).
#include "overlap/overlap_dd.hpp"

#include <cmath>

#include "arith/dd.hpp"
#include "dispatch/kernels.hpp"
#include "eval/f_dd.hpp"

namespace pw85 {

namespace {

using dd::DD;

template <bool F>
PW85_ALWAYS_INLINE DD prod(double a, double b) noexcept { return dd::two_prod<F>(a, b); }
// add and sub are dd::add and dd::sub (found by argument-dependent lookup).
inline DD twice(DD a) noexcept { return DD{2.0 * a.hi, 2.0 * a.lo}; }

// sum_ij A_ij Y_ij, A in Sym3 order {00, 01, 02, 11, 12, 22}, Y the products
// {y0 y0, y1 y1, y2 y2, y0 y1, y0 y2, y1 y2} (the order of quad() in
// overlap.cpp).
template <bool F>
PW85_ALWAYS_INLINE DD quad(DD const a[kSym], DD const yy[kSym]) noexcept {
  using dd::mul;
  DD const diag = add(add(mul<F>(a[0], yy[0]), mul<F>(a[3], yy[1])), mul<F>(a[5], yy[2]));
  DD const off = add(add(mul<F>(a[1], yy[3]), mul<F>(a[2], yy[4])), mul<F>(a[4], yy[5]));
  return add(diag, twice(off));
}

template <bool F>
PW85_ALWAYS_INLINE void outer(DD const y[kDim], DD yy[kSym]) noexcept {
  using dd::mul;
  yy[0] = mul<F>(y[0], y[0]);
  yy[1] = mul<F>(y[1], y[1]);
  yy[2] = mul<F>(y[2], y[2]);
  yy[3] = mul<F>(y[0], y[1]);
  yy[4] = mul<F>(y[0], y[2]);
  yy[5] = mul<F>(y[1], y[2]);
}

// det q and adjugate entries m[] (Sym3 order) of a double-double matrix.
template <bool F>
PW85_ALWAYS_INLINE DD det_adj(DD const q[kSym], DD m[kSym]) noexcept {
  using dd::mul;
  m[0] = sub(mul<F>(q[3], q[5]), mul<F>(q[4], q[4]));
  m[1] = sub(mul<F>(q[2], q[4]), mul<F>(q[1], q[5]));
  m[2] = sub(mul<F>(q[1], q[4]), mul<F>(q[2], q[3]));
  m[3] = sub(mul<F>(q[0], q[5]), mul<F>(q[2], q[2]));
  m[4] = sub(mul<F>(q[1], q[2]), mul<F>(q[0], q[4]));
  m[5] = sub(mul<F>(q[0], q[3]), mul<F>(q[1], q[1]));
  return add(add(mul<F>(q[0], m[0]), mul<F>(q[1], m[1])), mul<F>(q[2], m[2]));
}

// det q - y^T adj(q) y for a double-double offset y.
template <bool F>
PW85_ALWAYS_INLINE double g_dd(Sym3 const &q, DD const y[kDim]) noexcept {
  DD qd[kSym], m[kSym], yy[kSym];
  for (int i = 0; i < kSym; ++i) qd[i] = DD{q[i], 0.0};
  DD const det = det_adj<F>(qd, m);
  outer<F>(y, yy);
  return dd::to_double(sub(det, quad<F>(m, yy)));
}

template <bool F>
PW85_ALWAYS_INLINE double witness_g_impl(Sym3 const &q, Vec3 const &x, Vec3 const &c) noexcept {
  DD y[kDim];
  for (int i = 0; i < kDim; ++i) y[i] = dd::two_sum(x[i], -c[i]);
  return g_dd<F>(q, y);
}

template <bool F>
PW85_ALWAYS_INLINE bool witness_point_impl(double l, Vec3 const &r, Sym3 const &q1,
                                           Sym3 const &q2, bool from_c2, Vec3 &hi, Vec3 &lo,
                                           double &df) noexcept {
  DD s[kDim], phi;
  if (!solve_dd_impl<F>(l, r, q1, q2, s, phi)) return false;
  DD t1[kDim], t2[kDim];  // Q1 s, Q2 s
  df = dd::to_double(products_from_s_impl<F>(l, q1, q2, s, t1, t2));
  DD const om = dd::two_sum(1.0, -l);  // 1 - l, exactly
  bool finite = std::isfinite(df);
  for (int i = 0; i < kDim; ++i) {
    DD const y = from_c2 ? dd::mul<F>(t2[i], -l) : dd::mul<F>(t1[i], om);
    hi[i] = y.hi;
    lo[i] = y.lo;
    finite = finite && std::isfinite(y.hi) && std::isfinite(y.lo);
  }
  return finite;
}

template <bool F>
PW85_ALWAYS_INLINE void witness_pair_impl(Sym3 const &q1, Sym3 const &q2, Vec3 const &r,
                                          Vec3 const &hi, Vec3 const &lo, bool from_c2,
                                          double g[2]) noexcept {
  DD y1[kDim], y2[kDim];  // offsets from the centres of E1 (0) and E2 (r)
  for (int i = 0; i < kDim; ++i) {
    DD const e = dd::two_sum(hi[i], lo[i]);  // exact
    DD const rr{r[i], 0.0};
    if (from_c2) {
      y2[i] = e;
      y1[i] = add(e, rr);
    } else {
      y1[i] = e;
      y2[i] = sub(e, rr);
    }
  }
  g[0] = g_dd<F>(q1, y1);
  g[1] = g_dd<F>(q2, y2);
}

template <bool F>
PW85_ALWAYS_INLINE double p_impl(double l, Vec3 const &r, Sym3 const &q1,
                                 Sym3 const &q2) noexcept {
  double const nu = 1.0 - l;  // exact: l on the grid 2^-52 Z
  DD q[kSym], m[kSym], rd[kDim], rr[kSym];
  for (int i = 0; i < kSym; ++i) q[i] = add(prod<F>(nu, q1[i]), prod<F>(l, q2[i]));
  DD const det = det_adj<F>(q, m);
  for (int i = 0; i < kDim; ++i) rd[i] = DD{r[i], 0.0};
  outer<F>(rd, rr);
  DD const p = sub(det, dd::mul<F>(quad<F>(m, rr), prod<F>(l, nu)));
  return dd::to_double(p);
}

// The kernels of one variant, compiled with the target attribute TARGET
// with Dekker's product (FMA false) or the fused multiply-add (FMA true).
#define PW85_OVERLAP_DD_VARIANT(name, TARGET, FMA)                                            \
  TARGET double witness_g_##name(Sym3 const &q, Vec3 const &x, Vec3 const &c) noexcept {     \
    return witness_g_impl<FMA>(q, x, c);                                                      \
  }                                                                                           \
  TARGET double p_##name(double l, Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept { \
    return p_impl<FMA>(l, r, q1, q2);                                                         \
  }                                                                                           \
  TARGET bool witness_point_##name(double l, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,  \
                                   bool from_c2, Vec3 &hi, Vec3 &lo, double &df) noexcept {   \
    return witness_point_impl<FMA>(l, r, q1, q2, from_c2, hi, lo, df);                        \
  }                                                                                           \
  TARGET void witness_pair_##name(Sym3 const &q1, Sym3 const &q2, Vec3 const &r,             \
                                  Vec3 const &hi, Vec3 const &lo, bool from_c2,               \
                                  double g[2]) noexcept {                                     \
    witness_pair_impl<FMA>(q1, q2, r, hi, lo, from_c2, g);                                    \
  }                                                                                           \
  constexpr OverlapDdKernels kOverlapDd_##name = {witness_g_##name, p_##name,                \
                                                  witness_point_##name, witness_pair_##name};

PW85_OVERLAP_DD_VARIANT(portable, , kStaticFma)
#if PW85_ISA_FMA
PW85_OVERLAP_DD_VARIANT(fma, PW85_TARGET_FMA, true)
#endif

}  // namespace

const OverlapDdKernels overlap_dd_kernels[kVariantCount] = {
    kOverlapDd_portable, PW85_IF_FMA(kOverlapDd_fma, kOverlapDd_portable),
    PW85_IF_FMA(kOverlapDd_fma, kOverlapDd_portable),
    PW85_IF_FMA(kOverlapDd_fma, kOverlapDd_portable)};

double witness_g_dd(Sym3 const &q, Vec3 const &x, Vec3 const &c) noexcept {
  return kernels().overlap_dd->witness_g(q, x, c);
}

bool witness_point_dd(double l, Vec3 const &r, Sym3 const &q1, Sym3 const &q2, bool from_c2,
                      Vec3 &hi, Vec3 &lo, double &df) noexcept {
  return kernels().overlap_dd->witness_point(l, r, q1, q2, from_c2, hi, lo, df);
}

void witness_pair_dd(Sym3 const &q1, Sym3 const &q2, Vec3 const &r, Vec3 const &hi,
                     Vec3 const &lo, bool from_c2, double g[2]) noexcept {
  kernels().overlap_dd->witness_pair(q1, q2, r, hi, lo, from_c2, g);
}

double p_dd(double l, Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept {
  return kernels().overlap_dd->p(l, r, q1, q2);
}

}  // namespace pw85
