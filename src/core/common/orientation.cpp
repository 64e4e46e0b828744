#include "common/orientation.hpp"

#include <cmath>

#include "arith/dd.hpp"
#include "common/ellipsoid.hpp"
#include "common/fp.hpp"
#include "common/isa.hpp"
#include "dispatch/kernels.hpp"
#include "common/magnitude.hpp"
#include "common/scaling.hpp"
#include "common/spd.hpp"

namespace pw85 {

namespace {

using dd::DD;

template <bool F>
PW85_ALWAYS_INLINE DD sq(double a) noexcept { return dd::two_prod<F>(a, a); }
template <bool F>
PW85_ALWAYS_INLINE DD prod(double a, double b) noexcept { return dd::two_prod<F>(a, b); }
PW85_ALWAYS_INLINE DD twice(DD a) noexcept { return DD{2.0 * a.hi, 2.0 * a.lo}; }

// (O1) The rotation of the quaternion q = (w, x, y, z) (Hamilton product,
// p -> q p q* / |q|^2, body frame to lab frame) is R = M / |q|^2 with
//   M = [w²+x²−y²−z²   2(xy − wz)     2(xz + wy)  ]
//       [2(xy + wz)     w²−x²+y²−z²   2(yz − wx)  ]
//       [2(xz − wy)     2(yz + wx)     w²−x²−y²+z²],
// and M M^T = |q|^4 I exactly. Column k of R is body axis k in the lab.
// (O2) Q = R diag(a²) R^T = s I + sum_k (a_k² − s) M_:k M_:k^T / |q|^4 for
// any s, taken as the median a_k²: a sphere gives s I exactly and a
// spheroid one rank-one term. Everything in double-double (error a few
// u² max_k a_k², absolute) on radii scaled by 2^-e (exact), so each entry is
// within u |Q_ij| + a few u² max_k a_k² of the exact Q of quat / |quat|.
// F: fused multiply-add in the error-free products (common/isa.hpp); both
// are exact, so F changes no bit unless a product underflows.
// Q of radii and quat / |quat| (|quat|^2 = n2) through the rotation matrix
// in double and ellipsoid(): for radii too different for the scaled
// double-double frame of quat_body.
Status quat_by_rotation(Vec3 const &radii, double const quat[4], double n2,
                        Sym3 &q) noexcept {
  double const w = quat[0], x = quat[1], y = quat[2], z = quat[3];
  double const s = 1.0 / n2;
  // Row k of axes = column k of R (O1).
  double const axes[9] = {(w * w + x * x - y * y - z * z) * s, 2 * (x * y + w * z) * s,
                          2 * (x * z - w * y) * s, 2 * (x * y - w * z) * s,
                          (w * w - x * x + y * y - z * z) * s, 2 * (y * z + w * x) * s,
                          2 * (x * z + w * y) * s, 2 * (y * z - w * x) * s,
                          (w * w - x * x - y * y + z * z) * s};
  return ellipsoid(radii, axes, kAxesTol, q);
}

template <bool F>
PW85_ALWAYS_INLINE Status quat_body(Vec3 const &radii, double const quat[4], Sym3 &q) noexcept {
  for (int k = 0; k < kDim; ++k)
    if (!(radii[k] > 0.0)) return kNotSpd;
  double const w = quat[0], x = quat[1], y = quat[2], z = quat[3];
  DD const ww = sq<F>(w), xx = sq<F>(x), yy = sq<F>(y), zz = sq<F>(z);
  DD const n2 = dd::add_sloppy(dd::add_sloppy(ww, xx), dd::add_sloppy(yy, zz));
  if (!(std::fabs(n2.hi - 1.0) <= kQuatTol)) return kNotOrthonormal;
  for (int k = 0; k < kDim; ++k) {
    double const a2 = radii[k] * radii[k];
    if (!(a2 >= kMinNormal && a2 <= kMaxDouble)) return kRange;
  }
  DD const xy = prod<F>(x, y), xz = prod<F>(x, z), yz = prod<F>(y, z);
  DD const wx = prod<F>(w, x), wy = prod<F>(w, y), wz = prod<F>(w, z);
  auto const sum = [](DD a, DD b) { return dd::add_sloppy(a, b); };
  auto const dif = [](DD a, DD b) { return dd::sub_sloppy(a, b); };
  DD const m[3][3] = {
      {dif(sum(ww, xx), sum(yy, zz)), twice(dif(xy, wz)), twice(sum(xz, wy))},
      {twice(sum(xy, wz)), dif(sum(ww, yy), sum(xx, zz)), twice(dif(yz, wx))},
      {twice(dif(xz, wy)), twice(sum(yz, wx)), dif(sum(ww, zz), sum(xx, yy))}};
  int const e = max_exponent(radii.x, kDim);
  Vec3 scaled_radii;
  scale_by_power_of_two(radii.x, scaled_radii.x, kDim, -e);
  DD a2[3];
  for (int k = 0; k < kDim; ++k) a2[k] = sq<F>(scaled_radii[k]);
  // A radius^2 below 2^-900 of the largest underflows in the double-double
  // sums of the scaled frame: then the rotation matrix of quat in double,
  // and the sums of ellipsoid() (ellipsoid.cpp; radii 2^500, 2^-500, 1 with
  // quat = 1 give the exact diagonal).
  for (int k = 0; k < kDim; ++k)
    if (a2[k].hi < 0x1p-900) return quat_by_rotation(radii, quat, n2.hi, q);
  // Median of the three a_k² (by their leading parts; ties pick any).
  int const lo = a2[0].hi <= a2[1].hi ? 0 : 1, hi = 1 - lo;
  int const med = a2[2].hi <= a2[lo].hi ? lo : (a2[2].hi >= a2[hi].hi ? hi : 2);
  DD const s = a2[med];
  DD d[3];
  for (int k = 0; k < kDim; ++k) d[k] = dd::sub_sloppy(a2[k], s);
  DD const inv = dd::recip<F>(n2);
  DD const inv2 = dd::mul<F>(inv, inv);
  Sym3 scaled;
  int idx = 0;
  for (int i = 0; i < kDim; ++i) {
    for (int j = i; j < kDim; ++j, ++idx) {
      DD acc{0.0, 0.0};
      for (int k = 0; k < kDim; ++k) {
        if (d[k].hi == 0.0) continue;
        acc = dd::add_sloppy(acc, dd::mul<F>(d[k], dd::mul<F>(m[i][k], m[j][k])));
      }
      acc = dd::mul<F>(acc, inv2);
      if (i == j) acc = dd::add_sloppy(acc, s);
      scaled[idx] = dd::to_double(acc);
    }
  }
  Sym3 out;
  scale_by_power_of_two(scaled.a, out.a, kSym, 2 * e);
  // Radii so different that Q rounded to double is not positive definite:
  // not representable (kRange, as ellipsoid() in ellipsoid.cpp).
  if (!positive_definite(out.a)) return kRange;
  q = out;
  return kOk;
}

Status quat_portable(Vec3 const &radii, double const quat[4], Sym3 &q) noexcept {
  return quat_body<kStaticFma>(radii, quat, q);
}
constexpr OrientationKernels kOrientation_portable = {quat_portable};

#if PW85_ISA_FMA
PW85_TARGET_FMA Status quat_fma(Vec3 const &radii, double const quat[4], Sym3 &q) noexcept {
  return quat_body<true>(radii, quat, q);
}
constexpr OrientationKernels kOrientation_fma = {quat_fma};
#endif

}  // namespace

const OrientationKernels orientation_kernels[kVariantCount] = {
    kOrientation_portable, PW85_IF_FMA(kOrientation_fma, kOrientation_portable),
    PW85_IF_FMA(kOrientation_fma, kOrientation_portable),
    PW85_IF_FMA(kOrientation_fma, kOrientation_portable)};

Status ellipsoid_quat(Vec3 const &radii, double const quat[4], Sym3 &q) noexcept {
  return kernels().orientation->ellipsoid_quat(radii, quat, q);
}

namespace {

// (O3) One Jacobi rotation in the plane (p, r) (Golub and Van Loan, Matrix
// Computations, 4th ed., algorithms 8.5.1-8.5.2): with
// tau = (a_rr − a_pp) / (2 a_pr), t = sign(tau) / (|tau| + sqrt(1 + tau²)),
// c = 1 / sqrt(1 + t²), s = t c, A <- J^T A J zeroes a_pr and V <- V J.
void rotate(double a[3][3], double v[3][3], int p, int r) noexcept {
  double const apr = a[p][r];
  double const tau = (a[r][r] - a[p][p]) / (2.0 * apr);
  double t;
  if (std::fabs(tau) > 0x1p500)
    t = 0.5 / tau;  // tau² would overflow; t = 1/(2 tau) to within u
  else
    t = (tau >= 0.0 ? 1.0 : -1.0) / (std::fabs(tau) + std::sqrt(1.0 + tau * tau));
  // Updates as corrections, x + s (...), with tau' = s / (1 + c) (1 - c = s tau'),
  // small in the late sweeps where s is small (Rutishauser).
  double const c = 1.0 / std::sqrt(1.0 + t * t), s = t * c, tr = s / (1.0 + c);
  a[p][p] -= t * apr;
  a[r][r] += t * apr;
  a[p][r] = a[r][p] = 0.0;
  int const o = 3 - p - r;  // the third index
  double const gp = a[o][p], gr = a[o][r];
  a[o][p] = a[p][o] = gp - s * (gr + tr * gp);
  a[o][r] = a[r][o] = gr + s * (gp - tr * gr);
  for (int i = 0; i < kDim; ++i) {
    double const vp = v[i][p], vr = v[i][r];
    v[i][p] = vp - s * (vr + tr * vp);
    v[i][r] = vr + s * (vp - tr * vr);
  }
}

// (O4) The unit quaternion (w, x, y, z) of a proper rotation R (the inverse
// of (O1), Shepperd, J. Guidance Control 1(3), 223, 1978): the largest of
// 4w² = 1 + tr R, 4x² = 1 + R00 − R11 − R22, ... is taken by a square root,
// the others from the sums and differences of off-diagonal pairs,
// 4wx = R21 − R12, 4xy = R01 + R10, ...; then w >= 0 (when w = 0: the first
// non-zero of x, y, z positive) and the result normalised.
void quaternion_of(double const r[3][3], double out[4]) noexcept {
  double const tr = r[0][0] + r[1][1] + r[2][2];
  double w, x, y, z;
  if (tr >= r[0][0] && tr >= r[1][1] && tr >= r[2][2]) {
    w = 0.5 * std::sqrt(1.0 + tr);
    double const f = 0.25 / w;
    x = (r[2][1] - r[1][2]) * f;
    y = (r[0][2] - r[2][0]) * f;
    z = (r[1][0] - r[0][1]) * f;
  } else if (r[0][0] >= r[1][1] && r[0][0] >= r[2][2]) {
    x = 0.5 * std::sqrt(1.0 + r[0][0] - r[1][1] - r[2][2]);
    double const f = 0.25 / x;
    w = (r[2][1] - r[1][2]) * f;
    y = (r[0][1] + r[1][0]) * f;
    z = (r[0][2] + r[2][0]) * f;
  } else if (r[1][1] >= r[2][2]) {
    y = 0.5 * std::sqrt(1.0 - r[0][0] + r[1][1] - r[2][2]);
    double const f = 0.25 / y;
    w = (r[0][2] - r[2][0]) * f;
    x = (r[0][1] + r[1][0]) * f;
    z = (r[1][2] + r[2][1]) * f;
  } else {
    z = 0.5 * std::sqrt(1.0 - r[0][0] - r[1][1] + r[2][2]);
    double const f = 0.25 / z;
    w = (r[1][0] - r[0][1]) * f;
    x = (r[0][2] + r[2][0]) * f;
    y = (r[1][2] + r[2][1]) * f;
  }
  bool const flip =
      w < 0.0 || (w == 0.0 && (x < 0.0 || (x == 0.0 && (y < 0.0 || (y == 0.0 && z < 0.0)))));
  double const n = (flip ? -1.0 : 1.0) / std::sqrt(w * w + x * x + y * y + z * z);
  out[0] = w * n;
  out[1] = x * n;
  out[2] = y * n;
  out[3] = z * n;
}

constexpr int kMaxSweeps = 32;

}  // namespace

// Cyclic Jacobi on Q scaled by 2^-e (e even, exact): rotations in the planes
// (0,1), (0,2), (1,2) until every off-diagonal a_pr is at most
// u sqrt(a_pp a_rr) (then set to 0: below the rounding of the diagonal,
// Demmel and Veselic, SIAM J. Matrix Anal. Appl. 13(4), 1992). The diagonal
// holds the eigenvalues a_k², V's columns the axes; sorted ascending, then
// columns 0 and 1 with their largest-magnitude component positive, column 2
// negated if needed so that det V = +1. Repeated eigenvalues: V is the
// basis the rotations reach (Q diagonal: a permutation of the identity,
// signs as above; a sphere gives the identity).
Status ellipsoid_axes(Sym3 const &q, Vec3 &radii, double rot[9], double quat[4]) noexcept {
  int e = max_exponent(q.a, kSym);
  e += e & 1;
  Sym3 scaled;
  scale_by_power_of_two(q.a, scaled.a, kSym, -e);
  double a[3][3], v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  int idx = 0;
  for (int i = 0; i < kDim; ++i)
    for (int j = i; j < kDim; ++j, ++idx) a[i][j] = a[j][i] = scaled[idx];
  static constexpr int kPlanes[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  Status status = kNoConvergence;
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    int rotations = 0;
    for (auto const &pl : kPlanes) {
      int const p = pl[0], r = pl[1];
      if (a[p][r] == 0.0) continue;
      double const scale = std::sqrt(std::fabs(a[p][p])) * std::sqrt(std::fabs(a[r][r]));
      if (std::fabs(a[p][r]) <= kU * scale) {
        a[p][r] = a[r][p] = 0.0;
        continue;
      }
      rotate(a, v, p, r);
      ++rotations;
    }
    if (rotations == 0) {
      status = kOk;
      break;
    }
  }
  int ord[3] = {0, 1, 2};  // ascending eigenvalues, stable
  for (int i = 1; i < kDim; ++i)
    for (int j = i; j > 0 && a[ord[j]][ord[j]] < a[ord[j - 1]][ord[j - 1]]; --j) {
      int const t = ord[j];
      ord[j] = ord[j - 1];
      ord[j - 1] = t;
    }
  double r[3][3];
  for (int k = 0; k < kDim; ++k) {
    double const lam = a[ord[k]][ord[k]];
    if (!(lam > 0.0)) return kInaccurate;  // below the accuracy of the sweeps
    radii[k] = std::ldexp(std::sqrt(lam), e / 2);
    for (int i = 0; i < kDim; ++i) r[i][k] = v[i][ord[k]];
  }
  for (int k = 0; k < 2; ++k) {
    int big = 0;
    for (int i = 1; i < kDim; ++i)
      if (std::fabs(r[i][k]) > std::fabs(r[big][k])) big = i;
    if (r[big][k] < 0.0)
      for (int i = 0; i < kDim; ++i) r[i][k] = -r[i][k];
  }
  double const det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
                     r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                     r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
  if (det < 0.0)
    for (int i = 0; i < kDim; ++i) r[i][2] = -r[i][2];
  double qt[4];
  quaternion_of(r, qt);
  // The outputs must give a q back through both constructors (their checks:
  // orthonormal axes, radii^2 in range, the rebuilt Q positive definite);
  // a smallest eigenvalue near the accuracy of the sweeps may not.
  double axes[9];
  for (int i = 0; i < kDim; ++i)
    for (int j = 0; j < kDim; ++j) axes[3 * j + i] = r[i][j];
  Sym3 back;
  if (ellipsoid(radii, axes, kAxesTol, back) != kOk || ellipsoid_quat(radii, qt, back) != kOk)
    return kInaccurate;
  if (rot != nullptr)
    for (int i = 0; i < kDim; ++i)
      for (int j = 0; j < kDim; ++j) rot[3 * i + j] = r[i][j];
  if (quat != nullptr)
    for (int i = 0; i < 4; ++i) quat[i] = qt[i];
  return status;
}

}  // namespace pw85
