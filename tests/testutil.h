/* Helpers shared by the GLib test programs (libpw85 and libpw85_legacy):
 * the relative error, the construction of matrices (random rotations and
 * semi-axes, Q from semi-axes and axes, the spheroids of the reference grid),
 * independent reference computations in long double and __float128 (never
 * the library's own code), and the reference-data path. Reading the
 * reference data file: refdata.h. */
#ifndef PW85_TESTUTIL_H
#define PW85_TESTUTIL_H

#include <glib.h>

/* |act - exp| / |exp| (or |act| when exp == 0); 0 when act == exp, so
 * that equal infinities count as exact. */
double rel_error(double act, double exp);

/* Number of correct digits floor(-log10(rel_error(act, exp))), clamped to
 * [0, num_bins - 1]; act == exp counts as num_bins - 1 (pw85 documentation,
 * Fig. 4.1); NaN, and act != 0 against exp == 0, count as 0. */
int correct_digits(double act, double exp, int num_bins);

/* A uniformly distributed random rotation; rows of axes are orthonormal. */
void random_axes(GRand *rng, double axes[9]);

/* Semi-axes log-uniform in [lo, hi]. */
void random_radii(GRand *rng, double lo, double hi, double radii[3]);

/* Q = sum_k radii[k]^2 v_k v_k^T computed in long double, rounded. */
void make_q(const double radii[3], const double axes[9], double q[6]);

/* A random symmetric positive definite matrix R diag(e) R^T: eigenvalues e
 * log-uniform in [1/sqrt(cond), sqrt(cond)], R = random_axes(). */
void random_spd(GRand *rng, double cond, double a[6]);

/* The sphere of radius a: Q = a^2 I. */
void sphere_q(double a, double q[6]);

/* Independent evaluations in long double through the adjugate:
 * f(lambda) = lambda (1 - lambda) r^T adj(Q) r / det(Q). */
long double f_ld(long double lambda, const double r[3], const double q1[6],
                 const double q2[6]);

/* max of f on [0, 1] by golden-section search in long double (f is concave
 * on [0, 1]); *lambda receives the maximiser. */
long double mu2_ld(const double r[3], const double q1[6], const double q2[6],
                   long double *lambda);

/* x^T A^{-1} x in long double for a symmetric A (upper triangle). */
long double xT_inv_x_ld(const double a[6], const long double x[3]);

/* Path of the reference data: $PW85_REF_DATA if set, else the build-time
 * PW85_REF_DATA_PATH. */
const char *ref_data_path(void);



/* f'(lambda) and f''(lambda) in long double (pw85 documentation, chapter 4,
 * eqs. (6) and (9)), with Q^{-1} by cofactors. */
void df_ld(long double lambda, const double r[3], const double q1[6], const double q2[6],
           long double *df, long double *d2f);

/* Ellipsoid i of the pw85 test grid: spheroids for (a, c, n) in
 * {0.01999, 1.999, 9.999}^2 x icosahedron vertices (108 in all), and the 12
 * unit directions. */
void grid_direction(int k, double n[3]);
void grid_spheroid(int i, double q[6]);

/* Symmetric 3x3 algebra in __float128 on pw85 storage (upper triangle). */
__float128 q_det_sym(const __float128 a[6]);
__float128 q_xT_adjA_x(const __float128 x[3], const __float128 a[6]);
/* (1 - lambda) q1 + lambda q2, exact in __float128 for double inputs and
 * lambda = k/10 rounded to double (the product of two doubles is exact). */
void q_interpolate(const double q1[6], const double q2[6], double lambda, __float128 q[6]);
/* f, f', f'' (pw85 documentation, section 4.1, eqs. (4)-(9)), with
 * Q^{-1} = adj(Q) / det(Q) in __float128. */
void q_f_derivs(double lambda, const double r[3], const double q1[6], const double q2[6],
                double out[3]);
#endif
