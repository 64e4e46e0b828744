/* Outputs aliasing inputs: every one-pair function of both libraries reads
 * all its inputs before it writes an output (include/pw85.h,
 * include/pw85_legacy.h), so passing an input array as the output gives the
 * bits of the call with separate arrays. Each test makes the call both ways
 * for a valid pair (and the output written over r12, q1 or q2). */
#include <math.h>
#include <string.h>

#include <pw85.h>
#include <pw85_legacy.h>

#include "testutil.h"

static double const R12[3] = {0.7, -0.7, 1.1};
static double const Q1[6] = {100.0, 3.0, -1.0, 50.0, 2.0, 0.5};
static double const Q2[6] = {25.0, 0.0, 0.5, 0.25, 0.0, 0.25};

static void assert_same_bits(double const *a, double const *b, int n) {
  for (int i = 0; i < n; ++i) {
    if (memcmp(&a[i], &b[i], sizeof(double)) != 0)
      g_error("output %d: %.17g with separate arrays, %.17g aliased", i, a[i], b[i]);
  }
}

/* An input copy big enough for any output (as a double array or a struct). */
typedef union {
  double d[16];
  pw85_result res;
  pw85_contact_t c;
} buffer;

static void test_cholesky(void) {
  double l[6];
  buffer b;
  pw85__cholesky_decomp(Q1, l);
  memcpy(b.d, Q1, sizeof Q1);
  pw85__cholesky_decomp(b.d, b.d);
  assert_same_bits(l, b.d, 6);

  double x[3];
  pw85__cholesky_solve(l, R12, x);
  memcpy(b.d, R12, sizeof R12);
  pw85__cholesky_solve(l, b.d, b.d); /* x over b */
  assert_same_bits(x, b.d, 3);
  memcpy(b.d, l, sizeof l);
  pw85__cholesky_solve(b.d, R12, b.d); /* x over l */
  assert_same_bits(x, b.d, 3);
}

static void test_constructors(void) {
  double const n[3] = {0.6, 0.0, 0.8};
  double q[6];
  buffer b;
  pw85_spheroid(2.0, 0.5, n, q);
  memcpy(b.d, n, sizeof n);
  pw85_spheroid(2.0, 0.5, b.d, b.d);
  assert_same_bits(q, b.d, 6);

  double const radii[3] = {1.0, 2.0, 3.0};
  double const axes[9] = {0.6, 0.0, 0.8, 0.0, 1.0, 0.0, -0.8, 0.0, 0.6};
  int const s = pw85_ellipsoid(radii, axes, q);
  g_assert_cmpint(s, ==, PW85_OK);
  memcpy(b.d, axes, sizeof axes);
  g_assert_cmpint(pw85_ellipsoid(radii, b.d, b.d), ==, s); /* q over axes */
  assert_same_bits(q, b.d, 6);
  double r6[6] = {1.0, 2.0, 3.0};
  g_assert_cmpint(pw85_ellipsoid(r6, axes, r6), ==, s); /* q over radii */
  assert_same_bits(q, r6, 6);
}

static void test_orientation(void) {
  double const radii[3] = {1.0, 2.0, 3.0}, quat[4] = {0.5, 0.5, -0.5, 0.5};
  double const rot[9] = {0.6, 0.0, -0.8, 0.0, 1.0, 0.0, 0.8, 0.0, 0.6};
  double q[6];
  buffer b;
  g_assert_cmpint(pw85_ellipsoid_quat(radii, quat, q), ==, PW85_OK);
  memcpy(b.d, quat, sizeof quat);
  g_assert_cmpint(pw85_ellipsoid_quat(radii, b.d, b.d), ==, PW85_OK); /* q over quat */
  assert_same_bits(q, b.d, 6);
  memcpy(b.d, radii, sizeof radii);
  g_assert_cmpint(pw85_ellipsoid_quat(b.d, quat, b.d), ==, PW85_OK); /* q over radii */
  assert_same_bits(q, b.d, 6);

  g_assert_cmpint(pw85_ellipsoid_rotation(radii, rot, q), ==, PW85_OK);
  memcpy(b.d, rot, sizeof rot);
  g_assert_cmpint(pw85_ellipsoid_rotation(radii, b.d, b.d), ==, PW85_OK); /* q over rot */
  assert_same_bits(q, b.d, 6);

  double r[3], ro[9], qt[4];
  g_assert_cmpint(pw85_ellipsoid_axes(Q1, r, ro, qt), ==, PW85_OK);
  double r2[3], qt2[4];
  memcpy(b.d, Q1, sizeof Q1);
  g_assert_cmpint(pw85_ellipsoid_axes(b.d, r2, b.d, qt2), ==, PW85_OK); /* rot over q */
  assert_same_bits(ro, b.d, 9);
  assert_same_bits(r, r2, 3);
  assert_same_bits(qt, qt2, 4);
  memcpy(b.d, Q1, sizeof Q1);
  g_assert_cmpint(pw85_ellipsoid_axes(b.d, b.d, NULL, b.d + 3), ==, PW85_OK); /* radii, quat over q */
  assert_same_bits(r, b.d, 3);
  assert_same_bits(qt, b.d + 3, 4);
}

static void test_residual(void) {
  double out[3];
  buffer b;
  pw85__residual(0.3, R12, Q1, Q2, out);
  memcpy(b.d, R12, sizeof R12);
  pw85__residual(0.3, b.d, Q1, Q2, b.d);
  assert_same_bits(out, b.d, 3);
  memcpy(b.d, Q2, sizeof Q2);
  pw85__residual(0.3, R12, Q1, b.d, b.d);
  assert_same_bits(out, b.d, 3);
}

static void test_contact_function(void) {
  double out[2];
  buffer b;
  int const s = pw85_contact_function(R12, Q1, Q2, out);
  memcpy(b.d, R12, sizeof R12);
  g_assert_cmpint(pw85_contact_function(b.d, Q1, Q2, b.d), ==, s);
  assert_same_bits(out, b.d, 2);
  memcpy(b.d, Q1, sizeof Q1);
  g_assert_cmpint(pw85_contact_function(R12, b.d, Q2, b.d), ==, s);
  assert_same_bits(out, b.d, 2);
}

static void test_contact_function_method(void) {
  for (int m = PW85_METHOD_DEFAULT; m <= PW85_METHOD_ZHENG; ++m) {
    pw85_result res;
    buffer b;
    int const s = pw85_contact_function_method(R12, Q1, Q2, m, &res);
    memcpy(b.d, R12, sizeof R12);
    g_assert_cmpint(pw85_contact_function_method(b.d, Q1, Q2, m, &b.res), ==, s);
    g_assert_true(memcmp(&res, &b.res, sizeof res) == 0);
    memcpy(b.d, Q2, sizeof Q2);
    g_assert_cmpint(pw85_contact_function_method(R12, Q1, b.d, m, &b.res), ==, s);
    g_assert_true(memcmp(&res, &b.res, sizeof res) == 0);
  }
}

static void test_dca(void) {
  for (int m = PW85_METHOD_DEFAULT; m <= PW85_METHOD_ZHENG; ++m) {
    double d;
    buffer b;
    int const s = pw85_dca(R12, Q1, Q2, m, &d);
    memcpy(b.d, R12, sizeof R12);
    g_assert_cmpint(pw85_dca(b.d, Q1, Q2, m, &b.d[0]), ==, s);
    assert_same_bits(&d, b.d, 1);
    memcpy(b.d, Q1, sizeof Q1);
    g_assert_cmpint(pw85_dca(R12, b.d, Q2, m, &b.d[0]), ==, s);
    assert_same_bits(&d, b.d, 1);
  }
  double d;
  int ev, ev2;
  buffer b;
  int const s = pw85_dca_ex(R12, Q1, Q2, 1e-6, &d, &ev);
  memcpy(b.d, R12, sizeof R12);
  g_assert_cmpint(pw85_dca_ex(b.d, Q1, Q2, 1e-6, &b.d[0], &ev2), ==, s);
  assert_same_bits(&d, b.d, 1);
  g_assert_cmpint(ev, ==, ev2);
  memcpy(b.d, Q2, sizeof Q2);
  g_assert_cmpint(pw85_dca_ex(R12, Q1, b.d, 1e-6, &b.d[5], NULL), ==, s);
  assert_same_bits(&d, &b.d[5], 1);
}

static void test_2d(void) {
  double const u[2] = {0.7, -0.4}, p1[3] = {4.0, 0.5, 1.0}, p2[3] = {1.0, -0.2, 0.3};
  double d, out[2];
  buffer b;
  int s = pw85_dca_2d(u, p1, p2, &d);
  memcpy(b.d, u, sizeof u);
  g_assert_cmpint(pw85_dca_2d(b.d, p1, p2, &b.d[1]), ==, s);
  assert_same_bits(&d, &b.d[1], 1);
  memcpy(b.d, p1, sizeof p1);
  g_assert_cmpint(pw85_dca_2d(u, b.d, p2, &b.d[0]), ==, s);
  assert_same_bits(&d, b.d, 1);

  s = pw85_contact_function_2d(u, p1, p2, out);
  memcpy(b.d, u, sizeof u);
  g_assert_cmpint(pw85_contact_function_2d(b.d, p1, p2, b.d), ==, s);
  assert_same_bits(out, b.d, 2);
  memcpy(b.d, p2, sizeof p2);
  g_assert_cmpint(pw85_contact_function_2d(u, p1, b.d, b.d), ==, s);
  assert_same_bits(out, b.d, 2);
}

static void test_contact(void) {
  pw85_contact_t c;
  buffer b;
  int const s = pw85_contact(R12, Q1, Q2, &c);
  memcpy(b.d, R12, sizeof R12);
  g_assert_cmpint(pw85_contact(b.d, Q1, Q2, &b.c), ==, s);
  g_assert_true(memcmp(&c, &b.c, sizeof c) == 0);
  memcpy(b.d, Q1, sizeof Q1);
  g_assert_cmpint(pw85_contact(R12, b.d, Q2, &b.c), ==, s);
  g_assert_true(memcmp(&c, &b.c, sizeof c) == 0);
}

static void test_legacy(void) {
  double q3[6], q4[6], a[3], pb[4], out[3], v;
  buffer b;
  for (int i = 0; i < 6; ++i) {
    q3[i] = 2.0 * Q1[i] - Q2[i];
    q4[i] = 0.5 * (Q1[i] + Q2[i]);
  }
  pw85_legacy__rT_adjQ_r_as_poly(R12, Q1, Q2, q3, a);
  memcpy(b.d, R12, sizeof R12);
  pw85_legacy__rT_adjQ_r_as_poly(b.d, Q1, Q2, q3, b.d);
  assert_same_bits(a, b.d, 3);
  pw85_legacy__detQ_as_poly(Q1, Q2, q3, q4, pb);
  memcpy(b.d, Q1, sizeof Q1);
  pw85_legacy__detQ_as_poly(b.d, Q2, q3, q4, b.d);
  assert_same_bits(pb, b.d, 4);

  double (*const f[2])(double, double const *, double const *, double const *, double *) = {
      pw85_legacy_f1, pw85_legacy_f2};
  for (int k = 0; k < 2; ++k) {
    v = f[k](0.3, R12, Q1, Q2, out);
    memcpy(b.d, R12, sizeof R12);
    double const w = f[k](0.3, b.d, Q1, Q2, b.d);
    assert_same_bits(&v, &w, 1);
    assert_same_bits(out, b.d, 3);
  }
  int (*const cf[2])(double const *, double const *, double const *, double *) = {
      pw85_legacy_contact_function1, pw85_legacy_contact_function2};
  for (int k = 0; k < 2; ++k) {
    int const s = cf[k](R12, Q1, Q2, out);
    memcpy(b.d, R12, sizeof R12);
    g_assert_cmpint(cf[k](b.d, Q1, Q2, b.d), ==, s);
    assert_same_bits(out, b.d, 2);
    memcpy(b.d, Q2, sizeof Q2);
    g_assert_cmpint(cf[k](R12, Q1, b.d, b.d), ==, s);
    assert_same_bits(out, b.d, 2);
  }
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/aliasing/pw85__cholesky", test_cholesky);
  g_test_add_func("/aliasing/constructors", test_constructors);
  g_test_add_func("/aliasing/orientation", test_orientation);
  g_test_add_func("/aliasing/pw85__residual", test_residual);
  g_test_add_func("/aliasing/pw85_contact_function", test_contact_function);
  g_test_add_func("/aliasing/pw85_contact_function_method", test_contact_function_method);
  g_test_add_func("/aliasing/pw85_dca", test_dca);
  g_test_add_func("/aliasing/2d", test_2d);
  g_test_add_func("/aliasing/pw85_contact", test_contact);
  g_test_add_func("/aliasing/legacy", test_legacy);
  return g_test_run();
}
