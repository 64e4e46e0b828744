// Benchmark of the distance of closest approach (docs/dca.md).
// NOT a test: built by meson, never run by `meson test`, not installed.
//
//   bench_dca [--n N] [--reps R] [--seed S] OUT.csv
//
// For each of the four classes of the reference data (three semi-axes
// log-uniform in [0.5, 2], [0.1, 10], [0.01, 100], [0.001, 1000], uniformly
// random orientations, direction u uniform on the sphere), N random pairs:
//  - reference d = 1 / sqrt(mu2(u)), mu2 computed in __float128 from the
//    double inputs (bisection on f', f and f' through the adjugate of
//    Q(lambda) in __float128) -- independent of the library;
//  - timed: pw85_dca with PW85_METHOD_ZHENG (plane rotation), and the
//    contact-function routes pw85_dca with PW85_METHOD_BRENT and
//    PW85_METHOD_DEFAULT (d = 1 / sqrt(F(u))); ns per call = thread CPU
//    time of one pass over the N pairs / N; median (min, max) over R passes;
//  - errors: max / median relative error of d, number of pairs above 1e-9,
//    and the mean / max number of plane evaluations of the Zheng method.
// Also the 2D functions (pw85_dca_2d, 1 / sqrt(pw85_contact_function_2d))
// on random ellipse pairs of the same classes, reference in __float128.
// Prints a table, writes OUT.csv.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <quadmath.h>
#include <time.h>

#include "bench_common.hpp"
#include "pw85.h"

namespace {

using quad = __float128;

// ---- random pairs (xorshift64*, reproducible) ------------------------------
struct Rng {
  std::uint64_t s;
  double uniform() {
    s ^= s >> 12;
    s ^= s << 25;
    s ^= s >> 27;
    return double((s * 2685821657736338717ULL) >> 11) * 0x1p-53;
  }
  double normal() {
    double u1 = uniform(), u2 = uniform();
    if (u1 < 1e-300) u1 = 1e-300;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }
};

const double kClassLo[4] = {0.5, 0.1, 0.01, 0.001};
const double kClassHi[4] = {2.0, 10.0, 100.0, 1000.0};

// Q = R^T diag(a^2) R for a random rotation R (from a unit quaternion),
// accumulated in __float128, rounded once.
void random_q(Rng &rng, int cls, double q[6]) {
  double w[4], n = 0.0;
  for (double &x : w) {
    x = rng.normal();
    n += x * x;
  }
  n = std::sqrt(n);
  double const a = w[0] / n, b = w[1] / n, c = w[2] / n, d = w[3] / n;
  double const r[9] = {a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c),
                       2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b),
                       2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d};
  double radii[3];
  for (double &x : radii)
    x = std::exp(std::log(kClassLo[cls]) +
                 (std::log(kClassHi[cls]) - std::log(kClassLo[cls])) * rng.uniform());
  int idx = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j, ++idx) {
      quad s = 0;
      for (int k = 0; k < 3; ++k) s += (quad)radii[k] * radii[k] * r[3 * k + i] * r[3 * k + j];
      q[idx] = (double)s;
    }
}

void random_unit(Rng &rng, double *u, int n) {
  double s = 0.0;
  for (int i = 0; i < n; ++i) {
    u[i] = rng.normal();
    s += u[i] * u[i];
  }
  s = std::sqrt(s);
  for (int i = 0; i < n; ++i) u[i] /= s;
}

// ---- __float128 references ------------------------------------------------
// f'(lambda) and f(lambda) for n = 2 or 3, s = adj(Q) r / det(Q).
void f_df_quad(quad l, int n, double const *r, double const *q1, double const *q2, quad &f,
               quad &df) {
  int const m = n == 3 ? 6 : 3;
  quad q[6], dq[6], rr[3];
  for (int i = 0; i < m; ++i) {
    q[i] = (1 - l) * (quad)q1[i] + l * (quad)q2[i];
    dq[i] = (quad)q2[i] - (quad)q1[i];
  }
  for (int i = 0; i < n; ++i) rr[i] = r[i];
  quad s[3];
  if (n == 3) {
    quad const c00 = q[3] * q[5] - q[4] * q[4], c01 = q[2] * q[4] - q[1] * q[5],
               c02 = q[1] * q[4] - q[2] * q[3], c11 = q[0] * q[5] - q[2] * q[2],
               c12 = q[1] * q[2] - q[0] * q[4], c22 = q[0] * q[3] - q[1] * q[1];
    quad const det = q[0] * c00 + q[1] * c01 + q[2] * c02;
    s[0] = (c00 * rr[0] + c01 * rr[1] + c02 * rr[2]) / det;
    s[1] = (c01 * rr[0] + c11 * rr[1] + c12 * rr[2]) / det;
    s[2] = (c02 * rr[0] + c12 * rr[1] + c22 * rr[2]) / det;
    quad const rs = rr[0] * s[0] + rr[1] * s[1] + rr[2] * s[2];
    quad const ds0 = dq[0] * s[0] + dq[1] * s[1] + dq[2] * s[2];
    quad const ds1 = dq[1] * s[0] + dq[3] * s[1] + dq[4] * s[2];
    quad const ds2 = dq[2] * s[0] + dq[4] * s[1] + dq[5] * s[2];
    quad const sds = s[0] * ds0 + s[1] * ds1 + s[2] * ds2;
    f = l * (1 - l) * rs;
    df = (1 - 2 * l) * rs - l * (1 - l) * sds;
  } else {
    quad const det = q[0] * q[2] - q[1] * q[1];
    s[0] = (q[2] * rr[0] - q[1] * rr[1]) / det;
    s[1] = (-q[1] * rr[0] + q[0] * rr[1]) / det;
    quad const rs = rr[0] * s[0] + rr[1] * s[1];
    quad const sds = dq[0] * s[0] * s[0] + 2 * dq[1] * s[0] * s[1] + dq[2] * s[1] * s[1];
    f = l * (1 - l) * rs;
    df = (1 - 2 * l) * rs - l * (1 - l) * sds;
  }
}

// d = 1 / sqrt(max f): f is concave, bisection on f' (110 halvings: lambda
// to 1e-33, f stationary there).
double reference_d(int n, double const *u, double const *q1, double const *q2) {
  quad lo = 0, hi = 1, f, df;
  for (int i = 0; i < 110; ++i) {
    quad const m = (lo + hi) / 2;
    f_df_quad(m, n, u, q1, q2, f, df);
    if (df > 0)
      lo = m;
    else
      hi = m;
  }
  f_df_quad((lo + hi) / 2, n, u, q1, q2, f, df);
  return (double)(1 / sqrtq(f));
}

// ---- timing ---------------------------------------------------------------
double thread_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

struct Pair {
  double u[3], q1[6], q2[6], dref;
};

struct Row {
  std::string dim, method;
  int cls;
  double ns_med, ns_min, ns_max, err_max, err_med;
  int above, bad_status;
  double ev_mean;
  int ev_max;
};

using DcaFn = int (*)(Pair const &p, double *d, int *ev);

int zheng(Pair const &p, double *d, int *ev) { return pw85_dca_ex(p.u, p.q1, p.q2, 0.0, d, ev); }
int brent(Pair const &p, double *d, int *ev) {
  *ev = 0;
  return pw85_dca(p.u, p.q1, p.q2, PW85_METHOD_BRENT, d);
}
int dflt(Pair const &p, double *d, int *ev) {
  *ev = 0;
  return pw85_dca(p.u, p.q1, p.q2, PW85_METHOD_DEFAULT, d);
}
int dca2d(Pair const &p, double *d, int *ev) {
  *ev = 0;
  return pw85_dca_2d(p.u, p.q1, p.q2, d);
}
int cf2d(Pair const &p, double *d, int *ev) {
  *ev = 0;
  double out[2];
  int const s = pw85_contact_function_2d(p.u, p.q1, p.q2, out);
  *d = 1.0 / std::sqrt(out[0]);
  return s;
}

Row run(char const *dim, char const *name, DcaFn fn, int cls, std::vector<Pair> const &pairs,
        int reps) {
  Row row;
  row.dim = dim;
  row.method = name;
  row.cls = cls;
  std::size_t const n = pairs.size();
  std::vector<double> d(n), err(n), times;
  std::vector<int> ev(n);
  std::vector<int> st(n);
  for (int r = 0; r < reps; ++r) {
    double const t0 = thread_seconds();
    for (std::size_t i = 0; i < n; ++i) st[i] = fn(pairs[i], &d[i], &ev[i]);
    times.push_back((thread_seconds() - t0) / n * 1e9);
  }
  std::sort(times.begin(), times.end());
  row.ns_med = times[times.size() / 2];
  row.ns_min = times.front();
  row.ns_max = times.back();
  row.above = row.bad_status = 0;
  row.ev_max = 0;
  double ev_sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    err[i] = std::fabs(d[i] - pairs[i].dref) / pairs[i].dref;
    if (!(err[i] <= 1e-9)) ++row.above;
    if (st[i] != PW85_OK) ++row.bad_status;
    ev_sum += ev[i];
    row.ev_max = std::max(row.ev_max, ev[i]);
  }
  row.ev_mean = ev_sum / n;
  row.err_max = *std::max_element(err.begin(), err.end(),
                                  [](double a, double b) { return !(a >= b); });
  std::nth_element(err.begin(), err.begin() + n / 2, err.end());
  row.err_med = err[n / 2];
  return row;
}

}  // namespace

int main(int argc, char **argv) {
  int n = 2000, reps = 7;
  std::uint64_t seed = 20081014;
  char const *out = nullptr;
  bool bad = false;
  for (int i = 1; i < argc; ++i) {
    if (int const k = bench::common_option(argc, argv, i, n, reps, seed))
      i += k - 1;
    else if (argv[i][0] == '-')
      bad = true;  // unknown option, or one missing its value
    else
      out = argv[i];
  }
  if (bad || out == nullptr || n <= 0 || reps <= 0) {
    std::fprintf(stderr, "usage: bench_dca [--n N] [--reps R] [--seed S] OUT.csv\n");
    return 2;
  }
  Rng rng{seed | 1};
  std::vector<Row> rows;
  for (int cls = 0; cls < 4; ++cls) {
    std::vector<Pair> p3(n), p2(n);
    for (Pair &p : p3) {
      random_q(rng, cls, p.q1);
      random_q(rng, cls, p.q2);
      random_unit(rng, p.u, 3);
      p.dref = reference_d(3, p.u, p.q1, p.q2);
    }
    for (Pair &p : p2) {
      for (double *q : {p.q1, p.q2}) {
        double const lo = std::log(kClassLo[cls]), hi = std::log(kClassHi[cls]);
        double const a = std::exp(lo + (hi - lo) * rng.uniform());
        double const b = std::exp(lo + (hi - lo) * rng.uniform());
        double const t = M_PI * rng.uniform();
        quad const c = cosq(t), s = sinq(t);
        q[0] = (double)((quad)a * a * c * c + (quad)b * b * s * s);
        q[1] = (double)(((quad)a * a - (quad)b * b) * c * s);
        q[2] = (double)((quad)a * a * s * s + (quad)b * b * c * c);
      }
      random_unit(rng, p.u, 2);
      p.dref = reference_d(2, p.u, p.q1, p.q2);
    }
    rows.push_back(run("3D", "pw85_dca(ZHENG)", zheng, cls, p3, reps));
    rows.push_back(run("3D", "pw85_dca(BRENT)", brent, cls, p3, reps));
    rows.push_back(run("3D", "pw85_dca(DEFAULT)", dflt, cls, p3, reps));
    rows.push_back(run("2D", "pw85_dca_2d", dca2d, cls, p2, reps));
    rows.push_back(run("2D", "1/sqrt(pw85_contact_function_2d)", cf2d, cls, p2, reps));
  }
  std::FILE *f = std::fopen(out, "w");
  if (f == nullptr) {
    std::perror(out);
    return 1;
  }
  std::fprintf(f, "# bench_dca: n=%d reps=%d seed=%llu; ns per call = thread CPU time / n, "
                  "median (min, max) over reps; errors of d against a __float128 reference\n",
               n, reps, (unsigned long long)seed);
  std::fprintf(f, "dim,method,class,ns_median,ns_min,ns_max,rel_err_max,rel_err_median,"
                  "n_above_1e-9,n_status_not_ok,evaluations_mean,evaluations_max\n");
  std::printf("%-3s %-34s %5s %10s %10s %10s %10s %8s %8s %8s\n", "dim", "method", "class",
              "ns/call", "err max", "err med", ">1e-9", "status", "ev mean", "ev max");
  for (Row const &r : rows) {
    std::fprintf(f, "%s,%s,%d,%.1f,%.1f,%.1f,%.3g,%.3g,%d,%d,%.2f,%d\n", r.dim.c_str(),
                 r.method.c_str(), r.cls, r.ns_med, r.ns_min, r.ns_max, r.err_max, r.err_med,
                 r.above, r.bad_status, r.ev_mean, r.ev_max);
    std::printf("%-3s %-34s %5d %10.1f %10.3g %10.3g %8d %8d %8.2f %8d\n", r.dim.c_str(),
                r.method.c_str(), r.cls, r.ns_med, r.err_max, r.err_med, r.above,
                r.bad_status, r.ev_mean, r.ev_max);
  }
  std::fclose(f);
  return 0;
}
