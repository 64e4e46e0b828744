// Cost of pw85_contact_derivatives against one PW85_METHOD_DEFAULT
// pw85_contact_function_method call on the same pairs in the same run
// (docs/performance.md, "Derivatives"). Pairs of bench_contact's four semi-axis
// classes (bench_common.hpp: semi-axes log-uniform in [0.5, 2], [0.1, 10],
// [0.01, 100], [0.001, 1000], random orientations, centre distances from deep
// overlap to 3.2 times the reach). Each repetition times one pass of each
// call over the n pairs of a class, alternating the order, in thread CPU
// time; the table gives ns per call, median over the repetitions, and the
// ratio of the medians. Also pw85_contact (contact point and normal) for
// scale, and the batch forms over the same pairs on one thread:
// pw85_contact_function_pairs (DEFAULT) and pw85_contact_derivatives_pairs,
// with the ratio of their medians; and the flag PW85_DERIVATIVES_FORCES
// (pw85_contact_derivatives_ex, pw85_contact_derivatives_pairs_ex), with the
// ratios of its one-pair call to DEFAULT and of its pairs call to
// pw85_contact_function_pairs.
//
//   build/bench/bench_derivatives [--n 20000] [--reps 9] [--seed 20260521]
//
// --count M --class C: no timing; one pass of call M (none, default,
// derivatives, forces) over the pairs of class C, for instruction counts:
// (Ir of M - Ir of none) / n under valgrind --tool=callgrind.
#include <pw85.h>
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "bench_common.hpp"

namespace {

double thread_ns() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e9 * t.tv_sec + t.tv_nsec;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  size_t const m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

volatile double sink;

// Calls timed in each repetition: 0 DEFAULT, 1 pw85_contact_derivatives,
// 2 pw85_contact, 3 pw85_contact_function_pairs, 4
// pw85_contact_derivatives_pairs, 5 pw85_contact_derivatives_ex and 6
// pw85_contact_derivatives_pairs_ex with PW85_DERIVATIVES_FORCES.
constexpr int kCalls = 7;

}  // namespace

int main(int argc, char **argv) {
  int n = 20000, reps = 9;
  uint64_t seed = 20260521;
  int count = -1, only = -1;  // --count: 0 none, 1 default, 2 derivatives, 3 forces
  for (int i = 1; i < argc;) {
    int k = bench::common_option(argc, argv, i, n, reps, seed);
    if (k == 0 && i + 1 < argc && !std::strcmp(argv[i], "--class")) {
      only = std::atoi(argv[i + 1]);
      k = 2;
    } else if (k == 0 && i + 1 < argc && !std::strcmp(argv[i], "--count")) {
      char const *m = argv[i + 1];
      count = !std::strcmp(m, "none") ? 0 : !std::strcmp(m, "default") ? 1
              : !std::strcmp(m, "derivatives") ? 2 : !std::strcmp(m, "forces") ? 3 : -2;
      k = count == -2 ? 0 : 2;
    }
    if (k == 0) {
      std::fprintf(stderr,
                   "usage: %s [--n N] [--reps R] [--seed S] "
                   "[--count none|default|derivatives|forces --class C]\n",
                   argv[0]);
      return 2;
    }
    i += k;
  }
  double const lo[4] = {0.5, 0.1, 0.01, 0.001}, hi[4] = {2.0, 10.0, 100.0, 1000.0};
  if (count < 0) {
    std::printf("# bench_derivatives: %s, seed %llu, n %d per class, reps %d\n", pw85_version(),
                (unsigned long long)seed, n, reps);
    std::printf("# time: ns per call = (thread CPU time of one pass over the n pairs) / n, median over reps\n");
    std::printf("class,axis_min,axis_max,n,default_ns,derivatives_ns,contact_ns,ratio_derivatives_default,"
                "pairs_default_ns,pairs_derivatives_ns,ratio_pairs,n_status_nonzero,"
                "forces_ns,ratio_forces_default,pairs_forces_ns,ratio_pairs_forces\n");
  }
  bench::Rng g{seed};
  for (int c = 0; c < 4; ++c) {
    std::vector<double> r(3 * n), q1(6 * n), q2(6 * n);
    for (int k = 0; k < n; ++k) {
      double a1[3], a2[3], m1[3][3], m2[3][3];
      bench::random_axes(g, lo[c], hi[c], a1, m1);
      bench::random_axes(g, lo[c], hi[c], a2, m2);
      bench::q_from_axes(a1, m1, &q1[6 * k]);
      bench::q_from_axes(a2, m2, &q2[6 * k]);
      double const reach = *std::max_element(a1, a1 + 3) + *std::max_element(a2, a2 + 3);
      bench::random_offset(g, reach, bench::kContactSpan, &r[3 * k]);
    }
    if (count >= 0) {
      if (c != only) continue;
      double acc = 0.0;
      for (int k = 0; k < n && count > 0; ++k) {
        if (count == 1) {
          pw85_result res;
          pw85_contact_function_method(&r[3 * k], &q1[6 * k], &q2[6 * k], PW85_METHOD_DEFAULT, &res);
          acc += res.mu2;
        } else {
          pw85_derivatives_t d;
          pw85_contact_derivatives_ex(&r[3 * k], &q1[6 * k], &q2[6 * k],
                                      count == 3 ? PW85_DERIVATIVES_FORCES : PW85_DERIVATIVES_ALL,
                                      &d);
          acc += d.d_r12[0];
        }
      }
      sink = acc;
      continue;
    }
    std::vector<double> t_def, t_der, t_con, t_pdef, t_pder, t_for, t_pfor;
    std::vector<double> *const times[kCalls] = {&t_def, &t_der, &t_con, &t_pdef,
                                                &t_pder, &t_for, &t_pfor};
    std::vector<pw85_result> pres(n);
    std::vector<pw85_derivatives_t> pder(n);
    std::vector<int> pst(n);
    int bad = 0;
    for (int rep = 0; rep < reps; ++rep) {
      for (int which = 0; which < kCalls; ++which) {
        int const w = (which + rep) % kCalls;
        double acc = 0.0;
        double const t0 = thread_ns();
        if (w == 3) {
          pw85_contact_function_pairs(n, r.data(), q1.data(), q2.data(), PW85_METHOD_DEFAULT,
                                      pres.data(), pst.data(), 1);
          acc += pres[n - 1].mu2;
        } else if (w == 4) {
          pw85_contact_derivatives_pairs(n, r.data(), q1.data(), q2.data(), pder.data(),
                                         pst.data(), 1);
          acc += pder[n - 1].d_r12[0];
        } else if (w == 6) {
          pw85_contact_derivatives_pairs_ex(n, r.data(), q1.data(), q2.data(),
                                            PW85_DERIVATIVES_FORCES, pder.data(), pst.data(), 1);
          acc += pder[n - 1].d_r12[0];
        }
        for (int k = 0; k < n && (w < 3 || w == 5); ++k) {
          if (w == 0) {
            pw85_result res;
            if (pw85_contact_function_method(&r[3 * k], &q1[6 * k], &q2[6 * k],
                                             PW85_METHOD_DEFAULT, &res) != PW85_OK && rep == 0)
              ++bad;
            acc += res.mu2;
          } else if (w == 1) {
            pw85_derivatives_t d;
            if (pw85_contact_derivatives(&r[3 * k], &q1[6 * k], &q2[6 * k], &d) != PW85_OK &&
                rep == 0)
              ++bad;
            acc += d.d_r12[0];
          } else if (w == 5) {
            pw85_derivatives_t d;
            pw85_contact_derivatives_ex(&r[3 * k], &q1[6 * k], &q2[6 * k],
                                        PW85_DERIVATIVES_FORCES, &d);
            acc += d.d_r12[0];
          } else {
            pw85_contact_t ct;
            pw85_contact(&r[3 * k], &q1[6 * k], &q2[6 * k], &ct);
            acc += ct.x0[0];
          }
        }
        double const dt = (thread_ns() - t0) / n;
        sink = acc;
        times[w]->push_back(dt);
      }
    }
    double const md = median(t_def), mv = median(t_der), mc = median(t_con);
    double const mpd = median(t_pdef), mpv = median(t_pder);
    double const mf = median(t_for), mpf = median(t_pfor);
    std::printf("%d,%g,%g,%d,%.1f,%.1f,%.1f,%.2f,%.1f,%.1f,%.2f,%d,%.1f,%.2f,%.1f,%.2f\n", c,
                lo[c], hi[c], n, md, mv, mc, mv / md, mpd, mpv, mpv / mpd, bad, mf, mf / md, mpf,
                mpf / mpd);
    std::fflush(stdout);
  }
  return 0;
}
