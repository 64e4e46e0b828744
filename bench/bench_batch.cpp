// Cost per pair of the batch calls over per-pair arrays and scenes
// (docs/batch.md, docs/guide.md), against the loop of one-pair calls over
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
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <time.h>

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

}  // namespace

int main(int argc, char **argv) {
  int m = 100000, reps = 9;
  uint64_t seed = 1;
  char const *csv_path = nullptr;
  for (int i = 1; i < argc;) {
    int const used = bench::common_option(argc, argv, i, m, reps, seed);
    if (used) {
      i += used;
    } else if (argv[i][0] != '-' && !csv_path) {
      csv_path = argv[i++];
    } else {
      std::fprintf(stderr, "usage: bench_batch [--n M] [--reps R] [--seed S] OUT.csv\n");
      return 2;
    }
  }
  if (!csv_path || m < 1 || reps < 1) {
    std::fprintf(stderr, "usage: bench_batch [--n M] [--reps R] [--seed S] OUT.csv\n");
    return 2;
  }
  bench::Rng g{seed};
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
  for (auto &grp : groups) {
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
        // Each batch call gives the loop's results (the Brent row of the
        // DEFAULT group is checked in the Brent group).
        bool same = true;
        size_t const g = &grp - groups.data();
        if (f == 0 || (g == 1 && f == grp.size() - 1)) continue;
        if (g == 0)
          same = std::equal(ov.begin(), ov.end(), ov_loop.begin());
        else if (g == 1)
          same = std::memcmp(cf.data(), cf_loop.data(), m * sizeof(pw85_result)) == 0;
        else if (g == 2)
          same = std::memcmp(out2.data(), out2_loop.data(), 2 * m * sizeof(double)) == 0;
        else
          same = std::memcmp(ct.data(), ct_loop.data(), m * sizeof(pw85_contact_t)) == 0;
        if (!same) std::printf("WARNING: %s differs from the loop\n", grp[f].name.c_str());
      }
    }
  }
  getloadavg(load1, 3);
  std::fprintf(csv, "function,median_ns,min_ns,max_ns,ratio_to_loop_median,ratio_min,ratio_max\n");
  std::printf("%-46s %9s %9s %9s %7s %7s %7s\n", "function (1 thread)", "median_ns", "min_ns",
              "max_ns", "ratio", "r_min", "r_max");
  for (auto &grp : groups)
    for (auto &f : grp) {
      double const mn = *std::min_element(f.ns.begin(), f.ns.end());
      double const mx = *std::max_element(f.ns.begin(), f.ns.end());
      double const rmn = *std::min_element(f.ratio.begin(), f.ratio.end());
      double const rmx = *std::max_element(f.ratio.begin(), f.ratio.end());
      std::printf("%-46s %9.1f %9.1f %9.1f %7.3f %7.3f %7.3f\n", f.name.c_str(), median(f.ns), mn,
                  mx, median(f.ratio), rmn, rmx);
      std::fprintf(csv, "%s,%.1f,%.1f,%.1f,%.4f,%.4f,%.4f\n", f.name.c_str(), median(f.ns), mn, mx,
                   median(f.ratio), rmn, rmx);
    }
  std::printf("load average (1/5/15 min): %.2f %.2f %.2f before, %.2f %.2f %.2f after\n", load0[0],
              load0[1], load0[2], load1[0], load1[1], load1[2]);
  std::fprintf(csv, "# load average (1/5/15 min): %.2f %.2f %.2f before, %.2f %.2f %.2f after\n",
               load0[0], load0[1], load0[2], load1[0], load1[1], load1[2]);
  std::fclose(csv);
  return 0;
}
