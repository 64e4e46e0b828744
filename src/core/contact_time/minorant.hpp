// Lower bound of mu(t) over a step (docs/contact_time.md (T2)-(T5)).
//
// mu is the gauge of r12 for the Minkowski sum of the two centred
// ellipsoids, whose support function is h1(u) + h2(u), h_i(u) = sqrt(u^T Q_i u):
//   mu(t) = max_u phi(u, t),  phi(u, t) = r12(t).u / (h1(u, t) + h2(u, t)),  (T2)
// attained at u = s = Q(lambda)^{-1} r12. For one fixed u and tau >= 0
// (t_k + tau), N(tau) = r12.u + tau v12.u exactly, and
//   |dh_i/dt| <= om_i = |w_i| (a_max - a_min)                                  (T3)
//   d^2h_i/dt^2 <= Om_i = |w_i|^2 (a_max^2 - a_min^2) / a_min                  (T4)
// so D(tau) = h1 + h2 <= D0 + min(om tau, D0' tau + Om tau^2 / 2) and, for a
// level m in (0, 1], phi(u, t_k + tau) >= m (hence mu >= m) while
//   g(tau) = (N0 - m D0) + v12.u tau - min(om tau, m D0' tau + Om tau^2 / 2) >= 0  (T5)
// (m om, m Om <= om, Om).
#pragma once

#include <cmath>
#include <limits>

#include "common/fp.hpp"
#include "common/sym3.hpp"
#include "contact_time/axes.hpp"
#include "contact_time/enclosure.hpp"
#include "contact_time/motion.hpp"

namespace pw85 {

// Constants of (T3), (T4) for the pair (rotation invariant).
struct RateBounds {
  double om;       // om_1 + om_2
  double Om;       // Om_1 + Om_2
  double om_i[2];  // om_1, om_2
  double c_i[2];   // |w_i|^2 (a_max^2 - a_min^2): Om_i = c_i / a_min
  double a_min_i[2];
};

// Terms of (T5) at t_k for the direction u = s / |s|, with rounding margins
// (gap and slopes lowered by bounds on their rounding errors).
struct Minorant {
  double h[2];   // h_1, h_2 at t_k
  double gap;    // N0 - m D0
  double n1;     // v12.u
  double d1;     // D0'
  double slope;  // v12.u - m D0'
};

// u^T Q u in double, and the sum of the magnitudes of its terms (its
// rounding error is below 6 u mag, that of h = sqrt(u^T Q u) ~3 u mag / h).
inline double support2(Sym3 const &q, Vec3 const &u, double &mag) noexcept {
  double const p01 = 2.0 * u[0] * u[1], p02 = 2.0 * u[0] * u[2], p12 = 2.0 * u[1] * u[2];
  double const diag = q[0] * (u[0] * u[0]) + q[3] * (u[1] * u[1]) + q[5] * (u[2] * u[2]);
  mag = diag + (std::fabs(q[1] * p01) + std::fabs(q[2] * p02) + std::fabs(q[4] * p12));
  return diag + (q[1] * p01 + q[2] * p02 + q[4] * p12);
}

// The same in double-double, Q's entries used exactly: h accurate to a few
// u even where u^T Q u << |Q| (u along a thin axis).
inline double support2_dd(Sym3 const &q, Vec3 const &u) noexcept {
  using namespace dd;
  DD s = mul<false>(two_prod<false>(u[0], u[0]), q[0]);
  s = add(s, mul<false>(two_prod<false>(u[1], u[1]), q[3]));
  s = add(s, mul<false>(two_prod<false>(u[2], u[2]), q[5]));
  s = add(s, mul<false>(two_prod<false>(2.0 * u[0], u[1]), q[1]));
  s = add(s, mul<false>(two_prod<false>(2.0 * u[0], u[2]), q[2]));
  s = add(s, mul<false>(two_prod<false>(2.0 * u[1], u[2]), q[4]));
  return to_double(s);
}

// h_1, h_2: in double where its error (~1.5 u mag / h) is below 2 u (h_1 + h_2),
// else by support2_dd.
inline void supports(Sym3 const &q1, Sym3 const &q2, Vec3 const &u, double &h1,
                     double &h2) noexcept {
  double m1, m2;
  h1 = std::sqrt(support2(q1, u, m1));
  h2 = std::sqrt(support2(q2, u, m2));
  double const d = h1 + h2;
  if (!(3.0 * m1 <= 4.0 * h1 * d)) h1 = std::sqrt(support2_dd(q1, u));
  if (!(3.0 * m2 <= 4.0 * h2 * d)) h2 = std::sqrt(support2_dd(q2, u));
}

inline dd::DD dot_dd(Vec3 const &a, Vec3 const &b) noexcept {
  using namespace dd;
  DD s = two_prod<false>(a[0], b[0]);
  s = add(s, two_prod<false>(a[1], b[1]));
  return add(s, two_prod<false>(a[2], b[2]));
}

// Terms of (T5) at t for u = s / |s|, the trajectory r0 + t v and the level
// m (a double in (0, 1]):
// N0 = r0.u + t v.u in double-double (no rounding of r12(t)), h_i by
// supports, D0' = sum_i w_i . (Q_i u x u) / h_i (d/dt of u^T R Q_i R^T u is
// 2 u.(w_i x Q_i u), dR/dt = [w_i]x R, and dh = d(h^2) / (2 h)). The margins
// bound the rounding errors: a few u D0 for the gap, u |v| for v.u and
// u |w_i| |Q_i|_1 / h_i for D0'.
inline bool minorant(Vec3 const &r0, Vec3 const &v, double t, Sym3 const &q1, Vec3 const &w1,
                     Sym3 const &q2, Vec3 const &w2, Vec3 const &s, double level,
                     Minorant &m) noexcept {
  double const sn = norm(s);
  if (!(sn > 0.0) || !std::isfinite(sn)) return false;
  Vec3 const u{{s[0] / sn, s[1] / sn, s[2] / sn}};
  double h1, h2;
  supports(q1, q2, u, h1, h2);
  if (!(h1 > 0.0) || !(h2 > 0.0)) return false;
  dd::DD const vu = dot_dd(v, u);
  dd::DD const n0 = dd::add(dot_dd(r0, u), dd::mul<false>(vu, t));
  double const d0 = h1 + h2;
  m.h[0] = h1;
  m.h[1] = h2;
  double const gap = dd::to_double(dd::sub(n0, dd::mul<false>(dd::two_sum(h1, h2), level)));
  Vec3 const q1u = multiply(q1, u), q2u = multiply(q2, u);
  double const d1 = dot(w1, cross(q1u, u)) / h1 + dot(w2, cross(q2u, u)) / h2;
  double qn1 = 0.0, qn2 = 0.0;
  for (int i = 0; i < kSym; ++i) {
    qn1 += std::fabs(q1[i]);
    qn2 += std::fabs(q2[i]);
  }
  double const rot = norm(w1) * qn1 / h1 + norm(w2) * qn2 / h2;
  m.gap = gap - 12 * kU * d0 - 8 * kU * kU * (norm(r0) + t * norm(v));
  m.n1 = dd::to_double(vu) - 4 * kU * norm(v);
  m.d1 = d1;
  m.slope = m.n1 - level * d1 - 32 * kU * rot;
  return std::isfinite(m.gap) && std::isfinite(m.slope);
}

// The same for a rotating pair at the exact pose (enclosure.hpp): h_i =
// sqrt(y_i^T Q_i y_i), y_i = R_i(t)^T u in double-double (spin.hpp), so that
// h_i is that of the exact Q_i(t) to ~2 u relative, thin directions
// included (the rounding of R_i^T u adds below 8 u^2 a_max,i^2 / h_i, in the
// margin); D0' = sum_i w_i . (Q_i y_i x y_i) / h_i (R_i^T w_i = w_i).
inline bool minorant_rotating(ExactPose const &pose, Vec3 const &v, Sym3 const &q1,
                              Vec3 const &w1, Sym3 const &q2, Vec3 const &w2,
                              AxisBounds const &ax1, AxisBounds const &ax2, Vec3 const &s,
                              double level, Minorant &m) noexcept {
  double const sn = norm(s);
  if (!(sn > 0.0) || !std::isfinite(sn)) return false;
  Vec3 const u{{s[0] / sn, s[1] / sn, s[2] / sn}};
  dd::DD const ud[kDim] = {{u[0], 0.0}, {u[1], 0.0}, {u[2], 0.0}};
  Vec3 y1, y2;
  double const h1 = std::sqrt(to_double(rotated_form(pose.sp1, q1, ud, &y1)));
  double const h2 = std::sqrt(to_double(rotated_form(pose.sp2, q2, ud, &y2)));
  if (!(h1 > 0.0) || !(h2 > 0.0)) return false;
  dd::DD const vu = dot_dd(v, u);
  dd::DD const n0 = dd::add(dot_dd(Vec3{{pose.r[0].hi, pose.r[1].hi, pose.r[2].hi}}, u),
                            dot_dd(Vec3{{pose.r[0].lo, pose.r[1].lo, pose.r[2].lo}}, u));
  double const d0 = h1 + h2;
  m.h[0] = h1;
  m.h[1] = h2;
  double const gap = dd::to_double(dd::sub(n0, dd::mul<false>(dd::two_sum(h1, h2), level)));
  double const d1 = dot(w1, cross(multiply(q1, y1), y1)) / h1 + dot(w2, cross(multiply(q2, y2), y2)) / h2;
  double qn1 = 0.0, qn2 = 0.0;
  for (int i = 0; i < kSym; ++i) {
    qn1 += std::fabs(q1[i]);
    qn2 += std::fabs(q2[i]);
  }
  double const rot = norm(w1) * qn1 / h1 + norm(w2) * qn2 / h2;
  double const thin = 8 * kU * kU * (ax1.a_max * ax1.a_max / h1 + ax2.a_max * ax2.a_max / h2);
  m.gap = gap - 12 * kU * d0 - thin - 8 * kU * kU * norm(Vec3{{pose.r[0].hi, pose.r[1].hi, pose.r[2].hi}});
  m.n1 = dd::to_double(vu) - 4 * kU * norm(v);
  m.d1 = d1;
  m.slope = m.n1 - level * d1 - 32 * kU * rot;
  return std::isfinite(m.gap) && std::isfinite(m.slope);
}

// Positive root of gap + a tau - Om tau^2 / 2 (+inf when none).
inline double parabola_root(double gap, double a, double Om) noexcept {
  if (Om > 0.0) {
    double const disc = std::sqrt(a * a + 2.0 * Om * gap);
    return a >= 0.0 ? (a + disc) / Om : 2.0 * gap / (disc - a);
  }
  return a >= 0.0 ? std::numeric_limits<double>::infinity() : gap / (-a);
}

// Largest tau with g >= 0 on [0, tau] (T5): the larger of the roots of the
// two branches, each a lower bound of g; +inf when g never vanishes. A third
// candidate uses (T4) with h_i >= h_i(t_k) - om_i tau >= h_i(t_k) / 2, valid
// for tau <= h_i(t_k) / (2 om_i): Om_i <= c_i / max(a_min, h_i(t_k) / 2).
inline double safe_step(Minorant const &m, RateBounds const &b) noexcept {
  double const inf = std::numeric_limits<double>::infinity();
  double const tau1 = b.om > m.n1 ? m.gap / (b.om - m.n1) : inf;
  double const tau2 = parabola_root(m.gap, m.slope, b.Om);
  double om_loc = 0.0, lim = inf;
  for (int i = 0; i < 2; ++i) {
    if (b.om_i[i] == 0.0) continue;
    om_loc += b.c_i[i] / std::fmax(b.a_min_i[i], 0.5 * m.h[i]);
    lim = std::fmin(lim, 0.5 * m.h[i] / b.om_i[i]);
  }
  double const tau3 = std::fmin(parabola_root(m.gap, m.slope, om_loc * (1.0 + 1e-12)), lim);
  return std::fmax(std::fmax(tau1, tau2), tau3);
}

}  // namespace pw85
