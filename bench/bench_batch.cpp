// Cost per pair of the batch calls over per-pair arrays and scenes
// (docs/performance.md, "Batch calls"), against the loop of one-pair calls over
// the same pairs, timed in the same repetitions.
// NOT a test: built by meson, never run by `meson test`, not installed.
//
//   bench_batch [--n M] [--reps R] [--seed S] OUT.csv
//
// Pairs: M pairs of class-0 ellipsoids (semi-axes log-uniform in [0.5, 2],
// random orientations), centre offsets as bench_contact's
// (bench::random_offset, from deep overlap to 3.2 times the sum of the
// largest semi-axes). Scene: ellipsoid 2k at a uniform point of a triclinic
// box {40, 40, 40, 0.3, 0.1, -0.2}, ellipsoid 2k+1 at that centre plus the
// offset of pair k; pair k = (2k, 2k+1); per-pair arrays: r12, q1, q2 of the
// same pairs (r12 = c_{2k+1} - c_{2k}). Every call on one thread
// (nthreads = 1). One untimed round, then R rounds; in each round every
// function of a group runs once over all pairs, one after the other, timed
// by the thread CPU time of the calling thread (with nthreads = 1 the
// OpenMP loop runs on it), so that time the shared machine gives to other
// processes is not counted, and a disturbance that remains (caches, the
// sibling of a shared core) hits the whole round. Per function: ns per pair (median, min, max over the
// rounds) and the ratio of its time to the group's one-pair loop in the same
// round (median, min, max). Checks after every call that the batch call
// gave the loop's results (bitwise) and prints a warning otherwise.
// Per class (--class-n M2, default M; 0 skips): M2 pairs of each of the four
// classes of bench_contact (semi-axes log-uniform in [0.5, 2], [0.1, 10],
// [0.01, 100], [0.001, 1000]) as per-pair arrays, pw85_overlap_pairs and
// pw85_contact_function_pairs (DEFAULT) against their one-pair loops, timed
// and reported the same way. Threads (--threads-n T, default 10^6; 0
// skips): T class-0 pairs, the two pairs calls on 1 and 2 threads
// alternately, wall clock; speed-up = median of the ratios of consecutive
// 1- and 2-thread passes (min, max); controls of what the machine offers: a
// read of the pairs' 15 doubles and the two one-pair loops, on one thread
// and split in two halves on two std::threads. --callgrind C F: only function F of
// class C (0 loop pw85_overlap, 1 pw85_overlap_pairs, 2 loop DEFAULT, 3
// pw85_contact_function_pairs DEFAULT) once over its --class-n pairs, in
// run_once, for instruction counts:
//   valgrind --tool=callgrind --toggle-collect='*run_once*'
//       build/bench/bench_batch --class-n 20000 --callgrind C F x.csv
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <time.h>

#include <chrono>

#include "bench_common.hpp"
#include "pw85.h"

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  size_t const n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double thread_ns() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}

struct Fn {
  std::string name;
  std::function<void()> run;
  std::vector<double> ns, ratio;
};

double wall_ns() {
  return (double)std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// m pairs of class (lo, hi) as per-pair arrays (the pairs of bench_contact's
// scenes: bench::random_axes, bench::random_offset with kContactSpan).
void make_pairs(bench::Rng &g, int m, double lo, double hi, std::vector<double> &r12,
                std::vector<double> &q1, std::vector<double> &q2) {
  r12.resize(3 * (size_t)m);
  q1.resize(6 * (size_t)m);
  q2.resize(6 * (size_t)m);
  for (int k = 0; k < m; ++k) {
    double a1[3], a2[3], rot[3][3];
    bench::random_axes(g, lo, hi, a1, rot);
    bench::q_from_axes(a1, rot, &q1[6 * k]);
    bench::random_axes(g, lo, hi, a2, rot);
    bench::q_from_axes(a2, rot, &q2[6 * k]);
    double const reach = *std::max_element(a1, a1 + 3) + *std::max_element(a2, a2 + 3);
    bench::random_offset(g, reach, bench::kContactSpan, &r12[3 * k]);
  }
}

// The function of --callgrind, out of line so that callgrind can count it
// alone.
__attribute__((noinline)) void run_once(std::function<void()> const &f) { f(); }

// One untimed round, then reps rounds of every function of every group
// (thread CPU time, ns per pair over m pairs; ratio to the group's first
// function, in the same round); same(g, f) checks the results of function f
// of group g against the group's first function.
void run_groups(std::vector<std::vector<Fn>> &groups, int reps, int m,
                std::function<bool(size_t, size_t)> const &same) {
  for (size_t g = 0; g < groups.size(); ++g) {
    auto &grp = groups[g];
    for (int rep = -1; rep < reps; ++rep) {
      double t_loop = 0.0;
      for (size_t f = 0; f < grp.size(); ++f) {
        double const t0 = thread_ns();
        grp[f].run();
        double const t = thread_ns() - t0;
        if (f == 0) t_loop = t;
        if (rep >= 0) {
          grp[f].ns.push_back(t / m);
          grp[f].ratio.push_back(t / t_loop);
        }
        if (f > 0 && !same(g, f))
          std::printf("WARNING: %s differs from the loop\n", grp[f].name.c_str());
      }
    }
  }
}

void print_groups(FILE *csv, std::vector<std::vector<Fn>> const &groups, char const *title) {
  std::printf("%-46s %9s %9s %9s %7s %7s %7s\n", title, "median_ns", "min_ns", "max_ns",
              "ratio", "r_min", "r_max");
  for (auto &grp : groups)
    for (auto &f : grp) {
      double const mn = *std::min_element(f.ns.begin(), f.ns.end());
      double const mx = *std::max_element(f.ns.begin(), f.ns.end());
      double const rmn = *std::min_element(f.ratio.begin(), f.ratio.end());
      double const rmx = *std::max_element(f.ratio.begin(), f.ratio.end());
      std::printf("%-46s %9.1f %9.1f %9.1f %7.3f %7.3f %7.3f\n", f.name.c_str(), median(f.ns),
                  mn, mx, median(f.ratio), rmn, rmx);
      std::fprintf(csv, "%s,%.1f,%.1f,%.1f,%.4f,%.4f,%.4f\n", f.name.c_str(), median(f.ns), mn,
                   mx, median(f.ratio), rmn, rmx);
    }
}

}  // namespace

int main(int argc, char **argv) {
  int m = 100000, reps = 9, class_n = -1, threads_n = 1000000, cg_class = -1, cg_fn = -1;
  uint64_t seed = 1;
  char const *csv_path = nullptr;
  for (int i = 1; i < argc;) {
    int const used = bench::common_option(argc, argv, i, m, reps, seed);
    if (used) {
      i += used;
    } else if (i + 1 < argc && !std::strcmp(argv[i], "--class-n")) {
      class_n = std::atoi(argv[i + 1]);
      i += 2;
    } else if (i + 2 < argc && !std::strcmp(argv[i], "--callgrind")) {
      cg_class = std::atoi(argv[i + 1]);
      cg_fn = std::atoi(argv[i + 2]);
      i += 3;
    } else if (i + 1 < argc && !std::strcmp(argv[i], "--threads-n")) {
      threads_n = std::atoi(argv[i + 1]);
      i += 2;
    } else if (argv[i][0] != '-' && !csv_path) {
      csv_path = argv[i++];
    } else {
      std::fprintf(stderr, "usage: bench_batch [--n M] [--reps R] [--seed S] [--class-n M2] [--threads-n T] [--callgrind C F] OUT.csv\n");
      return 2;
    }
  }
  if (class_n < 0) class_n = m;
  if (!csv_path || m < 1 || reps < 1 || threads_n < 0) {
    std::fprintf(stderr, "usage: bench_batch [--n M] [--reps R] [--seed S] [--class-n M2] [--threads-n T] [--callgrind C F] OUT.csv\n");
    return 2;
  }
  bench::Rng g{seed};
  double const class_lo[4] = {0.5, 0.1, 0.01, 0.001}, class_hi[4] = {2.0, 10.0, 100.0, 1000.0};
  if (cg_class >= 0) {
    if (cg_class > 3 || cg_fn < 0 || cg_fn > 3 || class_n < 1) return 2;
    int const mc = class_n;
    std::vector<double> cr, cq1, cq2;
    make_pairs(g, mc, class_lo[cg_class], class_hi[cg_class], cr, cq1, cq2);
    std::vector<int> o(mc);
    std::vector<pw85_result> f(mc);
    double const *CR = cr.data(), *CQ1 = cq1.data(), *CQ2 = cq2.data();
    std::function<void()> const fns[4] = {
        [&] { for (int k = 0; k < mc; ++k) o[k] = pw85_overlap(CR + 3 * k, CQ1 + 6 * k, CQ2 + 6 * k); },
        [&] { pw85_overlap_pairs(mc, CR, CQ1, CQ2, o.data(), nullptr, 1); },
        [&] { for (int k = 0; k < mc; ++k) pw85_contact_function_method(CR + 3 * k, CQ1 + 6 * k, CQ2 + 6 * k, PW85_METHOD_DEFAULT, &f[k]); },
        [&] { pw85_contact_function_pairs(mc, CR, CQ1, CQ2, PW85_METHOD_DEFAULT, f.data(), nullptr, 1); }};
    run_once(fns[cg_fn]);
    return 0;
  }
  double const box[6] = {40.0, 40.0, 40.0, 0.3, 0.1, -0.2};
  long long const n = 2LL * m;
  std::vector<double> c(3 * n), q(6 * n), r12(3 * m), q1(6 * m), q2(6 * m);
  std::vector<long long> pairs(2 * m);
  for (long long k = 0; k < m; ++k) {
    double a1[3], a2[3], rot[3][3], off[3];
    bench::random_axes(g, 0.5, 2.0, a1, rot);
    bench::q_from_axes(a1, rot, &q[12 * k]);
    bench::random_axes(g, 0.5, 2.0, a2, rot);
    bench::q_from_axes(a2, rot, &q[12 * k + 6]);
    double const reach = *std::max_element(a1, a1 + 3) + *std::max_element(a2, a2 + 3);
    bench::random_offset(g, reach, bench::kContactSpan, off);
    double const s[3] = {g.uniform(), g.uniform(), g.uniform()};
    // a point of the box: s0 a1 + s1 a2 + s2 a3
    c[6 * k + 0] = s[0] * box[0] + s[1] * box[3] * box[1] + s[2] * box[4] * box[2];
    c[6 * k + 1] = s[1] * box[1] + s[2] * box[5] * box[2];
    c[6 * k + 2] = s[2] * box[2];
    for (int d = 0; d < 3; ++d) c[6 * k + 3 + d] = c[6 * k + d] + off[d];
    for (int d = 0; d < 3; ++d) r12[3 * k + d] = c[6 * k + 3 + d] - c[6 * k + d];
    std::memcpy(&q1[6 * k], &q[12 * k], 6 * sizeof(double));
    std::memcpy(&q2[6 * k], &q[12 * k + 6], 6 * sizeof(double));
    pairs[2 * k] = 2 * k;
    pairs[2 * k + 1] = 2 * k + 1;
  }
  std::vector<int> ov_loop(m), ov(m), st(m);
  std::vector<pw85_result> cf_loop(m), cf(m);
  std::vector<double> out2_loop(2 * m), out2(2 * m);
  std::vector<pw85_contact_t> ct_loop(m), ct(m);
  int const one = 1;
  double const *R = r12.data(), *Q1 = q1.data(), *Q2 = q2.data(), *C = c.data(), *Q = q.data();
  long long const *P = pairs.data();

  // Groups: the first function of each is the one-pair loop (the ratio's
  // denominator).
  std::vector<std::vector<Fn>> groups = {
      {{"loop pw85_overlap", [&] { for (int k = 0; k < m; ++k) ov_loop[k] = pw85_overlap(R + 3 * k, Q1 + 6 * k, Q2 + 6 * k); }, {}, {}},
       {"pw85_overlap_pairs", [&] { pw85_overlap_pairs(m, R, Q1, Q2, ov.data(), st.data(), one); }, {}, {}},
       {"pw85_scene_overlap box=NULL", [&] { pw85_scene_overlap(n, C, Q, nullptr, m, P, ov.data(), st.data(), one); }, {}, {}},
       {"pw85_scene_overlap box", [&] { pw85_scene_overlap(n, C, Q, box, m, P, ov.data(), st.data(), one); }, {}, {}},
       {"pw85_overlap_batch", [&] { pw85_overlap_batch(n, C, Q, m, P, ov.data(), st.data(), one); }, {}, {}}},
      {{"loop pw85_contact_function_method DEFAULT", [&] { for (int k = 0; k < m; ++k) pw85_contact_function_method(R + 3 * k, Q1 + 6 * k, Q2 + 6 * k, PW85_METHOD_DEFAULT, &cf_loop[k]); }, {}, {}},
       {"pw85_contact_function_pairs DEFAULT", [&] { pw85_contact_function_pairs(m, R, Q1, Q2, PW85_METHOD_DEFAULT, cf.data(), st.data(), one); }, {}, {}},
       {"pw85_scene_contact_function DEFAULT box=NULL", [&] { pw85_scene_contact_function(n, C, Q, nullptr, m, P, PW85_METHOD_DEFAULT, cf.data(), st.data(), one); }, {}, {}},
       {"pw85_scene_contact_function DEFAULT box", [&] { pw85_scene_contact_function(n, C, Q, box, m, P, PW85_METHOD_DEFAULT, cf.data(), st.data(), one); }, {}, {}},
       {"pw85_contact_function_batch (Brent) vs DEFAULT", [&] { pw85_contact_function_batch(n, C, Q, m, P, out2.data(), st.data(), one); }, {}, {}}},
      {{"loop pw85_contact_function (Brent)", [&] { for (int k = 0; k < m; ++k) pw85_contact_function(R + 3 * k, Q1 + 6 * k, Q2 + 6 * k, &out2_loop[2 * k]); }, {}, {}},
       {"pw85_contact_function_batch (Brent)", [&] { pw85_contact_function_batch(n, C, Q, m, P, out2.data(), st.data(), one); }, {}, {}}},
      {{"loop pw85_contact", [&] { for (int k = 0; k < m; ++k) pw85_contact(R + 3 * k, Q1 + 6 * k, Q2 + 6 * k, &ct_loop[k]); }, {}, {}},
       {"pw85_contact_pairs", [&] { pw85_contact_pairs(m, R, Q1, Q2, ct.data(), st.data(), one); }, {}, {}},
       {"pw85_scene_contact box=NULL", [&] { pw85_scene_contact(n, C, Q, nullptr, m, P, ct.data(), st.data(), one); }, {}, {}},
       {"pw85_scene_contact box", [&] { pw85_scene_contact(n, C, Q, box, m, P, ct.data(), st.data(), one); }, {}, {}},
       {"pw85_contact_batch", [&] { pw85_contact_batch(n, C, Q, m, P, ct.data(), st.data(), one); }, {}, {}}},
  };

  FILE *csv = std::fopen(csv_path, "w");
  if (!csv) {
    std::perror(csv_path);
    return 1;
  }
  std::fprintf(csv, "# bench_batch --n %d --reps %d --seed %llu; cpu: %s; flags: %s\n", m, reps,
               (unsigned long long)seed, bench::cpu_model().c_str(),
#ifdef PW85_BENCH_FLAGS
               PW85_BENCH_FLAGS
#else
               "unknown"
#endif
  );
  double load0[3] = {-1, -1, -1}, load1[3] = {-1, -1, -1};
  getloadavg(load0, 3);
  run_groups(groups, reps, m, [&](size_t g, size_t f) {
    // Each batch call gives the loop's results (the Brent row of the
    // DEFAULT group is checked in the Brent group).
    if (g == 1 && f == groups[g].size() - 1) return true;
    if (g == 0) return std::equal(ov.begin(), ov.end(), ov_loop.begin());
    if (g == 1) return std::memcmp(cf.data(), cf_loop.data(), m * sizeof(pw85_result)) == 0;
    if (g == 2) return std::memcmp(out2.data(), out2_loop.data(), 2 * m * sizeof(double)) == 0;
    return std::memcmp(ct.data(), ct_loop.data(), m * sizeof(pw85_contact_t)) == 0;
  });
  std::fprintf(csv, "function,median_ns,min_ns,max_ns,ratio_to_loop_median,ratio_min,ratio_max\n");
  print_groups(csv, groups, "function (1 thread)");

  // ---- Per class: the pairs calls against their one-pair loops. ----
  for (int cls = 0; class_n > 0 && cls < 4; ++cls) {
    int const mc = class_n;
    std::vector<double> cr, cq1, cq2;
    make_pairs(g, mc, class_lo[cls], class_hi[cls], cr, cq1, cq2);
    std::vector<int> o_loop(mc), o(mc), s(mc);
    std::vector<pw85_result> f_loop(mc), f(mc);
    double const *CR = cr.data(), *CQ1 = cq1.data(), *CQ2 = cq2.data();
    std::vector<std::vector<Fn>> cg = {
        {{"loop pw85_overlap", [&] { for (int k = 0; k < mc; ++k) o_loop[k] = pw85_overlap(CR + 3 * k, CQ1 + 6 * k, CQ2 + 6 * k); }, {}, {}},
         {"pw85_overlap_pairs", [&] { pw85_overlap_pairs(mc, CR, CQ1, CQ2, o.data(), s.data(), one); }, {}, {}}},
        {{"loop pw85_contact_function_method DEFAULT", [&] { for (int k = 0; k < mc; ++k) pw85_contact_function_method(CR + 3 * k, CQ1 + 6 * k, CQ2 + 6 * k, PW85_METHOD_DEFAULT, &f_loop[k]); }, {}, {}},
         {"pw85_contact_function_pairs DEFAULT", [&] { pw85_contact_function_pairs(mc, CR, CQ1, CQ2, PW85_METHOD_DEFAULT, f.data(), s.data(), one); }, {}, {}}},
    };
    run_groups(cg, reps, mc, [&](size_t gi, size_t) {
      if (gi == 0) return std::equal(o.begin(), o.end(), o_loop.begin());
      return std::memcmp(f.data(), f_loop.data(), mc * sizeof(pw85_result)) == 0;
    });
    char title[96];
    std::snprintf(title, sizeof title, "class %d [%g, %g], %d pairs", cls, class_lo[cls],
                  class_hi[cls], mc);
    std::fprintf(csv, "# %s\n", title);
    print_groups(csv, cg, title);
  }

  // ---- Threads: 1 and 2 threads alternately, wall clock. ----
  if (threads_n > 0) {
    int const mt = threads_n;
    std::vector<double> tr, tq1, tq2;
    make_pairs(g, mt, 0.5, 2.0, tr, tq1, tq2);
    std::vector<int> o(mt);
    std::vector<pw85_result> f(mt);
    struct Th {
      char const *name;
      std::function<void(int)> run;
    };
    // Controls (what the machine offers): the one-pair loop over the same
    // pairs, on one thread, or split in two halves on two std::threads.
    auto halves = [&](int t, std::function<void(int, int)> const &loop) {
      if (t == 1) return loop(0, mt);
      std::thread other(loop, 0, mt / 2);
      loop(mt / 2, mt);
      other.join();
    };
    auto overlap_loop = [&](int k0, int k1) {
      for (int k = k0; k < k1; ++k)
        o[k] = pw85_overlap(&tr[3 * k], &tq1[6 * k], &tq2[6 * k]);
    };
    auto default_loop = [&](int k0, int k1) {
      for (int k = k0; k < k1; ++k)
        pw85_contact_function_method(&tr[3 * k], &tq1[6 * k], &tq2[6 * k], PW85_METHOD_DEFAULT,
                                     &f[k]);
    };
    // Reads the pairs' 15 doubles (the memory traffic of a pairs call).
    std::vector<double> sums(2);
    auto read_loop = [&](int k0, int k1) {
      double a = 0.0;
      for (int k = k0; k < k1; ++k) {
        for (int i = 0; i < 3; ++i) a += tr[3 * k + i];
        for (int i = 0; i < 6; ++i) a += tq1[6 * k + i] + tq2[6 * k + i];
      }
      sums[k0 == 0 ? 0 : 1] = a;
    };
    Th const th[5] = {
        {"control: read the arrays, std::threads", [&](int t) { halves(t, read_loop); }},
        {"pw85_overlap_pairs", [&](int t) { pw85_overlap_pairs(mt, tr.data(), tq1.data(), tq2.data(), o.data(), nullptr, t); }},
        {"control: loop pw85_overlap, std::threads", [&](int t) { halves(t, overlap_loop); }},
        {"pw85_contact_function_pairs DEFAULT", [&](int t) { pw85_contact_function_pairs(mt, tr.data(), tq1.data(), tq2.data(), PW85_METHOD_DEFAULT, f.data(), nullptr, t); }},
        {"control: loop DEFAULT, std::threads", [&](int t) { halves(t, default_loop); }},
    };
    std::printf("%-46s %9s %9s %9s %7s %7s %7s\n", "threads, class 0", "1t_ns", "2t_ns", "", "speedup", "s_min", "s_max");
    std::fprintf(csv, "# threads: %d class-0 pairs, wall clock\nfunction,ns_1thread,ns_2threads,speedup_median,speedup_min,speedup_max\n", mt);
    for (auto const &x : th) {
      std::vector<double> t1, t2, sp;
      x.run(2);
      for (int rep = 0; rep < reps; ++rep) {
        double t0 = wall_ns();
        x.run(1);
        double const a = wall_ns() - t0;
        t0 = wall_ns();
        x.run(2);
        double const b = wall_ns() - t0;
        t1.push_back(a / mt);
        t2.push_back(b / mt);
        sp.push_back(a / b);
      }
      double const smn = *std::min_element(sp.begin(), sp.end());
      double const smx = *std::max_element(sp.begin(), sp.end());
      std::printf("%-46s %9.1f %9.1f %9s %7.3f %7.3f %7.3f\n", x.name, median(t1), median(t2), "",
                  median(sp), smn, smx);
      std::fprintf(csv, "%s,%.1f,%.1f,%.4f,%.4f,%.4f\n", x.name, median(t1), median(t2),
                   median(sp), smn, smx);
    }
  }
  getloadavg(load1, 3);
  std::printf("load average (1/5/15 min): %.2f %.2f %.2f before, %.2f %.2f %.2f after\n", load0[0],
              load0[1], load0[2], load1[0], load1[1], load1[2]);
  std::fprintf(csv, "# load average (1/5/15 min): %.2f %.2f %.2f before, %.2f %.2f %.2f after\n",
               load0[0], load0[1], load0[2], load1[0], load1[1], load1[2]);
  std::fclose(csv);
  return 0;
}
