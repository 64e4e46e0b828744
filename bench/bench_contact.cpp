// Speed-accuracy benchmark of the contact-function methods (docs/methods.md).
// NOT a test: built by meson, never run by `meson test`, not installed.
//
//   bench_contact [--n N] [--reps R] [--seed S] [--dump K FILE] OUT.csv
//
// For each of four classes of random general ellipsoid pairs (three distinct
// semi-axes log-uniform in [0.5, 2], [0.1, 10], [0.01, 100], [0.001, 1000];
// orientations uniform (random unit quaternions); centre distance
// d = (a1max + a2max) 10^U(-2, 0.5), so from deep overlap to far apart), it
//  - computes a reference mu2 in __float128 (bisection then Newton on f'
//    evaluated through an LDL^T factorisation in __float128 of Q(lambda)
//    formed from the double inputs; see reference_mu2);
//  - times every method of the table `methods` below (R repetitions of one
//    pass over the N pairs; ns per call = thread CPU time of the pass / N;
//    median, min, max over the repetitions; the median wall-clock time too);
//  - records max / median relative error of mu2, fraction above 1e-10,
//    number of non-zero statuses, of "silent" failures (status PW85_OK but
//    relative error above the documented accuracy), and of NaN results;
//  - prints a table and writes OUT.csv with a header recording the machine,
//    the compiler and its flags.
// --dump K FILE writes the first K pairs of every class with their reference
// (for bench/check_bench_reference.py, which recomputes them with mpmath).
//
// To add a method to the chart: add one line to `methods` (a name, a
// function with the signature of ContactFn, and its documented relative
// accuracy).
#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <quadmath.h>
#include <sys/utsname.h>
#include <time.h>

#include "bench_common.hpp"
#include "pw85.h"

#ifndef PW85_BENCH_FLAGS
#define PW85_BENCH_FLAGS "unknown"
#endif

namespace {

// ---- methods --------------------------------------------------------------
// Returns a status; writes mu2.
// Returns a status; writes mu2 and the number of iterations (-1 if unknown).
using ContactFn = int (*)(double const *r, double const *q1, double const *q2, double *mu2,
                          int *iterations);

int run_legacy_api(double const *r, double const *q1, double const *q2, double *mu2,
                   int *iterations) {
  double out[2];
  int const s = pw85_contact_function(r, q1, q2, out);
  *mu2 = out[0];
  *iterations = -1;
  return s;
}

template <int M>
int run_method(double const *r, double const *q1, double const *q2, double *mu2,
               int *iterations) {
  pw85_result res;
  int const s = pw85_contact_function_method(r, q1, q2, M, &res);
  *mu2 = res.mu2;
  *iterations = res.iterations;
  return s;
}

struct MethodEntry {
  char const *name;
  ContactFn fn;
  double accuracy;  // documented relative accuracy (status PW85_OK => error below)
};

MethodEntry const methods[] = {
    {"pw85_contact_function", run_legacy_api, 1e-10},
    {"BRENT", run_method<PW85_METHOD_BRENT>, 1e-10},
    {"NEWTON", run_method<PW85_METHOD_NEWTON>, 1e-12},
    {"RATIONAL", run_method<PW85_METHOD_RATIONAL>, 1e-12},
    {"DEFAULT", run_method<PW85_METHOD_DEFAULT>, 1e-14},
    {"ZHENG", run_method<PW85_METHOD_ZHENG>, 1e-9},  // documented in pw85.h (docs/dca.md)
};

// ---- scenes ---------------------------------------------------------------
using bench::Rng;

struct Pair {
  double r[3], q1[6], q2[6];
  double ref;       // reference mu2 rounded to double
  __float128 refq;  // reference mu2 in __float128
};

void random_ellipsoid(Rng &g, double lo, double hi, double q[6], double &amax) {
  double a[3], rot[3][3];
  bench::random_axes(g, lo, hi, a, rot);
  amax = std::max({a[0], a[1], a[2]});
  bench::q_from_axes(a, rot, q);
}

// ---- reference in __float128 ----------------------------------------------
using F128 = __float128;

struct RefEval {
  F128 f, df, d2f;
};

bool ref_eval(F128 lam, Pair const &p, RefEval &e) {
  F128 q[6], d[6];
  for (int i = 0; i < 6; ++i) {
    q[i] = (1 - lam) * (F128)p.q1[i] + lam * (F128)p.q2[i];
    d[i] = (F128)p.q2[i] - (F128)p.q1[i];
  }
  // LDL^T
  F128 const d0 = q[0];
  if (!(d0 > 0)) return false;
  F128 const l10 = q[1] / d0, l20 = q[2] / d0;
  F128 const d1 = q[3] - l10 * q[1];
  if (!(d1 > 0)) return false;
  F128 const ee = q[4] - l20 * q[1];
  F128 const l21 = ee / d1;
  F128 const d2 = q[5] - l20 * q[2] - l21 * ee;
  if (!(d2 > 0)) return false;
  auto solve = [&](F128 const b[3], F128 x[3]) {
    F128 const y0 = b[0], y1 = b[1] - l10 * y0, y2 = b[2] - l20 * y0 - l21 * y1;
    x[2] = y2 / d2;
    x[1] = y1 / d1 - l21 * x[2];
    x[0] = y0 / d0 - l10 * x[1] - l20 * x[2];
  };
  auto mul = [&](F128 const a[6], F128 const x[3], F128 y[3]) {
    y[0] = a[0] * x[0] + a[1] * x[1] + a[2] * x[2];
    y[1] = a[1] * x[0] + a[3] * x[1] + a[4] * x[2];
    y[2] = a[2] * x[0] + a[4] * x[1] + a[5] * x[2];
  };
  F128 const r[3] = {p.r[0], p.r[1], p.r[2]};
  F128 s[3], u[3], v[3];
  solve(r, s);
  mul(d, s, u);
  solve(u, v);
  F128 const phi = r[0] * s[0] + r[1] * s[1] + r[2] * s[2];
  F128 const phi1 = -(s[0] * u[0] + s[1] * u[1] + s[2] * u[2]);
  F128 const phi2 = 2 * (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]);
  F128 const pp = lam * (1 - lam), p1 = 1 - 2 * lam;
  e.f = pp * phi;
  e.df = p1 * phi + pp * phi1;
  e.d2f = -2 * phi + 2 * p1 * phi1 + pp * phi2;
  return true;
}

// Maximiser of the concave f: bisection on the sign of f' down to a bracket
// of 2^-40, then Newton steps on f' in __float128 until the step is below
// 1e-30; mu2 = f at the final lambda (its error in lambda enters mu2 only
// to second order).
__float128 reference_mu2(Pair const &p) {
  F128 lo = 0, hi = 1;
  RefEval e;
  for (int k = 0; k < 40; ++k) {
    F128 const m = (lo + hi) / 2;
    if (!ref_eval(m, p, e)) return NAN;
    if (e.df > 0)
      lo = m;
    else
      hi = m;
  }
  F128 lam = (lo + hi) / 2;
  for (int k = 0; k < 8; ++k) {
    if (!ref_eval(lam, p, e)) return NAN;
    F128 const step = -e.df / e.d2f;
    F128 next = lam + step;
    if (!(next > lo && next < hi)) break;
    lam = next;
    if (fabsq(step) < (F128)1e-30) break;
  }
  if (!ref_eval(lam, p, e)) return NAN;
  return e.f;
}

using bench::cpu_model;
using bench::run_command;

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  size_t const i = (size_t)(q * (double)(v.size() - 1) + 0.5);
  return v[std::min(i, v.size() - 1)];
}

}  // namespace

int main(int argc, char **argv) {
  int n = 20000, reps = 7;
  uint64_t seed = 20260521;
  char const *out = nullptr;
  int dump_k = 0;
  char const *dump_path = nullptr;
  bool bad = false;
  for (int i = 1; i < argc; ++i) {
    if (int const k = bench::common_option(argc, argv, i, n, reps, seed))
      i += k - 1;
    else if (!std::strcmp(argv[i], "--dump") && i + 2 < argc) {
      dump_k = std::atoi(argv[++i]);
      dump_path = argv[++i];
    } else if (argv[i][0] == '-') {
      bad = true;  // unknown option, or one missing its value
    } else
      out = argv[i];
  }
  if (bad || !out || n <= 0 || reps <= 0) {
    std::fprintf(stderr, "usage: %s [--n N] [--reps R] [--seed S] [--dump K FILE] OUT.csv\n",
                 argv[0]);
    return 2;
  }
  double const bounds[4][2] = {{0.5, 2}, {0.1, 10}, {0.01, 100}, {0.001, 1000}};
  FILE *csv = std::fopen(out, "w");
  if (!csv) {
    std::perror(out);
    return 1;
  }
  FILE *dump = dump_path ? std::fopen(dump_path, "w") : nullptr;
  std::fprintf(csv, "# bench_contact: pw85 %s, seed %" PRIu64 ", n %d per class, reps %d\n",
               pw85_version(), seed, n, reps);
  std::fprintf(csv, "# machine: %s\n", run_command("uname -a").c_str());
  std::fprintf(csv, "# cpu: %s\n", cpu_model().c_str());
  std::fprintf(csv, "# compiler: g++ %s\n", __VERSION__);
  std::fprintf(csv, "# flags: %s\n", PW85_BENCH_FLAGS);
  std::fprintf(csv, "# time: ns per call = (thread CPU time of one pass over the n pairs) / n; "
                    "median/min/max over reps passes; median_wall_ns: same with wall-clock time\n");
  std::fprintf(csv, "# reference: mu2 maximised in __float128 from the double inputs\n");
  std::fprintf(csv, "method,class,axis_min,axis_max,n,median_ns,min_ns,max_ns,median_wall_ns,max_rel_err,"
                    "median_rel_err,frac_rel_err_gt_1e-10,n_status_nonzero,n_silent_fail,"
                    "n_nan,accuracy,mean_iterations\n");
  std::printf("%-22s %5s %10s %9s %9s %9s %10s %10s %9s %7s %6s %5s %6s\n", "method", "class",
              "median_ns", "min_ns", "max_ns", "wall_ns", "max_rel", "med_rel", ">1e-10", "status",
              "silent", "nan", "iter");
  Rng g{seed};
  volatile double sink = 0.0;
  for (int c = 0; c < 4; ++c) {
    std::vector<Pair> pairs(n);
    for (Pair &p : pairs) {
      double am1, am2;
      random_ellipsoid(g, bounds[c][0], bounds[c][1], p.q1, am1);
      random_ellipsoid(g, bounds[c][0], bounds[c][1], p.q2, am2);
      bench::random_offset(g, am1 + am2, bench::kContactSpan, p.r);
      p.refq = reference_mu2(p);
      p.ref = (double)p.refq;
    }
    if (dump)
      for (int i = 0; i < std::min(dump_k, n); ++i) {
        Pair const &p = pairs[i];
        std::fprintf(dump, "%d", c);
        for (double x : p.r) std::fprintf(dump, " %.17g", x);
        for (double x : p.q1) std::fprintf(dump, " %.17g", x);
        for (double x : p.q2) std::fprintf(dump, " %.17g", x);
        char buf[64];
        quadmath_snprintf(buf, sizeof buf, "%.36Qg", p.refq);
        std::fprintf(dump, " %s\n", buf);
      }
    for (MethodEntry const &m : methods) {
      // Accuracy pass.
      std::vector<double> err;
      err.reserve(n);
      int nonzero = 0, silent = 0, nans = 0, unknown = 0, gt = 0;
      double iter_sum = 0.0;
      for (Pair const &p : pairs) {
        double mu2 = NAN;
        int it = -1;
        int const s = m.fn(p.r, p.q1, p.q2, &mu2, &it);
        iter_sum += it;
        if (s == PW85_ERR_UNKNOWN_METHOD) {
          ++unknown;
          break;
        }
        if (std::isnan(mu2)) {
          ++nans;
          continue;
        }
        double const e = std::fabs(mu2 - p.ref) / p.ref;
        err.push_back(e);
        if (e > 1e-10) ++gt;
        if (s != PW85_OK) ++nonzero;
        if (s == PW85_OK && e > m.accuracy) ++silent;
      }
      if (unknown) continue;  // method not implemented in this build
      // Timing passes: thread CPU time (the machine is shared: wall-clock
      // time also counts the time other processes hold the core) and wall
      // time, both per call.
      std::vector<double> ns(reps), wall(reps);
      for (int rep = 0; rep < reps; ++rep) {
        double acc = 0.0;
        timespec c0, c1;
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c0);
        auto const t0 = std::chrono::steady_clock::now();
        for (Pair const &p : pairs) {
          double mu2;
          int it;
          m.fn(p.r, p.q1, p.q2, &mu2, &it);
          acc += mu2;
        }
        auto const t1 = std::chrono::steady_clock::now();
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c1);
        sink = sink + acc;
        ns[rep] = ((double)(c1.tv_sec - c0.tv_sec) * 1e9 + (double)(c1.tv_nsec - c0.tv_nsec)) / n;
        wall[rep] = std::chrono::duration<double, std::nano>(t1 - t0).count() / n;
      }
      double const wall_med = quantile(wall, 0.5);
      double const med = quantile(ns, 0.5);
      double const mn = *std::min_element(ns.begin(), ns.end());
      double const mx = *std::max_element(ns.begin(), ns.end());
      double const emax = err.empty() ? NAN : *std::max_element(err.begin(), err.end());
      double const emed = quantile(err, 0.5);
      double const frac = (double)gt / n;
      double const mean_it = iter_sum / n;
      std::printf("%-22s %5d %10.1f %9.1f %9.1f %9.1f %10.2e %10.2e %9.5f %7d %6d %5d %6.2f\n",
                  m.name, c, med, mn, mx, wall_med, emax, emed, frac, nonzero, silent, nans,
                  mean_it);
      std::fprintf(csv, "%s,%d,%g,%g,%d,%.2f,%.2f,%.2f,%.2f,%.3e,%.3e,%.6f,%d,%d,%d,%g,%.3f\n",
                   m.name, c, bounds[c][0], bounds[c][1], n, med, mn, mx, wall_med, emax, emed,
                   frac, nonzero, silent, nans, m.accuracy, mean_it);
      std::fflush(stdout);
    }
  }
  std::fclose(csv);
  if (dump) std::fclose(dump);
  return sink == 12345.0 ? 3 : 0;
}
