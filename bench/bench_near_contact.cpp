// The exact overlap predicate near contact and in a dense packing, against
// random pairs in the same run (docs/performance.md, "Near contact and dense
// packing"). NOT a test: built by meson, never run by `meson test`, not
// installed; it prints and writes CSV, and counts wrong verdicts.
//
//   bench_near_contact [--n N] [--reps R] [--seed S] [--no-dense]
//                      [--dense-cells K] [--aspect C_OVER_A] [--phi PHI] OUT.csv
//
// Sets of pairs, per class 0-3 of bench_contact (three distinct semi-axes
// log-uniform in [0.5, 2], [0.1, 10], [0.01, 100], [0.001, 1000], uniformly
// random orientations):
//  - random/classK: N pairs drawn as bench_contact draws them (centre
//    distance (a1max + a2max) 10^U(-2, 0.5), bench::random_offset);
//  - near/classK: N pairs of bench::near_contact_pair (pair_sets.hpp):
//    drawn the same way, then r12 scaled so that mu^2 hits 1 +- delta, delta
//    log-uniform in [1e-15, 1e-2], by DEFAULT's mu^2. The realised
//    |mu^2 - 1| is that of the reference below.
// Dense packing (dense/aspectA; --no-dense skips it): N = 4 K^3 spheroids
// (semi-axes 0.5, 0.5, 0.5 A) in a periodic orthorhombic box, made by the
// library's configuration object: an fcc lattice of spheres stretched by A
// along z at packing fraction PHI (aligned spheroids, no contact), then
// 10 cycles of (i) Monte Carlo sweeps (20 in the first cycle, then 2; trial
// moves checked by pw85_configuration_test_move, committed by
// pw85_configuration_move; translation uniform in [-dr, dr]^3 or rotation
// of the axis u to (u + dtheta g) / |u + dtheta g|, g standard normal; dr
// and dtheta scaled each sweep towards acceptance 0.3) and (ii) an affine
// compression of centres and box by the largest factor f >= 0.995 that
// leaves every pair at mu^2 >= 1 + 1e-9 (mu^2 scales as f^2:
// f = sqrt((1 + 1e-9) / min mu^2) over the pairs within s = sqrt 2 of
// pw85_configuration_pairs, whose mu^2 it returns), checked by
// pw85_configuration_pairs(s = 1) (no overlapping pair, else the
// compression is undone). The run ends on a compression: its closest pair
// at mu^2 = 1 + 1e-9, the others at the gaps the sweeps left. The workload:
// the neighbour pairs within s = sqrt 2 of the final configuration (r12 the
// minimum image), timed as pw85_overlap one-pair loop, pw85_overlap_pairs
// and pw85_scene_overlap (box given); dense/aspectA/gap<1e-2: its pairs
// with |mu^2 - 1| < 1e-2 (one-pair loop and pw85_overlap_pairs).
//
// Reference verdict of every pair: mu^2 < 1 with mu^2 maximised in
// __float128 from the double inputs (bench/reference_mu2.hpp); pairs with
// |mu^2_ref - 1| < 1e-24 are undecided and not counted. n_wrong counts the
// one-pair verdicts that differ from the reference; the batch calls must
// return the one-pair verdicts bitwise (n_wrong of their rows counts the
// differences from pw85_overlap).
//
// Timing: R repetitions; in each, one pass of every timed call over every
// set of a class, one after the other (so the random and near passes of a
// repetition see the same machine state); ns per pair = thread CPU time of
// the pass / pairs; median, min, max over the repetitions.
// ratio_to_random = median over the repetitions of (pass time per pair of the
// row) / (pass time per pair of the same call on random/classK in that
// repetition; class 0 for dense/*), with min and max. near/classK/1e-D rows:
// the near pairs whose realised |mu^2 - 1| lies in [1e-D, 1e-(D-1)) (one-pair
// loop only), to show where near contact costs.
#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <sys/utsname.h>
#include <time.h>

#include "bench_common.hpp"
#include "pair_sets.hpp"
#include "pw85.h"
#include "reference_mu2.hpp"

#ifndef PW85_BENCH_FLAGS
#define PW85_BENCH_FLAGS "unknown"
#endif

namespace {

using bench::Rng;

// A set of pairs in the layout of the pairs calls, with its reference.
struct PairSet {
  std::string name;
  int cls = 0;         // class of the random set it is compared with
  std::vector<double> r12, q1, q2;
  std::vector<int> ref;            // reference verdict: 1, 0, or -1 undecided
  std::vector<double> gap;         // |mu^2_ref - 1| (double)
  long long size() const { return (long long)ref.size(); }
  void add(double const r[3], double const a[6], double const b[6]) {
    r12.insert(r12.end(), r, r + 3);
    q1.insert(q1.end(), a, a + 6);
    q2.insert(q2.end(), b, b + 6);
  }
};

// Reference verdicts of every pair of the set, on two threads.
void reference_verdicts(PairSet &s) {
  long long const m = (long long)s.r12.size() / 3;
  s.ref.assign(m, -1);
  s.gap.assign(m, NAN);
  auto work = [&s, m](int id) {
    for (long long k = id; k < m; k += 2) {
      __float128 const mu2 = bench::reference_mu2(&s.r12[3 * k], &s.q1[6 * k], &s.q2[6 * k]);
      __float128 const d = mu2 - 1;
      double const gap = (double)(d < 0 ? -d : d);
      s.gap[k] = gap;
      s.ref[k] = !(gap >= 1e-24) ? -1 : (mu2 < 1 ? 1 : 0);
    }
  };
  std::thread helper(work, 1);
  work(0);
  helper.join();
}

double thread_ns() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  size_t const i = (size_t)(q * (double)(v.size() - 1) + 0.5);
  return v[std::min(i, v.size() - 1)];
}

// ---- dense packing ----------------------------------------------------------

struct Packing {
  int n = 0;
  double a = 0.5, c = 0.5;
  double box[6] = {0, 0, 0, 0, 0, 0};
  std::vector<double> x, u, q;  // centres in [0, L), unit axes, matrices
  double phi() const {
    return n * (4.0 / 3.0) * M_PI * a * a * c / (box[0] * box[1] * box[2]);
  }
};

void spheroid_q(double a, double c, double const u[3], double q[6]) {
  double const d = c * c - a * a;
  q[0] = a * a + d * u[0] * u[0], q[1] = d * u[0] * u[1], q[2] = d * u[0] * u[2];
  q[3] = a * a + d * u[1] * u[1], q[4] = d * u[1] * u[2], q[5] = a * a + d * u[2] * u[2];
}

double wrap(double v, double L) {
  v = std::fmod(v, L);
  if (v < 0) v += L;
  if (v >= L) v -= L;
  return v;
}

// Returns false (and prints why) when a library call fails.
bool check(int status, char const *what) {
  if (status == PW85_OK) return true;
  std::fprintf(stderr, "bench_near_contact: %s: %s\n", what, pw85_strerror(status));
  return false;
}

// Number of pairs within s of the configuration.
bool pair_count(pw85_configuration const *conf, double s, long long &count) {
  int const status =
      pw85_configuration_pairs(conf, s, 1, 0, nullptr, nullptr, nullptr, &count, nullptr);
  return check(status == PW85_ERR_CAPACITY ? PW85_OK : status, "pw85_configuration_pairs");
}

// The compression run of the header comment. Returns false on a library
// error; cycles and rejected receive its counts.
constexpr int kFirstSweeps = 20, kSweepsPerCompression = 2, kCompressions = 10;
bool make_packing(Rng &g, int cells, double aspect, double phi_target, Packing &p, int &cycles,
                  int &rejected) {
  p.n = 4 * cells * cells * cells;
  p.c = p.a * aspect;
  // fcc of spheres of diameter 1 at packing fraction phi_target.
  double const lattice = std::cbrt(4.0 * (4.0 / 3.0) * M_PI * 0.125 / phi_target);
  p.box[0] = p.box[1] = cells * lattice;
  p.box[2] = cells * lattice * aspect;
  double const basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  p.x.clear(), p.u.clear(), p.q.clear();
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j)
      for (int k = 0; k < cells; ++k)
        for (auto const &b : basis) {
          double const cell[3] = {i + b[0], j + b[1], k + b[2]};
          for (int d = 0; d < 3; ++d)
            p.x.push_back(cell[d] * lattice * (d == 2 ? aspect : 1.0));
          double const u[3] = {0, 0, 1};
          double q[6];
          spheroid_q(p.a, p.c, u, q);
          p.u.insert(p.u.end(), u, u + 3);
          p.q.insert(p.q.end(), q, q + 6);
        }
  pw85_configuration *conf = nullptr;
  if (!check(pw85_configuration_create(p.n, p.x.data(), p.q.data(), p.box, &conf, nullptr),
             "pw85_configuration_create"))
    return false;
  double dr = 0.05, dtheta = 0.05;
  cycles = rejected = 0;
  bool ok = true;
  std::vector<long long> pi, pj;
  std::vector<double> pmu2;
  for (; ok && cycles < kCompressions; ++cycles) {
    for (int sweep = 0; sweep < (cycles ? kSweepsPerCompression : kFirstSweeps) && ok; ++sweep) {
      int accepted = 0;
      for (int t = 0; t < p.n; ++t) {
        int const i = (int)(g.next() % (uint64_t)p.n);
        double x[3] = {p.x[3 * i], p.x[3 * i + 1], p.x[3 * i + 2]};
        double u[3] = {p.u[3 * i], p.u[3 * i + 1], p.u[3 * i + 2]};
        if (g.uniform() < 0.5) {
          for (int d = 0; d < 3; ++d) x[d] = wrap(x[d] + dr * (2 * g.uniform() - 1), p.box[d]);
        } else {
          double nu = 0;
          for (int d = 0; d < 3; ++d) u[d] += dtheta * g.normal(), nu += u[d] * u[d];
          for (double &v : u) v /= std::sqrt(nu);
        }
        double q[6];
        spheroid_q(p.a, p.c, u, q);
        long long j = -1;
        if (!(ok = check(pw85_configuration_test_move(conf, i, x, q, &j), "test_move"))) break;
        if (j >= 0) continue;
        if (!(ok = check(pw85_configuration_move(conf, i, x, q), "move"))) break;
        ++accepted;
        std::copy(x, x + 3, &p.x[3 * i]);
        std::copy(u, u + 3, &p.u[3 * i]);
        std::copy(q, q + 6, &p.q[6 * i]);
      }
      double const acc = (double)accepted / p.n;
      double const scale = std::min(1.5, std::max(0.5, acc / 0.3));
      dr = std::min(dr * scale, 0.5);
      dtheta = std::min(dtheta * scale, 1.0);
    }
    if (!ok) break;
    long long count = 0;
    if (!(ok = pair_count(conf, std::sqrt(2.0), count))) break;
    pi.resize(count), pj.resize(count), pmu2.resize(count);
    if (!(ok = check(pw85_configuration_pairs(conf, std::sqrt(2.0), 1, count, pi.data(), pj.data(),
                                              pmu2.data(), &count, nullptr),
                     "pw85_configuration_pairs")))
      break;
    double min_mu2 = INFINITY;
    for (double m : pmu2) min_mu2 = std::min(min_mu2, m);
    double const f = std::max(0.995, std::sqrt((1 + 1e-9) / min_mu2));
    if (!(f < 1)) continue;
    Packing trial = p;
    for (double &v : trial.x) v *= f;
    for (int d = 0; d < 3; ++d) trial.box[d] *= f;
    for (int i = 0; i < trial.n; ++i)
      for (int d = 0; d < 3; ++d) trial.x[3 * i + d] = wrap(trial.x[3 * i + d], trial.box[d]);
    if (!(ok = check(pw85_configuration_update(conf, trial.n, trial.x.data(), trial.q.data(),
                                               trial.box, nullptr),
                     "pw85_configuration_update")))
      break;
    long long overlapping = 0;
    if (!(ok = pair_count(conf, 1.0, overlapping))) break;
    if (overlapping == 0) {
      p = trial;
    } else {
      ++rejected;
      ok = check(pw85_configuration_update(conf, p.n, p.x.data(), p.q.data(), p.box, nullptr),
                 "pw85_configuration_update");
    }
  }
  pw85_configuration_destroy(conf);
  return ok;
}

// The neighbour pairs within s = sqrt 2 of the packing, r12 the minimum image
// (orthorhombic box: each component reduced by the nearest multiple of L).
bool packing_pairs(Packing const &p, PairSet &set, std::vector<long long> &index_pairs) {
  pw85_configuration *conf = nullptr;
  if (!check(pw85_configuration_create(p.n, p.x.data(), p.q.data(), p.box, &conf, nullptr),
             "pw85_configuration_create"))
    return false;
  long long count = 0;
  std::vector<long long> pi, pj;
  bool const ok = pair_count(conf, std::sqrt(2.0), count) &&
                  (pi.resize(count), pj.resize(count), true) &&
                  check(pw85_configuration_pairs(conf, std::sqrt(2.0), 1, count, pi.data(),
                                                 pj.data(), nullptr, &count, nullptr),
                        "pw85_configuration_pairs");
  pw85_configuration_destroy(conf);
  if (!ok) return false;
  for (long long k = 0; k < count; ++k) {
    long long const i = pi[k], j = pj[k];
    double r[3];
    for (int d = 0; d < 3; ++d) {
      double const v = p.x[3 * j + d] - p.x[3 * i + d];
      r[d] = v - p.box[d] * std::nearbyint(v / p.box[d]);
    }
    set.add(r, &p.q[6 * i], &p.q[6 * j]);
    index_pairs.push_back(i), index_pairs.push_back(j);
  }
  return true;
}

// ---- timing -------------------------------------------------------------------

// One timed call over a set: a pass returns the thread CPU ns per pair and
// writes the verdicts.
struct Timed {
  std::string set, call;
  int cls;
  PairSet const *pairs;
  std::function<void(std::vector<int> &)> pass;
  std::vector<double> ns;
  std::vector<int> verdict;
  Timed const *baseline = nullptr;  // the same call on the random set
  Timed const *one_pair = nullptr;  // the one-pair loop on the same set
};

// The loop of pw85_overlap over the set.
Timed one_pair_loop(PairSet const &s) {
  Timed one{s.name, "pw85_overlap", s.cls, &s, nullptr, {}, {}};
  long long const m = s.size();
  one.pass = [&s, m](std::vector<int> &v) {
    for (long long k = 0; k < m; ++k)
      v[k] = pw85_overlap(&s.r12[3 * k], &s.q1[6 * k], &s.q2[6 * k]);
  };
  return one;
}

}  // namespace

int main(int argc, char **argv) {
  int n = 100000, reps = 7, cells = 7;
  uint64_t seed = 20260521;
  double aspect = 2.0, phi_target = 0.62;
  bool dense = true, bad = false;
  char const *out = nullptr;
  for (int i = 1; i < argc; ++i) {
    if (int const k = bench::common_option(argc, argv, i, n, reps, seed))
      i += k - 1;
    else if (!std::strcmp(argv[i], "--no-dense"))
      dense = false;
    else if (!std::strcmp(argv[i], "--dense-cells") && i + 1 < argc)
      cells = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--aspect") && i + 1 < argc)
      aspect = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--phi") && i + 1 < argc)
      phi_target = std::atof(argv[++i]);
    else if (argv[i][0] == '-')
      bad = true;
    else
      out = argv[i];
  }
  if (bad || !out || n <= 0 || reps <= 0 || cells < 5 || !(aspect >= 0.2 && aspect <= 5) ||
      !(phi_target >= 0.5 && phi_target <= 0.7)) {
    std::fprintf(stderr,
                 "usage: %s [--n N] [--reps R] [--seed S] [--no-dense] [--dense-cells K >= 5]\n"
                 "          [--aspect A in [0.2, 5]] [--phi PHI in [0.5, 0.7]] OUT.csv\n",
                 argv[0]);
    return 2;
  }
  FILE *csv = std::fopen(out, "w");
  if (!csv) {
    std::perror(out);
    return 1;
  }
  std::vector<PairSet> sets;
  sets.reserve(10);
  Rng g{seed};
  for (int c = 0; c < 4; ++c) {
    PairSet rnd, near;
    rnd.name = "random/class" + std::to_string(c), rnd.cls = c;
    near.name = "near/class" + std::to_string(c), near.cls = c;
    double r[3], q1[6], q2[6];
    for (int k = 0; k < n; ++k) {
      bench::random_pair(g, c, bench::kContactSpan, r, q1, q2);
      rnd.add(r, q1, q2);
    }
    for (int k = 0; k < n; ++k) {
      bench::near_contact_pair(g, c, r, q1, q2);
      near.add(r, q1, q2);
    }
    reference_verdicts(rnd);
    reference_verdicts(near);
    sets.push_back(std::move(rnd));
    sets.push_back(std::move(near));
  }
  std::vector<long long> dense_index;
  Packing packing;
  int cycles = 0, rejected = 0;
  if (dense) {
    PairSet d;
    char name[64];
    std::snprintf(name, sizeof name, "dense/aspect%g", aspect);
    d.name = name, d.cls = 0;
    if (!make_packing(g, cells, aspect, phi_target, packing, cycles, rejected) ||
        !packing_pairs(packing, d, dense_index))
      return 1;
    reference_verdicts(d);
    PairSet close;
    close.name = d.name + "/gap<1e-2", close.cls = 0;
    for (long long k = 0; k < d.size(); ++k)
      if (d.gap[k] < 1e-2) {
        close.add(&d.r12[3 * k], &d.q1[6 * k], &d.q2[6 * k]);
        close.ref.push_back(d.ref[k]), close.gap.push_back(d.gap[k]);
      }
    sets.push_back(std::move(d));
    if (close.size()) sets.push_back(std::move(close));
  }

  // Timed calls.
  std::vector<Timed> timed;
  timed.reserve(128);
  std::vector<size_t> random_row(4 * 2);  // index in timed of (class, call) on random/*
  for (PairSet const &s : sets) {
    long long const m = s.size();
    Timed const one = one_pair_loop(s);
    Timed batch{s.name, "pw85_overlap_pairs", s.cls, &s, nullptr, {}, {}};
    batch.pass = [&s, m](std::vector<int> &v) {
      pw85_overlap_pairs(m, s.r12.data(), s.q1.data(), s.q2.data(), v.data(), nullptr, 1);
    };
    bool const is_random = s.name.compare(0, 7, "random/") == 0;
    if (is_random) random_row[2 * s.cls] = timed.size();
    timed.push_back(one);
    if (is_random) random_row[2 * s.cls + 1] = timed.size();
    timed.push_back(batch);
    if (dense && s.name == sets[8].name) {
      Timed scene{s.name, "pw85_scene_overlap", 0, &s, nullptr, {}, {}};
      Packing const *pk = &packing;
      std::vector<long long> const *idx = &dense_index;
      scene.pass = [pk, idx, m](std::vector<int> &v) {
        pw85_scene_overlap(pk->n, pk->x.data(), pk->q.data(), pk->box, m, idx->data(), v.data(),
                           nullptr, 1);
      };
      timed.push_back(scene);
    }
  }
  // Per-decade subsets of the near sets (one-pair loop).
  std::vector<PairSet> decades;
  decades.reserve(4 * 13);
  for (PairSet const &s : sets) {
    if (s.name.compare(0, 5, "near/")) continue;
    for (int dec = 15; dec >= 3; --dec) {
      PairSet sub;
      char name[64];
      std::snprintf(name, sizeof name, "%s/1e-%d", s.name.c_str(), dec);
      sub.name = name, sub.cls = s.cls;
      for (long long k = 0; k < s.size(); ++k)
        if (s.gap[k] >= std::pow(10.0, -dec) && s.gap[k] < std::pow(10.0, 1 - dec)) {
          sub.add(&s.r12[3 * k], &s.q1[6 * k], &s.q2[6 * k]);
          sub.ref.push_back(s.ref[k]), sub.gap.push_back(s.gap[k]);
        }
      if (sub.size()) decades.push_back(std::move(sub));
    }
  }
  for (PairSet const &s : decades) timed.push_back(one_pair_loop(s));
  for (Timed &t : timed) {
    t.baseline = &timed[random_row[2 * t.cls + (t.call == "pw85_overlap" ? 0 : 1)]];
    t.verdict.assign(t.pairs->size(), -99);
    for (Timed &o : timed)
      if (o.pairs == t.pairs && o.call == "pw85_overlap") t.one_pair = &o;
  }
  for (Timed &t : timed) t.pass(t.verdict);  // untimed pass, verdicts
  for (int rep = 0; rep < reps; ++rep)
    for (Timed &t : timed) {
      std::vector<int> v(t.pairs->size());
      double const t0 = thread_ns();
      t.pass(v);
      t.ns.push_back((thread_ns() - t0) / (double)std::max(1LL, t.pairs->size()));
    }

  // Output.
  std::fprintf(csv, "# bench_near_contact: pw85 %s, seed %" PRIu64 ", n %d per set, reps %d\n",
               pw85_version(), seed, n, reps);
  std::fprintf(csv, "# machine: %s\n", bench::run_command("uname -a").c_str());
  std::fprintf(csv, "# cpu: %s\n", bench::cpu_model().c_str());
  std::fprintf(csv, "# load: %s\n", bench::run_command("cat /proc/loadavg").c_str());
  std::fprintf(csv, "# compiler: g++ %s\n", __VERSION__);
  std::fprintf(csv, "# flags: %s\n", PW85_BENCH_FLAGS);
  if (dense) {
    long long near6 = 0, near9 = 0, near2 = 0;
    PairSet const &d = sets[8];
    for (double gp : d.gap) near2 += gp < 1e-2, near6 += gp < 1e-6, near9 += gp < 1e-8;
    std::fprintf(csv,
                 "# %s: %d spheroids (0.5, 0.5, %g), box %.6f x %.6f x %.6f, phi %.4f after %d "
                 "compression cycles (%d undone); %lld neighbour pairs within s = sqrt 2, of "
                 "which %lld with |mu2 - 1| < 1e-2, %lld < 1e-6, %lld < 1e-8\n",
                 d.name.c_str(), packing.n, packing.c, packing.box[0], packing.box[1],
                 packing.box[2], packing.phi(), cycles, rejected, d.size(), near2, near6, near9);
  }
  std::fprintf(csv, "# time: ns per pair = thread CPU time of a pass / pairs, median/min/max "
                    "over reps; ratio_to_random: per-repetition ratio to the same call on "
                    "random/classK (class 0 for dense), median/min/max; one thread\n");
  std::fprintf(csv, "# reference: mu2 maximised in __float128 (bench/reference_mu2.hpp); "
                    "n_undecided: |mu2_ref - 1| < 1e-24; n_wrong: one-pair verdict != reference, "
                    "batch rows: verdict != pw85_overlap's\n");
  std::fprintf(csv, "set,class,call,n,median_ns,min_ns,max_ns,ratio_to_random,ratio_min,ratio_max,"
                    "n_wrong,n_undecided,n_errors\n");
  std::printf("%-24s %-20s %7s %9s %9s %9s %8s %8s %8s %6s %6s\n", "set", "call", "n", "median",
              "min", "max", "ratio", "r_min", "r_max", "wrong", "undec");
  int total_wrong = 0;
  for (Timed const &t : timed) {
    std::vector<double> ratio(reps);
    for (int r = 0; r < reps; ++r) ratio[r] = t.ns[r] / t.baseline->ns[r];
    int wrong = 0, undecided = 0, errors = 0;
    for (long long k = 0; k < t.pairs->size(); ++k) {
      int const v = t.verdict[k];
      if (v < 0) ++errors;
      if (t.call == "pw85_overlap") {
        if (t.pairs->ref[k] < 0)
          ++undecided;
        else if (v != t.pairs->ref[k])
          ++wrong;
      } else if (v != t.one_pair->verdict[k]) {
        ++wrong;
      }
    }
    total_wrong += wrong;
    double const med = quantile(t.ns, 0.5);
    double const mn = *std::min_element(t.ns.begin(), t.ns.end());
    double const mx = *std::max_element(t.ns.begin(), t.ns.end());
    double const rmed = quantile(ratio, 0.5);
    double const rmn = *std::min_element(ratio.begin(), ratio.end());
    double const rmx = *std::max_element(ratio.begin(), ratio.end());
    std::printf("%-24s %-20s %7lld %9.1f %9.1f %9.1f %8.2f %8.2f %8.2f %6d %6d\n", t.set.c_str(),
                t.call.c_str(), t.pairs->size(), med, mn, mx, rmed, rmn, rmx, wrong, undecided);
    std::fprintf(csv, "%s,%d,%s,%lld,%.2f,%.2f,%.2f,%.3f,%.3f,%.3f,%d,%d,%d\n", t.set.c_str(),
                 t.cls, t.call.c_str(), t.pairs->size(), med, mn, mx, rmed, rmn, rmx, wrong,
                 undecided, errors);
  }
  std::fclose(csv);
  std::printf("wrong verdicts: %d\n", total_wrong);
  return total_wrong ? 1 : 0;
}
