#include "refgroup.h"

#include <glib.h>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <stdio.h>

#include "testutil.h"

int ref_group_load(const char *name, ref_group *g) {
  const char *path = ref_data_path();
  g->n = 0;
  g->r12 = g->q1 = g->q2 = g->mu2 = NULL;
  g->cls = NULL;
  if (!g_file_test(path, G_FILE_TEST_EXISTS)) {
    g_test_skip("reference data file absent");
    return 0;
  }
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  g_assert_cmpint(f, >=, 0);
  char ds[128];
  snprintf(ds, sizeof ds, "%s/mu2", name);
  if (H5LTfind_dataset(f, name + 1) <= 0 && H5Lexists(f, name, H5P_DEFAULT) <= 0) {
    H5Fclose(f);
    g_test_skip("reference group absent");
    return 0;
  }
  hsize_t dims[2] = {0, 0};
  g_assert_cmpint(H5LTget_dataset_info(f, ds, dims, NULL, NULL), >=, 0);
  g->n = (size_t)dims[0];
  g->r12 = g_new(double, 3 * g->n);
  g->q1 = g_new(double, 6 * g->n);
  g->q2 = g_new(double, 6 * g->n);
  g->mu2 = g_new(double, g->n);
  g->cls = g_new(int, g->n);
  snprintf(ds, sizeof ds, "%s/r12", name);
  g_assert_cmpint(H5LTread_dataset_double(f, ds, g->r12), >=, 0);
  snprintf(ds, sizeof ds, "%s/q1", name);
  g_assert_cmpint(H5LTread_dataset_double(f, ds, g->q1), >=, 0);
  snprintf(ds, sizeof ds, "%s/q2", name);
  g_assert_cmpint(H5LTread_dataset_double(f, ds, g->q2), >=, 0);
  snprintf(ds, sizeof ds, "%s/mu2", name);
  g_assert_cmpint(H5LTread_dataset_double(f, ds, g->mu2), >=, 0);
  snprintf(ds, sizeof ds, "%s/class", name);
  g_assert_cmpint(H5LTread_dataset_int(f, ds, g->cls), >=, 0);
  H5Fclose(f);
  return 1;
}

void ref_group_free(ref_group *g) {
  g_free(g->r12);
  g_free(g->q1);
  g_free(g->q2);
  g_free(g->mu2);
  g_free(g->cls);
  g->n = 0;
}
