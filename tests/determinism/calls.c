/* See calls.h. */
#include "calls.h"

#include <math.h>
#include <string.h>

#include "pw85.h"
#include "pw85_legacy.h"

uint64_t rng_next(test_rng *g) {
  uint64_t z = (g->s += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double rng_uniform(test_rng *g) { return (double)(rng_next(g) >> 11) * 0x1p-53; }

static double uni(test_rng *g, double lo, double hi) { return lo + (hi - lo) * rng_uniform(g); }

/* 10^u, u uniform in [lo, hi]. */
static double pow10u(test_rng *g, double lo, double hi) { return pow(10.0, uni(g, lo, hi)); }

/* A random rotation (unit quaternion from four uniform components): rows of
 * rot are the axes. */
static void rotation(test_rng *g, double rot[9]) {
  double q[4], n = 0.0;
  do {
    n = 0.0;
    for (int i = 0; i < 4; ++i) {
      q[i] = uni(g, -1.0, 1.0);
      n += q[i] * q[i];
    }
  } while (n < 1e-3 || n > 1.0);
  n = sqrt(n);
  double const w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
  double const m[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),
                       2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
                       2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)};
  memcpy(rot, m, sizeof m);
}

/* q = sum_i s[i] v_i v_i^T (s: squared radii, v_i: rows of rot). */
static void quad_form(double const s[3], double const rot[9], double q[6]) {
  int k = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      double a = 0.0;
      for (int l = 0; l < 3; ++l) a += s[l] * rot[3 * l + i] * rot[3 * l + j];
      q[k++] = a;
    }
}

static void random_form(test_rng *g, double lo, double hi, double q[6]) {
  double rot[9], s[3];
  rotation(g, rot);
  for (int i = 0; i < 3; ++i) s[i] = pow10u(g, lo, hi);
  quad_form(s, rot, q);
}

static double special(test_rng *g) {
  static double const v[] = {NAN, INFINITY, -INFINITY, 0.0, -0.0, 1e308, 5e-324, -1.0};
  return v[rng_next(g) % (sizeof v / sizeof v[0])];
}

void gen_input(test_rng *g, int kind, test_input *in) {
  memset(in, 0, sizeof *in);
  in->kind = kind;
  double scale = 1.0;
  switch (kind) {
    case 0: /* moderate */
      random_form(g, -2, 2, in->q1);
      random_form(g, -2, 2, in->q2);
      break;
    case 1: /* one scale for the pair, 1e-300..1e300 */
      scale = pow10u(g, -300, 300);
      random_form(g, -1, 1, in->q1);
      random_form(g, -1, 1, in->q2);
      for (int i = 0; i < 6; ++i) {
        in->q1[i] *= scale;
        in->q2[i] *= scale;
      }
      scale = sqrt(scale);
      break;
    case 2: { /* aspect ratios up to 1e16 (squared radii up to 1e32 apart) */
      double rot[9], s[3];
      for (int e = 0; e < 2; ++e) {
        rotation(g, rot);
        if (rng_next(g) & 1) /* axis-aligned: SPD however large the aspect */
          for (int i = 0; i < 9; ++i) rot[i] = i % 4 == 0 ? 1.0 : 0.0;
        double const asp = pow10u(g, 0, 16);
        s[0] = 1.0;
        s[1] = rng_next(g) & 1 ? 1.0 : asp * asp;
        s[2] = 1.0 / (asp * asp);
        quad_form(s, rot, e ? in->q2 : in->q1);
      }
      break;
    }
    case 3: { /* near-singular: v v^T + eps I */
      for (int e = 0; e < 2; ++e) {
        double v[3];
        for (int i = 0; i < 3; ++i) v[i] = uni(g, -1, 1);
        double const eps = pow10u(g, -17, -8);
        double *q = e ? in->q2 : in->q1;
        int k = 0;
        for (int i = 0; i < 3; ++i)
          for (int j = i; j < 3; ++j) q[k++] = v[i] * v[j] + (i == j ? eps : 0.0);
      }
      break;
    }
    case 4: /* r12 = 0 handled below */
    case 5: /* NaN/Inf set below */
    case 7: /* not SPD, set below */
      random_form(g, -2, 2, in->q1);
      random_form(g, -2, 2, in->q2);
      break;
    case 6: /* random bit patterns */
      for (int i = 0; i < 6; ++i) {
        uint64_t b = rng_next(g);
        memcpy(&in->q1[i], &b, 8);
        b = rng_next(g);
        memcpy(&in->q2[i], &b, 8);
      }
      break;
    case 8: /* very different scales */
      random_form(g, -300, -100, in->q1);
      random_form(g, 100, 300, in->q2);
      scale = 1e-50;
      break;
    default: { /* near tangency: two unit spheres, |r12| = 2 within a few ulps */
      for (int e = 0; e < 2; ++e) {
        double *q = e ? in->q2 : in->q1;
        q[0] = q[3] = q[5] = 1.0;
      }
      scale = 2.0;
      break;
    }
  }
  double r[3], n2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    r[i] = uni(g, -1, 1);
    n2 += r[i] * r[i];
  }
  double const len = kind == 9 ? 1.0 / sqrt(n2) : uni(g, 0.1, 3.0);
  for (int i = 0; i < 3; ++i) in->r12[i] = r[i] * len * scale;
  if (kind == 9)
    for (int i = 0; i < 3; ++i) in->r12[i] = nextafter(in->r12[i], (rng_next(g) & 1) ? 10.0 : -10.0);
  if (kind == 6)
    for (int i = 0; i < 3; ++i) {
      uint64_t b = rng_next(g);
      memcpy(&in->r12[i], &b, 8);
    }
  if (kind == 4) in->r12[0] = in->r12[1] = in->r12[2] = (rng_next(g) & 1) ? 0.0 : -0.0;
  if (kind == 5) {
    unsigned const k = rng_next(g) % 15;
    double const v = special(g);
    if (k < 3) in->r12[k] = v;
    else if (k < 9) in->q1[k - 3] = v;
    else in->q2[k - 9] = v;
  }
  if (kind == 7) {
    double *q = (rng_next(g) & 1) ? in->q1 : in->q2;
    q[(rng_next(g) & 1) ? 0 : 5] *= -1.0;
    if (rng_next(g) & 1) q[1] = 1e3 * (fabs(q[0]) + fabs(q[3])); /* indefinite */
  }

  static double const lambdas[] = {0.0, 1.0, 0.5, -0.25, 1.25, NAN};
  unsigned const li = rng_next(g) % 12;
  in->lambda = li < 6 ? lambdas[li] : rng_uniform(g);

  /* spheroid and ellipsoid arguments from the same magnitudes */
  in->a = sqrt(fabs(in->q1[0]));
  in->c = sqrt(fabs(in->q2[5]));
  if (kind == 5) in->c = special(g);
  for (int i = 0; i < 3; ++i) in->n[i] = in->r12[i];
  rotation(g, in->axes);
  if (rng_next(g) % 4 == 0) in->axes[rng_next(g) % 9] += pow10u(g, -12, -6);
  for (int i = 0; i < 3; ++i) in->radii[i] = sqrt(fabs(in->q1[2 * i]));
  if (kind == 7) in->radii[rng_next(g) % 3] *= -1.0;
  in->theta_tol = (rng_next(g) & 1) ? 0.0 : pow10u(g, -10, -3);
}

void sink_print(test_sink *s, char const *fn, long long status, double const *v, int n) {
  fprintf(s->out, "%lld %s %lld", s->call++, fn, status);
  for (int i = 0; i < n; ++i) {
    uint64_t b;
    memcpy(&b, &v[i], 8);
    fprintf(s->out, " %016llx", (unsigned long long)b);
  }
  fputc('\n', s->out);
}

static uint64_t fnv(uint64_t h, void const *p, size_t n) {
  unsigned char const *c = p;
  for (size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 0x100000001B3ULL;
  return h;
}

void sink_hash(test_sink *s, char const *fn, long long status, double const *v, int n) {
  s->call++;
  s->hash = fnv(s->hash, fn, strlen(fn));
  s->hash = fnv(s->hash, &status, sizeof status);
  s->hash = fnv(s->hash, v, sizeof *v * (size_t)n);
}

void call_all(test_input const *in, test_sink *s) {
  double const *r = in->r12, *q1 = in->q1, *q2 = in->q2;
  double out[8], l[6], x[3];

  pw85__cholesky_decomp(q1, l);
  s->put(s, "pw85__cholesky_decomp", 0, l, 6);
  pw85__cholesky_solve(l, r, x);
  s->put(s, "pw85__cholesky_solve", 0, x, 3);
  pw85_spheroid(in->a, in->c, in->n, out);
  s->put(s, "pw85_spheroid", 0, out, 6);
  int st = pw85_ellipsoid(in->radii, in->axes, out);
  s->put(s, "pw85_ellipsoid", st, out, 6);
  st = pw85_ellipsoid_rotation(in->radii, in->axes, out);
  s->put(s, "pw85_ellipsoid_rotation", st, out, 6);
  {
    /* a quaternion from the rotation's entries, unit up to rounding */
    double const *a = in->axes, nq = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3]);
    double const quat[4] = {a[0] / nq, a[1] / nq, a[2] / nq, a[3] / nq};
    st = pw85_ellipsoid_quat(in->radii, quat, out);
    s->put(s, "pw85_ellipsoid_quat", st, out, 6);
    double radii[3], rot[9], qt[4];
    st = pw85_ellipsoid_axes(q1, radii, rot, qt);
    s->put(s, "pw85_ellipsoid_axes", st, radii, 3);
    s->put(s, "pw85_ellipsoid_axes/rot", st, rot, 9);
    s->put(s, "pw85_ellipsoid_axes/quat", st, qt, 4);
  }

  double params[15];
  memcpy(params, r, 3 * sizeof(double));
  memcpy(params + 3, q1, 6 * sizeof(double));
  memcpy(params + 9, q2, 6 * sizeof(double));
  out[0] = pw85_f_neg(in->lambda, params);
  s->put(s, "pw85_f_neg", 0, out, 1);
  pw85__residual(in->lambda, r, q1, q2, out);
  s->put(s, "pw85__residual", 0, out, 3);
  st = pw85_contact_function(r, q1, q2, out);
  s->put(s, "pw85_contact_function", st, out, 2);

  static int const methods[] = {PW85_METHOD_DEFAULT, PW85_METHOD_BRENT, PW85_METHOD_NEWTON,
                                PW85_METHOD_RATIONAL, PW85_METHOD_ZHENG, 7};
  static char const *const method_fn[] = {"pw85_contact_function_method/DEFAULT",
                                          "pw85_contact_function_method/BRENT",
                                          "pw85_contact_function_method/NEWTON",
                                          "pw85_contact_function_method/RATIONAL",
                                          "pw85_contact_function_method/ZHENG",
                                          "pw85_contact_function_method/7"};
  static char const *const dca_fn[] = {"pw85_dca/DEFAULT", "pw85_dca/BRENT", "pw85_dca/NEWTON",
                                       "pw85_dca/RATIONAL", "pw85_dca/ZHENG", "pw85_dca/7"};
  for (int m = 0; m < 6; ++m) {
    pw85_result res;
    st = pw85_contact_function_method(r, q1, q2, methods[m], &res);
    double const v[5] = {res.mu2, res.lambda, res.mu2_error, (double)res.iterations,
                         (double)res.method};
    s->put(s, method_fn[m], st, v, 5);
    double d;
    st = pw85_dca(r, q1, q2, methods[m], &d);
    s->put(s, dca_fn[m], st, &d, 1);
  }
  {
    double d;
    int ev;
    st = pw85_dca_ex(r, q1, q2, in->theta_tol, &d, &ev);
    double const v[2] = {d, (double)ev};
    s->put(s, "pw85_dca_ex", st, v, 2);
  }
  {
    double const u2[2] = {r[0], r[1]};
    double const p1[3] = {q1[0], q1[1], q1[3]}, p2[3] = {q2[0], q2[1], q2[3]};
    double d;
    st = pw85_dca_2d(u2, p1, p2, &d);
    s->put(s, "pw85_dca_2d", st, &d, 1);
    st = pw85_contact_function_2d(u2, p1, p2, out);
    s->put(s, "pw85_contact_function_2d", st, out, 2);
  }
  {
    double const mr[3] = {-r[0], -r[1], -r[2]};
    st = pw85_overlap(r, q1, q2);
    s->put(s, "pw85_overlap", st, NULL, 0);
    st = pw85_overlap(mr, q2, q1);
    s->put(s, "pw85_overlap/swapped", st, NULL, 0);
  }
  {
    pw85_contact_t c;
    st = pw85_contact(r, q1, q2, &c);
    double const v[12] = {c.mu2,  c.lambda, c.x0[0], c.x0[1], c.x0[2], c.n[0],
                          c.n[1], c.n[2],   c.dca,   c.depth, c.depth_n, 0.0};
    s->put(s, "pw85_contact", st, v, 11);
  }

  {
    pw85_derivatives_t d;
    st = pw85_contact_derivatives(r, q1, q2, &d);
    s->put(s, "pw85_contact_derivatives", st, &d.mu2,
           (int)(sizeof d / sizeof(double)));
  }
  if (in->kind != 2 && in->kind != 3) {
    /* Approaching at unit speed along -r12 for a unit time, ellipsoid 1
     * rotating about one of the random axes: a crossing within the horizon
     * for most pairs apart by less than twice their size. Not for the
     * aspect ratios up to 1e16 and the nearly singular matrices, where a
     * rotating needle can spend the whole budget of 1e5 evaluations (0.1 s
     * each call; the contact-time tests cover those). */
    double const v12[3] = {-r[0], -r[1], -r[2]}, w2[3] = {0.0, 0.0, 0.0};
    double const w1[3] = {0.5 * in->axes[0], 0.5 * in->axes[1], 0.5 * in->axes[2]};
    double t;
    int evaluations = 0;
    st = pw85_contact_time_ex(r, v12, q1, w1, q2, w2, 1.0, &t, &evaluations);
    double const v[2] = {t, (double)evaluations};
    s->put(s, "pw85_contact_time_ex", st, v, 2);
  }

  /* libpw85_legacy */
  out[0] = pw85_legacy__det_sym(q1);
  s->put(s, "pw85_legacy__det_sym", 0, out, 1);
  out[0] = pw85_legacy__xT_adjA_x(r, q1);
  s->put(s, "pw85_legacy__xT_adjA_x", 0, out, 1);
  double q3[6], q4[6];
  for (int i = 0; i < 6; ++i) {
    q3[i] = 2.0 * q1[i] - q2[i];
    q4[i] = 0.5 * (q1[i] + q2[i]);
  }
  pw85_legacy__rT_adjQ_r_as_poly(r, q1, q2, q3, out);
  s->put(s, "pw85_legacy__rT_adjQ_r_as_poly", 0, out, 3);
  pw85_legacy__detQ_as_poly(q1, q2, q3, q4, out);
  s->put(s, "pw85_legacy__detQ_as_poly", 0, out, 4);
  out[3] = pw85_legacy_f1(in->lambda, r, q1, q2, out);
  s->put(s, "pw85_legacy_f1", 0, out, 4);
  out[3] = pw85_legacy_f2(in->lambda, r, q1, q2, out);
  s->put(s, "pw85_legacy_f2", 0, out, 4);
  st = pw85_legacy_contact_function1(r, q1, q2, out);
  s->put(s, "pw85_legacy_contact_function1", st, out, 2);
  st = pw85_legacy_contact_function2(r, q1, q2, out);
  s->put(s, "pw85_legacy_contact_function2", st, out, 2);
}
