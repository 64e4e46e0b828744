/* Correctness and cost of pw85_contact_time (docs/contact_time.md) against
 * the independent long-double reference of tests/ct_reference.h (dense
 * sampling, golden-section refinement of every sampled minimum, bisection of
 * each crossing; it never calls the library).
 *
 * For each of the four semi-axis classes, n trajectories: 60 % random
 * (rotations up to half a turn), 20 % grazing (translations tangent to the
 * level set mu^2 = 1 + delta, delta = +-1e-6, +-1e-9, +-1e-12), 20 % spinning
 * (2-5 turns of each ellipsoid within the horizon); then n / 5 rotating
 * grazes (kind rotgraze: a stationary minimum of mu^2 at 1 + delta,
 * delta = +-1e-6, +-1e-9, +-1e-12, while each ellipsoid turns 0.5-3 times).
 * Counts (ct_verdict of
 * tests/ct_reference.h, tol = 1e-9 t_max):
 *   missed: the reference finds mu^2 < 1 - 1e-12 at t_a and the library
 *           reports no contact or a time after t_a + tol;
 *   early:  the library reports t < t_c - tol, t_c the reference's first
 *           crossing of mu^2 = 1;
 *   false:  the library reports a contact, the reference's minimum of mu^2
 *           is above 1
 *   (early and false waived when the reference finds mu^2 <= 1 at t or
 *   t + tol: a dip narrower than its samples);
 *   failed: a status other than PW85_OK.
 * err: |t - t_c| / t_max over the trajectories with mu^2 < 1 - 1e-12
 * somewhere; err_g12: the same over the grazing trajectories tangent to
 * mu^2 = 1 - 1e-12 (the crossing of 1 least determined; rotating grazes of
 * minimum 1 - 1e-12 for rotgraze). Evaluations: those of
 * pw85_contact_time_ex. ns per call: thread CPU time of one pass over the
 * trajectories of a kind, median over the repetitions (spread: min-max); baseline
 * in the same passes: one PW85_METHOD_DEFAULT evaluation at t = 0 per
 * trajectory (ns_default), and the cost per evaluation over it.
 *
 *   build/bench/bench_contact_time [--verbose] [--still] [--class C] [--n 1000] [--reps 5] [--seed 42] > docs/bench_contact_time.csv
 *
 * --still: the same trajectories with w1 = w2 = 0 (translation only; the
 * kinds keep their names).
 *
 * The table goes to stderr, the CSV to stdout. Benchmark only. */
#define _POSIX_C_SOURCE 199309L
#include <pw85.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../tests/ct_reference.h"

static double thread_ns(void) {
  struct timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e9 * t.tv_sec + t.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}
static double median(double *v, int n) {
  qsort(v, n, sizeof *v, cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static volatile double sink;

static const char *kind_name[CT_KINDS] = {"random", "grazing", "spinning", "rotgraze"};

int main(int argc, char **argv) {
  int n = 1000, reps = 5, verbose = 0, only = -1, still = 0;
  unsigned long long seed = 42;
  for (int i = 1; i < argc; i += 2) {
    if (!strcmp(argv[i], "--verbose")) { verbose = 1; i--; continue; }
    if (!strcmp(argv[i], "--still")) { still = 1; i--; continue; }
    if (i + 1 >= argc) { fprintf(stderr, "option %s needs a value\n", argv[i]); return 2; }
    if (!strcmp(argv[i], "--n")) n = atoi(argv[i + 1]);
    else if (!strcmp(argv[i], "--reps")) reps = atoi(argv[i + 1]);
    else if (!strcmp(argv[i], "--class")) only = atoi(argv[i + 1]);
    else if (!strcmp(argv[i], "--seed")) seed = strtoull(argv[i + 1], NULL, 10);
    else { fprintf(stderr, "unknown option %s\n", argv[i]); return 2; }
  }
  if (n < 10 || reps < 1 || reps > 64) return 2;
  const double lo[4] = {0.5, 0.1, 0.01, 0.001}, hi[4] = {2, 10, 100, 1000};
  printf("class,kind,n,contacts,missed,early,false,failed,max_err,median_err,max_err_g12,"
         "median_eval,max_eval,ns_median,ns_min,ns_max,ns_default,ns_per_eval_over_default,"
         "ref_median_eval\n");
  fprintf(stderr, "%-5s %-8s %6s %6s %6s %5s %5s %6s %9s %9s %9s %6s %7s %9s %9s\n", "class",
          "kind", "n", "contact", "missed", "early", "false", "failed", "max_err", "med_err",
          "err_g12", "med_ev", "max_ev", "ns/call", "spread");
  int const nr = n / 5, nt = n + nr;  /* n of the first three kinds, then n / 5 rotating grazes */
  ct_traj *tr = malloc(sizeof *tr * nt);
  double *t = malloc(sizeof *t * nt), *ev = malloc(sizeof *ev * nt), *err = malloc(sizeof *err * nt);
  double *rev = malloc(sizeof *rev * nt), *ns = malloc(sizeof *ns * reps);
  int *kind = malloc(sizeof *kind * nt), *st = malloc(sizeof *st * nt);
  for (int c = 0; c < 4; c++) {
    if (only >= 0 && c != only) continue;
    ct_rng g = {seed * 4 + c}, gr = {seed * 4 + c + 1000};
    for (int i = 0; i < n; i++) {
      kind[i] = i % 5 < 3 ? CT_RANDOM : (i % 5 == 3 ? CT_GRAZING : CT_SPINNING);
      ct_make(&g, lo[c], hi[c], kind[i], i / 5, &tr[i]);
    }
    for (int i = n; i < nt; i++) {
      kind[i] = CT_ROTGRAZE;
      ct_make(&gr, lo[c], hi[c], CT_ROTGRAZE, i - n, &tr[i]);
    }
    if (still) /* the same trajectories without rotation */
      for (int i = 0; i < nt; i++)
        for (int j = 0; j < 3; j++) tr[i].w1[j] = tr[i].w2[j] = 0.0;
    double sum = 0, nsk[CT_KINDS][64], nsd[64];
    for (int r = 0; r < reps; r++) {
      for (int k = 0; k < CT_KINDS; k++) {
        double const t0 = thread_ns();
        int cnt = 0;
        for (int i = 0; i < nt; i++) {
          if (kind[i] != k) continue;
          int e;
          st[i] = pw85_contact_time_ex(tr[i].r0, tr[i].v, tr[i].q1, tr[i].w1, tr[i].q2, tr[i].w2,
                                       tr[i].t_max, &t[i], &e);
          ev[i] = e;
          cnt++;
        }
        nsk[k][r] = (thread_ns() - t0) / cnt;
      }
      /* baseline in the same pass: one DEFAULT evaluation at t = 0 */
      double const t0 = thread_ns();
      for (int i = 0; i < n; i++) {
        pw85_result res;
        pw85_contact_function_method(tr[i].r0, tr[i].q1, tr[i].q2, PW85_METHOD_DEFAULT, &res);
        sum += res.mu2;
      }
      nsd[r] = (thread_ns() - t0) / n;
    }
    sink = sum;
    double const nsdef = median(nsd, reps);
    for (int k = 0; k < CT_KINDS; k++) {
      int cnt = 0, contacts = 0, missed = 0, early = 0, falsec = 0, failed = 0, nerr = 0;
      double maxerr = 0, maxerr_g12 = 0, evk[nt], revk[nt];
      for (int i = 0; i < nt; i++) {
        if (kind[i] != k) continue;
        ct_ref ref;
        ct_reference(&tr[i], &ref);
        revk[cnt] = ref.evaluations;
        evk[cnt++] = ev[i];
        if (ref.t[0] != INFINITY) contacts++;
        if (st[i] != PW85_OK) { failed++; continue; }
        int const v = ct_verdict(&tr[i], &ref, t[i]);
        missed += !!(v & CT_MISSED);
        early += !!(v & CT_EARLY);
        falsec += !!(v & CT_FALSE);
        if (verbose && v) {
          ctr_real lam = 0.5L;
          double const m = t[i] == INFINITY ? NAN : (double)ctr_mu2_at(&tr[i], t[i], &lam);
          fprintf(stderr, "%s%s%s class %d #%d: t %.17g, reference t(1-1e-12) %.17g t(1) %.17g, "
                  "min mu2 - 1 %.3g, reference mu2(t) - 1 %.3g, %g evaluations\n",
                  v & CT_MISSED ? "missed " : "", v & CT_EARLY ? "early " : "",
                  v & CT_FALSE ? "false " : "", c, i, t[i], ref.t[0], ref.t[1],
                  ref.min_mu2 - 1, m - 1, ev[i]);
        }
        if (ref.t[0] != INFINITY) {
          double const e = fabs(t[i] - ref.t[1]) / tr[i].t_max;
          err[nerr++] = e;
          if (e > maxerr) maxerr = e;
          if (k == CT_GRAZING && (i / 5) % 6 == 5 && e > maxerr_g12) maxerr_g12 = e;
          if (k == CT_ROTGRAZE && (i - n) % 6 == 5 && e > maxerr_g12) maxerr_g12 = e;
        }
      }
      double const mederr = nerr ? median(err, nerr) : 0;
      double evsum = 0;
      for (int i = 0; i < cnt; i++) evsum += evk[i];
      double const nsmed = median(nsk[k], reps), nsmin = nsk[k][0], nsmax = nsk[k][reps - 1];
      double maxev = 0;
      for (int i = 0; i < cnt; i++) maxev = fmax(maxev, evk[i]);
      double const medev = median(evk, cnt), medrev = median(revk, cnt);
      printf("%d,%s,%d,%d,%d,%d,%d,%d,%.3g,%.3g,%.3g,%g,%g,%.0f,%.0f,%.0f,%.1f,%.2f,%g\n", c,
             kind_name[k], cnt, contacts, missed, early, falsec, failed, maxerr, mederr,
             maxerr_g12, medev, maxev, nsmed, nsmin, nsmax, nsdef, nsmed / (evsum / cnt) / nsdef,
             medrev);
      fprintf(stderr, "%-5d %-8s %6d %6d %6d %5d %5d %6d %9.2e %9.2e %9.2e %6g %7g %9.0f %4.0f-%.0f\n",
              c, kind_name[k], cnt, contacts, missed, early, falsec, failed, maxerr, mederr,
              maxerr_g12, medev, maxev, nsmed, nsmin, nsmax);
    }
  }
  free(tr); free(t); free(ev); free(err); free(rev); free(ns); free(kind); free(st);
  return 0;
}
