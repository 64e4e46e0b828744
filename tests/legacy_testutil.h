/* Helpers of the libpw85_legacy tests: reference data access, independent
 * __float128 evaluations (never the library's own code), error histograms. */
#ifndef PW85_LEGACY_TESTUTIL_H
#define PW85_LEGACY_TESTUTIL_H

#include <glib.h>
#include <hdf5.h>

/* Path of the reference data: $PW85_REF_DATA if set, else PW85_REF_DATA_PATH. */
const char *legacy_ref_data_path(void);

/* Opens the reference data read-only; returns a negative id (after
 * g_test_skip) when the file is absent. */
hid_t legacy_open_ref_data(void);

/* Reads a whole float64 (or int32) dataset; *count receives the number of
 * elements. g_free the result. Fails the test if the dataset is missing. */
double *legacy_read_double(hid_t file, const char *name, gsize *count);
int *legacy_read_int(hid_t file, const char *name, gsize *count);

/* Symmetric 3x3 algebra in __float128 on pw85 storage (upper triangle). */
__float128 q_det_sym(const __float128 a[6]);
__float128 q_xT_adjA_x(const __float128 x[3], const __float128 a[6]);
/* (1 - lambda) q1 + lambda q2, exact in __float128 for double inputs and
 * lambda = k/10 rounded to double (the product of two doubles is exact). */
void q_interpolate(const double q1[6], const double q2[6], double lambda, __float128 q[6]);
/* f, f', f'' of section 4.1 (eqs. (4)-(9)), with Q^{-1} = adj(Q) / det(Q) in
 * __float128. */
void q_f_derivs(double lambda, const double r[3], const double q1[6], const double q2[6],
                double out[3]);

/* Number of correct digits floor(-log10(|act - exp| / |exp|)), clamped to
 * [0, num_bins - 1]; act == exp counts as num_bins - 1 (pw85's Fig. 4.1). */
int legacy_correct_digits(double act, double exp, int num_bins);

double legacy_rel_error(double act, double exp);

#endif
