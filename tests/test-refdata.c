/* The integrity of the reference data file data/pw85_ref_data.h5
 * (data/README.md): the SHA-256 of every dataset, recomputed here with GLib,
 * against the one stored in its attribute. The comparisons of the library
 * with the file are in the programs of the functions they test
 * (test-contact-function.c, test-f-neg-residual.c, ...). The test skips
 * (g_test_skip) when the file is absent; $PW85_REF_DATA overrides the
 * build-time path. */
#include <string.h>

#include <hdf5.h>

#include "refdata.h"
#include "testutil.h"

/* ---- integrity: SHA-256 of every dataset ------------------------------- */

static herr_t collect_dataset(hid_t obj, const char *name, const H5O_info_t *info,
                              void *data) {
  (void)obj;
  if (info->type == H5O_TYPE_DATASET) g_ptr_array_add(data, g_strdup(name));
  return 0;
}

/* SHA-256 of the raw bytes of a dataset: little-endian C order for numbers
 * (the byte order of the file and of this machine's native types on x86 and
 * ARM), the stored bytes for fixed-length strings. NULL on error. */
static char *dataset_sha256(hid_t file, const char *name) {
  char *digest = NULL;
  hid_t const dset = H5Dopen2(file, name, H5P_DEFAULT);
  if (dset < 0) return NULL;
  hid_t const ftype = H5Dget_type(dset);
  hid_t const space = H5Dget_space(dset);
  hid_t mtype = -1;
  if (ftype < 0 || space < 0) goto done;
  H5T_class_t const cls = H5Tget_class(ftype);
  if (cls == H5T_FLOAT || cls == H5T_INTEGER) {
    mtype = H5Tget_native_type(ftype, H5T_DIR_ASCEND);
    if (mtype >= 0 && H5Tget_order(mtype) != H5T_ORDER_LE &&
        H5Tset_order(mtype, H5T_ORDER_LE) < 0)
      goto done;
  } else if (cls == H5T_STRING && H5Tis_variable_str(ftype) == 0) {
    mtype = H5Tcopy(ftype);
  } else {
    g_test_message("%s: unsupported datatype class %d", name, (int)cls);
    goto done;
  }
  if (mtype < 0) goto done;
  hssize_t const npoints = H5Sget_simple_extent_npoints(space);
  size_t const size = H5Tget_size(mtype);
  if (npoints < 0 || size == 0) goto done;
  gsize const nbytes = (gsize)npoints * size;
  guchar *buf = g_malloc(nbytes > 0 ? nbytes : 1);
  if (H5Dread(dset, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0)
    digest = g_compute_checksum_for_data(G_CHECKSUM_SHA256, buf, nbytes);
  g_free(buf);
done:
  if (mtype >= 0) H5Tclose(mtype);
  if (space >= 0) H5Sclose(space);
  if (ftype >= 0) H5Tclose(ftype);
  H5Dclose(dset);
  return digest;
}

static void test_checksums(void) {
  hid_t file;
  if (!refdata_open_or_skip(&file)) return;
  GPtrArray *names = g_ptr_array_new_with_free_func(g_free);
#if H5_VERSION_GE(1, 12, 0)
  herr_t const st =
      H5Ovisit(file, H5_INDEX_NAME, H5_ITER_INC, collect_dataset, names, H5O_INFO_BASIC);
#else
  herr_t const st = H5Ovisit(file, H5_INDEX_NAME, H5_ITER_INC, collect_dataset, names);
#endif
  g_assert_cmpint(st, >=, 0);
  /* The 5 datasets of the pw85 layout and at least 6 per contact group. */
  g_assert_cmpuint(names->len, >=, 5 + 3 * 6);
  guint bad = 0;
  for (guint i = 0; i < names->len; i++) {
    const char *name = g_ptr_array_index(names, i);
    char *expected = refdata_read_string_attribute(file, name, "sha256");
    char *actual = dataset_sha256(file, name);
    char *description = refdata_read_string_attribute(file, name, "description");
    if (expected == NULL || actual == NULL || strcmp(expected, actual) != 0 ||
        description == NULL || description[0] == '\0') {
      g_test_message("%s: sha256 attribute %s, computed %s%s", name,
                     expected ? expected : "(unreadable)", actual ? actual : "(unreadable)",
                     description ? "" : ", no description attribute");
      bad++;
    }
    g_free(expected);
    g_free(actual);
    g_free(description);
  }
  g_test_message("sha256 of %u datasets checked, %u mismatches", names->len, bad);
  g_assert_cmpuint(bad, ==, 0);
  g_ptr_array_free(names, TRUE);
  refdata_close(file);
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/refdata/checksums", test_checksums);
  return g_test_run();
}
