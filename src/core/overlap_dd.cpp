// Double-double sign certificates of the overlap filters (docs/overlap.md,
// eq. (O15)). Products of doubles are exact (two_prod, Dekker's form: this
// path is rare, no FMA dispatch), so the 2x2 minors of the input matrices
// carry one rounding of 2^-106 relative to their own value instead of
// 2^-53 relative to the size of their terms.
#include "overlap_dd.hpp"

#include <cmath>

#include "dd.hpp"
#include "f_dd.hpp"

namespace pw85 {

namespace {

using dd::DD;
constexpr bool kFma = false;

inline DD prod(double a, double b) noexcept { return dd::two_prod<kFma>(a, b); }
inline DD mul(DD a, DD b) noexcept { return dd::mul<kFma>(a, b); }
inline DD mul(DD a, double b) noexcept { return dd::mul<kFma>(a, b); }
// add and sub are dd::add and dd::sub (found by argument-dependent lookup).
inline DD twice(DD a) noexcept { return DD{2.0 * a.hi, 2.0 * a.lo}; }

// sum_ij A_ij Y_ij, A in Sym3 order {00, 01, 02, 11, 12, 22}, Y the products
// {y0 y0, y1 y1, y2 y2, y0 y1, y0 y2, y1 y2} (the order of quad() in
// overlap.cpp).
inline DD quad(DD const a[kSym], DD const yy[kSym]) noexcept {
  DD const diag = add(add(mul(a[0], yy[0]), mul(a[3], yy[1])), mul(a[5], yy[2]));
  DD const off = add(add(mul(a[1], yy[3]), mul(a[2], yy[4])), mul(a[4], yy[5]));
  return add(diag, twice(off));
}

inline void outer(DD const y[kDim], DD yy[kSym]) noexcept {
  yy[0] = mul(y[0], y[0]);
  yy[1] = mul(y[1], y[1]);
  yy[2] = mul(y[2], y[2]);
  yy[3] = mul(y[0], y[1]);
  yy[4] = mul(y[0], y[2]);
  yy[5] = mul(y[1], y[2]);
}

// det q and adjugate entries m[] (Sym3 order) of a double-double matrix.
inline DD det_adj(DD const q[kSym], DD m[kSym]) noexcept {
  m[0] = sub(mul(q[3], q[5]), mul(q[4], q[4]));
  m[1] = sub(mul(q[2], q[4]), mul(q[1], q[5]));
  m[2] = sub(mul(q[1], q[4]), mul(q[2], q[3]));
  m[3] = sub(mul(q[0], q[5]), mul(q[2], q[2]));
  m[4] = sub(mul(q[1], q[2]), mul(q[0], q[4]));
  m[5] = sub(mul(q[0], q[3]), mul(q[1], q[1]));
  return add(add(mul(q[0], m[0]), mul(q[1], m[1])), mul(q[2], m[2]));
}

// det q - y^T adj(q) y for a double-double offset y.
inline double g_dd(Sym3 const &q, DD const y[kDim]) noexcept {
  DD qd[kSym], m[kSym], yy[kSym];
  for (int i = 0; i < kSym; ++i) qd[i] = DD{q[i], 0.0};
  DD const det = det_adj(qd, m);
  outer(y, yy);
  return dd::to_double(sub(det, quad(m, yy)));
}

}  // namespace

double witness_g_dd(Sym3 const &q, Vec3 const &x, Vec3 const &c) noexcept {
  DD y[kDim];
  for (int i = 0; i < kDim; ++i) y[i] = dd::two_sum(x[i], -c[i]);
  return g_dd(q, y);
}

bool witness_point_dd(double l, Vec3 const &r, Sym3 const &q1, Sym3 const &q2, bool from_c2,
                      Vec3 &hi, Vec3 &lo, double &df) noexcept {
  DD s[kDim], phi;
  if (!solve_dd_impl<kFma>(l, r, q1, q2, s, phi)) return false;
  DD t1[kDim], t2[kDim];  // Q1 s, Q2 s
  df = dd::to_double(products_from_s_impl<kFma>(l, q1, q2, s, t1, t2));
  DD const om = dd::two_sum(1.0, -l);  // 1 - l, exactly
  bool finite = std::isfinite(df);
  for (int i = 0; i < kDim; ++i) {
    DD const y = from_c2 ? mul(t2[i], -l) : mul(t1[i], om);
    hi[i] = y.hi;
    lo[i] = y.lo;
    finite = finite && std::isfinite(y.hi) && std::isfinite(y.lo);
  }
  return finite;
}

void witness_pair_dd(Sym3 const &q1, Sym3 const &q2, Vec3 const &r, Vec3 const &hi,
                     Vec3 const &lo, bool from_c2, double g[2]) noexcept {
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
  g[0] = g_dd(q1, y1);
  g[1] = g_dd(q2, y2);
}

double p_dd(double l, Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept {
  double const nu = 1.0 - l;  // exact: l on the grid 2^-52 Z
  DD q[kSym], m[kSym], rd[kDim], rr[kSym];
  for (int i = 0; i < kSym; ++i) q[i] = add(prod(nu, q1[i]), prod(l, q2[i]));
  DD const det = det_adj(q, m);
  for (int i = 0; i < kDim; ++i) rd[i] = DD{r[i], 0.0};
  outer(rd, rr);
  DD const p = sub(det, mul(quad(m, rr), prod(l, nu)));
  return dd::to_double(p);
}

}  // namespace pw85
