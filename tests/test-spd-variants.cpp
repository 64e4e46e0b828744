/* One positive-definiteness decision in every call and on every
 * instruction-set variant (src/core/common/spd.hpp; docs/api.md, "Positive
 * definiteness"). A fixed adversarial set of matrices -- the nearly
 * singular ones where a floating-point test may go either way: det = 0 to
 * within a few ulps of one entry, rank-deficient products R diag(a^2) R^T
 * with a tiny radius, exactly singular sums of integer outer products, 2x2
 * minors at zero to a few ulps, the example of the
 * issue that found the CPU-dependent verdicts, copies scaled by 2^+-700 and
 * matrices whose entries span the double range -- each paired with a
 * well-conditioned matrix, is run through every call that validates a
 * matrix. The reference is independent of the library: the signs of the
 * leading principal minors in exact expansion arithmetic (error-free
 * products and sums, Shewchuk 1997), computed on the unscaled matrix.
 *
 * Checked: every call returns PW85_ERR_NOT_SPD exactly when the reference
 * says the matrix is not positive definite (pw85_overlap in both orders
 * (r, q1, q2) and (-r, q2, q1), pw85_overlap_pairs, the overlap lanes of
 * both widths called directly (x86-64-v3 and x86-64-v4 variants on an
 * AVX-512 machine), pw85_contact_function_method with every method and its
 * pairs form, pw85_contact_function, pw85_contact, pw85_dca, pw85_contact_time,
 * pw85_contact_derivatives and its pairs form, pw85_ellipsoid_axes, and the
 * 2D calls on the upper-left 2x2 block); the two overlap orders, the lanes
 * and the pairs form give the same verdict; the pairs forms the same status
 * as the one-pair calls. The program runs natively (the highest variant of
 * the CPU), under valgrind (spd-variants-valgrind: x86-64-v3 and FMA) and in
 * the isa_dispatch=false build (portable); it prints a digest of every
 * status and verdict, which .ci/run compares across the three. */
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <glib.h>

#include "overlap/overlap.hpp"
#include "pw85.h"

namespace {

// ---- Exact reference: signs of sums of products of doubles ----------------

void two_sum(double a, double b, double &s, double &e) {
  s = a + b;
  double const bb = s - a;
  e = (a - (s - bb)) + (b - bb);
}

// A nonoverlapping expansion in increasing magnitude (Shewchuk's
// GROW-EXPANSION, zeros kept): its sign is that of its last nonzero
// component. Exact while no product underflows or overflows (the set keeps
// entries in [2^-200, 2^200] or 0).
struct Expansion {
  double c[256];
  int n = 0;
  void grow(double b) {
    double q = b;
    for (int i = 0; i < n; ++i) {
      double s, e;
      two_sum(q, c[i], s, e);
      c[i] = e;
      q = s;
    }
    c[n++] = q;
  }
  // += sign * a * b * c exactly (four components).
  void add_product(double a, double b, double d, double sign) {
    double const p = a * b, pe = std::fma(a, b, -p);
    double const x = p * d, xe = std::fma(p, d, -x);
    double const y = pe * d, ye = std::fma(pe, d, -y);
    grow(sign * x);
    grow(sign * xe);
    grow(sign * y);
    grow(sign * ye);
  }
  int sign() const {
    for (int i = n - 1; i >= 0; --i)
      if (c[i] != 0.0) return c[i] > 0 ? 1 : -1;
    return 0;
  }
};

// Sylvester's criterion on the exact entries (Sym3 storage).
bool reference_spd(double const *a) {
  if (!(a[0] > 0.0)) return false;
  Expansion m2;
  m2.add_product(a[0], a[3], 1.0, 1.0);
  m2.add_product(a[1], a[1], 1.0, -1.0);
  if (m2.sign() <= 0) return false;
  Expansion m3;  // a00 (a11 a22 - a12^2) + a01 (a02 a12 - a01 a22) + a02 (a01 a12 - a02 a11)
  m3.add_product(a[0], a[3], a[5], 1.0);
  m3.add_product(a[0], a[4], a[4], -1.0);
  m3.add_product(a[1], a[2], a[4], 1.0);
  m3.add_product(a[1], a[1], a[5], -1.0);
  m3.add_product(a[2], a[1], a[4], 1.0);
  m3.add_product(a[2], a[2], a[3], -1.0);
  return m3.sign() > 0;
}

// The upper-left 2x2 block: a00 > 0 and a00 a11 - a01^2 > 0.
bool reference_spd_2d(double const *a) {
  if (!(a[0] > 0.0)) return false;
  Expansion m2;
  m2.add_product(a[0], a[3], 1.0, 1.0);
  m2.add_product(a[1], a[1], 1.0, -1.0);
  return m2.sign() > 0;
}

// ---- The adversarial set ---------------------------------------------------

struct Rng {
  std::uint64_t s;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform() { return (next() >> 11) * 0x1p-53; }  // [0, 1)
  double sym() { return 2.0 * uniform() - 1.0; }         // [-1, 1)
};

struct Matrix {
  double q[6];
  bool spd, spd_2d;  // the references
};

void push(std::vector<Matrix> &set, double const *q, bool spd, bool spd_2d) {
  Matrix m;
  for (int i = 0; i < 6; ++i) m.q[i] = q[i];
  m.spd = spd;
  m.spd_2d = spd_2d;
  set.push_back(m);
}

void push_ref(std::vector<Matrix> &set, double const *q) {
  push(set, q, reference_spd(q), reference_spd_2d(q));
}

// Rotation matrix from a random unit quaternion.
void random_rotation(Rng &g, double rot[3][3]) {
  double w, x, y, z, n;
  do {
    w = g.sym();
    x = g.sym();
    y = g.sym();
    z = g.sym();
    n = w * w + x * x + y * y + z * z;
  } while (n > 1.0 || n < 1e-3);
  n = std::sqrt(n);
  w /= n;
  x /= n;
  y /= n;
  z /= n;
  double const r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rot[i][j] = r[i][j];
}

std::vector<Matrix> adversarial_set() {
  std::vector<Matrix> set;
  Rng g{20240601u};
  // The example of the issue: det = +2.8e-35, positive definite exactly;
  // its L D L^T pivots in floating point decide either way.
  double const issue[6] = {0x1.3d309aa66da1cp-1, -0x1.b79b0ccb151b3p-2, -0x1.d0635705bd7b9p-3,
                           0x1.30a21b072a3bcp-2, 0x1.41ce80f19c03p-3,  0x1.53f2beafea01dp-4};
  push_ref(set, issue);
  // det = 0 to within a few ulps of a22: a22 solved from the other entries,
  // then moved by k ulps.
  for (int i = 0; i < 60; ++i) {
    double a[6];
    a[0] = 0.5 + g.uniform();
    a[3] = 0.5 + g.uniform();
    a[1] = 0.6 * g.sym() * std::sqrt(a[0] * a[3]);
    a[2] = g.sym();
    a[4] = g.sym();
    double const m2 = a[0] * a[3] - a[1] * a[1];
    double const a5 = (a[0] * a[4] * a[4] - 2 * a[1] * a[2] * a[4] + a[3] * a[2] * a[2]) / m2;
    for (int k = -4; k <= 4; ++k) {
      double x = a5;
      for (int j = 0; j < std::abs(k); ++j) x = std::nextafter(x, k > 0 ? 2.0 * a5 + 1 : -1.0);
      a[5] = x;
      push_ref(set, a);
    }
  }
  // R diag(a0^2, a1^2, a2^2) R^T in floating point, a2 / a0 from 2^-20 to
  // 2^-34: positive definite, singular or indefinite after rounding.
  for (int i = 0; i < 300; ++i) {
    double rot[3][3];
    random_rotation(g, rot);
    double const rad[3] = {0.5 + g.uniform(), 0.5 + g.uniform(),
                           std::ldexp(0.5 + g.uniform(), -20 - (i % 15))};
    double q[6];
    int const idx[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
    for (int k = 0; k < 6; ++k) {
      double s = 0.0;
      for (int m = 0; m < 3; ++m)
        s += rot[idx[k][0]][m] * (rad[m] * rad[m]) * rot[idx[k][1]][m];
      q[k] = s;
    }
    push_ref(set, q);
  }
  // 2x2 minor at zero to a few ulps: a11 = a01^2 / a00 moved by k ulps.
  for (int i = 0; i < 30; ++i) {
    double a[6];
    a[0] = 0.5 + g.uniform();
    a[1] = g.sym();
    a[2] = 0.1 * g.sym();
    a[4] = 0.1 * g.sym();
    a[5] = 1.0 + g.uniform();
    double const a3 = a[1] * a[1] / a[0];
    for (int k = -2; k <= 2; ++k) {
      double x = a3;
      for (int j = 0; j < std::abs(k); ++j) x = std::nextafter(x, k > 0 ? 2.0 : -1.0);
      a[3] = x;
      push_ref(set, a);
    }
  }
  // Exactly singular: v v^T + w w^T for integer vectors (exact entries,
  // det = 0, m2 > 0 unless v, w are parallel), and the same plus 1 on one
  // diagonal entry (det > 0: positive definite, tiny smallest eigenvalue
  // relative to the largest for long vectors).
  for (int i = 0; i < 40; ++i) {
    double v[3], w[3];
    for (int k = 0; k < 3; ++k) {
      v[k] = std::floor(2000.0 * g.uniform()) - 1000.0;
      w[k] = std::floor(2000.0 * g.uniform()) - 1000.0;
    }
    double q[6] = {v[0] * v[0] + w[0] * w[0], v[0] * v[1] + w[0] * w[1],
                   v[0] * v[2] + w[0] * w[2], v[1] * v[1] + w[1] * w[1],
                   v[1] * v[2] + w[1] * w[2], v[2] * v[2] + w[2] * w[2]};
    push_ref(set, q);
    q[5 - 2 * (i % 3) - (i % 3 == 2 ? 1 : 0)] += 1.0;
    push_ref(set, q);
  }
  // Copies scaled by 2^700 and 2^-700 (exact scalings, same references).
  std::size_t const n0 = set.size();
  for (std::size_t i = 0; i < n0; i += 7)
    for (int e : {700, -700}) {
      double q[6];
      for (int k = 0; k < 6; ++k) q[k] = std::ldexp(set[i].q[k], e);
      push(set, q, set[i].spd, set[i].spd_2d);
    }
  // Entries spanning the double range, references by hand.
  double const wide_spd[6] = {DBL_MAX, 0.0, 0.0, 4.9e-324, 0.0, 1.0};
  push(set, wide_spd, true, true);
  double const tiny_spd[6] = {4.9e-324, 0.0, 0.0, 4.9e-324, 0.0, 4.9e-324};
  push(set, tiny_spd, true, true);
  double const singular[6] = {1.0, 1.0, 0.0, 1.0, 0.0, 1.0};
  push(set, singular, false, false);
  double const last_zero[6] = {1.0, 0.0, 0.0, 1.0, 0.0, 0.0};
  push(set, last_zero, false, true);
  double const huge_singular[6] = {0x1p1000, 0x1p1000, 0.0, 0x1p1000, 0.0, 1.0};
  push(set, huge_singular, false, false);
  double const negative[6] = {1.0, 0.0, 0.0, -4.9e-324, 0.0, 1.0};
  push(set, negative, false, false);
  return set;
}

std::vector<Matrix> const &the_set() {
  static std::vector<Matrix> const set = adversarial_set();
  return set;
}

// The partner of every matrix, and the centre offsets (one overlapping,
// one apart, for a unit-sized matrix).
double const kPartner[6] = {1.0, 0.1, -0.2, 2.0, 0.3, 0.5};
double const kOffsets[2][3] = {{0.3, -0.2, 0.1}, {1.7, 2.1, -1.3}};

// FNV-1a over every status and verdict, in order. With PW85_SPD_DUMP set to
// a file name, each value is also written there, one per line with the
// call and matrix, to find where two digests part.
std::uint64_t digest = 0xcbf29ce484222325ULL;
std::FILE *dump = nullptr;
void mix(int v, char const *call = "", std::size_t k = 0) {
  digest ^= static_cast<std::uint32_t>(v);
  digest *= 0x100000001b3ULL;
  if (dump != nullptr) std::fprintf(dump, "%s %zu %d\n", call, k, v);
}

// Offsets scaled to the matrix: sqrt of its largest diagonal entry.
void offset_for(Matrix const &m, int j, double r[3]) {
  double d = std::fmax(std::fabs(m.q[0]), std::fmax(std::fabs(m.q[3]), std::fabs(m.q[5])));
  double const s = std::isfinite(std::sqrt(d)) && d > 0 ? std::sqrt(d) : 1.0;
  for (int i = 0; i < 3; ++i) r[i] = kOffsets[j][i] * s;
}

// status == NOT_SPD exactly when the reference refuses; counted per call.
int check_refusal(char const *call, int status, bool spd, std::size_t k) {
  mix(status, call, k);
  bool const refused = status == PW85_ERR_NOT_SPD;
  if (refused == !spd) return 0;
  g_test_message("%s, matrix %zu: status %d, reference %s", call, k, status,
                 spd ? "positive definite" : "not positive definite");
  return 1;
}

void test_overlap(void) {
  auto const &set = the_set();
  int bad = 0, lanes_bad = 0, orders = 0, both = 0;
  for (std::size_t k = 0; k < set.size(); ++k) {
    Matrix const &m = set[k];
    for (int j = 0; j < 2; ++j) {
      double r[3], nr[3];
      offset_for(m, j, r);
      for (int i = 0; i < 3; ++i) nr[i] = -r[i];
      int const a = pw85_overlap(r, m.q, kPartner);
      int const b = pw85_overlap(nr, kPartner, m.q);
      bad += check_refusal("pw85_overlap(r, q, p)", a, m.spd, k);
      bad += check_refusal("pw85_overlap(-r, p, q)", b, m.spd, k);
      mix(a, "pw85_overlap verdict", k);
      if (a != b) {
        g_test_message("matrix %zu: pw85_overlap %d, reversed %d", k, a, b);
        orders++;
      }
      int const c = pw85_overlap(r, m.q, m.q);  // both matrices the nearly singular one
      bad += check_refusal("pw85_overlap(r, q, q)", c, m.spd, k);
      both += m.spd && !(c == 0 || c == 1);
      // The lanes of both widths, the pair in every lane: a decided lane
      // has pw85_overlap's verdict; a matrix not positive definite is
      // never decided.
      double const *rp[8], *q1p[8], *q2p[8];
      for (int l = 0; l < 8; ++l) {
        rp[l] = r;
        q1p[l] = m.q;
        q2p[l] = kPartner;
      }
      int v4[4], v8[8];
      pw85::overlap_lanes<pw85::kOverlapLanes>(rp, q1p, q2p, v4);
      pw85::overlap_lanes<pw85::kOverlapLanesV4>(rp, q1p, q2p, v8);
      for (int l = 0; l < 8; ++l) {
        int const v = l < 4 ? v4[l] : v8[l];
        mix(v, "lanes", k);
        if (v >= 0 && v != a) {
          g_test_message("matrix %zu: lane %d verdict %d, pw85_overlap %d", k, l, v, a);
          lanes_bad++;
        }
      }
    }
  }
  g_test_message("%zu matrices: %d refusals differing from the reference, %d order "
                 "mismatches, %d lane mismatches",
                 set.size(), bad, orders, lanes_bad);
  g_assert_cmpint(bad, ==, 0);
  g_assert_cmpint(orders, ==, 0);
  g_assert_cmpint(lanes_bad, ==, 0);
  g_assert_cmpint(both, ==, 0);
}

// The set as per-pair arrays: pair k = (offset k % 2, matrix k, the partner).
struct PairArrays {
  long long m;
  std::vector<double> r, q1, q2;
};

PairArrays pair_arrays() {
  auto const &set = the_set();
  long long const m = static_cast<long long>(set.size());
  PairArrays p{m, std::vector<double>(3 * m), std::vector<double>(6 * m),
               std::vector<double>(6 * m)};
  for (long long k = 0; k < m; ++k) {
    offset_for(set[k], static_cast<int>(k % 2), &p.r[3 * k]);
    for (int i = 0; i < 6; ++i) {
      p.q1[6 * k + i] = set[k].q[i];
      p.q2[6 * k + i] = kPartner[i];
    }
  }
  return p;
}

void test_overlap_pairs(void) {
  auto const &set = the_set();
  PairArrays const p = pair_arrays();
  long long const m = p.m;
  std::vector<double> const &r = p.r, &q1 = p.q1, &q2 = p.q2;
  std::vector<int> ov(m), st(m);
  pw85_overlap_pairs(m, r.data(), q1.data(), q2.data(), ov.data(), st.data(), 1);
  int bad = 0, differ = 0;
  for (long long k = 0; k < m; ++k) {
    bad += check_refusal("pw85_overlap_pairs", st[k], set[k].spd, static_cast<std::size_t>(k));
    differ += ov[k] != pw85_overlap(&r[3 * k], &q1[6 * k], &q2[6 * k]);
  }
  g_assert_cmpint(bad, ==, 0);
  g_assert_cmpint(differ, ==, 0);
}

void test_methods(void) {
  auto const &set = the_set();
  int const methods[5] = {PW85_METHOD_DEFAULT, PW85_METHOD_BRENT, PW85_METHOD_NEWTON,
                          PW85_METHOD_RATIONAL, PW85_METHOD_ZHENG};
  char const *names[5] = {"DEFAULT", "BRENT", "NEWTON", "RATIONAL", "ZHENG"};
  int bad[5] = {0, 0, 0, 0, 0};
  PairArrays p = pair_arrays();
  long long const m = p.m;
  std::vector<double> &r = p.r, &q1 = p.q1, &q2 = p.q2;
  for (int t = 0; t < 5; ++t) {
    std::vector<pw85_result> res(m);
    std::vector<int> st(m);
    pw85_contact_function_pairs(m, r.data(), q1.data(), q2.data(), methods[t], res.data(),
                                st.data(), 1);
    for (long long k = 0; k < m; ++k) {
      pw85_result one;
      int const s = pw85_contact_function_method(&r[3 * k], &q1[6 * k], &q2[6 * k],
                                                 methods[t], &one);
      bad[t] += check_refusal(names[t], s, set[k].spd, static_cast<std::size_t>(k));
      g_assert_cmpint(st[k], ==, s);
      // reversed pair: the same status
      double nr[3] = {-r[3 * k], -r[3 * k + 1], -r[3 * k + 2]};
      int const s2 =
          pw85_contact_function_method(nr, &q2[6 * k], &q1[6 * k], methods[t], &one);
      bad[t] += check_refusal(names[t], s2, set[k].spd, static_cast<std::size_t>(k));
    }
  }
  for (int t = 0; t < 5; ++t) {
    g_test_message("%s: %d refusals differing from the reference", names[t], bad[t]);
    g_assert_cmpint(bad[t], ==, 0);
  }
}

void test_other_calls(void) {
  auto const &set = the_set();
  enum { kCf, kContact, kDcaDefault, kDcaBrent, kDcaZheng, kTime, kDeriv, kDerivPairs,
         kAxes, kDca2d, kCf2d, kCalls };
  char const *names[kCalls] = {"pw85_contact_function", "pw85_contact", "pw85_dca DEFAULT",
                               "pw85_dca BRENT", "pw85_dca ZHENG", "pw85_contact_time",
                               "pw85_contact_derivatives", "pw85_contact_derivatives_pairs",
                               "pw85_ellipsoid_axes", "pw85_dca_2d",
                               "pw85_contact_function_2d"};
  int bad[kCalls] = {};
  double const zero[3] = {0.0, 0.0, 0.0};
  double const p2[3] = {kPartner[0], kPartner[1], kPartner[3]};
  for (std::size_t k = 0; k < set.size(); ++k) {
    Matrix const &m = set[k];
    double r[3];
    offset_for(m, static_cast<int>(k % 2), r);
    double out[2], d;
    pw85_contact_t c;
    pw85_derivatives_t dv, dvp;
    bad[kCf] += check_refusal(names[kCf], pw85_contact_function(r, m.q, kPartner, out), m.spd, k);
    bad[kContact] += check_refusal(names[kContact], pw85_contact(r, m.q, kPartner, &c), m.spd, k);
    bad[kDcaDefault] += check_refusal(
        names[kDcaDefault], pw85_dca(r, m.q, kPartner, PW85_METHOD_DEFAULT, &d), m.spd, k);
    bad[kDcaBrent] += check_refusal(names[kDcaBrent],
                                    pw85_dca(r, m.q, kPartner, PW85_METHOD_BRENT, &d), m.spd, k);
    bad[kDcaZheng] += check_refusal(names[kDcaZheng],
                                    pw85_dca(r, m.q, kPartner, PW85_METHOD_ZHENG, &d), m.spd, k);
    double const v[3] = {-r[0], -r[1], -r[2]};
    bad[kTime] += check_refusal(names[kTime],
                                pw85_contact_time(r, v, m.q, zero, kPartner, zero, 1.0, &d),
                                m.spd, k);
    int const sd = pw85_contact_derivatives(r, m.q, kPartner, &dv);
    bad[kDeriv] += check_refusal(names[kDeriv], sd, m.spd, k);
    int sp;
    pw85_contact_derivatives_pairs(1, r, m.q, kPartner, &dvp, &sp, 1);
    bad[kDerivPairs] += check_refusal(names[kDerivPairs], sp, m.spd, k);
    g_assert_cmpint(sp, ==, sd);
    double radii[3], rot[9], quat[4];
    bad[kAxes] += check_refusal(names[kAxes], pw85_ellipsoid_axes(m.q, radii, rot, quat),
                                m.spd, k);
    double const q2d[3] = {m.q[0], m.q[1], m.q[3]};
    double const r2[2] = {r[0], r[1] != 0.0 ? r[1] : 1.0};
    bad[kDca2d] += check_refusal(names[kDca2d], pw85_dca_2d(r2, q2d, p2, &d), m.spd_2d, k);
    bad[kCf2d] += check_refusal(names[kCf2d], pw85_contact_function_2d(r2, q2d, p2, out),
                                m.spd_2d, k);
  }
  int total = 0;
  for (int t = 0; t < kCalls; ++t) {
    g_test_message("%s: %d refusals differing from the reference", names[t], bad[t]);
    total += bad[t];
  }
  g_assert_cmpint(total, ==, 0);
}

void test_set(void) {
  // The set is adversarial: both answers common, and the issue's example
  // positive definite.
  auto const &set = the_set();
  int spd = 0;
  for (auto const &m : set) spd += m.spd;
  g_test_message("%zu matrices, %d positive definite", set.size(), spd);
  g_assert_true(set[0].spd);
  g_assert_cmpint(spd, >, static_cast<int>(set.size()) / 4);
  g_assert_cmpint(spd, <, 3 * static_cast<int>(set.size()) / 4);
}

}  // namespace

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  // Every count is reported, even after a failed check.
  g_test_set_nonfatal_assertions();
  if (char const *path = std::getenv("PW85_SPD_DUMP")) dump = std::fopen(path, "w");
  g_test_add_func("/positive_definite/set", test_set);
  g_test_add_func("/positive_definite/pw85_overlap", test_overlap);
  g_test_add_func("/positive_definite/pw85_overlap_pairs", test_overlap_pairs);
  g_test_add_func("/positive_definite/pw85_contact_function_method", test_methods);
  g_test_add_func("/positive_definite/other_calls", test_other_calls);
  int const status = g_test_run();
  // The digest of every status and verdict, for the comparison across
  // builds and variants (.ci/run).
  std::printf("# spd-variants digest %016llx\n", static_cast<unsigned long long>(digest));
  if (dump != nullptr) std::fclose(dump);
  return status;
}
