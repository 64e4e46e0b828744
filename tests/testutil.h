/* Helpers shared by the GLib test programs: independent reference
 * computations in long double (never the library's own code), random
 * ellipsoids, relative errors, and the reference-data path. */
#ifndef PW85_TESTUTIL_H
#define PW85_TESTUTIL_H

#include <glib.h>

/* |act - exp| / |exp| (or |act| when exp == 0). */
double rel_error(double act, double exp);

/* A uniformly distributed random rotation; rows of axes are orthonormal. */
void random_axes(GRand *rng, double axes[9]);

/* Semi-axes log-uniform in [lo, hi]. */
void random_radii(GRand *rng, double lo, double hi, double radii[3]);

/* Q = sum_k radii[k]^2 v_k v_k^T computed in long double, rounded. */
void make_q(const double radii[3], const double axes[9], double q[6]);

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
#endif
