/* Reading the reference data file data/pw85_ref_data.h5 (layout: data/README.md)
 * from the GLib test programs, with the HDF5 high-level API (H5LT). Every
 * test program that reads the file goes through these functions, so that
 * the path ($PW85_REF_DATA or the build-time path, ref_data_path() of
 * testutil.h) and the skip when the file is absent are the same everywhere.
 *
 * Typical use in a test function:
 *
 *     hid_t file;
 *     if (!refdata_open_or_skip(&file)) return;     // g_test_skip() was called
 *     RefPairs *p = refdata_pairs_read(file, "/contact");
 *     g_assert_nonnull(p);                          // file present: must read
 *     ... p->r12 + 3 * i, p->q1 + 6 * i, p->mu2[i], p->cls[i] ...
 *     refdata_pairs_free(p);
 *     refdata_close(file);
 *
 * Failures to read a file that exists are reported through g_test_message()
 * and a NULL / negative return, so that the caller can assert. */
#ifndef PW85_REFDATA_H
#define PW85_REFDATA_H

#include <glib.h>
#include <hdf5.h>

/* Opens ref_data_path() read-only (HDF5's automatic error printing is
 * silenced around the open, which is expected to fail when the file is
 * absent). Returns the file id, or a negative value and sets *why (a newly
 * allocated message, when why is not NULL) on failure. */
hid_t refdata_open(char **why);

/* refdata_open(); on failure calls g_test_skip() with the path and the reason
 * and returns FALSE. */
gboolean refdata_open_or_skip(hid_t *file);

/* Closes a file opened by refdata_open() (ignores negative ids). */
void refdata_close(hid_t file);

/* Reads the whole dataset `name` (e.g. "/F", "/contact/q1") as doubles / int.
 * The dataset must have rank `rank` (1..4); its dimensions are written to
 * dims[0..rank-1] (dims may be NULL). Returns a g_malloc'ed array to release
 * with g_free(), or NULL on any error (missing dataset, wrong rank, HDF5
 * failure). */
double *refdata_read_double(hid_t file, const char *name, int rank, hsize_t *dims);
int *refdata_read_int(hid_t file, const char *name, int rank, hsize_t *dims);

/* The same for a dataset of any rank (1..4); *count receives the number of
 * elements. NULL on error. */
double *refdata_read_double_all(hid_t file, const char *name, gsize *count);
int *refdata_read_int_all(hid_t file, const char *name, gsize *count);

/* Rows of one of the groups /contact, /near_contact, /special. Optional
 * datasets that the group does not have are NULL. */
typedef struct {
  char *group;         /* e.g. "/contact" */
  hsize_t n;           /* number of rows */
  double *r12;         /* n x 3, c2 - c1 */
  double *q1, *q2;     /* n x 6, upper triangles */
  double *mu2;         /* n, correctly rounded mu^2 */
  double *lambda;      /* n, maximiser (NaN when r12 = 0) */
  int *cls;            /* n, size class 0..3 or -1 */
  int *kind;           /* n, /special only (codes: attribute `kinds`) */
  double *mu2_target;  /* n, /special only */
  double *eps_target;  /* n, /near_contact only */
  int *side_target;    /* n, /near_contact only (-1: mu^2 < 1, +1: > 1) */
  double *radii1;      /* n x 3, semi-axes of ellipsoid 1 (when stored) */
  double *radii2;      /* n x 3, semi-axes of ellipsoid 2 (when stored) */
} RefPairs;

/* Reads the mandatory datasets r12, q1, q2, mu2, lambda, class of `group`
 * (checking that they have consistent shapes) and the optional ones. Returns
 * NULL on error. */
RefPairs *refdata_pairs_read(hid_t file, const char *group);
void refdata_pairs_free(RefPairs *p);

/* Opens the file, reads `group` and closes the file. Returns NULL after
 * g_test_skip() when the file is absent (refdata_open_or_skip); a file that
 * is present but cannot be read fails the test. */
RefPairs *refdata_pairs_or_skip(const char *group);

/* Largest over smallest of the six semi-axes of row i (radii1, radii2 must
 * be stored). */
double refdata_pair_aspect(const RefPairs *p, gsize i);

/* Reads the string attribute `attr` of the object `obj` (fixed-length or
 * variable-length string). Returns a newly allocated, NUL-terminated string
 * or NULL on error. */
char *refdata_read_string_attribute(hid_t file, const char *obj, const char *attr);

#endif
