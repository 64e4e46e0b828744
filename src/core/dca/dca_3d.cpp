// Distance of closest approach of two ellipsoids by rotating a plane about
// the line of centres: X. Zheng, W. Iglesias, P. Palffy-Muhoray, "Distance of
// closest approach of two arbitrary hard ellipsoids" (preprint, 2008),
// section 2; docs/dca.md, eqs. (D9)-(D12).
//
//  (D9)  plane normal p(theta) = cos(theta) p0 + sin(theta) (p0 x u),
//        theta in [0, pi) (paper, eq. (4)); s = p x u; the plane is spanned
//        by the orthonormal pair (u, s). p0 is u x e_k / |u x e_k| with e_k
//        the coordinate axis least aligned with u (the paper takes a
//        principal axis of ellipsoid 1, eqs. (2)-(3), which needs a fallback
//        when u is along it; this choice never does).
//  (D10) section of {m : m^T Q^{-1} m <= 1} by the plane: the 2x2 matrix
//        Q_2D = (P^T Q^{-1} P)^{-1}, P = [u s], which is the Schur complement
//        Q_2D = P^T Q P - (P^T Q p)(p^T Q P) / (p^T Q p), so that Q^{-1} is
//        never formed (the paper builds the same ellipse from the principal
//        axes, eqs. (8)-(13));
//  (D11) d = max over theta of d_2D(theta) (paper, section 2.2.1): d_2D is
//        pi-periodic and has one maximum and one minimum on [0, pi);
//  (D12) search: kSamples = 4 equally spaced samples, then Brent's
//        parabolic/golden-section maximisation on the two sample intervals
//        around the best sample. For a periodic function with one maximum and
//        one minimum, any triple a < x < b with d(x) >= d(a), d(x) >= d(b)
//        brackets the maximum (docs/dca.md proves it), and Brent's method
//        keeps such a triple at every step; this replaces the paper's
//        modified golden-section search (section 2.2.2), which needs a
//        finite-difference derivative in one of its cases.
//
// The maximiser lambda of the contact function is the one of the 2D problem
// in the optimal plane (docs/dca.md, eq. (D7)): at the contact point the 2D
// normals are the projections of the 3D ones, so their ratio is the same.
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/fp.hpp"
#include "dca/dca.hpp"
#include "eval/f_cholesky.hpp"
#include "common/magnitude.hpp"
#include "common/scaling.hpp"

namespace pw85 {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSamples = 4;
constexpr double kGolden = 0.3819660112501051;  // (3 - sqrt(5)) / 2

inline Vec3 cross(Vec3 const &a, Vec3 const &b) noexcept {
  return Vec3{{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
               a[0] * b[1] - a[1] * b[0]}};
}

inline Vec3 scaled(Vec3 const &a, double k) noexcept {
  return Vec3{{k * a[0], k * a[1], k * a[2]}};
}

class PlaneDca {
 public:
  PlaneDca(Vec3 const &u, Sym3 const &q1, Sym3 const &q2) noexcept : u_(u), q1_(q1), q2_(q2) {
    int k = 0;
    for (int i = 1; i < kDim; ++i)
      if (std::fabs(u[i]) < std::fabs(u[k])) k = i;
    Vec3 e{{0.0, 0.0, 0.0}};
    e[k] = 1.0;
    Vec3 const p0 = cross(u, e);
    p0_ = scaled(p0, 1.0 / std::sqrt(dot(p0, p0)));
    p0u_ = cross(p0_, u);
    q1u_ = multiply(q1, u);
    q2u_ = multiply(q2, u);
  }

  // d_2D(theta); lambda of the 2D problem in *lambda. False on failure.
  bool operator()(double theta, double &d, double &lambda) noexcept {
    ++evaluations;
    double const c = std::cos(theta), sn = std::sin(theta);
    Vec3 p;
    for (int i = 0; i < kDim; ++i) p[i] = c * p0_[i] + sn * p0u_[i];  // (D9)
    Vec3 const s = cross(p, u_);
    Sym2 const a1 = section(q1_, q1u_, s, p);
    Sym2 const a2 = section(q2_, q2u_, s, p);
    Dca2dResult r;
    if (!is_positive_definite(a1) || !is_positive_definite(a2)) return false;
    Status const st = dca_2d(Vec2{{1.0, 0.0}}, a1, a2, r);
    if (st != kOk && st != kNoConvergence) return false;
    d = r.d;
    lambda = r.lambda;
    return std::isfinite(d);
  }

  int evaluations = 0;

 private:
  // (D10) in the basis (u, s) of the plane.
  Sym2 section(Sym3 const &q, Vec3 const &qu, Vec3 const &s, Vec3 const &p) const noexcept {
    Vec3 const qs = multiply(q, s);
    Vec3 const qp = multiply(q, p);
    double const pp = dot(p, qp);
    double const up = dot(qu, p), sp = dot(qs, p);
    return Sym2{{dot(u_, qu) - up * up / pp, dot(s, qu) - up * sp / pp,
                 dot(s, qs) - sp * sp / pp}};
  }

  Vec3 u_;
  Sym3 q1_, q2_;
  Vec3 p0_, p0u_, q1u_, q2u_;
};

int even_scale_exponent(Sym3 const &a, Sym3 const &b) noexcept {
  int const e = std::max(max_exponent(a.a, kSym), max_exponent(b.a, kSym));
  return 2 * (e / 2);
}

}  // namespace

Status dca_zheng(Vec3 const &u, Sym3 const &q1_in, Sym3 const &q2_in, double theta_tol,
                 int max_eval, DcaResult &res) noexcept {
  res.d = res.lambda = res.theta = std::numeric_limits<double>::quiet_NaN();
  res.evaluations = 0;
  // Exact rescaling by an even power of two: d scales by its square root.
  int const e2 = even_scale_exponent(q1_in, q2_in);
  Sym3 q1, q2;
  scale_matrices(q1_in, q2_in, -e2, q1, q2);
  PlaneDca dca(u, q1, q2);

  // Samples; x is the best one, a and b its neighbours (unwrapped, period pi).
  double fs[kSamples], ls[kSamples];
  int best = 0;
  for (int k = 0; k < kSamples; ++k) {
    if (!dca(k * kPi / kSamples, fs[k], ls[k])) {
      res.evaluations = dca.evaluations;
      return kNoConvergence;
    }
    if (fs[k] > fs[best]) best = k;
  }
  double const step = kPi / kSamples;
  double x = best * step, fx = fs[best], lx = ls[best];
  double a = x - step, b = x + step;

  // Brent's method maximising d_2D on [a, b]: x best point so far, w the
  // second best, v the previous w; parabolic steps through (v, w, x) when
  // they are acceptable, golden-section steps otherwise.
  double w = x, v = x, fw = fx, fv = fx;
  double dstep = 0.0, e = 0.0;
  bool converged = false;
  while (dca.evaluations < max_eval) {
    double const mid = 0.5 * (a + b);
    double const tol1 = theta_tol + 2.0 * kEps * std::fabs(x);
    double const tol2 = 2.0 * tol1;
    if (std::fabs(x - mid) <= tol2 - 0.5 * (b - a)) {
      converged = true;
      break;
    }
    bool golden = true;
    if (std::fabs(e) > tol1) {
      // Vertex of the parabola through (v, fv), (w, fw), (x, fx), as x + p/q.
      double const r = (x - w) * (fx - fv);
      double qq = (x - v) * (fx - fw);
      double pp = (x - v) * qq - (x - w) * r;
      qq = 2.0 * (qq - r);
      if (qq > 0.0) pp = -pp;
      qq = std::fabs(qq);
      double const e_prev = e;
      e = dstep;
      if (std::fabs(pp) < std::fabs(0.5 * qq * e_prev) && pp > qq * (a - x) &&
          pp < qq * (b - x)) {
        dstep = pp / qq;
        double const t = x + dstep;
        if (t - a < tol2 || b - t < tol2) dstep = (x < mid) ? tol1 : -tol1;
        golden = false;
      }
    }
    if (golden) {
      e = (x >= mid) ? a - x : b - x;
      dstep = kGolden * e;
    }
    double const t = x + (std::fabs(dstep) >= tol1 ? dstep : std::copysign(tol1, dstep));
    double ft, lt;
    if (!dca(t, ft, lt)) break;
    if (ft >= fx) {
      if (t >= x)
        a = x;
      else
        b = x;
      v = w;
      fv = fw;
      w = x;
      fw = fx;
      x = t;
      fx = ft;
      lx = lt;
    } else {
      if (t < x)
        a = t;
      else
        b = t;
      if (ft >= fw || w == x) {
        v = w;
        fv = fw;
        w = t;
        fw = ft;
      } else if (ft >= fv || v == x || v == w) {
        v = t;
        fv = ft;
      }
    }
  }
  res.d = std::ldexp(fx, e2 / 2);
  res.lambda = lx;
  res.theta = std::fmod(x + kPi, kPi);
  res.evaluations = dca.evaluations;
  return converged ? kOk : kNoConvergence;
}

}  // namespace pw85
