/* Tests of pw85_contact_time, pw85_contact_time_ex and
 * pw85_contact_time_pairs (docs/contact_time.md). References, all
 * independent of the library: the contact time of two spheres (root of
 * |r12 + t v12| = a1 + a2, in long double), that of two identical
 * ellipsoids spinning together (closed form below), and for random,
 * grazing and spinning trajectories of the four semi-axis classes the
 * sampled long-double / __float128 reference of tests/ct_reference.h;
 * rotating trajectories against the mpmath references of
 * tests/ct_rotating_reference.h (data/generate_ct_rotating.py: exact
 * rotation of the double inputs at 40 digits). */
#include <float.h>
#include <math.h>
#include <pw85.h>
#include <string.h>

#include "ct_reference.h"
#include "testutil.h"

/* One rotating trajectory and its mpmath reference (t_max = 1): kind 0 a
 * stationary minimum of mu^2 at 1 + delta while spinning, 1 random (up to a
 * turn), 2 spinning (2-5 turns), 3 the class-2 false contact reported
 * against an earlier version; mu0, min: mu^2(0) - 1 and the smallest
 * mu^2 - 1 (at t_min; exact only when below 1e-2); t_c the first crossing of
 * mu^2 = 1, t_a the first time with mu^2 < 1 - 2.3e-13, t_d the last
 * crossing of 1 at or before t_a (INFINITY when none). */
typedef struct {
  int cls, kind;
  double delta, r0[3], v[3], q1[6], w1[3], q2[6], w2[3], t_max;
  double mu0, min, t_min, t_c, t_d, t_a;
} ct_rot_case;
#include "ct_rotating_reference.h"

static void bad_one(double const r[3], double const v[3], double const q1[6], double const w1[3],
                    double const q2[6], double const w2[3], double t_max, int expected) {
  double t = 1.0;
  int ev = -1;
  g_assert_cmpint(pw85_contact_time_ex(r, v, q1, w1, q2, w2, t_max, &t, &ev), ==, expected);
  g_assert_true(isnan(t));
  t = 1.0;
  g_assert_cmpint(pw85_contact_time(r, v, q1, w1, q2, w2, t_max, &t), ==, expected);
  g_assert_true(isnan(t));
}

static void test_bad_input(void) {
  double const r[3] = {3, 0, 0}, v[3] = {-1, 0, 0}, w[3] = {0, 0, 1};
  double const q[6] = {1, 0, 0, 1, 0, 1}, notspd[6] = {1, 2, 0, 1, 0, 1};
  double t = 0;
  int const E = PW85_ERR_INVALID_ARGUMENT;
  g_assert_cmpint(pw85_contact_time(r, v, q, w, q, w, 1.0, NULL), ==, E);
  bad_one(NULL, v, q, w, q, w, 1.0, E);
  bad_one(r, NULL, q, w, q, w, 1.0, E);
  bad_one(r, v, NULL, w, q, w, 1.0, E);
  bad_one(r, v, q, NULL, q, w, 1.0, E);
  bad_one(r, v, q, w, NULL, w, 1.0, E);
  bad_one(r, v, q, w, q, NULL, 1.0, E);
  double const bad_values[3] = {NAN, INFINITY, -INFINITY};
  for (int b = 0; b < 3; b++)
    for (int i = 0; i < 3; i++) {
      double rr[3], vv[3], ww[3];
      memcpy(rr, r, sizeof rr);
      memcpy(vv, v, sizeof vv);
      memcpy(ww, w, sizeof ww);
      rr[i] = bad_values[b];
      bad_one(rr, v, q, w, q, w, 1.0, E);
      vv[i] = bad_values[b];
      bad_one(r, vv, q, w, q, w, 1.0, E);
      ww[i] = bad_values[b];
      bad_one(r, v, q, ww, q, w, 1.0, E);
      bad_one(r, v, q, w, q, ww, 1.0, E);
    }
  for (int i = 0; i < 6; i++) {
    double qq[6];
    memcpy(qq, q, sizeof qq);
    qq[i] = NAN;
    bad_one(r, v, qq, w, q, w, 1.0, E);
    bad_one(r, v, q, w, qq, w, 1.0, E);
  }
  bad_one(r, v, notspd, w, q, w, 1.0, PW85_ERR_NOT_SPD);
  bad_one(r, v, q, w, notspd, w, 1.0, PW85_ERR_NOT_SPD);
  double const bad_tmax[5] = {0.0, -1.0, NAN, INFINITY, -INFINITY};
  for (int k = 0; k < 5; k++) bad_one(r, v, q, w, q, w, bad_tmax[k], E);
  /* motion leaving the range of double within the horizon */
  double const vbig[3] = {DBL_MAX, 0, 0};
  bad_one(r, vbig, q, w, q, w, 4.0, E);
  /* NULL evaluations is allowed */
  double t2 = 0;
  g_assert_cmpint(pw85_contact_time_ex(r, v, q, w, q, w, 2.0, &t, NULL), ==, PW85_OK);
  g_assert_cmpint(pw85_contact_time(r, v, q, w, q, w, 2.0, &t2), ==, PW85_OK);
  g_assert_cmpfloat(t, ==, t2);
  g_assert_cmpfloat(fabs(t - 1.0), <=, 1e-14); /* unit spheres 3 apart, speed 1 */
}

/* Spheres: |r + t v| = a1 + a2 in long double (the smaller root), spins
 * that change nothing; contacts, misses, receding pairs, overlaps at 0. */
static void test_spheres(void) {
  GRand *rng = g_rand_new_with_seed(4201);
  double max_err = 0;
  int contacts = 0, none = 0;
  for (int n = 0; n < 2000; n++) {
    double a1 = exp(g_rand_double_range(rng, log(0.01), log(100)));
    double a2 = exp(g_rand_double_range(rng, log(0.01), log(100)));
    double q1[6], q2[6], r[3], v[3], w1[3], w2[3], t;
    sphere_q(a1, q1);
    sphere_q(a2, q2);
    double const R = a1 + a2, dist = R * g_rand_double_range(rng, 0.5, 5.0);
    for (int i = 0; i < 3; i++) {
      r[i] = g_rand_double_range(rng, -1, 1);
      v[i] = R * g_rand_double_range(rng, -3, 3);
      w1[i] = g_rand_double_range(rng, -50, 50);
      w2[i] = g_rand_double_range(rng, -50, 50);
    }
    double const rn = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (int i = 0; i < 3; i++) r[i] *= dist / rn;
    double const t_max = 2.0;
    long double const rr = (long double)r[0] * r[0] + (long double)r[1] * r[1] + (long double)r[2] * r[2];
    long double const b = (long double)r[0] * v[0] + (long double)r[1] * v[1] + (long double)r[2] * v[2];
    long double const vv = (long double)v[0] * v[0] + (long double)v[1] * v[1] + (long double)v[2] * v[2];
    long double const c = rr - (long double)R * R, disc = b * b - vv * c;
    double exact;
    if (c <= 0) exact = 0;
    else if (disc <= 0 || b >= 0) exact = INFINITY;
    else exact = (double)(c / (-b + sqrtl(disc)));  /* = (-b - sqrt(disc)) / vv */
    if (exact > t_max) exact = INFINITY;
    /* skip near-tangent lines and contacts within 1e-6 of the horizon */
    if (disc > 0 && disc < 1e-6L * b * b) continue;
    if (isfinite(exact) && exact > t_max * (1 - 1e-6)) continue;
    g_assert_cmpint(pw85_contact_time(r, v, q1, w1, q2, w2, t_max, &t), ==, PW85_OK);
    if (isinf(exact)) {
      g_assert_true(isinf(t) && t > 0);
      none++;
    } else {
      double const e = fabs(t - exact) / t_max;
      if (e > max_err) max_err = e;
      g_assert_cmpfloat(e, <=, 1e-13);
      contacts++;
    }
  }
  if (g_test_verbose())
    g_test_message("spheres: %d contacts, %d none, max |t - exact| / t_max %.3g", contacts, none,
                   max_err);
  g_assert_cmpint(contacts, >, 200);
  g_assert_cmpint(none, >, 200);
  g_rand_free(rng);
}

/* Two identical ellipsoids spinning together (Q1(t) = Q2(t) = Q(t)), fixed
 * centres: mu^2 = r^T Q(t)^{-1} r / 4. Semi-axes A > B > C along the body
 * axes, spin w about the third axis, r = d e_2 in the body frame at t = 0:
 * mu^2(t) = d^2 (sin^2(wt) / A^2 + cos^2(wt) / B^2) / 4 = 1 first at
 * cos^2(wt) = (4 / d^2 - 1 / A^2) / (1 / B^2 - 1 / A^2), 2B < d < 2A.
 * Everything is then turned by a random rotation G (the answer is
 * invariant). */
static void test_spinning_pair(void) {
  GRand *rng = g_rand_new_with_seed(4202);
  double max_err = 0;
  for (int n = 0; n < 200; n++) {
    long double const A = 2.0 + 3 * g_rand_double(rng), B = 0.2 + g_rand_double(rng);
    long double const C = 0.1 * B, om = g_rand_double_range(rng, 0.5, 20);
    long double const d = 2 * B + (2 * A - 2 * B) * g_rand_double_range(rng, 0.05, 0.95);
    long double const c2 = (4 / (d * d) - 1 / (A * A)) / (1 / (B * B) - 1 / (A * A));
    long double const exact = acosl(sqrtl(c2)) / om;
    double G[9];
    random_axes(rng, G);
    double const radii[3] = {(double)A, (double)B, (double)C};
    double q[6], r[3], w[3], v[3] = {0, 0, 0};
    make_q(radii, G, q);
    /* body axis k is row k of G (make_q: Q = sum_k radii_k^2 G_k G_k^T) */
    for (int i = 0; i < 3; i++) {
      r[i] = (double)(d * G[3 + i]);
      w[i] = (double)(om * G[6 + i]);
    }
    double t;
    int ev;
    double const t_max = (double)(4 / om);
    g_assert_cmpint(pw85_contact_time_ex(r, v, q, w, q, w, t_max, &t, &ev), ==, PW85_OK);
    double const e = (double)fabsl(t - exact) / t_max;
    if (e > max_err) max_err = e;
    /* inputs rounded to double: the exact answer moves by ~1e-16 relative */
    g_assert_cmpfloat(e, <=, 1e-12);
  }
  if (g_test_verbose()) g_test_message("spinning pair: max |t - exact| / t_max %.3g", max_err);
  g_rand_free(rng);
}

static void test_special(void) {
  double const q[6] = {4, 0, 0, 1, 0, 0.25}, z[3] = {0, 0, 0};
  double r[3] = {1, 0.5, 0}, v[3] = {1, 0, 0}, t = -1;
  int ev = -1;
  /* overlapping at t = 0 */
  g_assert_cmpint(pw85_contact_time_ex(r, v, q, z, q, z, 1.0, &t, &ev), ==, PW85_OK);
  g_assert_cmpfloat(t, ==, 0.0);
  g_assert_cmpint(ev, ==, 1);
  /* no relative motion, apart: no contact, one evaluation */
  r[0] = 10;
  g_assert_cmpint(pw85_contact_time_ex(r, z, q, z, q, z, 1e300, &t, &ev), ==, PW85_OK);
  g_assert_true(isinf(t) && t > 0);
  g_assert_cmpint(ev, ==, 1);
  /* receding without rotation: the tangent bound never reaches 1 */
  g_assert_cmpint(pw85_contact_time_ex(r, v, q, z, q, z, 1e300, &t, &ev), ==, PW85_OK);
  g_assert_true(isinf(t) && t > 0);
  g_assert_cmpint(ev, ==, 1);
  /* approaching head-on: gap 10 - 2 * 2 = 6 at unit speed */
  double const vin[3] = {-1, 0, 0}, r0[3] = {10, 0, 0};
  g_assert_cmpint(pw85_contact_time_ex(r0, vin, q, z, q, z, 100.0, &t, &ev), ==, PW85_OK);
  g_assert_cmpfloat(fabs(t - 6.0), <=, 6.0 * 4 * DBL_EPSILON);
  g_assert_cmpint(ev, <=, 3);
  /* the same beyond the horizon */
  g_assert_cmpint(pw85_contact_time(r0, vin, q, z, q, z, 5.9, &t), ==, PW85_OK);
  g_assert_true(isinf(t));
  /* a needle spinning fast next to a sphere it never reaches: budget
   * exhausted, *t certified free of contact (mu^2 > 1 everywhere) */
  double const radii[3] = {10, 0.01, 0.01}, axes[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double needle[6], ball[6], rn[3] = {0, 10.6, 0}, wn[3] = {0, 0, 1e7};
  make_q(radii, axes, needle);
  sphere_q(0.5, ball);
  g_assert_cmpint(pw85_contact_time_ex(rn, z, needle, wn, ball, z, 1.0, &t, &ev), ==,
                  PW85_ERR_NO_CONVERGENCE);
  g_assert_cmpint(ev, >=, PW85_CONTACT_TIME_MAX_EVAL);
  g_assert_true(t > 0 && t < 1.0);
  /* touching that needle tip-on at t = 0 is reported at 0 */
  rn[1] = 0;
  rn[0] = 10.5;
  g_assert_cmpint(pw85_contact_time(rn, z, needle, wn, ball, z, 1.0, &t), ==, PW85_OK);
  g_assert_cmpfloat(t, ==, 0.0);
}

/* Two spinning needles (class 3) whose crossing is steeper than mu^2 can be
 * resolved across one ulp of t: the search ends there (T6), against the
 * reference. */
static void test_steep_crossing(void) {
  ct_traj tr = {{-13.228060262786865, -1683.0097124255508, -1252.6309527731314},
                {-92.291492931827861, 1998.9167652903966, 1301.4400012036137},
                {609.82202038421224, 5323.8763234743174, -2851.6919041809065, 46479.600600379948,
                 -24896.231760520521, 13335.400742009047},
                {-22.227079719578761, -11.342089554329005, -10.681750629154825},
                {32484.158976247676, -27829.54685986925, -94387.490816569378, 23842.987208523908,
                 80865.210799117209, 274261.85747009405},
                {-25.120962546555674, 9.5544416021060137, -2.4033332501720799},
                1.0};
  double t;
  int ev;
  g_assert_cmpint(pw85_contact_time_ex(tr.r0, tr.v, tr.q1, tr.w1, tr.q2, tr.w2, tr.t_max, &t, &ev), ==, PW85_OK);
  ct_ref ref;
  ct_reference(&tr, &ref);
  g_assert_cmpint(ct_verdict(&tr, &ref, t), ==, 0);
  g_assert_true(ref.t[0] != INFINITY);
  g_assert_cmpint(ev, <, 1000);
  /* A spinning class-3 pair (trajectory 1095 of class 3 in the slow mode
   * of /pw85_contact_time/reference) whose crossing falls within one ulp
   * of t: the refinement's probe across Newton's root would leave the
   * bracket; it is placed on the near side and closes it (T8). */
  ct_traj const tr2 = {{-0x1.472f5e5798ea2p+8, 0x1.5c1e25048fd69p+10, -0x1.ff6208fd7c24p+7},
                       {0x1.e8753512d88bcp+9, -0x1.e314ee1709f53p+11, 0x1.98730919b1efcp+9},
                       {0x1.63a030dfa4a49p+17, -0x1.74fb6f1e02b0ep+16, 0x1.1987b7fc1b61cp+18,
                        0x1.872f8b1874c27p+15, -0x1.2745303b37c67p+17, 0x1.bdbec7ed0501fp+18},
                       {-0x1.4ea69f55d53e7p-2, 0x1.48462e778a351p+0, -0x1.793e101fb46dap-1},
                       {0x1.f33144c78550bp+8, 0x1.765806332e1dp+10, -0x1.4e7f7e0b78f31p+13,
                        0x1.18b877c47693ep+12, -0x1.f5ae062f993c2p+14, 0x1.c047a5987a318p+17},
                       {-0x1.7cf0ff7547645p-1, -0x1.1bb23fcf3ec0cp+0, 0x1.f144b01fe7a26p+0},
                       1.0};
  g_assert_cmpint(pw85_contact_time_ex(tr2.r0, tr2.v, tr2.q1, tr2.w1, tr2.q2, tr2.w2, tr2.t_max, &t, &ev), ==, PW85_OK);
  ct_reference(&tr2, &ref);
  g_assert_true(ref.t[1] != INFINITY);
  g_assert_cmpint(ct_verdict(&tr2, &ref, t), ==, 0);
  g_assert_cmpfloat(fabs(t - ref.t[1]), <=, 1e-10);
}

/* The domain of the certificate is decided from the inputs before any
 * evaluation: a semi-axis ratio above 1e7 (here 1e8, translation only and
 * with a spinning sphere) gives PW85_ERR_INACCURATE with *t = 0 and no
 * evaluation; at 1e6 the same approach is answered: the rod (semi-axes 1,
 * 1e-6, 1e-6 along x, y, z) meets the unit sphere tip-on at t = 3. */
static void test_domain(void) {
  double const z[3] = {0, 0, 0}, w[3] = {0, 0, 1}, ball[6] = {1, 0, 0, 1, 0, 1};
  double const r[3] = {5, 0, 0}, v[3] = {-1, 0, 0};
  for (int k = 0; k < 2; k++) {
    double const thin = k == 0 ? 1e-8 : 1e-6;
    double const rod[6] = {1, 0, 0, thin * thin, 0, thin * thin};
    for (int spin = 0; spin < 2; spin++) {
      double t = -1;
      int ev = -1;
      int const st = pw85_contact_time_ex(r, v, rod, z, ball, spin ? w : z, 10.0, &t, &ev);
      if (k == 0) {
        g_assert_cmpint(st, ==, PW85_ERR_INACCURATE);
        g_assert_cmpfloat(t, ==, 0.0);
        g_assert_cmpint(ev, ==, 0);
      } else {
        g_assert_cmpint(st, ==, PW85_OK);
        g_assert_cmpfloat(fabs(t - 3.0), <=, 1e-12);
      }
    }
  }
}

/* The rate of the event-driven recipe (docs/contact_time.md): dmu^2/dt =
 * d_r12.v12 + d_theta1.w1 + d_theta2.w2 of pw85_contact_derivatives, against
 * central differences of the reference mu^2(t) in long double (step 1e-8:
 * truncation and rounding both below 1e-11 relative). */
static void test_rate(void) {
  ct_rng g = {55};
  for (int n = 0; n < 50; n++) {
    ct_traj tr;
    ct_make(&g, 0.1, 10, CT_SPINNING, n, &tr);
    pw85_derivatives_t d;
    g_assert_cmpint(pw85_contact_derivatives(tr.r0, tr.q1, tr.q2, &d), ==, PW85_OK);
    double rate = 0;
    for (int i = 0; i < 3; i++)
      rate += d.d_r12[i] * tr.v[i] + d.d_theta1[i] * tr.w1[i] + d.d_theta2[i] * tr.w2[i];
    ctr_real const h = 1e-8L;
    ctr_real lam = 0.5L;
    ctr_real const up = ctr_mu2_at(&tr, h, &lam), down = ctr_mu2_at(&tr, -h, &lam);
    double const fd = (double)((up - down) / (2 * h));
    g_assert_cmpfloat(fabs(rate - fd), <=, 1e-9 * (fabs(fd) + d.mu2));
  }
}

/* Random, grazing and spinning trajectories of the four classes against
 * the sampled reference (counts as bench/bench_contact_time.c). */
static void test_reference(void) {
  const double lo[4] = {0.5, 0.1, 0.01, 0.001}, hi[4] = {2, 10, 100, 1000};
  int const n = g_test_slow() ? 2000 : 100;
  for (int c = 0; c < 4; c++) {
    ct_rng g = {1000 + c};
    int missed = 0, early = 0, falsec = 0, contacts = 0;
    double max_err = 0;
    for (int i = 0; i < n; i++) {
      int const kind = i % 5 < 3 ? CT_RANDOM : (i % 5 == 3 ? CT_GRAZING : CT_SPINNING);
      ct_traj tr;
      ct_make(&g, lo[c], hi[c], kind, i / 5, &tr);
      double t;
      int ev;
      g_assert_cmpint(pw85_contact_time_ex(tr.r0, tr.v, tr.q1, tr.w1, tr.q2, tr.w2, tr.t_max, &t, &ev), ==, PW85_OK);
      ct_ref ref;
      ct_reference(&tr, &ref);
      int const v = ct_verdict(&tr, &ref, t);
      contacts += ref.t[0] != INFINITY;
      missed += !!(v & CT_MISSED);
      early += !!(v & CT_EARLY);
      falsec += !!(v & CT_FALSE);
      /* clear crossings (mu^2 below 1 - 1e-9): time to 1e-9 t_max */
      if (ref.min_mu2 < 1 - 1e-9 && ref.t[1] != INFINITY) {
        double const e = fabs(t - ref.t[1]) / tr.t_max;
        if (e > max_err) max_err = e;
      }
    }
    if (g_test_verbose())
      g_test_message("class %d: %d trajectories, %d contacts, %d missed, %d early, %d false, "
                     "max err %.3g", c, n, contacts, missed, early, falsec, max_err);
    g_assert_cmpint(missed, ==, 0);
    g_assert_cmpint(early, ==, 0);
    g_assert_cmpint(falsec, ==, 0);
    g_assert_cmpint(contacts, >, n / 5);
    g_assert_cmpfloat(max_err, <=, 1e-9);
  }
}

/* The edges of the grazing band (docs/contact_time.md (T6), (T8)),
 * translations tangent to mu^2 = 1 + delta at t = 1/2 in the four classes:
 * delta = 1e-14 .. 1e-13 (minimum above 1): no contact, +INFINITY;
 * delta = -1e-12: the first crossing of mu^2 = 1 within 1e-9 t_max of the
 * reference's. The constructed minimum is checked against the reference
 * (its inputs are rounded to double). */
static void test_grazing_band(void) {
  const double lo[4] = {0.5, 0.1, 0.01, 0.001}, hi[4] = {2, 10, 100, 1000};
  const double above[4] = {1e-14, 2e-14, 5e-14, 1e-13};
  int const n = g_test_slow() ? 100 : 12;
  for (int c = 0; c < 4; c++) {
    ct_rng g = {4200 + c};
    int none = 0, crossings = 0;
    double max_err = 0;
    for (int i = 0; i < n; i++) {
      for (int k = 0; k < 5; k++) {
        ct_traj tr;
        double a1, a2, d[3];
        ct_ellipsoid(&g, lo[c], hi[c], tr.q1, &a1);
        ct_ellipsoid(&g, lo[c], hi[c], tr.q2, &a2);
        tr.t_max = 1.0;
        for (int j = 0; j < 3; j++) tr.w1[j] = tr.w2[j] = 0.0;
        ct_unit(&g, d);
        double const delta = k < 4 ? above[k] : -1e-12;
        ct_graze(&g, a1, a2, d, delta, &tr);
        ct_ref ref;
        ct_reference(&tr, &ref);
        double t;
        int ev;
        g_assert_cmpint(pw85_contact_time_ex(tr.r0, tr.v, tr.q1, tr.w1, tr.q2, tr.w2, tr.t_max,
                                             &t, &ev), ==, PW85_OK);
        g_assert_cmpint(ev, <, 200);
        if (k < 4) {
          if (!(ref.min_mu2 > 1 + 0.5 * delta)) continue;
          g_assert_true(isinf(t) && t > 0);
          none++;
        } else {
          if (!(ref.min_mu2 < 1 - 0.5e-12) || ref.t[1] == INFINITY) continue;
          double const e = fabs(t - ref.t[1]) / tr.t_max;
          if (e > max_err) max_err = e;
          g_assert_cmpfloat(e, <=, 1e-9);
          crossings++;
        }
      }
    }
    if (g_test_verbose())
      g_test_message("class %d: %d minima in (1, 1 + 1e-13] without contact, %d crossings of "
                     "1 - 1e-12 grazing, max |t - t_c| / t_max %.3g", c, none, crossings, max_err);
    g_assert_cmpint(none, >=, 3 * n);
    g_assert_cmpint(crossings, >=, n / 2);
  }
}

/* Lengths scaled by 2^k (r12, v12 by 2^k, Q by 2^2k): the same bits of t,
 * from 2^-450 to 2^450 (the computation runs on lengths rescaled near 1). */
static void test_scaling(void) {
  ct_rng g = {91};
  for (int n = 0; n < 20; n++) {
    ct_traj tr;
    ct_make(&g, 0.1, 10, n % 2 ? CT_SPINNING : CT_RANDOM, n, &tr);
    double t0;
    g_assert_cmpint(pw85_contact_time(tr.r0, tr.v, tr.q1, tr.w1, tr.q2, tr.w2, 1.0, &t0), ==, PW85_OK);
    for (int k = -450; k <= 450; k += 75) {
      double r[3], v[3], q1[6], q2[6], t;
      for (int i = 0; i < 3; i++) {
        r[i] = ldexp(tr.r0[i], k);
        v[i] = ldexp(tr.v[i], k);
      }
      for (int i = 0; i < 6; i++) {
        q1[i] = ldexp(tr.q1[i], 2 * k);
        q2[i] = ldexp(tr.q2[i], 2 * k);
      }
      g_assert_cmpint(pw85_contact_time(r, v, q1, tr.w1, q2, tr.w2, 1.0, &t), ==, PW85_OK);
      g_assert_true(memcmp(&t, &t0, sizeof t) == 0);
    }
  }
  /* centres 1e200 apart, unit spheres, closing at 1e200 per unit time:
   * mu^2 ~ 1e400 beyond the double range at t = 0 */
  double const q[6] = {1, 0, 0, 1, 0, 1}, z[3] = {0, 0, 0}, r[3] = {1e200, 0, 0},
               v[3] = {-1e200, 0, 0};
  double t;
  g_assert_cmpint(pw85_contact_time(r, v, q, z, q, z, 2.0, &t), ==, PW85_OK);
  g_assert_cmpfloat(fabs(t - 1.0), <=, 1e-14);
}

static void test_pairs(void) {
  enum { M = 60 };
  double r[3 * M], v[3 * M], q1[6 * M], q2[6 * M], w1[3 * M], w2[3 * M], t[M], t1;
  int status[M];
  ct_rng g = {77};
  for (int k = 0; k < M; k++) {
    ct_traj tr;
    ct_make(&g, 0.1, 10, k % 3 == 0 ? CT_SPINNING : CT_RANDOM, k, &tr);
    memcpy(r + 3 * k, tr.r0, sizeof tr.r0);
    memcpy(v + 3 * k, tr.v, sizeof tr.v);
    memcpy(w1 + 3 * k, tr.w1, sizeof tr.w1);
    memcpy(w2 + 3 * k, tr.w2, sizeof tr.w2);
    memcpy(q1 + 6 * k, tr.q1, sizeof tr.q1);
    memcpy(q2 + 6 * k, tr.q2, sizeof tr.q2);
  }
  q2[6 * 7 + 1] = 100;  /* pair 7 not positive definite */
  r[3 * 9] = NAN;       /* pair 9 invalid */
  for (int nt = 0; nt <= 3; nt++) {
    for (int k = 0; k < M; k++) t[k] = -2, status[k] = 99;
    g_assert_cmpint(pw85_contact_time_pairs(M, r, v, q1, w1, q2, w2, 1.0, t, status, nt), ==,
                    PW85_ERR_NOT_SPD);
    for (int k = 0; k < M; k++) {
      int const s = pw85_contact_time(r + 3 * k, v + 3 * k, q1 + 6 * k, w1 + 3 * k, q2 + 6 * k,
                                      w2 + 3 * k, 1.0, &t1);
      g_assert_cmpint(status[k], ==, s);
      g_assert_true(memcmp(&t1, &t[k], sizeof t1) == 0);
    }
    g_assert_cmpint(status[7], ==, PW85_ERR_NOT_SPD);
    g_assert_cmpint(status[9], ==, PW85_ERR_INVALID_ARGUMENT);
    g_assert_cmpint(pw85_contact_time_pairs(M, r, v, q1, w1, q2, w2, 1.0, t, NULL, nt), ==,
                    PW85_ERR_NOT_SPD);
  }
  /* call-level errors: nothing written */
  for (int k = 0; k < M; k++) t[k] = -2, status[k] = 99;
  g_assert_cmpint(pw85_contact_time_pairs(0, NULL, NULL, NULL, NULL, NULL, NULL, 1.0, NULL, NULL, 0), ==, PW85_OK);
  g_assert_cmpint(pw85_contact_time_pairs(-1, r, v, q1, w1, q2, w2, 1.0, t, status, 0), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_contact_time_pairs(M, r, v, q1, w1, q2, w2, 0.0, t, status, 0), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_contact_time_pairs(M, r, v, q1, w1, q2, w2, NAN, t, status, 0), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_contact_time_pairs(M, r, v, q1, w1, q2, w2, 1.0, NULL, status, 0), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_contact_time_pairs(M, r, NULL, q1, w1, q2, w2, 1.0, t, status, 0), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_contact_time_pairs(M, r, v, q1, NULL, q2, w2, 1.0, t, status, 0), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_contact_time_pairs(M, r, v, q1, w1, q2, w2, 1.0, t, status, -1), ==, PW85_ERR_INVALID_ARGUMENT);
  for (int k = 0; k < M; k++) {
    g_assert_cmpfloat(t[k], ==, -2);
    g_assert_cmpint(status[k], ==, 99);
  }
}

/* The documented limits (docs/contact_time.md, "Limits"), with unit spheres
 * approaching head-on (Q = I; contact for |r12(t)| <= 2, t_c = |r12| - 2 at
 * unit speed):
 *  - time resolution: at unit speed from r12 = (2^k, 2^(k-3), 0), t_max =
 *    2^(k+1), the contact lasts 4 time units; for k <= 52 (ulp(t_c) <= 1)
 *    it is found, *t within 1e-15 t_max of t_c;
 *  - far pairs: from r12 = (2^k, 0, 0) at speed 2^k (t_c just below 1,
 *    t_max = 2): PW85_OK and *t within 1e-15 of t_c for k <= 996;
 *    k = 997 ... 1000: PW85_ERR_NO_CONVERGENCE after one evaluation,
 *    *t = 0 (nothing certified). */
static void test_limits(void) {
  double const q[6] = {1, 0, 0, 1, 0, 1}, w[3] = {0, 0, 0};
  for (int k = 2; k <= 52; k++) {
    double const r[3] = {ldexp(1.0, k), ldexp(1.0, k - 3), 0.0};
    double const n = hypot(r[0], r[1]);
    double const v[3] = {-r[0] / n, -r[1] / n, 0.0};
    double t;
    g_assert_cmpint(pw85_contact_time(r, v, q, w, q, w, ldexp(1.0, k + 1), &t), ==, PW85_OK);
    g_assert_cmpfloat(fabs(t - (n - 2.0)), <=, 1e-15 * ldexp(1.0, k + 1));
  }
  for (int k = 900; k <= 1000; k++) {
    double const x = ldexp(1.0, k);
    double const r[3] = {x, 0, 0}, v[3] = {-x, 0, 0};
    double t;
    int ev;
    int const s = pw85_contact_time_ex(r, v, q, w, q, w, 2.0, &t, &ev);
    if (k <= 996) {
      g_assert_cmpint(s, ==, PW85_OK);
      g_assert_cmpfloat(fabs(t - (x - 2.0) / x), <=, 1e-15);
    } else {
      g_assert_cmpint(s, ==, PW85_ERR_NO_CONVERGENCE);
      g_assert_cmpfloat(t, ==, 0.0);
      g_assert_cmpint(ev, ==, 1);
    }
  }
}

/* Rotating trajectories against the mpmath references (the guarantees of
 * include/pw85.h, tol = 1e-10 t_max, the width of the certified bracket):
 * PW85_OK; no contact where the exact minimum of mu^2 is above 1 (false);
 * never after the first time with mu^2 < 1 - 2.3e-13 (late; +INFINITY
 * there counts as late); never before the first crossing of 1 by more than
 * tol (early); where mu^2 goes below 1 - 2.3e-13, within tol of a crossing
 * of 1: the first one, or the one that starts the dip below 1 - 2.3e-13
 * (error). */
static void test_rotating_reference(void) {
  int n[4] = {0}, failed[4] = {0}, falsec[4] = {0}, late[4] = {0}, early[4] = {0},
      inexact[4] = {0}, contacts[4] = {0}, grazes[4] = {0}, issue = 0;
  double max_err[4] = {0}, max_ev[4] = {0}, sum_ev[4] = {0};
  for (int k = 0; k < ct_rot_count; k++) {
    ct_rot_case const *c = &ct_rot_cases[k];
    double const tol = 1e-10 * c->t_max;
    double t;
    int ev;
    int const st = pw85_contact_time_ex(c->r0, c->v, c->q1, c->w1, c->q2, c->w2, c->t_max, &t, &ev);
    int const i = c->cls;
    n[i]++;
    grazes[i] += c->kind == 0;
    sum_ev[i] += ev;
    if (ev > max_ev[i]) max_ev[i] = ev;
    if (c->kind == 3) {  /* the reported false contact: min 1 + 9.94e-14 */
      g_assert_cmpfloat(c->min, >, 9e-14);
      g_assert_cmpint(st, ==, PW85_OK);
      g_assert_true(isinf(t) && t > 0);
      issue++;
    }
    if (st != PW85_OK) {
      failed[i]++;
      if (g_test_verbose()) g_test_message("case %d (class %d): status %d", k, i, st);
      continue;
    }
    int bad = 0;
    if (isfinite(t) && c->min > 0) falsec[i]++, bad = 1;
    if (isfinite(c->t_a) && !(t <= nextafter(c->t_a, INFINITY))) late[i]++, bad = 1;
    if (isfinite(t) && isfinite(c->t_c) && t < c->t_c - tol) early[i]++, bad = 1;
    if (isfinite(c->t_a) && isfinite(t)) {
      contacts[i]++;
      double const e = fmin(fabs(t - c->t_c), fabs(t - c->t_d)) / c->t_max;
      if (e > max_err[i]) max_err[i] = e;
      if (!(e <= 1e-10)) inexact[i]++, bad = 1;
    }
    if (bad && g_test_verbose())
      g_test_message("case %d (class %d, kind %d, delta %g): t %.17g, t_c %.17g, t_a %.17g, "
                     "min %g", k, i, c->kind, c->delta, t, c->t_c, c->t_a, c->min);
  }
  for (int i = 0; i < 4; i++) {
    if (g_test_verbose())
      g_test_message("class %d: %d trajectories (%d grazes), %d contacts below the band, %d failed, "
                     "%d false, %d late, %d early, %d beyond 1e-10; max error %.3g, evaluations "
                     "mean %.0f max %.0f", i, n[i], grazes[i], contacts[i], failed[i], falsec[i],
                     late[i], early[i], inexact[i], max_err[i], sum_ev[i] / n[i], max_ev[i]);
    g_assert_cmpint(n[i], >=, 200);
    g_assert_cmpint(failed[i], ==, 0);
    g_assert_cmpint(falsec[i], ==, 0);
    g_assert_cmpint(late[i], ==, 0);
    g_assert_cmpint(early[i], ==, 0);
    g_assert_cmpint(inexact[i], ==, 0);
    g_assert_cmpint(contacts[i], >=, 20);
  }
  g_assert_cmpint(issue, ==, 1);
}

/* A spin about an axis of symmetry leaves Q(t) constant: the rate bounds
 * come from ||[W, Q]|| (T3'), so the cost does not grow with |w|. A rod
 * (semi-axes 10, 1, 1) spinning about its long axis approaches a unit
 * sphere head-on (contact at t = 3, the same as without spin), along the
 * coordinate axes and turned by a random rotation (then Q and w are
 * rounded: ||[W, Q]|| ~ u |w| |Q|). */
static void test_symmetric_spin(void) {
  double const radii[3] = {10, 1, 1}, ident[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double rod[6], ball[6], z[3] = {0, 0, 0};
  make_q(radii, ident, rod);
  sphere_q(1.0, ball);
  GRand *rng = g_rand_new_with_seed(5405);
  for (int turned = 0; turned < 2; turned++) {
    double G[9];
    if (turned) random_axes(rng, G);
    else memcpy(G, ident, sizeof G);
    double q[6], r[3], v[3];
    make_q(radii, G, q);
    /* body axes: rows of G (make_q); approach along the second one */
    for (int i = 0; i < 3; i++) {
      r[i] = 5 * G[3 + i];
      v[i] = -G[3 + i];
    }
    double t0;
    g_assert_cmpint(pw85_contact_time(r, v, q, z, ball, z, 10.0, &t0), ==, PW85_OK);
    g_assert_cmpfloat(fabs(t0 - 3.0), <=, 1e-12);
    for (double wn = 1.0; wn <= 1e10; wn *= 10) {
      double w[3], t;
      int ev;
      for (int i = 0; i < 3; i++) w[i] = wn * G[i];
      g_assert_cmpint(pw85_contact_time_ex(r, v, q, w, ball, z, 10.0, &t, &ev), ==, PW85_OK);
      if (g_test_verbose())
        g_test_message("rod %s, |w| = %g: t - 3 = %.3g, %d evaluations",
                       turned ? "turned" : "on the axes", wn, t - 3.0, ev);
      g_assert_cmpfloat(fabs(t - 3.0), <=, 1e-12);
      g_assert_cmpint(ev, <=, 20);
    }
  }
  /* t_max |w| above 2^50: the angle cannot be reduced accurately, no
   * certificate (*t: certified up to 0) */
  double const wbig[3] = {1e15, 0, 0}, r[3] = {0, 5, 0}, v[3] = {0, -1, 0};
  double t = -1;
  g_assert_cmpint(pw85_contact_time(r, v, rod, wbig, ball, z, 10.0, &t), ==, PW85_ERR_INACCURATE);
  g_assert_cmpfloat(t, ==, 0.0);
  g_rand_free(rng);
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/pw85_contact_time/bad-input", test_bad_input);
  g_test_add_func("/pw85_contact_time/spheres", test_spheres);
  g_test_add_func("/pw85_contact_time/spinning-pair", test_spinning_pair);
  g_test_add_func("/pw85_contact_time/special", test_special);
  g_test_add_func("/pw85_contact_time/steep-crossing", test_steep_crossing);
  g_test_add_func("/pw85_contact_time/domain", test_domain);
  g_test_add_func("/pw85_contact_time/rate", test_rate);
  g_test_add_func("/pw85_contact_time/reference", test_reference);
  g_test_add_func("/pw85_contact_time/grazing-band", test_grazing_band);
  g_test_add_func("/pw85_contact_time/scaling", test_scaling);
  g_test_add_func("/pw85_contact_time/pairs", test_pairs);
  g_test_add_func("/pw85_contact_time/limits", test_limits);
  g_test_add_func("/pw85_contact_time/rotating-reference", test_rotating_reference);
  g_test_add_func("/pw85_contact_time/symmetric-spin", test_symmetric_spin);
  return g_test_run();
}
