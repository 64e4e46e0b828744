#include "refdata.h"

#include <hdf5_hl.h>
#include <math.h>
#include <string.h>

#include "testutil.h"

/* HDF5 prints a stack trace on every failing call unless told otherwise.
 * These two bracket the calls whose failure is an expected outcome. */
typedef struct {
  H5E_auto2_t func;
  void *data;
} ErrorPrinter;

static ErrorPrinter errors_off(void) {
  ErrorPrinter saved = {NULL, NULL};
  H5Eget_auto2(H5E_DEFAULT, &saved.func, &saved.data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  return saved;
}

static void errors_restore(ErrorPrinter saved) {
  H5Eset_auto2(H5E_DEFAULT, saved.func, saved.data);
}

hid_t refdata_open(char **why) {
  const char *path = ref_data_path();
  if (!g_file_test(path, G_FILE_TEST_EXISTS)) {
    if (why != NULL) *why = g_strdup_printf("reference data file %s not found", path);
    return -1;
  }
  ErrorPrinter saved = errors_off();
  hid_t const file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  errors_restore(saved);
  if (file < 0 && why != NULL)
    *why = g_strdup_printf("%s exists but H5Fopen failed (not an HDF5 file?)", path);
  return file;
}

gboolean refdata_open_or_skip(hid_t *file) {
  char *why = NULL;
  *file = refdata_open(&why);
  if (*file >= 0) return TRUE;
  if (!g_file_test(ref_data_path(), G_FILE_TEST_EXISTS)) {
    char *msg = g_strdup_printf("%s (set PW85_REF_DATA to its path)", why);
    g_test_skip(msg);
    g_free(msg);
  } else {
    /* A file that is there but unreadable is an error, not a skip. */
    g_test_message("%s", why);
    g_test_fail();
  }
  g_free(why);
  return FALSE;
}

void refdata_close(hid_t file) {
  if (file >= 0) H5Fclose(file);
}

/* Number of elements of dataset `name` if it has rank `rank`, else 0. */
static hsize_t dataset_size(hid_t file, const char *name, int rank, hsize_t *dims) {
  int ndims = -1;
  if (H5LTget_dataset_ndims(file, name, &ndims) < 0) {
    g_test_message("refdata: cannot read the rank of %s", name);
    return 0;
  }
  if (ndims != rank || rank < 1 || rank > 4) {
    g_test_message("refdata: %s has rank %d, expected %d", name, ndims, rank);
    return 0;
  }
  hsize_t d[4];
  if (H5LTget_dataset_info(file, name, d, NULL, NULL) < 0) {
    g_test_message("refdata: cannot read the dimensions of %s", name);
    return 0;
  }
  hsize_t n = 1;
  for (int i = 0; i < rank; i++) {
    n *= d[i];
    if (dims != NULL) dims[i] = d[i];
  }
  return n;
}

/* The whole dataset as a new array of n elements of the given memory type
 * (converted by HDF5), or NULL with a message. */
static void *read_as(hid_t file, const char *name, int rank, hsize_t *dims, hid_t type,
                     size_t size) {
  hsize_t const n = dataset_size(file, name, rank, dims);
  if (n == 0) return NULL;
  void *buf = g_malloc_n(n, size);
  if (H5LTread_dataset(file, name, type, buf) < 0) {
    g_test_message("refdata: cannot read %s", name);
    g_free(buf);
    return NULL;
  }
  return buf;
}

double *refdata_read_double(hid_t file, const char *name, int rank, hsize_t *dims) {
  return read_as(file, name, rank, dims, H5T_NATIVE_DOUBLE, sizeof(double));
}

int *refdata_read_int(hid_t file, const char *name, int rank, hsize_t *dims) {
  return read_as(file, name, rank, dims, H5T_NATIVE_INT, sizeof(int));
}

/* Every element of a dataset of rank 1..4. */
static void *read_all_as(hid_t file, const char *name, gsize *count, hid_t type,
                         size_t size) {
  int ndims = -1;
  *count = 0;
  if (H5LTget_dataset_ndims(file, name, &ndims) < 0) {
    g_test_message("refdata: cannot read the rank of %s", name);
    return NULL;
  }
  hsize_t dims[4];
  void *buf = read_as(file, name, ndims, dims, type, size);
  if (buf != NULL) {
    gsize n = 1;
    for (int i = 0; i < ndims; i++) n *= dims[i];
    *count = n;
  }
  return buf;
}

double *refdata_read_double_all(hid_t file, const char *name, gsize *count) {
  return read_all_as(file, name, count, H5T_NATIVE_DOUBLE, sizeof(double));
}

int *refdata_read_int_all(hid_t file, const char *name, gsize *count) {
  return read_all_as(file, name, count, H5T_NATIVE_INT, sizeof(int));
}

/* TRUE if group/name exists (the group itself may be missing: expected
 * failure, printing silenced). */
static gboolean has_dataset(hid_t file, const char *path) {
  ErrorPrinter saved = errors_off();
  htri_t const found = H5Lexists(file, path, H5P_DEFAULT);
  errors_restore(saved);
  return found > 0;
}

/* Reads group/name, a rank-`rank` array whose first dimension must be n and
 * second (if rank 2) must be cols. */
static void *read_member(hid_t file, const char *group, const char *name, gboolean is_int,
                         hsize_t *n, int cols, gboolean *ok) {
  char *path = g_strdup_printf("%s/%s", group, name);
  int const rank = cols > 0 ? 2 : 1;
  hsize_t dims[2] = {0, 0};
  void *buf = is_int ? (void *)refdata_read_int(file, path, rank, dims)
                     : (void *)refdata_read_double(file, path, rank, dims);
  if (buf != NULL) {
    if (*n == 0) *n = dims[0];
    if (dims[0] != *n || (cols > 0 && dims[1] != (hsize_t)cols)) {
      g_test_message("refdata: %s has shape (%llu, %llu), expected (%llu, %d)", path,
                     (unsigned long long)dims[0], (unsigned long long)dims[1],
                     (unsigned long long)*n, cols);
      g_free(buf);
      buf = NULL;
    }
  }
  if (buf == NULL) *ok = FALSE;
  g_free(path);
  return buf;
}

RefPairs *refdata_pairs_read(hid_t file, const char *group) {
  RefPairs *p = g_new0(RefPairs, 1);
  gboolean ok = TRUE;
  p->group = g_strdup(group);
  p->mu2 = read_member(file, group, "mu2", FALSE, &p->n, 0, &ok);
  p->r12 = read_member(file, group, "r12", FALSE, &p->n, 3, &ok);
  p->q1 = read_member(file, group, "q1", FALSE, &p->n, 6, &ok);
  p->q2 = read_member(file, group, "q2", FALSE, &p->n, 6, &ok);
  p->lambda = read_member(file, group, "lambda", FALSE, &p->n, 0, &ok);
  p->cls = read_member(file, group, "class", TRUE, &p->n, 0, &ok);
  static const char *const optional[] = {"kind",        "mu2_target", "eps_target",
                                          "side_target", "radii1",     "radii2"};
  static const int columns[] = {0, 0, 0, 0, 3, 3};
  void **dest[] = {(void **)&p->kind,        (void **)&p->mu2_target, (void **)&p->eps_target,
                   (void **)&p->side_target, (void **)&p->radii1,     (void **)&p->radii2};
  for (size_t i = 0; i < G_N_ELEMENTS(optional); i++) {
    char *path = g_strdup_printf("%s/%s", group, optional[i]);
    if (has_dataset(file, path)) {
      gboolean const is_int = optional[i][0] == 'k' || optional[i][0] == 's';
      *dest[i] = read_member(file, group, optional[i], is_int, &p->n, columns[i], &ok);
    }
    g_free(path);
  }
  if (!ok || p->n == 0) {
    refdata_pairs_free(p);
    return NULL;
  }
  return p;
}

void refdata_pairs_free(RefPairs *p) {
  if (p == NULL) return;
  g_free(p->group);
  g_free(p->r12);
  g_free(p->q1);
  g_free(p->q2);
  g_free(p->mu2);
  g_free(p->lambda);
  g_free(p->cls);
  g_free(p->kind);
  g_free(p->mu2_target);
  g_free(p->eps_target);
  g_free(p->side_target);
  g_free(p->radii1);
  g_free(p->radii2);
  g_free(p);
}

RefPairs *refdata_pairs_or_skip(const char *group) {
  hid_t file;
  if (!refdata_open_or_skip(&file)) return NULL;
  RefPairs *p = refdata_pairs_read(file, group);
  refdata_close(file);
  g_assert_nonnull(p);
  return p;
}

double refdata_pair_aspect(const RefPairs *p, gsize i) {
  g_assert_nonnull(p->radii1);
  g_assert_nonnull(p->radii2);
  double lo = INFINITY, hi = 0.0;
  for (int k = 0; k < 3; k++) {
    lo = fmin(lo, fmin(p->radii1[3 * i + k], p->radii2[3 * i + k]));
    hi = fmax(hi, fmax(p->radii1[3 * i + k], p->radii2[3 * i + k]));
  }
  return hi / lo;
}

char *refdata_read_string_attribute(hid_t file, const char *obj, const char *attr) {
  char *result = NULL;
  hid_t const a = H5Aopen_by_name(file, obj, attr, H5P_DEFAULT, H5P_DEFAULT);
  if (a < 0) return NULL;
  hid_t const ftype = H5Aget_type(a);
  hid_t const space = H5Aget_space(a);
  hid_t mtype = -1;
  if (ftype < 0 || space < 0 || H5Tget_class(ftype) != H5T_STRING ||
      H5Sget_simple_extent_npoints(space) != 1)
    goto done;
  mtype = H5Tcopy(H5T_C_S1);
  /* h5py writes str attributes as variable-length UTF-8; HDF5 does not
   * convert between character sets, so read with the stored one. */
  if (mtype < 0 || H5Tset_cset(mtype, H5Tget_cset(ftype)) < 0) goto done;
  htri_t const vlen = H5Tis_variable_str(ftype);
  if (vlen > 0) {
    char *s = NULL;
    if (H5Tset_size(mtype, H5T_VARIABLE) >= 0 && H5Aread(a, mtype, &s) >= 0 && s != NULL) {
      result = g_strdup(s);
      H5free_memory(s);
    }
  } else if (vlen == 0) {
    size_t const size = H5Tget_size(ftype);
    char *s = g_malloc0(size + 1);
    if (size > 0 && H5Tset_size(mtype, size + 1) >= 0 &&
        H5Tset_strpad(mtype, H5T_STR_NULLTERM) >= 0 && H5Aread(a, mtype, s) >= 0)
      result = s;
    else
      g_free(s);
  }
done:
  if (mtype >= 0) H5Tclose(mtype);
  if (space >= 0) H5Sclose(space);
  if (ftype >= 0) H5Tclose(ftype);
  H5Aclose(a);
  return result;
}
