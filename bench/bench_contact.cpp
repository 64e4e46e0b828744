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
//    formed from the double inputs; bench/reference_mu2.hpp);
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
#include "reference_mu2.hpp"
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
      p.refq = bench::reference_mu2(p.r, p.q1, p.q2);
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
