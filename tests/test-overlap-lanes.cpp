/* The overlap lanes of both widths and the one-pair hot path of every
 * variant this CPU runs (src/core/overlap/overlap_variants.cpp: portable,
 * x86-64-v3, x86-64-v4; docs/batch.md, "Throughput"), called directly
 * through the table of each variant (dispatch/kernels.hpp, kernels_of):
 * the public API takes only the variant and the width this CPU runs, so
 * without this program the portable and x86-64-v3 code would never run on
 * an AVX-512 machine, nor the 4-lane width there. Linked with the library's
 * own objects (pw85_core). Under valgrind (overlap-lanes-valgrind: no
 * AVX-512 emulated) the portable and v3 variants run; with
 * isa_dispatch=false only the portable one is built.
 *
 * For 2048 pairs of each class of bench_batch (semi-axes log-uniform in
 * [0.5, 2] ... [0.001, 1000], centre offsets from deep overlap to 3.2 times
 * the reach) with bad pairs among them (r12 = 0, NaN r12, a matrix not
 * positive definite, an infinite entry, a zero matrix), in blocks at every
 * offset 0 ... W - 1 (so that each pair visits every lane, next to other
 * neighbours): every decided lane (verdict 0 or 1) equals pw85_overlap's
 * verdict, a bad pair is never decided, each pair gets the same verdict in
 * every lane position, and at least 95 % of the good pairs are decided;
 * the one-pair path of each variant either declines (bad pairs, and only
 * those with r12 != 0 that pw85_overlap rejects) or gives pw85_overlap's
 * verdict and status.
 *
 * The rows of the reference groups /contact, /near_contact and /special
 * (mu^2 from exact rational arithmetic), each in every lane position of
 * both widths and through each one-pair path: every decided verdict is the
 * reference verdict (the near-tangent and special pairs are where a wrong
 * rounding margin of a certificate shows). */
#include <cmath>
#include <vector>

#include <glib.h>

#include "dispatch/kernels.hpp"
#include "overlap/overlap.hpp"
#include "pw85.h"
#include "../bench/bench_common.hpp"
extern "C" {
#include "refdata.h"
}

namespace {

constexpr int kPairs = 2048;

// The overlap kernels of the variants this CPU runs, each table once (a
// variant without overlap kernels of its own shares another's table).
struct OverlapVariant {
  pw85::Variant variant;
  pw85::OverlapKernels const *kernels;
};
std::vector<OverlapVariant> overlap_variants() {
  std::vector<OverlapVariant> out;
  pw85::Variant const all[] = {pw85::Variant::portable, pw85::Variant::fma, pw85::Variant::v3,
                               pw85::Variant::v4};
  for (pw85::Variant v : all) {
    if (!pw85::variant_runs(v)) continue;
    pw85::OverlapKernels const *k = pw85::kernels_of(v).overlap;
    bool seen = false;
    for (OverlapVariant const &o : out) seen = seen || o.kernels == k;
    if (!seen) out.push_back({v, k});
  }
  return out;
}

template <int W>
void lanes(pw85::OverlapKernels const &k, double const *const rp[W], double const *const q1p[W],
           double const *const q2p[W], int v[W]) {
  static_assert(W == 4 || W == 8, "the widths of OverlapKernels");
  if constexpr (W == 8)
    k.lanes8(rp, q1p, q2p, v);
  else
    k.lanes4(rp, q1p, q2p, v);
}

struct Pairs {
  std::vector<double> r, q1, q2;
  std::vector<int> ref;   // pw85_overlap: 1, 0 or a negative status
  std::vector<bool> bad;  // an argument pw85_overlap rejects, or r12 = 0
};

Pairs make_pairs(int cls) {
  double const lo[4] = {0.5, 0.1, 0.01, 0.001}, hi[4] = {2.0, 10.0, 100.0, 1000.0};
  bench::Rng g{1234u + static_cast<unsigned>(cls)};
  Pairs p;
  p.r.resize(3 * kPairs);
  p.q1.resize(6 * kPairs);
  p.q2.resize(6 * kPairs);
  p.ref.resize(kPairs);
  p.bad.assign(kPairs, false);
  for (int k = 0; k < kPairs; ++k) {
    double a1[3], a2[3], rot[3][3];
    bench::random_axes(g, lo[cls], hi[cls], a1, rot);
    bench::q_from_axes(a1, rot, &p.q1[6 * k]);
    bench::random_axes(g, lo[cls], hi[cls], a2, rot);
    bench::q_from_axes(a2, rot, &p.q2[6 * k]);
    double const reach = std::fmax(a1[0], std::fmax(a1[1], a1[2])) +
                         std::fmax(a2[0], std::fmax(a2[1], a2[2]));
    bench::random_offset(g, reach, bench::kContactSpan, &p.r[3 * k]);
  }
  for (int k = 5; k < kPairs; k += 97) {
    p.bad[k] = true;
    switch ((k / 97) % 5) {
      case 0: p.r[3 * k] = p.r[3 * k + 1] = p.r[3 * k + 2] = 0.0; break;
      case 1: p.r[3 * k + 1] = NAN; break;
      case 2: p.q1[6 * k] = -1.0; break;
      case 3: p.q2[6 * k + 4] = INFINITY; break;
      default:
        for (int i = 0; i < 6; ++i) p.q1[6 * k + i] = 0.0;
    }
  }
  for (int k = 0; k < kPairs; ++k)
    p.ref[k] = pw85_overlap(&p.r[3 * k], &p.q1[6 * k], &p.q2[6 * k]);
  return p;
}

template <int W>
void check_width(pw85::OverlapKernels const &kernels, Pairs const &p) {
  // verdict of pair k in each lane position, -2 before any
  std::vector<int> seen(kPairs, -2);
  int good = 0, decided = 0;
  for (int off = 0; off < W; ++off)
    for (int k0 = off; k0 + W <= kPairs; k0 += W) {
      double const *rp[W], *q1p[W], *q2p[W];
      for (int l = 0; l < W; ++l) {
        rp[l] = &p.r[3 * (k0 + l)];
        q1p[l] = &p.q1[6 * (k0 + l)];
        q2p[l] = &p.q2[6 * (k0 + l)];
      }
      int v[W];
      lanes<W>(kernels, rp, q1p, q2p, v);
      for (int l = 0; l < W; ++l) {
        int const k = k0 + l;
        g_assert_cmpint(v[l], >=, -1);
        g_assert_cmpint(v[l], <=, 1);
        if (v[l] >= 0) g_assert_cmpint(v[l], ==, p.ref[k]);
        if (p.bad[k]) g_assert_cmpint(v[l], ==, -1);
        if (seen[k] != -2) g_assert_cmpint(v[l], ==, seen[k]);
        seen[k] = v[l];
        if (off == 0 && !p.bad[k]) {
          good++;
          decided += v[l] >= 0;
        }
      }
    }
  g_assert_cmpint(good, >, kPairs / 2);
  g_assert_cmpint(decided, >=, 0.95 * good);
}

void test_class(gconstpointer data) {
  int const cls = *static_cast<int const *>(data);
  Pairs const p = make_pairs(cls);
  int n_overlap = 0, n_bad = 0;
  for (int k = 0; k < kPairs; ++k) {
    n_overlap += p.ref[k] == 1;
    n_bad += p.ref[k] < 0;
  }
  // both verdicts common; the rejected arguments rejected (r12 = 0 is not)
  g_assert_cmpint(n_overlap, >, kPairs / 5);
  g_assert_cmpint(n_overlap, <, 4 * kPairs / 5);
  g_assert_cmpint(n_bad, >, 0);
  for (OverlapVariant const &o : overlap_variants()) {
    pw85::OverlapKernels const &kernels = *o.kernels;
    g_test_message("variant %s", pw85::variant_name(o.variant));
    check_width<pw85::kOverlapLanes>(kernels, p);
    check_width<pw85::kOverlapLanesV4>(kernels, p);
    for (int k = 0; k < kPairs; ++k) {
      int verdict = -7;
      pw85::Status status = pw85::kOk;
      bool const screened =
          kernels.screened(&p.r[3 * k], &p.q1[6 * k], &p.q2[6 * k], verdict, status);
      if (p.ref[k] < 0) g_assert_false(screened);
      if (!screened) continue;
      g_assert_cmpint(status, ==, pw85::kOk);
      g_assert_cmpint(verdict, ==, p.ref[k]);
    }
  }
}

template <int W>
void check_reference_width(pw85::OverlapKernels const &kernels, RefPairs const *g, int &wrong,
                           int &decided) {
  long long const n = static_cast<long long>(g->n);
  for (int off = 0; off < W; ++off)
    for (long long k0 = -off; k0 < n; k0 += W) {
      double const *rp[W], *q1p[W], *q2p[W];
      for (int l = 0; l < W; ++l) {
        long long const k = ((k0 + l) % n + n) % n;  // wrap around: every row in every lane
        rp[l] = g->r12 + 3 * k;
        q1p[l] = g->q1 + 6 * k;
        q2p[l] = g->q2 + 6 * k;
      }
      int v[W];
      lanes<W>(kernels, rp, q1p, q2p, v);
      for (int l = 0; l < W; ++l) {
        long long const k = ((k0 + l) % n + n) % n;
        double const mu2 = g->mu2[k];
        if (v[l] < 0 || mu2 == 1.0) continue;
        decided++;
        if (v[l] != (mu2 < 1.0 ? 1 : 0)) {
          wrong++;
          g_test_message("%s row %lld, width %d, lane %d: verdict %d, reference mu2 %.17g",
                         g->group, k, W, l, v[l], mu2);
        }
      }
    }
}

void test_reference(gconstpointer data) {
  RefPairs *g = refdata_pairs_or_skip(static_cast<char const *>(data));
  if (g == nullptr) return;
  int wrong = 0, decided = 0;
  for (OverlapVariant const &o : overlap_variants()) {
    pw85::OverlapKernels const &kernels = *o.kernels;
    check_reference_width<pw85::kOverlapLanes>(kernels, g, wrong, decided);
    check_reference_width<pw85::kOverlapLanesV4>(kernels, g, wrong, decided);
    for (long long k = 0; k < static_cast<long long>(g->n); ++k) {
      int verdict = -7;
      pw85::Status status = pw85::kOk;
      double const mu2 = g->mu2[k];
      if (!kernels.screened(g->r12 + 3 * k, g->q1 + 6 * k, g->q2 + 6 * k, verdict, status) ||
          status != pw85::kOk || mu2 == 1.0)
        continue;
      decided++;
      if (verdict != (mu2 < 1.0 ? 1 : 0)) {
        wrong++;
        g_test_message("%s row %lld, one pair, variant %s: verdict %d, reference mu2 %.17g",
                       g->group, k, pw85::variant_name(o.variant), verdict, mu2);
      }
    }
  }
  g_test_message("%s: %llu rows, %d lane verdicts, %d wrong", g->group,
                 static_cast<unsigned long long>(g->n), decided, wrong);
  g_assert_cmpint(wrong, ==, 0);
  g_assert_cmpint(decided, >, 0);
  refdata_pairs_free(g);
}

}  // namespace

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  int const w = pw85::overlap_lanes_width();
  g_assert_true(w == pw85::kOverlapLanes || w == pw85::kOverlapLanesV4);
  static int const classes[4] = {0, 1, 2, 3};
  for (int c = 0; c < 4; ++c) {
    char path[64];
    g_snprintf(path, sizeof path, "/overlap_lanes/class-%d", c);
    g_test_add_data_func(path, &classes[c], test_class);
  }
  static char const *const groups[3] = {"/contact", "/near_contact", "/special"};
  for (char const *gname : groups) {
    char path[64];
    g_snprintf(path, sizeof path, "/overlap_lanes/reference%s", gname);
    g_test_add_data_func(path, gname, test_reference);
  }
  return g_test_run();
}
