#include "legacy_testutil.h"

#include <hdf5_hl.h>
#include <math.h>
#include <stdlib.h>

const char *legacy_ref_data_path(void) {
  const char *env = g_getenv("PW85_REF_DATA");
  return (env != NULL && env[0] != '\0') ? env : PW85_REF_DATA_PATH;
}

hid_t legacy_open_ref_data(void) {
  const char *path = legacy_ref_data_path();
  if (!g_file_test(path, G_FILE_TEST_EXISTS)) {
    gchar *msg = g_strdup_printf("reference data %s absent", path);
    g_test_skip(msg);
    g_free(msg);
    return -1;
  }
  hid_t const file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  g_assert_cmpint(file, >=, 0);
  return file;
}

static gsize dataset_size(hid_t file, const char *name) {
  int ndims = 0;
  g_assert_cmpint(H5LTget_dataset_ndims(file, name, &ndims), >=, 0);
  hsize_t dims[8] = {0};
  g_assert_cmpint(ndims, <=, 8);
  g_assert_cmpint(H5LTget_dataset_info(file, name, dims, NULL, NULL), >=, 0);
  gsize n = 1;
  for (int i = 0; i < ndims; ++i) n *= dims[i];
  return n;
}

double *legacy_read_double(hid_t file, const char *name, gsize *count) {
  gsize const n = dataset_size(file, name);
  double *buf = g_new(double, n);
  g_assert_cmpint(H5LTread_dataset_double(file, name, buf), >=, 0);
  *count = n;
  return buf;
}

int *legacy_read_int(hid_t file, const char *name, gsize *count) {
  gsize const n = dataset_size(file, name);
  int *buf = g_new(int, n);
  g_assert_cmpint(H5LTread_dataset_int(file, name, buf), >=, 0);
  *count = n;
  return buf;
}

/* Cofactor expansion of the full symmetric matrix, written out independently
 * of the library (by minors of the first column). */
__float128 q_det_sym(const __float128 a[6]) {
  __float128 const m00 = a[0], m01 = a[1], m02 = a[2];
  __float128 const m11 = a[3], m12 = a[4], m22 = a[5];
  return m00 * (m11 * m22 - m12 * m12) - m01 * (m01 * m22 - m02 * m12) +
         m02 * (m01 * m12 - m02 * m11);
}

__float128 q_xT_adjA_x(const __float128 x[3], const __float128 a[6]) {
  /* Full matrix and its 9 cofactors C_ij = (-1)^(i+j) M_ij; adj = C^T. */
  __float128 m[3][3] = {{a[0], a[1], a[2]}, {a[1], a[3], a[4]}, {a[2], a[4], a[5]}};
  __float128 s = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      int const r0 = (j + 1) % 3, r1 = (j + 2) % 3; /* rows of the minor of adj_ij = C_ji */
      int const c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      /* cyclic indices give the sign (-1)^(i+j) for free */
      __float128 const cof = m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
      s += x[i] * cof * x[j];
    }
  }
  return s;
}

void q_interpolate(const double q1[6], const double q2[6], double lambda, __float128 q[6]) {
  __float128 const l = lambda, one_minus = 1 - l;
  for (int i = 0; i < 6; ++i) q[i] = one_minus * q1[i] + l * q2[i];
}

static void q_solve(const __float128 q[6], __float128 det, const __float128 b[3],
                    __float128 x[3]) {
  __float128 const c00 = q[3] * q[5] - q[4] * q[4];
  __float128 const c01 = q[2] * q[4] - q[1] * q[5];
  __float128 const c02 = q[1] * q[4] - q[2] * q[3];
  __float128 const c11 = q[0] * q[5] - q[2] * q[2];
  __float128 const c12 = q[1] * q[2] - q[0] * q[4];
  __float128 const c22 = q[0] * q[3] - q[1] * q[1];
  x[0] = (c00 * b[0] + c01 * b[1] + c02 * b[2]) / det;
  x[1] = (c01 * b[0] + c11 * b[1] + c12 * b[2]) / det;
  x[2] = (c02 * b[0] + c12 * b[1] + c22 * b[2]) / det;
}

void q_f_derivs(double lambda, const double r[3], const double q1[6], const double q2[6],
                double out[3]) {
  __float128 q[6], d[6];
  q_interpolate(q1, q2, lambda, q);
  for (int i = 0; i < 6; ++i) d[i] = (__float128)q2[i] - q1[i];
  __float128 const det = q_det_sym(q);
  __float128 const rr[3] = {r[0], r[1], r[2]};
  __float128 s[3], u[3], v[3];
  q_solve(q, det, rr, s);
  u[0] = d[0] * s[0] + d[1] * s[1] + d[2] * s[2];
  u[1] = d[1] * s[0] + d[3] * s[1] + d[4] * s[2];
  u[2] = d[2] * s[0] + d[4] * s[1] + d[5] * s[2];
  q_solve(q, det, u, v);
  __float128 const rs = rr[0] * s[0] + rr[1] * s[1] + rr[2] * s[2];
  __float128 const su = s[0] * u[0] + s[1] * u[1] + s[2] * u[2];
  __float128 const uv = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  __float128 const l = lambda, w = l * (1 - l);
  out[0] = (double)(w * rs);
  out[1] = (double)((1 - 2 * l) * rs - w * su);
  out[2] = (double)(-2 * rs - 2 * (1 - 2 * l) * su + 2 * w * uv);
}

int legacy_correct_digits(double act, double exp, int num_bins) {
  if (act == exp) return num_bins - 1;
  double const err = fabs((act - exp) / exp);
  if (!(err < 1.0)) return 0; /* also NaN */
  int d = (int)floor(-log10(err));
  if (d < 0) d = 0;
  if (d > num_bins - 1) d = num_bins - 1;
  return d;
}

double legacy_rel_error(double act, double exp) {
  if (act == exp) return 0.0;
  return exp != 0.0 ? fabs((act - exp) / exp) : fabs(act);
}
