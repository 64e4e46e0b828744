// Benchmark of the exact overlap predicate pw85_overlap (docs/overlap.md)
// and of the batch calls (docs/batch.md).
// NOT a test: built by meson, never run by `meson test`, not installed.
//
//   bench_overlap [--n N] [--reps R] [--seed S] [--ref FILE]
//                 [--batch-n N] [--batch-m M] [--batch-reps R] [--batch-min-ms T]
//                 [--no-batch] [--overlap-only] OUT.csv
//
// Scenes (one row of the table per scene and function):
//  - contact_scene/class0..3: the scenes of bench_contact: N
//    random general ellipsoid pairs per class (three distinct semi-axes
//    log-uniform in [0.5, 2], [0.1, 10], [0.01, 100], [0.001, 1000];
//    orientations uniform (random unit quaternions); centre distance
//    |r12| = (a1max + a2max) 10^U(-2, 0.5)), the same pairs as bench_contact
//    for the same seed and N (bench::random_offset). The scene keeps both
//    representations: Q (for pw85) and radii + rotation (for FCL). Reference
//    verdict: mu2 of pw85_contact_function_method(PW85_METHOD_DEFAULT)
//    (documented relative accuracy 1e-14), trusted only where
//    |mu2 - 1| > 1e-8; the other pairs are timed but not counted
//    (column n_checked).
//  - gen/class0..3: as contact_scene but |r12| = (a1max + a2max) 10^U(-2, 1)
//    (up to 10 times the sum of the largest semi-axes: more far-apart
//    pairs, which the plane test decides cheaply; docs/overlap.md).
//  - ref/contact/class0..3 and ref/near_contact: the groups /contact (per
//    class) and /near_contact (|mu2 - 1| log-uniform in [1e-15, 1e-2]) of the
//    reference data file (default: PW85_REF_DATA_PATH, i.e.
//    data/pw85_ref_data.h5), reference verdict mu2 < 1 from its correctly
//    rounded mu2 (every pair counted). FCL gets radii and rotation from the
//    eigen-decomposition of Q (Eigen), so its input differs from Q by
//    rounding errors (~1e-16 relative).
// For each scene it times pw85_overlap, the full contact function
// (pw85_contact_function_method DEFAULT, verdict mu2 < 1) and, when built
// with FCL (meson option fcl), fcl::collide with a default request on
// Ellipsoidd objects: R passes over the whole scene, ns per pair = thread CPU
// time of a pass / number of pairs, median, min and max over the passes;
// and counts wrong verdicts against the reference. Per-pair latency (column
// median_pair_ns): each pair is called kLatCalls times in a row between two
// steady_clock reads, (elapsed - clock overhead) / kLatCalls is that pair's
// latency, the column is the median over the pairs (one such pass; repeated
// calls on one pair see warm caches and trained branch predictors, so this
// is a best-case latency, unlike the per-pass mean). --overlap-only skips
// the contact function and FCL rows, and the two contact batch calls.
// Batch: n random class-0 ellipsoids with centres uniform in a cube of side
// 2 n^(1/3) (so random pairs range from overlapping to far apart), m random
// index pairs (i != j), in random order and sorted by (i, j); wall-clock
// time of pw85_overlap_batch, pw85_contact_function_batch, pw85_contact_batch
// and of control loops on std::threads (what the shared machine offers at
// that moment): two compute-only loops with no library call (one
// latency-bound, one throughput-bound; the throughput one is timed in the
// same repetitions as each batch call, passes interleaved) and, for each
// batch call, control_pairs: its one-pair function over the same pairs
// without OpenMP (timed in the same repetitions; per-thread CPU ns per pair
// printed), with nthreads = 1 and 2 (one untimed
// pass each, then --batch-reps passes alternating 1 and 2 threads), median,
// min and max over the passes, speed-up = median time (1 thread) / median
// time (2 threads); a line per function with the ratio of each interleaved
// pair of passes, their median, the ratio of the fastest passes and the load
// averages before and after (docs/batch.md). --batch-min-ms T: each timed
// pass repeats the call until the one-thread pass lasts at least T ms
// (measured on the untimed pass; default 0: one call per pass).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include <hdf5.h>
#include <hdf5_hl.h>
#include <sys/utsname.h>
#include <time.h>

#ifdef PW85_HAVE_FCL
#include <Eigen/Dense>
#include <fcl/fcl.h>
#endif

#include "bench_common.hpp"
#include "pw85.h"

#ifndef PW85_BENCH_FLAGS
#define PW85_BENCH_FLAGS "unknown"
#endif
#ifndef PW85_REF_DATA_PATH
#define PW85_REF_DATA_PATH "data/pw85_ref_data.h5"
#endif

namespace {

using bench::Rng;

// One ellipsoid in both representations: q (upper triangle of Q) and
// radii a[k] along the columns k of rot.
struct Ell {
  double q[6];
  double a[3];
  double rot[3][3];
};

struct Pair {
  double r[3];
  Ell e1, e2;
  int ref;  // reference verdict: 1 overlap, 0 not, -1 unknown (not counted)
};

void q_from_axes(Ell &e) { bench::q_from_axes(e.a, e.rot, e.q); }

double random_ellipsoid(Rng &g, double lo, double hi, Ell &e) {
  bench::random_axes(g, lo, hi, e.a, e.rot);
  q_from_axes(e);
  return std::max({e.a[0], e.a[1], e.a[2]});
}

#ifdef PW85_HAVE_FCL
// Radii and rotation from the eigen-decomposition of Q (reference groups).
void axes_from_q(Ell &e) {
  Eigen::Matrix3d Q;
  Q << e.q[0], e.q[1], e.q[2], e.q[1], e.q[3], e.q[4], e.q[2], e.q[4], e.q[5];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(Q);
  Eigen::Matrix3d V = es.eigenvectors();
  if (V.determinant() < 0) V.col(0) = -V.col(0);
  for (int k = 0; k < 3; ++k) {
    e.a[k] = std::sqrt(std::max(es.eigenvalues()(k), 0.0));
    for (int i = 0; i < 3; ++i) e.rot[i][k] = V(i, k);
  }
}
#else
void axes_from_q(Ell &) {}
#endif

// ---- machine description ---------------------------------------------------
using bench::cpu_model;
using bench::run_command;

// The control loops of the batch rows: compute only, no library call, split
// over 1 or 2 std::threads (work(0) here, work(1) on a helper thread).
template <class Work>
void split_over_threads(int threads, Work const &work) {
  if (threads == 1) {
    work(0);
  } else {
    std::thread helper(work, 1);
    work(0);
    helper.join();
  }
}

// Latency-bound control (row "control_compute"): `items` iterations of 20
// dependent square roots (~50 ns each).
void control_latency(long long items, int threads, volatile double &sink) {
  double part[2] = {0.0, 0.0};
  split_over_threads(threads, [&part, items, threads](int id) {
    double s = 0.0;
    for (long long k = id; k < items; k += threads) {
      double x = (double)k;
      for (int it = 0; it < 20; ++it) x = std::sqrt(x + 1.0);
      s += x;
    }
    part[id] = s;
  });
  sink = sink + part[0] + part[1];
}

// Throughput-bound control (row "control_throughput"): `items` units of 8
// rounds of a multiply-add on 24 independent chains (twelve two-lane
// vectors), held in registers (the asm statement keeps them there and stops
// the compiler from collapsing the rounds): no memory traffic, and enough
// independent operations to keep the floating-point pipes of a core busy
// (a standalone copy measured 0.15 ns per two-lane multiply-add on one
// thread, about 27 double operations per ns; cycle counts are not available
// on this VM), so a second thread sharing the core (SMT) should gain little;
// two cores double it.
// (Accumulators in registers, not in an array on the stack, whose per-unit
// time would depend on the thread's stack placement.)
void control_throughput(long long items, int threads, volatile double &sink) {
  typedef double V2 __attribute__((vector_size(16)));
  double part[2] = {0.0, 0.0};
  split_over_threads(threads, [&part, items, threads](int id) {
    auto start = [](int c) { return V2{1.0 + 0.002 * c, 1.001 + 0.002 * c}; };
    V2 a0 = start(0), a1 = start(1), a2 = start(2), a3 = start(3), a4 = start(4), a5 = start(5),
       a6 = start(6), a7 = start(7), a8 = start(8), a9 = start(9), a10 = start(10), a11 = start(11);
    V2 const m = {0.9999999, 0.9999999}, c = {1e-7, 1e-7};
    for (long long k = id; k < items; k += threads) {
      for (int it = 0; it < 8; ++it) {
        a0 = a0 * m + c, a1 = a1 * m + c, a2 = a2 * m + c, a3 = a3 * m + c;
        a4 = a4 * m + c, a5 = a5 * m + c, a6 = a6 * m + c, a7 = a7 * m + c;
        a8 = a8 * m + c, a9 = a9 * m + c, a10 = a10 * m + c, a11 = a11 * m + c;
      }
      asm volatile("" : "+x"(a0), "+x"(a1), "+x"(a2), "+x"(a3), "+x"(a4), "+x"(a5));
      asm volatile("" : "+x"(a6), "+x"(a7), "+x"(a8), "+x"(a9), "+x"(a10), "+x"(a11));
    }
    V2 const s = (((a0 + a1) + (a2 + a3)) + ((a4 + a5) + (a6 + a7))) + ((a8 + a9) + (a10 + a11));
    part[id] = s[0] + s[1];
  });
  sink = sink + part[0] + part[1];
}

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

// The library's own work without OpenMP (rows "control_pairs[..]", timed in
// the same repetitions as the batch call they mirror, passes interleaved):
// the one-pair function (`one(k, r12, q_i, q_j)`: pw85_overlap,
// pw85_contact_function or pw85_contact) on the batch's pairs, split over 1
// or 2 std::threads that take chunks of `chunk` pairs from a shared counter
// (as the batch's dynamic schedule does) and prefetch pair k + 16 (as the
// batch does). Each thread also records its thread CPU time and pair
// count, so a 2-thread pass shows whether both vCPUs ran this code at the
// one-thread rate (docs/batch.md).
struct PairsThreadStat {
  long long pairs = 0;
  double cpu_ns = 0.0;
};

template <class One>
void control_pairs(long long n, double const *centres, double const *q, long long m,
                   long long const *pairs, long long chunk, int threads, PairsThreadStat stat[2],
                   One const &one) {
  constexpr long long kAhead = 16;
  std::atomic<long long> next{0};
  split_over_threads(threads, [&, n](int id) {
    double const c0 = thread_ns();
    long long done = 0;
    for (;;) {
      long long const k0 = next.fetch_add(chunk, std::memory_order_relaxed);
      if (k0 >= m) break;
      long long const k1 = std::min(m, k0 + chunk);
      for (long long k = k0; k < k1; ++k) {
        if (k + kAhead < m) {
          long long const a = pairs[2 * (k + kAhead)], b = pairs[2 * (k + kAhead) + 1];
          __builtin_prefetch(centres + 3 * a);
          __builtin_prefetch(centres + 3 * b);
          __builtin_prefetch(q + 6 * a);
          __builtin_prefetch(q + 6 * a + 5);
          __builtin_prefetch(q + 6 * b);
          __builtin_prefetch(q + 6 * b + 5);
        }
        long long const i = pairs[2 * k], j = pairs[2 * k + 1];
        if (i < 0 || j < 0 || i >= n || j >= n) continue;  // none in the benchmark's scene
        double const r[3] = {centres[3 * j] - centres[3 * i], centres[3 * j + 1] - centres[3 * i + 1],
                             centres[3 * j + 2] - centres[3 * i + 2]};
        one(k, r, q + 6 * i, q + 6 * j);
      }
      done += k1 - k0;
    }
    stat[id].pairs = done;
    stat[id].cpu_ns = thread_ns() - c0;
  });
}

// ---- reference data ----------------------------------------------------------
bool read_group(char const *path, char const *group, std::vector<Pair> &out,
                std::vector<int> &cls) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  hid_t const f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return false;
  std::string const g = group;
  hsize_t dims[2] = {0, 0};
  H5T_class_t tc;
  size_t ts;
  bool ok = H5LTget_dataset_info(f, (g + "/mu2").c_str(), dims, &tc, &ts) >= 0;
  size_t const n = ok ? dims[0] : 0;
  std::vector<double> r(3 * n), q1(6 * n), q2(6 * n), mu2(n);
  cls.assign(n, -1);
  ok = ok && H5LTread_dataset_double(f, (g + "/r12").c_str(), r.data()) >= 0 &&
       H5LTread_dataset_double(f, (g + "/q1").c_str(), q1.data()) >= 0 &&
       H5LTread_dataset_double(f, (g + "/q2").c_str(), q2.data()) >= 0 &&
       H5LTread_dataset_double(f, (g + "/mu2").c_str(), mu2.data()) >= 0 &&
       H5LTread_dataset_int(f, (g + "/class").c_str(), cls.data()) >= 0;
  H5Fclose(f);
  if (!ok) return false;
  out.resize(n);
  for (size_t i = 0; i < n; ++i) {
    Pair &p = out[i];
    std::memcpy(p.r, &r[3 * i], sizeof p.r);
    std::memcpy(p.e1.q, &q1[6 * i], sizeof p.e1.q);
    std::memcpy(p.e2.q, &q2[6 * i], sizeof p.e2.q);
    axes_from_q(p.e1);
    axes_from_q(p.e2);
    // mu2 is correctly rounded: mu2 == 1 could hide either side.
    p.ref = mu2[i] < 1.0 ? 1 : (mu2[i] > 1.0 ? 0 : -1);
  }
  return true;
}

// ---- verdict functions -------------------------------------------------------
struct Scene {
  std::string name;
  std::vector<Pair> pairs;
#ifdef PW85_HAVE_FCL
  std::vector<fcl::CollisionObjectd> o1, o2;
#endif
};

int verdict_overlap(Pair const &p, size_t) { return pw85_overlap(p.r, p.e1.q, p.e2.q); }

int verdict_contact(Pair const &p, size_t) {
  pw85_result res;
  int const s = pw85_contact_function_method(p.r, p.e1.q, p.e2.q, PW85_METHOD_DEFAULT, &res);
  if (s < 0 && s != PW85_ERR_INACCURATE && s != PW85_ERR_NO_CONVERGENCE) return s;
  return res.mu2 < 1.0;
}

struct Stats {
  double med, mn, mx, pair_med;
  int wrong, errors, checked;
};

constexpr int kLatCalls = 8;

double now_ns() {
  return std::chrono::duration<double, std::nano>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Median cost of two consecutive steady_clock reads (subtracted from the
// per-pair latencies).
double clock_overhead_ns() {
  std::vector<double> v(2001);
  for (double &x : v) {
    double const t0 = now_ns();
    double const t1 = now_ns();
    x = t1 - t0;
  }
  return median(v);
}

template <class F>
Stats run(Scene const &sc, int reps, F verdict) {
  Stats st{0, 0, 0, 0, 0, 0, 0};
  size_t const n = sc.pairs.size();
  for (size_t i = 0; i < n; ++i) {
    int const v = verdict(sc.pairs[i], i);
    if (v < 0) {
      ++st.errors;
      continue;
    }
    if (sc.pairs[i].ref < 0) continue;
    ++st.checked;
    if (v != sc.pairs[i].ref) ++st.wrong;
  }
  std::vector<double> ns(reps);
  volatile int sink = 0;
  for (int rep = 0; rep < reps; ++rep) {
    int acc = 0;
    double const t0 = thread_ns();
    for (size_t i = 0; i < n; ++i) acc += verdict(sc.pairs[i], i);
    double const t1 = thread_ns();
    sink = sink + acc;
    ns[rep] = (t1 - t0) / (double)n;
  }
  st.med = median(ns);
  st.mn = *std::min_element(ns.begin(), ns.end());
  st.mx = *std::max_element(ns.begin(), ns.end());
  double const overhead = clock_overhead_ns();
  std::vector<double> lat(n);
  int acc = 0;
  for (size_t i = 0; i < n; ++i) {
    double const t0 = now_ns();
    for (int k = 0; k < kLatCalls; ++k) acc += verdict(sc.pairs[i], i);
    double const t1 = now_ns();
    lat[i] = (t1 - t0 - overhead) / kLatCalls;
  }
  sink = sink + acc;
  st.pair_med = n ? median(lat) : 0.0;
  return st;
}

#ifdef PW85_HAVE_FCL
void make_fcl(Scene &sc) {
  sc.o1.reserve(sc.pairs.size());
  sc.o2.reserve(sc.pairs.size());
  for (Pair const &p : sc.pairs) {
    for (int w = 0; w < 2; ++w) {
      Ell const &e = w ? p.e2 : p.e1;
      auto geom = std::make_shared<fcl::Ellipsoidd>(e.a[0], e.a[1], e.a[2]);
      fcl::Transform3d tf = fcl::Transform3d::Identity();
      fcl::Matrix3d R;
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) R(i, k) = e.rot[i][k];
      tf.linear() = R;
      if (w) tf.translation() = fcl::Vector3d(p.r[0], p.r[1], p.r[2]);
      (w ? sc.o2 : sc.o1).emplace_back(geom, tf);
    }
  }
}
#endif

}  // namespace

int main(int argc, char **argv) {
  int n = 20000, reps = 7, batch_reps = 5;
  double batch_min_ms = 0.0;
  long long batch_n = 100000, batch_m = 1000000;
  bool batch = true, overlap_only = false;
  uint64_t seed = 20260521;
  char const *out = nullptr;
  char const *ref = std::getenv("PW85_REF_DATA");
  if (!ref) ref = PW85_REF_DATA_PATH;
  bool bad = false;
  for (int i = 1; i < argc; ++i) {
    if (int const k = bench::common_option(argc, argv, i, n, reps, seed))
      i += k - 1;
    else if (!std::strcmp(argv[i], "--ref") && i + 1 < argc)
      ref = argv[++i];
    else if (!std::strcmp(argv[i], "--batch-n") && i + 1 < argc)
      batch_n = std::atoll(argv[++i]);
    else if (!std::strcmp(argv[i], "--batch-m") && i + 1 < argc)
      batch_m = std::atoll(argv[++i]);
    else if (!std::strcmp(argv[i], "--batch-reps") && i + 1 < argc)
      batch_reps = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--batch-min-ms") && i + 1 < argc)
      batch_min_ms = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--no-batch"))
      batch = false;
    else if (!std::strcmp(argv[i], "--overlap-only"))
      overlap_only = true;
    else if (argv[i][0] == '-')
      bad = true;  // unknown option, or one missing its value
    else
      out = argv[i];
  }
  if (bad || !out || n <= 0 || reps <= 0 || batch_n < 2 || batch_m <= 0 || batch_reps <= 0 ||
      !(batch_min_ms >= 0.0)) {
    std::fprintf(stderr,
                 "usage: %s [--n N] [--reps R] [--seed S] [--ref FILE] [--batch-n N] "
                 "[--batch-m M] [--batch-reps R] [--batch-min-ms T] [--no-batch] [--overlap-only] OUT.csv\n",
                 argv[0]);
    return 2;
  }
  double const bounds[4][2] = {{0.5, 2}, {0.1, 10}, {0.01, 100}, {0.001, 1000}};
  std::vector<Scene> scenes;
  // Generated scenes: per class, n random pairs with centre offsets
  // 10^U(-2, -2 + span) times a1max + a2max (bench::random_offset).
  int gen_skipped[2][4] = {{0, 0, 0, 0}, {0, 0, 0, 0}};
  auto generate = [&](Rng &rng, char const *prefix, double span, int skipped[4]) {
    for (int c = 0; c < 4; ++c) {
      Scene sc;
      sc.name = prefix + std::to_string(c);
      sc.pairs.resize(n);
      for (Pair &p : sc.pairs) {
        double const am1 = random_ellipsoid(rng, bounds[c][0], bounds[c][1], p.e1);
        double const am2 = random_ellipsoid(rng, bounds[c][0], bounds[c][1], p.e2);
        bench::random_offset(rng, am1 + am2, span, p.r);
        pw85_result res;
        int const s = pw85_contact_function_method(p.r, p.e1.q, p.e2.q, PW85_METHOD_DEFAULT, &res);
        if (s == PW85_OK && std::fabs(res.mu2 - 1.0) > 1e-8)
          p.ref = res.mu2 < 1.0;
        else {
          p.ref = -1;
          ++skipped[c];
        }
      }
      scenes.push_back(std::move(sc));
    }
  };
  // contact_scene/classK: the pairs of bench_contact (same seed, generator
  // and span: identical for the same --n), the scenes of bench_contact.
  Rng g_contact{seed};
  generate(g_contact, "contact_scene/class", bench::kContactSpan, gen_skipped[1]);
  // gen/classK: the wider scenes (up to 10 times a1max +
  // a2max, hence more far-apart pairs); g then goes on to the batch scene.
  Rng g{seed};
  generate(g, "gen/class", 3.0, gen_skipped[0]);
  bool have_ref = false;
  {
    std::vector<Pair> all;
    std::vector<int> cls;
    if (read_group(ref, "/contact", all, cls)) {
      have_ref = true;
      for (int c = 0; c < 4; ++c) {
        Scene sc;
        sc.name = "ref/contact/class" + std::to_string(c);
        for (size_t i = 0; i < all.size(); ++i)
          if (cls[i] == c) sc.pairs.push_back(all[i]);
        scenes.push_back(std::move(sc));
      }
    }
    if (read_group(ref, "/near_contact", all, cls)) {
      Scene sc;
      sc.name = "ref/near_contact";
      sc.pairs = all;
      scenes.push_back(std::move(sc));
    } else {
      have_ref = false;
    }
  }
  if (!have_ref) std::fprintf(stderr, "warning: reference data %s not read; generated scenes only\n", ref);

  FILE *csv = std::fopen(out, "w");
  if (!csv) {
    std::perror(out);
    return 1;
  }
  std::fprintf(csv, "# bench_overlap: pw85 %s, seed %" PRIu64 ", n %d pairs per generated class, reps %d\n",
               pw85_version(), seed, n, reps);
  std::fprintf(csv, "# machine: %s\n", run_command("uname -a").c_str());
  std::fprintf(csv, "# cpu: %s (%s logical CPUs)\n", cpu_model().c_str(), run_command("nproc").c_str());
  std::fprintf(csv, "# load average at start (shared machine): %s\n",
               run_command("cat /proc/loadavg").c_str());
  std::fprintf(csv, "# compiler: g++ %s\n", __VERSION__);
  std::fprintf(csv, "# flags: %s\n", PW85_BENCH_FLAGS);
#ifdef PW85_HAVE_FCL
  std::fprintf(csv, "# fcl: %s, fcl::collide with a default CollisionRequestd (libccd)\n", FCL_VERSION);
#else
  std::fprintf(csv, "# fcl: not built (meson option fcl)\n");
#endif
  std::fprintf(csv, "# reference data: %s\n", have_ref ? ref : "not read");
  std::fprintf(csv, "# time: ns per pair = thread CPU time of one pass over the scene / pairs; "
                    "median, min, max over reps passes (median_ns, min_ns, max_ns: each the "
                    "MEAN over the pairs of one pass); median_pair_ns = median over the pairs of "
                    "the per-pair latency (%d consecutive calls on the pair between two "
                    "steady_clock reads, minus the clock overhead, / %d: warm caches and "
                    "branch predictors)\n", kLatCalls, kLatCalls);
  std::fprintf(csv, "# reference verdict: gen/* and contact_scene/* from mu2 of pw85_contact_function_method DEFAULT, "
                    "only pairs with |mu2 - 1| > 1e-8 counted (n_checked); ref/* from the "
                    "correctly rounded mu2 of the reference file\n");
  std::fprintf(csv, "# batch rows: scene = n ellipsoids / m pairs, median_ns = median wall-clock ns "
                    "per pair over batch reps, ratio column = speed-up (1-thread time / this time)\n");
  std::fprintf(csv, "# batch rows leave median_pair_ns out (10 fields)\n");
  std::fprintf(csv, "scene,function,n_pairs,n_checked,median_ns,min_ns,max_ns,wrong_verdicts,"
                    "errors,ratio_to_pw85_overlap,median_pair_ns\n");
  std::printf("%-22s %-22s %6s %7s %9s %9s %9s %6s %5s %7s %9s\n", "scene", "function", "pairs",
              "checked", "median_ns", "min_ns", "max_ns", "wrong", "err", "ratio", "pair_ns");
  auto emit = [&](Scene const &sc, char const *fn, Stats const &st, double ratio) {
    std::printf("%-22s %-22s %6zu %7d %9.1f %9.1f %9.1f %6d %5d %7.2f %9.1f\n", sc.name.c_str(),
                fn, sc.pairs.size(), st.checked, st.med, st.mn, st.mx, st.wrong, st.errors, ratio,
                st.pair_med);
    std::fprintf(csv, "%s,%s,%zu,%d,%.2f,%.2f,%.2f,%d,%d,%.3f,%.2f\n", sc.name.c_str(), fn,
                 sc.pairs.size(), st.checked, st.med, st.mn, st.mx, st.wrong, st.errors, ratio,
                 st.pair_med);
    std::fflush(stdout);
  };
  for (Scene &sc : scenes) {
    Stats const ov = run(sc, reps, verdict_overlap);
    emit(sc, "pw85_overlap", ov, 1.0);
    if (overlap_only) continue;
    Stats const cf = run(sc, reps, verdict_contact);
    emit(sc, "contact_function_DEFAULT", cf, cf.med / ov.med);
#ifdef PW85_HAVE_FCL
    make_fcl(sc);
    fcl::CollisionRequestd const request;
    Stats const fc = run(sc, reps, [&sc, &request](Pair const &, size_t i) {
      fcl::CollisionResultd result;
      fcl::collide(&sc.o1[i], &sc.o2[i], request, result);
      return result.isCollision() ? 1 : 0;
    });
    emit(sc, "fcl_collide", fc, fc.med / ov.med);
    sc.o1.clear();
    sc.o2.clear();
#endif
  }
  for (int k = 0; k < 2; ++k)
    for (int c = 0; c < 4; ++c)
      std::fprintf(csv, "# %s%d: %d of %d pairs not counted (|mu2 - 1| <= 1e-8 or status != OK)\n",
                   k ? "contact_scene/class" : "gen/class", c, gen_skipped[k][c], n);

  if (batch) {
    // Batch scene: class-0 ellipsoids in a cube.
    std::vector<double> centres(3 * batch_n), q(6 * batch_n);
    double const side = 2.0 * std::cbrt((double)batch_n);
    for (long long i = 0; i < batch_n; ++i) {
      Ell e;
      random_ellipsoid(g, 0.5, 2.0, e);
      std::memcpy(&q[6 * i], e.q, sizeof e.q);
      for (int d = 0; d < 3; ++d) centres[3 * i + d] = side * g.uniform();
    }
    std::vector<long long> pairs(2 * batch_m);
    for (long long k = 0; k < batch_m; ++k) {
      long long i = (long long)(g.next() % (uint64_t)batch_n), j;
      do j = (long long)(g.next() % (uint64_t)batch_n); while (j == i);
      pairs[2 * k] = i;
      pairs[2 * k + 1] = j;
    }
    std::vector<int> ov(batch_m), st(batch_m);
    std::vector<pw85_contact_t> ct(batch_m);
    char name[64];
    for (int order = 0; order < 2; ++order) {
    if (order == 1) {
      // Pairs sorted by (i, j), as a neighbour list would be: the centre and
      // matrix of i stay in cache.
      std::vector<std::pair<long long, long long>> v(batch_m);
      for (long long k = 0; k < batch_m; ++k) v[k] = {pairs[2 * k], pairs[2 * k + 1]};
      std::sort(v.begin(), v.end());
      for (long long k = 0; k < batch_m; ++k) pairs[2 * k] = v[k].first, pairs[2 * k + 1] = v[k].second;
    }
    std::snprintf(name, sizeof name, "batch/%lld/%lld/%s", batch_n, batch_m,
                  order ? "sorted" : "random");
    // Functions: 0 pw85_overlap_batch, 1 pw85_contact_function_batch,
    // 2 pw85_contact_batch, 3 and 4 controls (compute-only loops split over
    // 1 or 2 std::threads, no library call: the speed-up the machine itself
    // offers during the run; 3 latency-bound, 4 throughput-bound), 5
    // control_pairs[ov] (the one-pair pw85_overlap over the same pairs on
    // std::threads, no OpenMP), 6 and 7 control_pairs[cf] and [ct] (the same
    // with pw85_contact_function and pw85_contact). Each batch function is
    // timed in the same repetitions as its control_pairs and
    // control_throughput, passes interleaved in the order of the group, so
    // that a disturbance of the machine shows in the controls in the same
    // repetition (docs/batch.md).
    std::vector<int> ov_control(batch_m);
    int const groups[4][3] = {{0, 5, 4}, {1, 6, 4}, {2, 7, 4}, {3, -1, -1}};
    for (auto const &group : groups) {
      if (overlap_only && (group[0] == 1 || group[0] == 2)) continue;  // contact batch calls
      int const nfn = group[1] < 0 ? 1 : 3;
      // One untimed pass (caches, page faults of the outputs, OpenMP thread
      // pool), then reps passes alternating 1 and 2 threads, so that load
      // from other processes on the shared machine hits both alike; each
      // (1-thread, 2-thread) pair of consecutive passes gives one ratio.
      std::vector<double> w[3][3], ratios[3];
      std::vector<std::string> thread_rates;  // control_pairs: per-thread ns per pair, each pass
      std::vector<double> out2(group[0] == 1 ? 2 * batch_m : 0),
          out2_control(group[0] == 1 ? 2 * batch_m : 0);
      std::vector<pw85_contact_t> ct_control(group[0] == 2 ? batch_m : 0);
      int status[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
      double load0[3] = {0, 0, 0}, load1[3] = {0, 0, 0};
      if (getloadavg(load0, 3) < 0) load0[0] = load0[1] = load0[2] = -1.0;
      volatile double control_sink = 0.0;
      int calls[3] = {1, 1, 1};  // consecutive calls per timed pass, set after the untimed pass
      for (int rep = -1; rep < batch_reps; ++rep) {
        for (int f = 0; f < nfn; ++f) {
          int const fn = group[f];
          double pass[3] = {0, 0, 0};
          for (int threads = 1; threads <= 2; ++threads) {
            PairsThreadStat stat[2];
            auto const t0 = std::chrono::steady_clock::now();
            for (int call = 0; call < calls[f]; ++call) {
              int &stt = status[f][threads];
              if (fn == 0)
                stt = pw85_overlap_batch(batch_n, centres.data(), q.data(), batch_m, pairs.data(),
                                         ov.data(), st.data(), threads);
              else if (fn == 1)
                stt = pw85_contact_function_batch(batch_n, centres.data(), q.data(), batch_m,
                                                  pairs.data(), out2.data(), st.data(), threads);
              else if (fn == 2)
                stt = pw85_contact_batch(batch_n, centres.data(), q.data(), batch_m, pairs.data(),
                                         ct.data(), st.data(), threads);
              else if (fn == 3)
                control_latency(batch_m, threads, control_sink);
              else if (fn == 4)
                control_throughput(2 * batch_m, threads, control_sink);  // ~25 ms on one thread
              else if (fn == 5)
                control_pairs(batch_n, centres.data(), q.data(), batch_m, pairs.data(), 256,
                              threads, stat,
                              [&](long long k, double const *r, double const *qi, double const *qj) {
                                ov_control[k] = pw85_overlap(r, qi, qj);
                              });
              else if (fn == 6)
                control_pairs(batch_n, centres.data(), q.data(), batch_m, pairs.data(), 64,
                              threads, stat,
                              [&](long long k, double const *r, double const *qi, double const *qj) {
                                pw85_contact_function(r, qi, qj, &out2_control[2 * k]);
                              });
              else
                control_pairs(batch_n, centres.data(), q.data(), batch_m, pairs.data(), 64,
                              threads, stat,
                              [&](long long k, double const *r, double const *qi, double const *qj) {
                                pw85_contact(r, qi, qj, &ct_control[k]);
                              });
            }
            auto const t1 = std::chrono::steady_clock::now();
            pass[threads] = std::chrono::duration<double, std::nano>(t1 - t0).count() /
                            ((double)batch_m * calls[f]);
            if (rep >= 0) w[f][threads].push_back(pass[threads]);
            bool const pairs_control = fn >= 5;
            if (pairs_control && threads == 2 && rep >= 0) {
              // Thread CPU ns per pair of each thread (last call of the pass).
              char buf[48];
              std::snprintf(buf, sizeof buf, " %.1f/%.1f",
                            stat[0].cpu_ns / (double)std::max(1LL, stat[0].pairs),
                            stat[1].cpu_ns / (double)std::max(1LL, stat[1].pairs));
              thread_rates.push_back(buf);
            }
            if (pairs_control && threads == 1 && rep >= 0) {
              char buf[32];
              std::snprintf(buf, sizeof buf, " [1thr %.1f]",
                            stat[0].cpu_ns / (double)std::max(1LL, stat[0].pairs));
              thread_rates.push_back(buf);
            }
          }
          if (rep >= 0) ratios[f].push_back(pass[1] / pass[2]);
          // Passes of at least batch_min_ms (one thread): a single call of the
          // cheapest function lasts only ~10-30 ms (docs/batch.md).
          if (rep < 0)
            calls[f] = std::max(1, (int)std::ceil(batch_min_ms * 1e6 / (pass[1] * (double)batch_m)));
        }
      }
      if (getloadavg(load1, 3) < 0) load1[0] = load1[1] = load1[2] = -1.0;
      for (int f = 0; f < nfn; ++f) {
        int const fn = group[f];
        char const *fname = fn == 0 ? "pw85_overlap_batch"
                            : fn == 1 ? "pw85_contact_function_batch"
                            : fn == 2 ? "pw85_contact_batch"
                            : fn == 3 ? "control_compute"
                            : fn == 4 ? (group[0] == 0   ? "control_throughput[ov]"
                                         : group[0] == 1 ? "control_throughput[cf]"
                                                         : "control_throughput[ct]")
                            : fn == 5 ? "control_pairs[ov]"
                            : fn == 6 ? "control_pairs[cf]" : "control_pairs[ct]";
        double const t1thread = median(w[f][1]);
        for (int threads = 1; threads <= 2; ++threads) {
          double const med = median(w[f][threads]);
          char label[64];
          std::snprintf(label, sizeof label, "%s/%dthr", fname, threads);
          double const mn = *std::min_element(w[f][threads].begin(), w[f][threads].end());
          double const mx = *std::max_element(w[f][threads].begin(), w[f][threads].end());
          double const speedup = t1thread / med;
          std::printf("%-22s %-34s %6lld %7s %9.1f %9.1f %9.1f %6s %5d %7.2f\n", name, label,
                      batch_m, "-", med, mn, mx, "-", status[f][threads] != PW85_OK, speedup);
          std::fprintf(csv, "%s,%s,%lld,0,%.2f,%.2f,%.2f,,%d,%.3f\n", name, label, batch_m, med,
                       mn, mx, status[f][threads] != PW85_OK, speedup);
        }
        // Spread of the speed-up: the ratio of each interleaved pair of passes,
        // their median, and the ratio of the fastest passes (the least disturbed).
        std::string rs;
        for (double r : ratios[f]) {
          char buf[16];
          std::snprintf(buf, sizeof buf, " %.2f", r);
          rs += buf;
        }
        double const best = *std::min_element(w[f][1].begin(), w[f][1].end()) /
                            *std::min_element(w[f][2].begin(), w[f][2].end());
        std::printf("  %s (%d call(s) per pass) speed-up per pass:%s; median %.2f, ratio of "
                    "fastest passes %.2f; load average (1/5/15 min) %.2f %.2f %.2f before, "
                    "%.2f %.2f %.2f after\n",
                    fname, calls[f], rs.c_str(), median(ratios[f]), best, load0[0], load0[1],
                    load0[2], load1[0], load1[1], load1[2]);
        std::fprintf(csv, "# %s %s (%d call(s) per pass) speed-up per pass:%s; median %.3f; "
                          "fastest-pass ratio %.3f; loadavg %.2f %.2f %.2f before, %.2f %.2f %.2f after\n",
                     name, fname, calls[f], rs.c_str(), median(ratios[f]), best, load0[0], load0[1],
                     load0[2], load1[0], load1[1], load1[2]);
        if (f > 0) {
          // The batch function's speed-up over this control's, repetition by
          // repetition: above ~1, the batch call lost nothing the machine
          // did not also take from the control.
          std::vector<double> rel;
          for (size_t k = 0; k < ratios[0].size() && k < ratios[f].size(); ++k)
            rel.push_back(ratios[0][k] / ratios[f][k]);
          std::printf("  speed-up of %s / speed-up of %s, same repetition: median %.2f\n",
                      group[0] == 0   ? "pw85_overlap_batch"
                      : group[0] == 1 ? "pw85_contact_function_batch"
                                      : "pw85_contact_batch",
                      fname, median(rel));
          std::fprintf(csv, "# %s speed-up of function %d / speed-up of %s, same repetition: median %.3f\n",
                       name, group[0], fname, median(rel));
        }
        if (fn >= 5) {
          std::string tr;
          for (auto const &t : thread_rates) tr += t;
          std::printf("  %s thread CPU ns per pair, per repetition [1 thread] then "
                      "thread 0/thread 1 of the 2-thread pass:%s\n", fname, tr.c_str());
          std::fprintf(csv, "# %s %s thread CPU ns per pair ([1 thread] then thread "
                            "0/thread 1 of the 2-thread pass):%s\n", name, fname, tr.c_str());
          bool same = true;
          if (fn == 5)
            for (long long k = 0; k < batch_m; ++k) same = same && ov_control[k] == ov[k];
          else if (fn == 6)
            same = std::memcmp(out2_control.data(), out2.data(), out2.size() * sizeof(double)) == 0;
          else
            for (long long k = 0; k < batch_m; ++k)
              same = same && std::memcmp(&ct_control[k], &ct[k], sizeof ct[k]) == 0;
          if (!same) std::printf("  WARNING: %s results differ from the batch call's\n", fname);
        }
      }
      std::fflush(stdout);
    }
    }
    long long noverlap = 0;
    for (int v : ov) noverlap += v == 1;
    std::fprintf(csv, "# batch scene: %lld class-0 ellipsoids, centres uniform in a cube of side "
                      "%.3f, %lld random pairs (i != j), %lld of them overlapping; wall-clock time; "
                      "random: pairs in random order; sorted: the same pairs sorted by (i, j)\n",
                 batch_n, side, batch_m, noverlap);
  }
  std::fclose(csv);
  return 0;
}
