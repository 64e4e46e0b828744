// Closed-form distance of closest approach of two ellipses (2D).
//
// Approach of Zheng & Palffy-Muhoray (Phys. Rev. E 75, 061709, 2007): an
// affine map turns ellipse 1 into the unit circle, and the tangency condition
// becomes a quartic equation solved in closed form. The quartic used here is
// derived in docs/dca.md (eqs. (D1)-(D8)) in the variable h, the support
// value of the transformed ellipse 2 in the direction of the common normal;
// it is not the paper's variable, but the same problem. Summary:
//
//  (D1) Q1 = R diag(a^2, b^2) R^T, y = D^{-1} R^T x with D = diag(a, b):
//       ellipse 1 becomes the unit disc;
//  (D2) Q2' = D^{-1} R^T Q2 R D^{-1} = V diag(q_1, q_2) V^T,
//       w = V^T D^{-1} R^T u (the direction of centres, transformed);
//  (D3) tangency: d w lies on the unit offset curve of ellipse 2',
//       p(n) = (Q2' / h + I) n, h = sqrt(n^T Q2' n), |n| = 1;
//  (D4) p parallel to w  <=>  phi(h) = sum_i w_i^2 (h^2 - q_i) / (q_i + h)^2 = 0;
//       phi is increasing for h > 0 (D8), so phi has exactly one positive
//       root, in [sqrt(min q_i), sqrt(max q_i)];
//  (D5) multiplied by (q_1 + h)^2 (q_2 + h)^2 / |w|^2, (D4) is the quartic
//       h^4 + 2 (A q_2 + B q_1) h^3 + (A (q_2^2 - q_1) + B (q_1^2 - q_2)) h^2
//           - 2 q_1 q_2 h - q_1 q_2 (A q_2 + B q_1) = 0,
//       A = w_1^2 / |w|^2, B = w_2^2 / |w|^2;
//  (D6) d = 1 / (h |(Q2' + h I)^{-1} w|)
//         = 1 / (h sqrt(sum_i w_i^2 / (q_i + h)^2));
//  (D7) lambda = 1 / (1 + h): the ratio of the normals of the two ellipses at
//       the contact point, the maximiser of the contact function f;
//  (D8) phi'(h) = sum_i 2 w_i^2 q_i (1 + h) / (q_i + h)^3 > 0.
//
// Robustness:
//  - the ellipse with the smaller condition number is the one mapped to the
//    circle (the DCA is symmetric in the two ellipses since they are
//    centrally symmetric);
//  - the quartic is solved by Ferrari's method; of its four (complex) roots
//    the one kept is the physically meaningful one: the real part, clamped
//    to the bracket of (D4), at which the unexpanded equation (D4) has the
//    smallest residual |phi|; it is then polished by a safeguarded Newton
//    iteration on phi (bisection whenever a step leaves the bracket), which
//    also covers a closed form spoiled by cancellation (coefficients
//    spanning many orders of magnitude, see docs/dca.md);
//  - circles (q_1 ~ q_2) and directions along an axis (A or B ~ 0) need no
//    special branch: the bracket then shrinks to a point or the quartic
//    factorises, and neither case involves an equality test;
//  - Q1, Q2 are rescaled by an even power of two (exact), so that nothing
//    overflows or underflows.
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/fp.hpp"
#include "dca/dca.hpp"
#include "common/magnitude.hpp"
#include "common/scaling.hpp"

namespace pw85 {

namespace {

constexpr int kMaxPolish = 60;

// Largest real root of the monic cubic y^3 + a y^2 + b y + c (one always
// exists), in closed form (Cardano / Viete), then one Newton step.
double cubic_largest_root(double a, double b, double c) noexcept {
  double const a3 = a / 3.0;
  double const p = b - a * a3;                              // depressed: t^3 + p t + q
  double const q = (2.0 * a3 * a3 - b) * a3 + c;
  double const half_q = 0.5 * q;
  double const third_p = p / 3.0;
  double const disc = half_q * half_q + third_p * third_p * third_p;
  double t;
  if (disc > 0.0) {
    // One real root; the cube root is taken of the sum without cancellation.
    double const s = -half_q - std::copysign(std::sqrt(disc), half_q);
    double const u = std::cbrt(s);
    t = (u != 0.0) ? u - third_p / u : 0.0;
  } else {
    // Three real roots (p <= 0): the largest of the trigonometric form.
    double const m = std::sqrt(std::max(-third_p, 0.0));
    double const arg = (m > 0.0) ? std::clamp(-half_q / (m * m * m), -1.0, 1.0) : 0.0;
    t = 2.0 * m * std::cos(std::acos(arg) / 3.0);
  }
  double y = t - a3;
  double const f = ((y + a) * y + b) * y + c;
  double const df = (3.0 * y + 2.0 * a) * y + b;
  if (df != 0.0 && std::isfinite(f / df)) y -= f / df;
  return y;
}

// Roots of z^2 + beta z + gamma, as (re, im) pairs.
void quadratic_roots(double beta, double gamma, double re[2], double im[2]) noexcept {
  double const disc = beta * beta - 4.0 * gamma;
  if (disc >= 0.0) {
    double const s = -0.5 * (beta + std::copysign(std::sqrt(disc), beta));
    re[0] = s;
    re[1] = (s != 0.0) ? gamma / s : 0.0;
    im[0] = im[1] = 0.0;
  } else {
    re[0] = re[1] = -0.5 * beta;
    im[0] = 0.5 * std::sqrt(-disc);
    im[1] = -im[0];
  }
}

// The four roots of x^4 + b x^3 + c x^2 + d x + e by Ferrari's method: with
// x = z - b/4 the depressed quartic z^4 + p z^2 + q z + r is written
// (z^2 + p/2 + m)^2 = (s z - q/(2 s))^2, s = sqrt(2 m), where m > 0 is a root
// of the resolvent cubic m^3 + p m^2 + (p^2/4 - r) m - q^2/8 = 0; it splits
// into two quadratics. When m vanishes (q = 0) the quartic is biquadratic.
void quartic_roots(double b, double c, double d, double e, double re[4],
                   double im[4]) noexcept {
  double const b4 = 0.25 * b;
  double const b4sq = b4 * b4;
  double const p = c - 6.0 * b4sq;
  double const q = d - 2.0 * c * b4 + 8.0 * b4 * b4sq;
  double const r = e - d * b4 + c * b4sq - 3.0 * b4sq * b4sq;
  double const m = cubic_largest_root(p, 0.25 * p * p - r, -0.125 * q * q);
  if (m > 0.0 && std::isfinite(m)) {
    double const s = std::sqrt(2.0 * m);
    double const t = q / (2.0 * s);
    quadratic_roots(-s, 0.5 * p + m + t, re, im);
    quadratic_roots(s, 0.5 * p + m - t, re + 2, im + 2);
  } else {
    // z^4 + p z^2 + r: z^2 = zeta, zeta^2 + p zeta + r = 0.
    double zr[2], zi[2];
    quadratic_roots(p, r, zr, zi);
    for (int k = 0; k < 2; ++k) {
      // Principal square root of zeta = zr + i zi, and its opposite.
      double const mod = std::hypot(zr[k], zi[k]);
      double const sr = std::sqrt(std::max(0.5 * (mod + zr[k]), 0.0));
      double si = std::sqrt(std::max(0.5 * (mod - zr[k]), 0.0));
      if (zi[k] < 0.0) si = -si;
      re[2 * k] = sr;
      im[2 * k] = si;
      re[2 * k + 1] = -sr;
      im[2 * k + 1] = -si;
    }
  }
  for (int k = 0; k < 4; ++k) re[k] -= b4;
}

// phi(h) of (D4) and phi'(h) of (D8), with A, B the squared, normalised
// components of w and sq_i = sqrt(q_i); h^2 - q_i is formed as
// (h - sq_i)(h + sq_i) so that it keeps its relative accuracy near the root.
struct Phi {
  double wa, wb;    // A, B
  double q1, q2;    // eigenvalues of Q2'
  double sq1, sq2;  // their square roots
  double value(double h) const noexcept {
    double noise;
    return value(h, noise);
  }
  // Also returns in noise a bound of the rounding error of the value.
  double value(double h, double &noise) const noexcept {
    double const t1 = (h - sq1) * (h + sq1) / ((q1 + h) * (q1 + h));
    double const t2 = (h - sq2) * (h + sq2) / ((q2 + h) * (q2 + h));
    // h^2 - q_i carries an absolute error of a few eps (h + sq_i)^2.
    double const n1 = (h + sq1) / (q1 + h), n2 = (h + sq2) / (q2 + h);
    noise = 4.0 * kEps * (wa * n1 * n1 + wb * n2 * n2);
    return wa * t1 + wb * t2;
  }
  double derivative(double h) const noexcept {
    double const g1 = q1 + h, g2 = q2 + h;
    return 2.0 * (1.0 + h) * (wa * q1 / (g1 * g1 * g1) + wb * q2 / (g2 * g2 * g2));
  }
};

// Even exponent 2k such that the largest |x_i| * 2^-2k is of order one.
int even_scale_exponent(Sym2 const &a, Sym2 const &b) noexcept {
  int const e = std::max(max_exponent(a.a, 3), max_exponent(b.a, 3));
  return 2 * (e / 2);
}

}  // namespace

Status dca_2d(Vec2 const &u, Sym2 const &q1_in, Sym2 const &q2_in,
              Dca2dResult &res) noexcept {
  res.newton_steps = 0;
  res.closed_form = true;
  // Exact rescaling: Q -> 2^-2k Q multiplies every length, d included, by 2^-k.
  int const e2 = even_scale_exponent(q1_in, q2_in);
  Sym2 q1, q2;
  scale_matrices(q1_in, q2_in, -e2, q1, q2);
  Eigen2 e1 = eigen(q1);
  Eigen2 e2d = eigen(q2);
  // Map the rounder ellipse to the circle; swapping the ellipses leaves d
  // unchanged and turns lambda into 1 - lambda (D7).
  bool const swapped = e2d.big * e1.small < e1.big * e2d.small;
  Sym2 const &qo = swapped ? q1 : q2;   // the other one; the chosen one becomes the circle
  Eigen2 const &ec = swapped ? e2d : e1;
  if (!(ec.small > 0.0)) return kNotSpd;

  // (D1): columns of R are (c, s) and (-s, c); D = diag(sqrt(big), sqrt(small)).
  double const ia = 1.0 / std::sqrt(ec.big), ib = 1.0 / std::sqrt(ec.small);
  // R^T Qo R.
  double const c = ec.c, s = ec.s;
  Vec2 const col0 = multiply(qo, Vec2{{c, s}});
  Vec2 const col1 = multiply(qo, Vec2{{-s, c}});
  double const r00 = c * col0[0] + s * col0[1];
  double const r01 = c * col1[0] + s * col1[1];
  double const r11 = -s * col1[0] + c * col1[1];
  // (D2): Q2' and w before its rotation by V.
  Sym2 const qp{{r00 * ia * ia, r01 * ia * ib, r11 * ib * ib}};
  Vec2 const w0{{(c * u[0] + s * u[1]) * ia, (-s * u[0] + c * u[1]) * ib}};
  Eigen2 const ep = eigen(qp);
  double const qa = ep.big, qb = ep.small;
  if (!(qb > 0.0)) return kNotSpd;
  Vec2 const w{{ep.c * w0[0] + ep.s * w0[1], -ep.s * w0[0] + ep.c * w0[1]}};
  double const wnorm2 = w[0] * w[0] + w[1] * w[1];
  Phi phi;
  phi.wa = w[0] * w[0] / wnorm2;
  phi.wb = w[1] * w[1] / wnorm2;
  phi.q1 = qa;
  phi.q2 = qb;
  phi.sq1 = std::sqrt(qa);
  phi.sq2 = std::sqrt(qb);

  // Bracket of the physical root (D4).
  double lo = phi.sq2, hi = phi.sq1;
  double h;
  Status status = kOk;
  if (hi - lo <= 4.0 * kEps * hi) {
    // Transformed ellipse 2 is a circle: h = its radius, whatever w.
    h = 0.5 * (lo + hi);
  } else {
    // (D5): Ferrari, then the root selection described above.
    double const a3 = phi.wa * qb + phi.wb * qa;
    double re[4], im[4];
    quartic_roots(2.0 * a3, phi.wa * (qb * qb - qa) + phi.wb * (qa * qa - qb),
                  -2.0 * qa * qb, -qa * qb * a3, re, im);
    h = std::numeric_limits<double>::quiet_NaN();
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 4; ++k) {
      // The real part, clamped to the bracket: rounding may push the
      // physical root slightly out of it, or split a (near-)double real root
      // into a complex pair; what decides is the residual of (D4), the
      // unexpanded equation, there.
      double const x = std::clamp(re[k], lo, hi);
      double const score = std::fabs(phi.value(x));
      if (score < best) {
        best = score;
        h = x;
      }
    }
    if (!std::isfinite(h)) {
      res.closed_form = false;
      h = std::sqrt(lo * hi);
    }
    // Safeguarded Newton polishing on phi (increasing on [lo, hi]).
    bool converged = false;
    for (int it = 0; it < kMaxPolish; ++it) {
      double noise;
      double const f = phi.value(h, noise);
      if (std::fabs(f) <= noise) {
        // phi(h) is zero to within its rounding errors: h is the root.
        converged = true;
        break;
      }
      if (f < 0.0)
        lo = h;
      else
        hi = h;
      double next = h - f / phi.derivative(h);
      // Outside the bracket: bisect, geometrically when the bracket spans
      // orders of magnitude.
      if (!(next >= lo && next <= hi)) next = (hi > 4.0 * lo) ? std::sqrt(lo * hi) : 0.5 * (lo + hi);
      ++res.newton_steps;
      double const step = next - h;
      h = next;
      if (std::fabs(step) <= 2.0 * kEps * h || hi - lo <= 2.0 * kEps * hi) {
        converged = true;
        break;
      }
    }
    if (!converged) status = kNoConvergence;
  }
  // (D6), then undo the scaling; (D7).
  double const g0 = w[0] / (qa + h), g1 = w[1] / (qb + h);
  res.d = std::ldexp(1.0 / (h * std::hypot(g0, g1)), e2 / 2);
  res.lambda = swapped ? h / (1.0 + h) : 1.0 / (1.0 + h);
  if (!std::isfinite(res.d)) return kNoConvergence;
  return status;
}

}  // namespace pw85
