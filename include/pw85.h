/*
 * pw85.h - public C API of libpw85.
 *
 * libpw85 computes the Perram-Wertheim contact function of two ellipsoids
 * (J. Comp. Phys. 58(3), 409-416, 1985): the square mu^2 of the common
 * factor by which two ellipsoids, their centres fixed, must be scaled to be
 * externally tangent. mu^2 < 1: the ellipsoids overlap; mu^2 = 1: they touch;
 * mu^2 > 1: they are apart.
 *
 * The functions of pw85 1.0 keep their names, signatures and storage
 * conventions, so that programs written for pw85 1.0 compile and link
 * unchanged. New functions return a status code (PW85_OK or a negative
 * PW85_ERR_* value, see pw85_strerror()).
 *
 * Storage conventions:
 *  - a vector is a double[3] of its Cartesian coordinates;
 *  - a symmetric 3x3 matrix A is a double[6] a holding its upper triangle in
 *    row-major order: a = {A00, A01, A02, A11, A12, A22};
 *  - an ellipsoid of centre c is {m : (m - c)^T Q^{-1} (m - c) <= 1}, Q
 *    symmetric positive definite, Q = sum_i a_i^2 v_i v_i^T (semi-axes a_i,
 *    unit axes v_i).
 *
 * Positive definiteness: every function that takes a matrix q accepts it
 * when the real symmetric matrix whose entries are the doubles given is
 * positive definite, and refuses it with PW85_ERR_NOT_SPD otherwise. The
 * test is exact (Sylvester's criterion: Q00 > 0, Q00 Q11 - Q01^2 > 0,
 * det Q > 0 for the exact entries; floating-point minors with rigorous
 * error bounds, exact integer arithmetic where those cannot decide), so
 * every call and every CPU accept and refuse the same matrices, and none
 * accepts a matrix that is positive definite only after rounding. A matrix
 * that is positive definite but singular in double precision is accepted;
 * the calls that cannot answer for it say so by another status (documented
 * with each call). docs/api.md, "Positive definiteness".
 *
 * All functions are reentrant and thread-safe: the library has no global
 * mutable state, never prints, never aborts, and never changes GSL's
 * process-wide error handler.
 *
 * Outputs and inputs: every function that computes one result (all but the
 * batch calls) reads all its inputs before it writes an output, so an
 * output may be one of its input arrays (e.g. pw85_spheroid(a, c, n, n)
 * with n a double[6], or out == r12). The outputs of the batch calls
 * (pw85_*_batch) must not overlap their inputs.
 *
 * Results and the CPU: PW85_METHOD_DEFAULT runs a different algorithm on
 * x86-64 CPUs with AVX-512 (x86-64-v4) when the library is built with
 * GCC >= 12 and the meson option isa_dispatch enabled (its default): a
 * coefficient step in double-double first, the general method only when that
 * step declines. Its results there may differ in the last bits from those of
 * another CPU, both within the documented accuracy of the method. This
 * concerns pw85_contact_function_method() and pw85_dca() with
 * PW85_METHOD_DEFAULT, pw85_contact() and the batch calls built on them
 * (pw85_contact_batch(), pw85_contact_pairs(), ...), the derivatives, and
 * pw85_contact_time(), whose *t stays within its certified bracket. Likewise,
 * the double-double evaluations that the contact-function methods and
 * pw85_contact() use in their last steps run with a fused multiply-add on
 * x86 CPUs that have one, and may differ by an ulp from a CPU without.
 * Building with isa_dispatch=false gives the portable results everywhere.
 * The verdicts of pw85_overlap() and of the overlap batch calls are
 * identical on every CPU (they are exact), and so is the
 * positive-definiteness decision of every call (below). The number of
 * threads of a batch call never changes any result.
 */
#ifndef PW85_H
#define PW85_H

#if defined(_WIN32) && !defined(__GNUC__)
#  ifdef PW85_BUILDING
#    define PW85_API __declspec(dllexport)
#  else
#    define PW85_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__)
#  define PW85_API __attribute__((visibility("default")))
#else
#  define PW85_API
#endif

#ifdef __cplusplus
#  define PW85_BEGIN_DECLS extern "C" {
#  define PW85_END_DECLS }
#else
#  define PW85_BEGIN_DECLS
#  define PW85_END_DECLS
#endif

/* Version of this header (major, minor, patch and the string
 * "MAJOR.MINOR.PATCH"); the build reads it from here. pw85_version() gives
 * the version of the library actually loaded. */
#define PW85_VERSION_MAJOR 2
#define PW85_VERSION_MINOR 0
#define PW85_VERSION_PATCH 0
#define PW85_VERSION "2.0.0"

/* Dimension of the physical space: length of a vector (double[3]). */
#define PW85_DIM 3
/* Dimension of the space of symmetric 3x3 matrices: length of a matrix
 * (double[6], upper triangle row by row). */
#define PW85_SYM 6

/* Absolute tolerance on lambda of the Brent iterations of
 * pw85_contact_function(). */
#define PW85_LAMBDA_ATOL 1e-6
/* Maximum number of Brent iterations of pw85_contact_function(). */
#define PW85_MAX_ITER 25
/* Number of Newton-Raphson refinement steps of pw85_contact_function(). */
#define PW85_NR_ITER 3

/* Status codes returned by the functions of this header; negative values
 * are errors, the values are pinned (ABI); pw85_strerror() describes them.
 * Success. */
#define PW85_OK 0
/* A pointer argument is NULL or a value is NaN or infinite. */
#define PW85_ERR_INVALID_ARGUMENT (-1)
/* A matrix is not symmetric positive definite (or a radius is not > 0). */
#define PW85_ERR_NOT_SPD (-2)
/* An iteration did not converge; the best estimate is still written. */
#define PW85_ERR_NO_CONVERGENCE (-3)
/* Axes passed to pw85_ellipsoid() or pw85_ellipsoid_rotation() are not
 * orthonormal to 1e-10, or a quaternion is not unit to 1e-5. */
#define PW85_ERR_NOT_ORTHONORMAL (-4)
/* The method argument names no method of this function. */
#define PW85_ERR_UNKNOWN_METHOD (-5)
/* A result was computed (and written) but its error estimate exceeds the
 * accuracy the method documents (or, for pw85_overlap(), the exact stage
 * ran out of capacity). */
#define PW85_ERR_INACCURATE (-6)
/* The result is out of the range of double (a quantity above DBL_MAX or
 * below DBL_MIN, the smallest normal double): it is written rounded to the
 * nearest double, so +Inf above DBL_MAX and a subnormal or 0 below DBL_MIN;
 * the other outputs are as for PW85_OK. docs/stability.md lists where. */
#define PW85_ERR_RANGE (-7)
/* An output array is too small: the count it needs is returned, nothing
 * else is written (pw85_configuration_pairs()). */
#define PW85_ERR_CAPACITY (-8)
/* Memory could not be allocated (pw85_configuration_*); nothing changed. */
#define PW85_ERR_NO_MEMORY (-9)

PW85_BEGIN_DECLS

/* Version of the library actually loaded. Returns a static string
 * "MAJOR.MINOR.PATCH" (compare with PW85_VERSION, the version of the header
 * compiled against). Cannot fail. */
PW85_API const char *pw85_version(void);

/* Description of a status code. Returns a static, human-readable string,
 * never NULL; a value that is no status code gives "unknown status".
 * Cannot fail. */
PW85_API const char *pw85_strerror(int status);

/* Cholesky decomposition A = L L^T of a symmetric positive definite matrix a.
 * The lower-triangular L is stored in l as
 *     L = [l[0]  0     0   ]
 *         [l[1]  l[3]  0   ]
 *         [l[2]  l[4]  l[5]].
 * Returns nothing (pw85 1.0 signature). Fails when A is not positive
 * definite or holds NaN: all six entries of l are then NaN. A NULL pointer:
 * nothing is written. */
PW85_API void pw85__cholesky_decomp(double const a[PW85_SYM],
                                    double l[PW85_SYM]);

/* Solves L L^T x = b by forward and backward substitution, l as returned by
 * pw85__cholesky_decomp(); writes the solution to x. Returns nothing
 * (pw85 1.0 signature). l is not checked: a NaN-filled l gives a NaN x. A
 * NULL pointer: nothing is written. */
PW85_API void pw85__cholesky_solve(double const l[PW85_SYM],
                                   double const b[PW85_DIM],
                                   double x[PW85_DIM]);

/* Quadratic form of a spheroid of equatorial radius a, polar radius c and
 * axis of revolution n: writes Q = a^2 (I - m m^T) + c^2 m m^T, m = n / |n|,
 * to q (for unit n, pw85 1.0's Q = a^2 I + (c^2 - a^2) n n^T), each entry
 * within a few roundings of a^2 |(I - m m^T)_ij| + c^2 |(m m^T)_ij| at any
 * aspect c / a. n need not be unit. Returns nothing (pw85 1.0 signature).
 * Fails on a or c not > 0, NaN or infinite values, n = 0 or n NULL, and when
 * Q is not representable (an entry beyond DBL_MAX, or a diagonal entry that
 * rounds to 0): q is then filled with NaN (q NULL: nothing is written). */
PW85_API void pw85_spheroid(double a, double c, double const n[PW85_DIM],
                            double q[PW85_SYM]);

/* Quadratic form of a general ellipsoid: writes Q = sum_i radii[i]^2 v_i v_i^T
 * to q, where v_i = (axes[3i], axes[3i+1], axes[3i+2]) is the i-th row of
 * axes.
 * Returns PW85_OK, PW85_ERR_INVALID_ARGUMENT (NULL pointer, NaN or infinite
 * values), PW85_ERR_NOT_SPD (a radius <= 0), PW85_ERR_NOT_ORTHONORMAL
 * (|axes axes^T - I| > 1e-10 entrywise) or PW85_ERR_RANGE (Q not
 * representable: a radius^2 outside [DBL_MIN, DBL_MAX], i.e. a radius
 * outside about [1.5e-154, 1.3e154], or radii so different -- the smallest
 * below about 1e-8 of the largest, depending on the axes -- that Q rounded
 * to double is not positive definite). On error q is filled with NaN (when
 * q is not NULL). */
PW85_API int pw85_ellipsoid(double const radii[PW85_DIM],
                            double const axes[PW85_DIM * PW85_DIM],
                            double q[PW85_SYM]);

/* Quadratic form of the ellipsoid of semi-axes radii rotated by the
 * quaternion quat = (w, x, y, z) (HOOMD-blue, GSD, LAMMPS order; body frame
 * to lab frame, p -> quat p quat^* (Hamilton product)): writes
 * Q = R diag(radii^2) R^T to q, R the rotation matrix of quat / |quat|, whose
 * column k is body axis k. quat need not be unit: |quat|^2 within 1e-5 of 1
 * (float32 components, six significant digits) is accepted and normalised.
 * Each entry of Q is within u |Q_ij| + 8 u^2 max(radii)^2 of the exact Q of
 * quat / |quat| (u = 2^-53; double-double evaluation; entries below DBL_MIN
 * rounded once more as subnormals; a sphere gives radius^2 I exactly). Same
 * bits with and without a fused multiply-add (the error-free products are
 * exact either way), unless a product of components underflows.
 * Returns PW85_OK, PW85_ERR_INVALID_ARGUMENT (NULL pointer, NaN or infinite
 * values), PW85_ERR_NOT_SPD (a radius <= 0), PW85_ERR_NOT_ORTHONORMAL
 * (| |quat|^2 - 1 | > 1e-5, quat = 0 included) or PW85_ERR_RANGE (a
 * radius^2 outside [DBL_MIN, DBL_MAX], or the rounded Q not positive
 * definite, as pw85_ellipsoid). On error q is filled with NaN (when q is
 * not NULL). */
PW85_API int pw85_ellipsoid_quat(double const radii[PW85_DIM], double const quat[4],
                                 double q[PW85_SYM]);

/* Quadratic form of the ellipsoid of semi-axes radii whose body axes are
 * the COLUMNS of the row-major rotation matrix rot (rot[3i + j] = R_ij, body
 * axis k = (R_0k, R_1k, R_2k), the usual R mapping body to lab frame): writes
 * Q = R diag(radii^2) R^T to q. pw85_ellipsoid takes the axes as ROWS (the
 * transpose): same result for axes = R^T. Orthonormality is checked as
 * pw85_ellipsoid (|R^T R - I| <= 1e-10 entrywise); det R = -1 (a reflection)
 * is accepted, it gives the same ellipsoid. Each entry within a few
 * roundings of sum_k radii[k]^2 |R_ik R_jk|.
 * Returns and fails as pw85_ellipsoid: PW85_ERR_INVALID_ARGUMENT,
 * PW85_ERR_NOT_SPD (a radius <= 0), PW85_ERR_NOT_ORTHONORMAL,
 * PW85_ERR_RANGE; on error q is filled with NaN (when q is not NULL). */
PW85_API int pw85_ellipsoid_rotation(double const radii[PW85_DIM],
                                     double const rot[PW85_DIM * PW85_DIM],
                                     double q[PW85_SYM]);

/* Semi-axes and orientation of the ellipsoid of quadratic form q: writes
 * radii in ascending order, the proper rotation rot (det +1, row-major,
 * column k = unit axis of radii[k], as pw85_ellipsoid_rotation) and its
 * quaternion quat = (w, x, y, z) with w >= 0 (w = 0: the first non-zero of
 * x, y, z positive), so that pw85_ellipsoid_rotation(radii, rot) and
 * pw85_ellipsoid_quat(radii, quat) give q back. rot and quat may be NULL.
 * Signs of the axes: columns 0 and 1 have their largest-magnitude component
 * positive, column 2 completes det = +1. Repeated semi-axes (spheroids,
 * spheres): the axes of the repeated radius are one orthonormal basis of its
 * eigenspace (a diagonal q: the coordinate axes; a sphere: rot = I).
 * Cyclic Jacobi rotations: rot diag(radii^2) rot^T reproduces q within
 * 10 u ||q|| entrywise and rot^T rot = I within 8 u (u = 2^-53; ||q|| the
 * largest radius^2), so radii[k]^2 is within about 10 u ||q|| of the exact
 * eigenvalue (tests/test-orientation.c: measured 6.2 u, 5.6 u; 2.7 u on
 * exact rational Q).
 * Returns PW85_OK (the outputs are accepted back by pw85_ellipsoid_rotation
 * and pw85_ellipsoid_quat), PW85_ERR_INVALID_ARGUMENT (q or radii NULL, NaN
 * or infinite values), PW85_ERR_NOT_SPD (q not positive definite),
 * PW85_ERR_INACCURATE (q positive definite, but its smallest eigenvalue is
 * below the accuracy of the sweeps, about 10 u ||q||: an eigenvalue came
 * out <= 0, or the outputs would not give a positive definite q back) or
 * PW85_ERR_NO_CONVERGENCE (Jacobi sweeps exhausted; outputs written). On the other errors radii, rot and quat are
 * filled with NaN (those not NULL). */
PW85_API int pw85_ellipsoid_axes(double const q[PW85_SYM], double radii[PW85_DIM],
                                 double rot[PW85_DIM * PW85_DIM], double quat[4]);

/* Returns -f(lambda), where
 *     f(lambda) = lambda (1 - lambda) r12^T Q^{-1} r12,
 *     Q = (1 - lambda) Q1 + lambda Q2,
 * evaluated through a Cholesky decomposition of Q. params holds r12, q1 and
 * q2 one after the other (15 doubles). The signature is pw85 1.0's and
 * matches gsl_function. Inputs of any magnitude are rescaled by powers of two
 * (exact); a value beyond the double range is returned rounded (-Inf, or a
 * subnormal or 0). Fails with NaN for NULL params, a NaN or infinite value,
 * or a Q that is not positive definite. */
PW85_API double pw85_f_neg(double lambda, double const *params);

/* Residual g(lambda) = mu2^2 - mu1^2 of the Newton refinement of
 * pw85_contact_function() (pw85 1.0 documentation, chapter 5,
 * eqs. (4)-(5)). Writes
 *     out[0] = f(lambda), out[1] = g(lambda), out[2] = g'(lambda).
 * Inputs of any magnitude are rescaled by powers of two (exact); values
 * beyond the double range are written rounded (+-Inf, subnormal or 0).
 * Returns nothing (pw85 1.0 signature). Fails on a NULL pointer, a NaN or
 * infinite value, or a Q(lambda) that is not positive definite: out is then
 * filled with NaN (out NULL: nothing is written). */
PW85_API void pw85__residual(double lambda, double const r12[PW85_DIM],
                             double const q1[PW85_SYM],
                             double const q2[PW85_SYM], double out[3]);

/* Contact function of two ellipsoids, by pw85 1.0's algorithm: Brent's
 * minimisation of -f over [0, 1] (GSL), then PW85_NR_ITER Newton steps on
 * the residual g, keeping whichever estimate has the smaller |g|.
 *     out[0] = mu^2,  out[1] = lambda (the maximiser of f).
 * r12 = c2 - c1 joins the centres; q1, q2 are the quadratic forms.
 * r12 = 0 gives mu^2 = 0 and lambda = 0.5 with PW85_OK.
 * Returns PW85_OK (mu^2 within 1e-10 relative, according to the error
 * estimate of PW85_METHOD_BRENT, docs/methods.md eq. (M10)),
 * PW85_ERR_INVALID_ARGUMENT (NULL, NaN, infinity),
 * PW85_ERR_NOT_SPD (q1 or q2 not positive definite),
 * PW85_ERR_NO_CONVERGENCE (Brent did not reach PW85_LAMBDA_ATOL in
 * PW85_MAX_ITER iterations and the refined residual does not show
 * convergence; the estimate is still written, mu^2 NaN if f could not be
 * evaluated), PW85_ERR_RANGE (mu^2 above DBL_MAX or below DBL_MIN, written
 * rounded: +Inf, subnormal or 0) or PW85_ERR_INACCURATE (converged, but
 * that estimate exceeds 1e-10 mu^2: ill-conditioned Q(lambda); pw85 1.0
 * returned success). The
 * status is that of pw85_contact_function_method() with PW85_METHOD_BRENT,
 * and out holds pw85 1.0's values whatever the status. On the first two
 * errors out is filled with NaN (when out is not NULL). */
PW85_API int pw85_contact_function(double const r12[PW85_DIM],
                                   double const q1[PW85_SYM],
                                   double const q2[PW85_SYM], double out[2]);

/* ---- Distance of closest approach (docs/dca.md) ----------------------------
 * The distance of closest approach d(u) of two ellipsoids (or ellipses) whose
 * centres lie on a line of direction u is the distance between the centres
 * at which they are externally tangent. Since the contact function is
 * homogeneous of degree 2 in r12 and equals 1 at tangency,
 * d(u) = 1 / sqrt(F(u / |u|, Q1, Q2)).
 * In 2D an ellipse is {m : (m - c)^T Q^{-1} (m - c) <= 1} with Q symmetric
 * positive definite stored as its upper triangle q = {Q00, Q01, Q11}.
 * Directions u need not be unit vectors: any finite non-zero u is normalised.
 * The method identifiers PW85_METHOD_* are defined with
 * pw85_contact_function_method() below. */

/* Default absolute tolerance (radians) on the angle of the cutting plane of
 * the plane-rotation method (pw85_dca with PW85_METHOD_ZHENG, pw85_dca_ex
 * with theta_tol = 0). The error of d it leaves is of order
 * d''(theta) tol^2 / 2, far below the rounding errors (docs/dca.md). */
#define PW85_DCA_THETA_TOL 1e-8
/* Budget of 2D evaluations (cutting planes) of the plane-rotation method;
 * exhausting it gives PW85_ERR_NO_CONVERGENCE. */
#define PW85_DCA_MAX_EVAL 100

/* Distance of closest approach of two ellipses centred on a line of direction
 * u, by the closed-form solution of the 2D problem (Zheng & Palffy-Muhoray,
 * Phys. Rev. E 75, 061709 (2007): a quartic, solved by Ferrari's method, its
 * physical root polished by a safeguarded Newton iteration).
 * Writes d to *d. q1, q2: 2D storage {Q00, Q01, Q11}.
 * Returns PW85_OK, PW85_ERR_INVALID_ARGUMENT (NULL, NaN, infinity, u = 0),
 * PW85_ERR_NOT_SPD (q1 or q2 not positive definite),
 * PW85_ERR_NO_CONVERGENCE (polishing did not converge; *d still written) or
 * PW85_ERR_INACCURATE (q1 or q2 positive definite but singular in double
 * precision: condition number above about 1/DBL_EPSILON, or q1 and q2 of
 * magnitudes more than about 2^1000 apart). On the other errors *d is NaN
 * (when d is not NULL). */
PW85_API int pw85_dca_2d(double const u[2], double const q1[3],
                         double const q2[3], double *d);

/* Contact function of two ellipses (the 2D analogue of
 * pw85_contact_function): out[0] = mu^2 = max over [0, 1] of
 * f(lambda) = lambda (1 - lambda) r12^T ((1 - lambda) Q1 + lambda Q2)^{-1} r12,
 * out[1] = lambda, its maximiser; computed to full double precision by a
 * safeguarded Newton iteration on f'. r12 = 0 gives mu^2 = 0, lambda = 0.5.
 * pw85_dca_2d(u) = 1 / sqrt(out[0]) for r12 = u / |u|.
 * Returns PW85_OK, PW85_ERR_INVALID_ARGUMENT (NULL, NaN, infinity),
 * PW85_ERR_NOT_SPD (q1 or q2 not positive definite),
 * PW85_ERR_NO_CONVERGENCE (estimate still written), PW85_ERR_RANGE
 * (mu^2 above DBL_MAX or below DBL_MIN, written rounded: +Inf, subnormal or
 * 0) or PW85_ERR_INACCURATE (as pw85_dca_2d; out is NaN). On the first two
 * errors out is filled with NaN (when out is not NULL). */
PW85_API int pw85_contact_function_2d(double const r12[2], double const q1[3],
                                      double const q2[3], double out[2]);

/* Distance of closest approach of two ellipsoids centred on a line of
 * direction u, written to *d. method:
 *  - PW85_METHOD_ZHENG: rotation of a plane through the line of centres, the
 *    2D problem of the two sections solved as by pw85_dca_2d (Zheng,
 *    Iglesias & Palffy-Muhoray, 2008), tolerance PW85_DCA_THETA_TOL;
 *  - any other method of pw85_contact_function_method (PW85_METHOD_DEFAULT,
 *    PW85_METHOD_BRENT, ...): d = 1 / sqrt(F(u / |u|)), F by that method.
 * Returns PW85_OK, PW85_ERR_INVALID_ARGUMENT (NULL, NaN, infinity, u = 0),
 * PW85_ERR_NOT_SPD, PW85_ERR_UNKNOWN_METHOD, or, with *d still written,
 * PW85_ERR_NO_CONVERGENCE or PW85_ERR_INACCURATE (as returned by
 * pw85_contact_function_method for the contact-function methods; ZHENG
 * returns no PW85_ERR_INACCURATE). On the other errors *d is NaN (when d is
 * not NULL). With PW85_METHOD_DEFAULT the last bits of d may depend on the
 * CPU (top of this header). */
PW85_API int pw85_dca(double const u[PW85_DIM], double const q1[PW85_SYM],
                      double const q2[PW85_SYM], int method, double *d);

/* pw85_dca(..., PW85_METHOD_ZHENG, d) with an explicit tolerance theta_tol
 * (radians, >= 0; 0 selects PW85_DCA_THETA_TOL) on the angle of the optimal
 * plane, reporting in *evaluations (may be NULL) the number of 2D problems
 * solved (at most PW85_DCA_MAX_EVAL). Returns as pw85_dca, plus
 * PW85_ERR_INVALID_ARGUMENT for a negative or non-finite theta_tol and
 * PW85_ERR_NO_CONVERGENCE when the budget is exhausted (*d still written).
 * *d is NaN on the other errors (when d is not NULL). */
PW85_API int pw85_dca_ex(double const u[PW85_DIM], double const q1[PW85_SYM],
                         double const q2[PW85_SYM], double theta_tol,
                         double *d, int *evaluations);

/* ---- Method-selecting contact function ------------------------------------
 * Methods of pw85_contact_function_method() and pw85_dca(); the values are
 * pinned (ABI). Their formulas, cost and accuracy are in docs/methods.md. */

/* The recommended method: safeguarded Halley iteration in double (adjugate
 * of Q(lambda)); when the estimated error exceeds 4e-15 mu2, f is
 * re-evaluated by a compensated (double-double) stationary form, then if
 * needed by L D L^T in double-double. On x86-64 CPUs with AVX-512 (GCC >= 12,
 * isa_dispatch enabled) a coefficient step in double-double comes first, so the
 * last bits may differ from another CPU's (top of this header). Documented
 * relative accuracy of mu2: 1e-14. Known exception, not fixed: where q1 or
 * q2 is numerically singular in double (semi-axes about 2^46 or more
 * apart, rotated off the coordinate axes), PW85_OK can rarely come with a
 * larger error (1.7e-10 measured; docs/stability.md). */
#define PW85_METHOD_DEFAULT 0
/* pw85 1.0's algorithm, what pw85_contact_function() computes (Brent, then
 * Newton on the residual, mu2 by a compensated form). Documented relative
 * accuracy: 1e-10. */
#define PW85_METHOD_BRENT 1
/* Safeguarded Halley iteration on f' = -g bracketed in [0, 1], f and its
 * derivatives in double through LDL^T of Q(lambda). Documented relative
 * accuracy: 1e-12. */
#define PW85_METHOD_NEWTON 2
/* Rational-fraction formulation f = l (1 - l) a(l) / b(l), coefficients of
 * a and b computed once per pair in double. Documented relative accuracy:
 * 1e-12. */
#define PW85_METHOD_RATIONAL 3
/* Distance-of-closest-approach method (Zheng, Iglesias & Palffy-Muhoray,
 * 2008): mu2 = |r12|^2 / d^2, d by plane rotation as pw85_dca; lambda from
 * the optimal plane, polished by Newton steps (docs/dca.md). Documented
 * relative accuracy: 1e-9 up to pair aspect ratio 100. */
#define PW85_METHOD_ZHENG 4

/* Result of pw85_contact_function_method(). A plain struct of C types, so
 * that Fortran can mirror it with type, bind(c). */
typedef struct pw85_result {
  double mu2;       /* contact function mu^2 (0 when r12 = 0) */
  double lambda;    /* maximiser of f on [0, 1] (0.5 when r12 = 0) */
  double mu2_error; /* estimate of the absolute error on mu2 */
  int iterations;   /* iterations of the method: evaluations of f for
                       DEFAULT, NEWTON, RATIONAL, Brent iterations for BRENT,
                       2D evaluations (cutting planes) for ZHENG */
  int method;       /* method actually used (a PW85_METHOD_* value; DEFAULT
                       for PW85_METHOD_DEFAULT) */
} pw85_result;

/* Contact function of two ellipsoids by a chosen method (PW85_METHOD_*).
 * r12 = c2 - c1, q1 and q2 the quadratic forms (as pw85_contact_function()).
 * Writes every field of *res. Returns
 *   PW85_OK                    mu2 is within the method's documented accuracy
 *                              (according to its error estimate mu2_error);
 *   PW85_ERR_INACCURATE        result written, but mu2_error exceeds the
 *                              documented relative accuracy times mu2;
 *   PW85_ERR_NO_CONVERGENCE    the iteration stopped early; best estimate
 *                              written (finite; where the method has none,
 *                              the largest f met by bisection on f', with
 *                              mu2_error +inf when no bound is known, and
 *                              mu2 = 0, lambda = 0.5 when f cannot be
 *                              evaluated at all);
 *   PW85_ERR_RANGE             mu2 above DBL_MAX or below DBL_MIN: written
 *                              rounded (+Inf, subnormal or 0), lambda as
 *                              for PW85_OK;
 *   PW85_ERR_INVALID_ARGUMENT  NULL pointer, NaN or infinite value;
 *   PW85_ERR_NOT_SPD           q1 or q2 not positive definite;
 *   PW85_ERR_UNKNOWN_METHOD    method is not a PW85_METHOD_* value.
 * With the first four, lambda is in [0, 1], mu2 >= 0 (+inf only where
 * mu2 exceeds the range of double) and mu2_error is never NaN.
 * On the last three errors mu2, lambda and mu2_error are NaN and iterations
 * is 0 (nothing is written when res is NULL). Never allocates. With
 * PW85_METHOD_DEFAULT the last bits may depend on the CPU (top of this
 * header). */
PW85_API int pw85_contact_function_method(double const r12[PW85_DIM],
                                          double const q1[PW85_SYM],
                                          double const q2[PW85_SYM], int method,
                                          pw85_result *res);

/* ---- Overlap, contact geometry and batch calls over a scene ---------------
 * docs/overlap.md, docs/contact_geometry.md, docs/batch.md. */

/* Exact overlap predicate. Returns 1 when the interiors of the two
 * ellipsoids intersect (mu^2 < 1), 0 when they do not (mu^2 >= 1; external
 * tangency counts as not overlapping). The verdict is exact for the doubles
 * given, however close to tangency: floating-point filters with rigorous
 * error bounds decide almost every pair, the rest is decided by a Sturm
 * sequence in exact integer arithmetic (no heap allocation). r12 = 0 gives 1.
 * Returns a negative status on error: PW85_ERR_INVALID_ARGUMENT (NULL, NaN,
 * infinity), PW85_ERR_NOT_SPD (q1 or q2 not positive definite) or
 * PW85_ERR_INACCURATE (exact stage out of capacity: only for matrices whose
 * entries span more than about 2^300 in magnitude, docs/overlap.md). The
 * verdict is the same on every CPU. */
PW85_API int pw85_overlap(double const r12[PW85_DIM], double const q1[PW85_SYM],
                          double const q2[PW85_SYM]);

/* Contact geometry of two ellipsoids (docs/contact_geometry.md). A plain
 * struct of doubles, mirrored in Fortran by type(pw85_contact_t), bind(c). */
typedef struct pw85_contact_t {
  double mu2;     /* contact function mu^2 */
  double lambda;  /* maximiser of f on [0, 1] */
  double x0[3];   /* contact point of the two ellipsoids scaled by mu,
                     relative to centre 1: (1 - lambda) Q1 Q^{-1} r12 */
  double n[3];    /* unit common normal at x0, pointing from 1 towards 2 */
  double dca;     /* distance of closest approach along r12: |r12| / mu */
  double depth;   /* overlap depth along r12: dca - |r12| (> 0: overlap) */
  double depth_n; /* depth projected on the normal: depth (r12/|r12|) . n */
} pw85_contact_t;

/* Contact geometry of the pair (r12 = c2 - c1, q1, q2): fills every field of
 * *c, mu2 by PW85_METHOD_DEFAULT. Returns PW85_OK,
 * PW85_ERR_INVALID_ARGUMENT (NULL, NaN, infinity, or r12 = 0 where the
 * geometry is undefined), PW85_ERR_NOT_SPD (q1 or q2 not positive definite),
 * PW85_ERR_NO_CONVERGENCE (the contact-function solve or the contact point
 * did not converge; the fields hold the estimates, NaN where there is none)
 * PW85_ERR_INACCURATE (every field written, but the error estimate of mu2
 * exceeds PW85_METHOD_DEFAULT's documented accuracy) or PW85_ERR_RANGE
 * (every field written; mu2, dca or the largest |x0_i| is above DBL_MAX or
 * below DBL_MIN, or |depth| above DBL_MAX: those rounded to the nearest
 * double, +Inf or a subnormal or 0; docs/contact_geometry.md (G12)). Any r12
 * and matrices of the double range are accepted. On the first two
 * errors every field of *c is NaN (when c is not NULL). The last bits may
 * depend on the CPU (top of this header). */
PW85_API int pw85_contact(double const r12[PW85_DIM], double const q1[PW85_SYM],
                          double const q2[PW85_SYM], pw85_contact_t *c);

/* Batch calls over a scene of n ellipsoids: centres[3i..3i+2] and
 * q[6i..6i+5] are the centre and quadratic form of ellipsoid i; pairs holds
 * m index pairs (pairs[2k], pairs[2k+1]) = (i, j), and pair k is computed
 * with r12 = c_j - c_i (rounded to double) exactly as the one-pair function
 * does, so the results are identical to it and independent of the number of
 * threads. nthreads: number of OpenMP threads requested (0: the OpenMP
 * default); every batch call of this header runs on at most
 * min(nthreads, omp_get_num_procs(), m) threads, so any nthreads >= 0 is
 * safe (INT_MAX included); the process-wide OpenMP settings are never
 * changed; ignored without OpenMP. status (may be NULL) receives the status
 * of each pair. Indices and counts are long long (64-bit), so that the
 * header needs no other header and Fortran passes integer(c_long_long).
 * The scene and pairs calls further below (pw85_scene_*, pw85_*_pairs) are
 * the implementation; the three *_batch calls keep their signatures and
 * behaviour (ABI): pw85_overlap_batch and pw85_contact_batch are one-line
 * wrappers of pw85_scene_overlap and pw85_scene_contact with box NULL;
 * pw85_contact_function_batch runs pw85_contact_function (pw85 1.0's Brent
 * iteration, several times slower than PW85_METHOD_DEFAULT) through the
 * same scene loop (docs/batch.md). */

/* pw85_scene_overlap(n, centres, q, NULL, m, pairs, overlap, status,
 * nthreads): overlap verdicts of m pairs, overlap[k] = pw85_overlap() of
 * pair k (1, 0, or a negative status), status[k] = PW85_OK or that status.
 * Returns PW85_OK when every pair succeeded (m = 0 included), else the status
 * of the first failing pair (lowest k): PW85_ERR_INVALID_ARGUMENT (also for
 * an index < 0 or >= n), PW85_ERR_NOT_SPD or PW85_ERR_INACCURATE, as
 * pw85_overlap(). Returns PW85_ERR_INVALID_ARGUMENT with nothing written
 * when m < 0, or when m > 0 and centres, q, pairs or overlap is NULL, n < 0
 * or nthreads < 0. The verdicts are the same on every CPU. */
PW85_API int pw85_overlap_batch(long long n, double const *centres, double const *q,
                                long long m, long long const *pairs, int *overlap,
                                int *status, int nthreads);

/* Contact functions of m pairs: out[2k], out[2k+1] = mu^2, lambda of pair
 * k, status[k] its status, as pw85_contact_function(). Returns PW85_OK when
 * every pair succeeded (m = 0 included), else the status of the first failing
 * pair (lowest k): PW85_ERR_INVALID_ARGUMENT (also for an index < 0 or >= n;
 * that pair's out is NaN), PW85_ERR_NOT_SPD or PW85_ERR_NO_CONVERGENCE.
 * Returns PW85_ERR_INVALID_ARGUMENT with nothing written when m < 0, or
 * when m > 0 and centres, q, pairs or out is NULL, n < 0 or nthreads < 0. */
PW85_API int pw85_contact_function_batch(long long n, double const *centres,
                                         double const *q, long long m,
                                         long long const *pairs, double *out,
                                         int *status, int nthreads);

/* pw85_scene_contact(n, centres, q, NULL, m, pairs, c, status, nthreads):
 * contact geometry of m pairs, c[k] = pw85_contact() of pair k, status[k]
 * its status. Returns PW85_OK when every pair succeeded (m = 0 included),
 * else the status of the first failing pair (lowest k):
 * PW85_ERR_INVALID_ARGUMENT (also for an index < 0 or >= n; that pair's
 * fields are NaN), PW85_ERR_NOT_SPD, PW85_ERR_NO_CONVERGENCE or
 * PW85_ERR_INACCURATE. Returns PW85_ERR_INVALID_ARGUMENT with nothing written
 * when m < 0, or when m > 0 and centres, q, pairs or c is NULL, n < 0 or
 * nthreads < 0. As pw85_contact(), the last bits may depend on the CPU (top
 * of this header). */
PW85_API int pw85_contact_batch(long long n, double const *centres, double const *q,
                                long long m, long long const *pairs, pw85_contact_t *c,
                                int *status, int nthreads);

/* ---- Batch calls over per-pair arrays and periodic scenes -----------------
 * Common conventions (docs/batch.md): each pair is computed by the one-pair
 * function, so its result is bitwise that of the one-pair call, whatever the
 * number of threads, its position k and the other pairs. status (may be
 * NULL) receives each pair's status (PW85_OK or negative). The return value
 * is PW85_OK when every pair succeeded (m = 0 included, a no-op), else the
 * status of the lowest failing k. PW85_ERR_INVALID_ARGUMENT with nothing
 * written: m < 0, or m > 0 and a required pointer NULL, nthreads < 0 (and
 * for the scene calls n < 0 or an invalid box). A NaN or infinite value or
 * a matrix that is not positive definite fails that pair only. nthreads as
 * for the *_batch calls above (clamped to the CPUs and to m).
 *
 * Per-pair arrays (pw85_*_pairs): pair k is r12[3k..3k+2], q1[6k..6k+5],
 * q2[6k..6k+5]. */

/* overlap[k] = pw85_overlap() of pair k (1, 0 or a negative status). */
PW85_API int pw85_overlap_pairs(long long m, double const *r12, double const *q1,
                                double const *q2, int *overlap, int *status, int nthreads);

/* res[k] = pw85_contact_function_method() of pair k by method (any
 * PW85_METHOD_*; an unknown method: PW85_ERR_UNKNOWN_METHOD, nothing
 * written). */
PW85_API int pw85_contact_function_pairs(long long m, double const *r12, double const *q1,
                                         double const *q2, int method, pw85_result *res,
                                         int *status, int nthreads);

/* c[k] = pw85_contact() of pair k. */
PW85_API int pw85_contact_pairs(long long m, double const *r12, double const *q1,
                                double const *q2, pw85_contact_t *c, int *status,
                                int nthreads);

/* Scenes (pw85_scene_*): n ellipsoids, centre i at centres[3i..3i+2], matrix
 * i at q[6i..6i+5]; pair k is (i, j) = (pairs[2k], pairs[2k+1]), computed
 * with r12 = c_j - c_i. box (may be NULL: no periodicity) is a periodic box
 * in the HOOMD/GSD convention {Lx, Ly, Lz, xy, xz, yz}: lattice vectors
 * (Lx, 0, 0), (xy Ly, Ly, 0), (xz Lz, yz Lz, Lz), the tilt offsets rounded
 * to double. With a box, r12 is the image of c_j - c_i (rounded to double)
 * given by the triclinic wrap of HOOMD's Box::minImage in exact arithmetic
 * (z, then y, then x, each by the nearest integer number of lattice vectors,
 * ties away from zero; within a relative 2^-48 of a tie either count),
 * each component rounded to double once; it lies in |x| <= Lx/2,
 * |y| <= Ly/2, |z| <= Lz/2. A pair whose wrap needs a count beyond 2^50
 * lattice vectors along a2 when xy != 0, or along a3 when xz or yz != 0
 * (or overflows), fails with PW85_ERR_INVALID_ARGUMENT; without tilt any
 * distance is reduced exactly. It is the nearest image whenever the
 * nearest image is shorter than min(Lx, Ly, Lz)/2, hence for every pair
 * that overlaps or touches in some image; for longer separations in a
 * tilted box it may be another image (docs/batch.md). To keep that guarantee, a pair whose
 * bounding spheres (radius: square root of the smaller of the trace and the
 * largest Gershgorin row sum of |Q|) have radii summing to more than
 * min(Lx, Ly, Lz)/2 (less a relative 1e-9) fails with
 * PW85_ERR_INVALID_ARGUMENT, as does an index < 0 or >= n; that pair's
 * outputs are then NaN (overlap[k] the status). The box is invalid (call
 * error) when a length is not finite and > 0, a tilt is not finite, or a
 * tilt times its length overflows. */

/* overlap[k] = pw85_overlap() of pair k. */
PW85_API int pw85_scene_overlap(long long n, double const *centres, double const *q,
                                double const box[6], long long m, long long const *pairs,
                                int *overlap, int *status, int nthreads);

/* res[k] = pw85_contact_function_method() of pair k by method (unknown
 * method: PW85_ERR_UNKNOWN_METHOD, nothing written). */
PW85_API int pw85_scene_contact_function(long long n, double const *centres, double const *q,
                                         double const box[6], long long m,
                                         long long const *pairs, int method, pw85_result *res,
                                         int *status, int nthreads);

/* c[k] = pw85_contact() of pair k. */
PW85_API int pw85_scene_contact(long long n, double const *centres, double const *q,
                                double const box[6], long long m, long long const *pairs,
                                pw85_contact_t *c, int *status, int nthreads);

/* ---- Configurations: N ellipsoids in a box --------------------------------
 * docs/scene.md. A pw85_configuration holds n ellipsoids (centre i at
 * centres[3i..3i+2], matrix i at q[6i..6i+5], copied) and an optional
 * periodic box (the convention of the pw85_scene_* calls above), and finds
 * the pairs among them: the overlapping pairs, the pairs within a scale
 * factor, the particles a trial move would overlap. (The name is not
 * "scene": the pw85_scene_* calls take index pairs the caller found; a
 * configuration finds them.) Every pair (i, j), i < j, is judged on r12 =
 * c_j - c_i, or its image given by the pw85_scene_* calls' wrap, with the
 * exact overlap predicate, so its verdict is that of pw85_scene_overlap()
 * on the pair (i, j). A configuration is used by one thread at a time when
 * it is changed (update, move); the other calls may run concurrently on
 * the same configuration. Memory: O(n), about 160 bytes per particle, and
 * a pairs query allocates O(n + pairs) more for its duration. */
typedef struct pw85_configuration pw85_configuration;

/* Creates a configuration of n >= 0 ellipsoids; box (may be NULL: no
 * periodicity) as for pw85_scene_overlap(). Each centre must be finite
 * and, with a box, at most 2^20 box lengths from the origin (2^500 without
 * one); each matrix finite and positive definite (as pw85_overlap() checks
 * it); with a box, the largest bounding sphere must satisfy the
 * pw85_scene_* calls' bound with itself (twice its radius at most
 * min(Lx, Ly, Lz)/2): no particle meets its own images, and any two
 * particles satisfy the bound together.
 * Returns PW85_OK and *configuration, or PW85_ERR_INVALID_ARGUMENT (NULL
 * pointer, n < 0, invalid box, NaN or infinite value, spheres too large for
 * the box), PW85_ERR_NOT_SPD, PW85_ERR_RANGE (a centre too far out) or
 * PW85_ERR_NO_MEMORY, with *configuration unchanged; *bad (may be NULL)
 * receives the index of the particle at fault, or -1. */
PW85_API int pw85_configuration_create(long long n, double const *centres, double const *q,
                                       double const box[6],
                                       pw85_configuration **configuration, long long *bad);

/* Frees a configuration (NULL: nothing). */
PW85_API void pw85_configuration_destroy(pw85_configuration *configuration);

/* Replaces the particles (and the box) of a configuration, as
 * pw85_configuration_create() would set them; no memory is allocated when
 * n does not exceed the largest n the configuration has held. On error
 * (statuses and *bad as for pw85_configuration_create()) the configuration
 * is unchanged. */
PW85_API int pw85_configuration_update(pw85_configuration *configuration, long long n,
                                       double const *centres, double const *q,
                                       double const box[6], long long *bad);

/* Number of particles, or -1 for NULL. */
PW85_API long long pw85_configuration_size(pw85_configuration const *configuration);

/* The pairs within the scale factor s >= 1: every pair i < j whose
 * ellipsoids, each scaled by s about its centre (matrices s2 Q, s2 = s s
 * rounded, each product rounded), overlap, decided exactly by the overlap
 * predicate; s = 1: the overlapping pairs, each verdict pw85_overlap()'s;
 * s2 a power of two: the scaled matrices are exact and the pairs are those
 * with mu^2 < s^2 exactly. Sorted by i, then j, the same for every thread
 * count. *count receives the number of pairs; when it is <= capacity, i[k],
 * j[k] receive pair k and mu2[k] (mu2 may be NULL) the contact function of
 * the unscaled pair by PW85_METHOD_DEFAULT (pw85_contact_function_method()'s
 * mu2, NaN where that call fails). Returns PW85_OK, PW85_ERR_CAPACITY (more
 * than capacity pairs: *count set, nothing else written; capacity = 0 with
 * i, j NULL asks for the count), PW85_ERR_INVALID_ARGUMENT (NULL pointer,
 * s < 1 or not finite, s^2 times a matrix entry beyond the range of
 * double, capacity < 0, nthreads < 0, or with a box s times the two
 * largest bounding radii summing to more than min(Lx, Ly, Lz)/2),
 * PW85_ERR_NOT_SPD or PW85_ERR_INACCURATE (as pw85_overlap() on a pair) or
 * PW85_ERR_NO_MEMORY, with nothing written. examined (may be NULL)
 * receives two counts of the broad phase: the pairs whose bounding spheres
 * (scaled by s) intersect, and those of them passed to the exact
 * predicate. nthreads as for the batch calls. */
PW85_API int pw85_configuration_pairs(pw85_configuration const *configuration, double s,
                                      int nthreads, long long capacity, long long *i,
                                      long long *j, double *mu2, long long *count,
                                      long long examined[2]);

/* Whether particle i moved to (centre, q) would overlap another particle:
 * *j receives the smallest index j != i whose ellipsoid it overlaps (the
 * verdict of the pair as pw85_configuration_pairs() would judge it after
 * the move), or -1. The configuration is not changed. Returns PW85_OK,
 * PW85_ERR_INVALID_ARGUMENT (NULL, i out of range, NaN or infinite value,
 * with a box a bounding sphere that breaks pw85_configuration_create()'s
 * bound with itself or with the largest one the configuration has held),
 * PW85_ERR_NOT_SPD,
 * PW85_ERR_RANGE (centre too far out), PW85_ERR_INACCURATE or
 * PW85_ERR_NO_MEMORY, with *j unchanged. */
PW85_API int pw85_configuration_test_move(pw85_configuration const *configuration,
                                          long long i, double const centre[PW85_DIM],
                                          double const q[PW85_SYM], long long *j);

/* The neighbours of particle i by centre distance: every j != i with
 * r12 . r12 < distance^2 (computed in double), r12 = c_j - c_i of the pair
 * (min(i, j), max(i, j)) or its image as pw85_configuration_pairs() takes
 * it, in ascending j. A superset of the particles whose ellipsoids lie
 * within a gap g of particle i's when distance >= R_i + R_max + g (R: the
 * largest semi-axes); event-driven dynamics keeps such lists with a skin.
 * *count receives their number; when it is <= capacity, j[0..*count-1]
 * receive them. Cost: the cells within distance of particle i, no
 * narrow phase. Returns PW85_OK, PW85_ERR_CAPACITY (*count set, nothing
 * else written; capacity = 0 with j NULL asks for the count),
 * PW85_ERR_INVALID_ARGUMENT (NULL pointer, i out of range, capacity < 0,
 * distance negative or not finite, or with a box larger than
 * min(Lx, Ly, Lz)/2 (less 1e-9 relative)) or PW85_ERR_NO_MEMORY, with
 * nothing written. */
PW85_API int pw85_configuration_neighbours(pw85_configuration const *configuration,
                                           long long i, double distance, long long capacity,
                                           long long *j, long long *count);

/* Moves particle i to (centre, q), with no overlap test. Returns as
 * pw85_configuration_test_move(); on error the configuration is
 * unchanged. */
PW85_API int pw85_configuration_move(pw85_configuration *configuration, long long i,
                                     double const centre[PW85_DIM],
                                     double const q[PW85_SYM]);

/* ---- Derivatives of the contact function ---------------------------------
 * docs/derivatives.md. */

/* Derivatives of mu^2 for forces and torques (molecular dynamics, DEM). A
 * plain struct of doubles, mirrored in Fortran by type(pw85_derivatives_t),
 * bind(c). Symmetric 3x3 quantities are stored as q (upper triangle, row
 * major: 11, 12, 13, 22, 23, 33). */
typedef struct pw85_derivatives_t {
  double mu2;          /* contact function mu^2 (PW85_METHOD_DEFAULT) */
  double lambda;       /* maximiser of f on [0, 1] */
  double d_r12[3];     /* gradient d mu^2 / d r12 = 2 lambda (1 - lambda) s,
                          s = Q(lambda)^{-1} r12 */
  double d_theta1[3];  /* d mu^2 / d theta1 = -x0 x d_r12: rotation of
                          ellipsoid 1 about its centre, Q1 -> R Q1 R^T */
  double d_theta2[3];  /* d mu^2 / d theta2 = (x0 - r12) x d_r12 */
  double d_q1[6];      /* d mu^2 / d q1[k] for each stored entry: an
                          off-diagonal q1[k] stands for both Q1_ij and Q1_ji,
                          so d_q1[k] = 2 x the matrix derivative there */
  double d_q2[6];      /* d mu^2 / d q2[k], same convention */
  double hess_r12[6];  /* Hessian d^2 mu^2 / d r12^2 (matrix entries) */
} pw85_derivatives_t;

/* Derivatives of mu^2 of the pair (r12 = c2 - c1, q1, q2); x0 is the contact
 * point of pw85_contact() (relative to centre 1). Returns PW85_OK,
 * PW85_ERR_INVALID_ARGUMENT (NULL, NaN, infinity, or r12 = 0 where mu^2 is
 * not differentiable), PW85_ERR_NOT_SPD (q1 or q2 not positive definite),
 * PW85_ERR_NO_CONVERGENCE (the solve did not converge; where DEFAULT
 * answers, only when a field is outside the range of double, the maximiser
 * has min(lambda, 1 - lambda) below about 1e-15, i.e. q1 and q2 of
 * magnitudes about 2^100 or more apart, or f is nearly flat at its maximum,
 * f(lambda -+ min(lambda, 1 - lambda) / 4) within 1e-6 of mu^2 relative,
 * where lambda is not determined in double (matrix entries spanning about
 * 2^100 or more), or q1 or q2 numerically singular in double (det q below
 * 2^-50 times the product of its diagonal entries: semi-axes about 2^25 or
 * more apart, rotated off the coordinate axes); docs/derivatives.md) or
 * PW85_ERR_INACCURATE (every field written, but the error estimate of mu2
 * exceeds PW85_METHOD_DEFAULT's documented accuracy). On the other errors
 * every field of *d is NaN (when d is not NULL). The last bits may depend on
 * the CPU (top of this header). */
PW85_API int pw85_contact_derivatives(double const r12[PW85_DIM], double const q1[PW85_SYM],
                                      double const q2[PW85_SYM], pw85_derivatives_t *d);

/* Values of the flags argument of the _ex derivatives calls: what to
 * compute. PW85_DERIVATIVES_ALL: every field (the calls without _ex).
 * PW85_DERIVATIVES_FORCES: mu2, lambda, d_r12, d_theta1 and d_theta2 only,
 * what forces and torques need; d_q1, d_q2 and hess_r12 are set to NaN and
 * not computed where skipping them does not change the other fields
 * (docs/derivatives.md). Where the PW85_DERIVATIVES_ALL call returns PW85_OK
 * or PW85_ERR_INACCURATE, the PW85_DERIVATIVES_FORCES call returns the same
 * status and the same bits in mu2, lambda, d_r12, d_theta1 and d_theta2.
 * Other values are invalid. */
#define PW85_DERIVATIVES_ALL 0u
#define PW85_DERIVATIVES_FORCES 1u

/* pw85_contact_derivatives() of the fields that flags selects
 * (PW85_DERIVATIVES_ALL or PW85_DERIVATIVES_FORCES); the fields not selected
 * are NaN. Flags of any other value: PW85_ERR_INVALID_ARGUMENT and every
 * field of *d NaN (when d is not NULL). */
PW85_API int pw85_contact_derivatives_ex(double const r12[PW85_DIM], double const q1[PW85_SYM],
                                         double const q2[PW85_SYM], unsigned flags,
                                         pw85_derivatives_t *d);

/* d[k] = pw85_contact_derivatives() of pair k of per-pair arrays
 * (conventions of pw85_contact_pairs). */
PW85_API int pw85_contact_derivatives_pairs(long long m, double const *r12, double const *q1,
                                            double const *q2, pw85_derivatives_t *d,
                                            int *status, int nthreads);

/* d[k] = pw85_contact_derivatives_ex(..., flags, ...) of pair k of per-pair
 * arrays (conventions of pw85_contact_pairs). Flags other than
 * PW85_DERIVATIVES_ALL and PW85_DERIVATIVES_FORCES: PW85_ERR_INVALID_ARGUMENT,
 * d and status untouched. */
PW85_API int pw85_contact_derivatives_pairs_ex(long long m, double const *r12,
                                               double const *q1, double const *q2,
                                               unsigned flags, pw85_derivatives_t *d,
                                               int *status, int nthreads);

/* d[k] = pw85_contact_derivatives() of pair k = (i, j) of a scene, r12 =
 * c_j - c_i or its periodic image (conventions of pw85_scene_contact); the
 * derivatives are with respect to r12 = c_j - c_i, q_i (d_q1, d_theta1) and
 * q_j (d_q2, d_theta2). */
PW85_API int pw85_scene_contact_derivatives(long long n, double const *centres,
                                            double const *q, double const box[6], long long m,
                                            long long const *pairs, pw85_derivatives_t *d,
                                            int *status, int nthreads);

/* d[k] = pw85_contact_derivatives_ex(..., flags, ...) of pair k = (i, j) of
 * a scene (conventions of pw85_scene_contact_derivatives). Flags other than
 * PW85_DERIVATIVES_ALL and PW85_DERIVATIVES_FORCES:
 * PW85_ERR_INVALID_ARGUMENT, d and status untouched. */
PW85_API int pw85_scene_contact_derivatives_ex(long long n, double const *centres,
                                               double const *q, double const box[6],
                                               long long m, long long const *pairs,
                                               unsigned flags, pw85_derivatives_t *d,
                                               int *status, int nthreads);

/* ---- Time of first contact ----------------------------------------------
 * docs/contact_time.md. */

/* Budget of contact-function evaluations of one pw85_contact_time() call:
 * no sample of mu^2(t) starts once it is spent. A sample takes one to three
 * evaluations (DEFAULT, an enclosure, the derivatives), so
 * pw85_contact_time_ex() reports at most PW85_CONTACT_TIME_MAX_EVAL + 2. */
#define PW85_CONTACT_TIME_MAX_EVAL 100000

/* First contact time of two moving ellipsoids. The centre offset moves as
 * r12(t) = r12 + t v12 and each ellipsoid rotates about its centre with
 * constant angular velocity w_i: Q_i(t) = R_i(t) Q_i R_i(t)^T,
 * R_i(t) = exp(t [w_i]x). Writes to *t the first time t_c in [0, t_max] at
 * which mu^2(t) <= 1 (0 when the pair overlaps or touches at t = 0), or
 * +INFINITY when there is none. Certified for the exact motion of the
 * double inputs, rotation included (R_i(t) and every product with Q_i(t)
 * in double-double from the inputs, mu^2 enclosed where a decision needs
 * it; docs/contact_time.md): *t is never later than the first t with
 * mu^2(t) < 1 - 2.3e-13; a contact at *t > 0 is reported only where
 * mu^2 <= 1 was certified, so never when mu^2 > 1 on (0, t_max];
 * trajectories whose minimum of mu^2 lies in [1 - 2.3e-13, 1] may go either
 * way. *t lies in a certified bracket of width 1e-10 t_max around a
 * crossing of mu^2 = 1: never earlier than the first crossing by more than
 * that, and within it of the first crossing, or of the one that starts the
 * first dip below 1 - 2.3e-13. A spin about an axis of symmetry (Q_i(t)
 * constant) costs no evaluations. Returns PW85_OK,
 * PW85_ERR_INVALID_ARGUMENT (NULL, NaN or infinite value, t_max <= 0, or
 * r12 + t v12 or t w_i overflowing within the horizon; *t is NaN),
 * PW85_ERR_NOT_SPD (q1 or q2 not positive definite; *t is NaN),
 * PW85_ERR_NO_CONVERGENCE (PW85_CONTACT_TIME_MAX_EVAL evaluations spent, an
 * evaluation failed, or no certified step can advance t; pairs at |r12| >=
 * 2^997 times the largest semi-axis: NO_CONVERGENCE with *t = 0; *t is
 * the time up to which mu^2 >= 1 - 2.3e-13 is certified on [0, *t]) or
 * PW85_ERR_INACCURATE (outside the certified domain, decided from the
 * inputs alone before any evaluation, the same on every CPU: a bound of
 * the semi-axis ratio above 1e7 in either ellipsoid, rotating or not, or
 * t_max |w_i| > 2^50; *t = 0). Limit of the certificate:
 * a contact shorter than the spacing of doubles around t_c (ulp(t_c)) can
 * be stepped over, giving +INFINITY with PW85_OK (unit spheres head-on at
 * unit speed from |r12| ~ 2^57; docs/contact_time.md, "Limits"). */
PW85_API int pw85_contact_time(double const r12[PW85_DIM], double const v12[PW85_DIM],
                               double const q1[PW85_SYM], double const w1[PW85_DIM],
                               double const q2[PW85_SYM], double const w2[PW85_DIM],
                               double t_max, double *t);

/* pw85_contact_time() that also writes to *evaluations (may be NULL) the
 * number of contact-function evaluations it took. Returns as
 * pw85_contact_time(). */
PW85_API int pw85_contact_time_ex(double const r12[PW85_DIM], double const v12[PW85_DIM],
                                  double const q1[PW85_SYM], double const w1[PW85_DIM],
                                  double const q2[PW85_SYM], double const w2[PW85_DIM],
                                  double t_max, double *t, int *evaluations);

/* t[k] = pw85_contact_time() of pair k of per-pair arrays (conventions of
 * pw85_contact_pairs; v12, w1, w2 as r12: 3 doubles per pair), one horizon
 * t_max for all pairs. Also PW85_ERR_INVALID_ARGUMENT with nothing written
 * when t_max is not finite and > 0. */
PW85_API int pw85_contact_time_pairs(long long m, double const *r12, double const *v12,
                                     double const *q1, double const *w1, double const *q2,
                                     double const *w2, double t_max, double *t, int *status,
                                     int nthreads);

PW85_END_DECLS

#endif /* PW85_H */
