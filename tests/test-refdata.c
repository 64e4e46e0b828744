/* pw85_f_neg and pw85_contact_function against the high-precision reference
 * data data/pw85_ref_data.h5 (data/README.md; issue 3), and the integrity of
 * that file (SHA-256 of every dataset, recomputed here with GLib).
 *
 * The reference values are exact (rational arithmetic on the stored doubles,
 * correctly rounded), so the relative errors measured here are the errors of
 * the library alone. Every test skips (g_test_skip) when the file is absent;
 * $PW85_REF_DATA overrides the build-time path. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hdf5.h>
#include <hdf5_hl.h>
#include <pw85.h>

#include "refdata.h"
#include "testutil.h"

/* ---- /F: pw85_f_neg --------------------------------------------------- */

/* Histogram of correct digits (pw85 documentation, section 4.3): bin
 * floor(-log10(relative error)) clamped to [0, 15]; exact results go to the
 * last bin. */
#define NUM_BINS 16

static int digits_bin(double err) {
  if (err == 0.0) return NUM_BINS - 1;
  double const d = floor(-log10(err));
  if (!(d > 0.0)) return 0; /* also NaN */
  if (d >= NUM_BINS - 1) return NUM_BINS - 1;
  return (int)d;
}

static void test_f_neg_reference(void) {
  hid_t file;
  if (!refdata_open_or_skip(&file)) return;
  hsize_t ds[2], dd[2], dl[1], df[4];
  double *spheroids = refdata_read_double(file, "/spheroids", 2, ds);
  double *directions = refdata_read_double(file, "/directions", 2, dd);
  double *lambdas = refdata_read_double(file, "/lambdas", 1, dl);
  double *F = refdata_read_double(file, "/F", 4, df);
  refdata_close(file);
  g_assert_nonnull(spheroids);
  g_assert_nonnull(directions);
  g_assert_nonnull(lambdas);
  g_assert_nonnull(F);
  g_assert_cmpuint(ds[1], ==, PW85_SYM);
  g_assert_cmpuint(dd[1], ==, PW85_DIM);
  g_assert_cmpuint(df[0], ==, ds[0]);
  g_assert_cmpuint(df[1], ==, ds[0]);
  g_assert_cmpuint(df[2], ==, dd[0]);
  g_assert_cmpuint(df[3], ==, dl[0]);
  g_assert_cmpuint(df[0] * df[1] * df[2] * df[3], ==, 108 * 108 * 12 * 11);

  guint64 hist[NUM_BINS] = {0};
  guint64 n = 0, zeros = 0, above = 0;
  double max_err = 0.0;
  gsize worst = 0;
  double params[PW85_DIM + 2 * PW85_SYM];
  const double *exp = F;
  for (hsize_t i1 = 0; i1 < df[0]; i1++) {
    memcpy(params + PW85_DIM, spheroids + PW85_SYM * i1, sizeof(double) * PW85_SYM);
    for (hsize_t i2 = 0; i2 < df[1]; i2++) {
      memcpy(params + PW85_DIM + PW85_SYM, spheroids + PW85_SYM * i2,
             sizeof(double) * PW85_SYM);
      for (hsize_t k = 0; k < df[2]; k++) {
        memcpy(params, directions + PW85_DIM * k, sizeof(double) * PW85_DIM);
        for (hsize_t j = 0; j < df[3]; j++, exp++, n++) {
          double const act = -pw85_f_neg(lambdas[j], params);
          double err;
          if (*exp == 0.0) {
            /* lambda = 0 or 1: f vanishes identically, exactly. */
            zeros++;
            err = act == 0.0 ? 0.0 : INFINITY;
          } else {
            err = isnan(act) ? INFINITY : rel_error(act, *exp);
          }
          if (err > max_err) max_err = err, worst = (gsize)(exp - F);
          if (err > 1e-10) above++;
          hist[digits_bin(err)]++;
        }
      }
    }
  }
  g_assert_cmpuint(n, ==, 108 * 108 * 12 * 11);

  /* The histogram, as a message and as CSV next to the test program. */
  GString *line = g_string_new("");
  GString *csv = g_string_new("digits,count,percent\n");
  for (int b = 0; b < NUM_BINS; b++) {
    double const pc = 100.0 * (double)hist[b] / (double)n;
    g_string_append_printf(line, " %d:%.2f%%", b, pc);
    g_string_append_printf(csv, "%d,%" G_GUINT64_FORMAT ",%.4f\n", b, hist[b], pc);
  }
  gsize const per_entry = df[3], per_dir = df[2] * per_entry, per_i2 = df[1] * per_dir;
  g_test_message("/F: %" G_GUINT64_FORMAT " entries (%" G_GUINT64_FORMAT
                 " exact zeros), max rel. error %.3g at [%zu,%zu,%zu,%zu], %" G_GUINT64_FORMAT
                 " above 1e-10",
                 n, zeros, max_err, worst / per_i2, (worst % per_i2) / per_dir,
                 (worst % per_dir) / per_entry, worst % per_entry, above);
  g_test_message("/F: correct digits (bin: percent of entries; bin 15 includes exact):%s",
                 line->str);
  char *csv_path = g_test_build_filename(G_TEST_BUILT, "refdata-f-neg-histogram.csv", NULL);
  GError *error = NULL;
  if (g_file_set_contents(csv_path, csv->str, -1, &error))
    g_test_message("/F: histogram written to %s", csv_path);
  else {
    g_test_message("/F: could not write %s: %s", csv_path, error->message);
    g_clear_error(&error);
  }
  g_free(csv_path);
  g_string_free(line, TRUE);
  g_string_free(csv, TRUE);

  g_assert_cmpuint(above, ==, 0);
  g_assert_cmpfloat(max_err, <=, 1e-10);
  g_free(spheroids);
  g_free(directions);
  g_free(lambdas);
  g_free(F);
}

/* ---- /contact, /near_contact, /special: pw85_contact_function ---------- */

/* Statistics of the relative error of mu^2 over a set of rows. */
typedef struct {
  GArray *err;       /* relative errors of all rows */
  double max_all;    /* max over all rows */
  double max_ok;     /* max over the rows with PW85_OK */
  gsize n, n_ok, n_noconv, n_other;
  gsize above;       /* rows with error > 1e-10 */
  gsize above_ok;    /* ... of which returned PW85_OK */
  gsize wrong_side;  /* overlap verdict (mu^2 < 1) differs from the reference */
  gsize tangent;     /* reference mu^2 == 1.0 exactly (no verdict) */
  gsize worst;       /* row of the largest error */
} Stats;

static void stats_init(Stats *s) {
  memset(s, 0, sizeof(*s));
  s->err = g_array_new(FALSE, FALSE, sizeof(double));
}

static int cmp_double(const void *a, const void *b) {
  double const x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double stats_max(const Stats *s) { return s->max_all; }

static double stats_median(const Stats *s) {
  if (s->err->len == 0) return NAN;
  double *v = g_memdup2(s->err->data, sizeof(double) * s->err->len);
  qsort(v, s->err->len, sizeof(double), cmp_double);
  guint const m = s->err->len / 2;
  double const med = s->err->len % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
  g_free(v);
  return med;
}

/* Runs pw85_contact_function on row i of p and accumulates. At most
 * `max_listed` rows beyond 1e-10 with PW85_OK are listed by name. */
static void run_row(const RefPairs *p, gsize i, Stats *s, int max_listed) {
  double out[2] = {NAN, NAN};
  int const status = pw85_contact_function(p->r12 + 3 * i, p->q1 + 6 * i, p->q2 + 6 * i, out);
  double const ref = p->mu2[i];
  double err;
  if (ref == 0.0) {
    /* Coincident centres: mu^2 = 0 exactly. */
    g_assert_cmpint(status, ==, PW85_OK);
    g_assert_cmpfloat(out[0], ==, 0.0);
    err = 0.0;
  } else {
    err = isnan(out[0]) ? INFINITY : rel_error(out[0], ref);
  }
  s->n++;
  if (status == PW85_OK) {
    s->n_ok++;
    s->max_ok = fmax(s->max_ok, err);
  } else if (status == PW85_ERR_NO_CONVERGENCE) {
    s->n_noconv++;
  } else {
    s->n_other++;
    g_test_message("%s[%zu]: unexpected status %d (%s)", p->group, i, status,
                   pw85_strerror(status));
  }
  if (err > 1e-10) {
    s->above++;
    if (status == PW85_OK) {
      s->above_ok++;
      if ((int)s->above_ok <= max_listed)
        g_test_message("%s[%zu] (class %d): rel. error %.3g with PW85_OK (mu^2 = %.17g, "
                       "lambda* = %.17g; got %.17g, %.17g)",
                       p->group, i, p->cls[i], err, ref, p->lambda[i], out[0], out[1]);
    }
  }
  if (ref == 1.0)
    s->tangent++;
  else if (ref > 0.0 && (out[0] < 1.0) != (ref < 1.0))
    s->wrong_side++;
  if (s->err->len == 0 || err > s->max_all) s->worst = i, s->max_all = err;
  g_array_append_val(s->err, err);
}

static void stats_report(const char *what, const Stats *s) {
  g_test_message("%s: %zu rows, rel. error of mu^2: max %.3g (max with PW85_OK %.3g, row %zu), "
                 "median %.3g; %zu above 1e-10 (%zu of them with PW85_OK); "
                 "PW85_ERR_NO_CONVERGENCE: %zu; other statuses: %zu",
                 what, s->n, stats_max(s), s->max_ok, s->worst, stats_median(s), s->above,
                 s->above_ok, s->n_noconv, s->n_other);
}

static void stats_clear(Stats *s) { g_array_free(s->err, TRUE); }

static RefPairs *read_group_or_skip(const char *group) {
  hid_t file;
  if (!refdata_open_or_skip(&file)) return NULL;
  RefPairs *p = refdata_pairs_read(file, group);
  refdata_close(file);
  g_assert_nonnull(p);
  return p;
}

/* Bounds actually met by pw85_contact_function (pw85 1.0's algorithm:
 * Brent to PW85_LAMBDA_ATOL, then Newton on the residual), measured with
 * this file (docs/reference-data-tests.md) and rounded up to the next power
 * of ten; the counts are the measured ones rounded up. Index: size class.
 *   all: max rel. error of mu^2 over every row;
 *   ok: over the rows that returned PW85_OK;
 *   max_noconv: rows returning PW85_ERR_NO_CONVERGENCE;
 *   max_above_ok: rows returning PW85_OK with a rel. error > 1e-10 (each one
 *   is listed by g_test_message for classes 0..2). */
typedef struct {
  const char *name;
  double all, ok;
  gsize max_noconv, max_above_ok;
} Bound;

/* Measured (after the final evaluation of mu^2 in the stationary form with
 * compensated sums, src/core/brent.cpp): max 0, 0, 0, 2.6e-11 (all rows;
 * the reference is correctly rounded and the result usually is too);
 * PW85_ERR_NO_CONVERGENCE 0, 0, 0, 87; PW85_OK beyond 1e-10: 0 in every
 * class. Before that change (f in double through Cholesky, as pw85 1.0):
 * 7.6e-16, 1.1e-13, 3.9e-10, 4.4e-6. */
static const Bound contact_bounds[4] = {
    {"class 0", 1e-15, 1e-15, 0, 0},
    {"class 1", 1e-15, 1e-15, 0, 0},
    {"class 2", 1e-15, 1e-15, 0, 0},
    {"class 3", 1e-10, 1e-10, 100, 0},
};

/* Measured: max 0, 0, 0, 3.1e-13 (1.4e-13 with PW85_OK);
 * PW85_ERR_NO_CONVERGENCE 0, 0, 0, 33; PW85_OK beyond 1e-10: 0. */
static const Bound near_bounds[4] = {
    {"class 0", 1e-15, 1e-15, 0, 0},
    {"class 1", 1e-15, 1e-15, 0, 0},
    {"class 2", 1e-15, 1e-15, 0, 0},
    {"class 3", 1e-12, 1e-12, 40, 0},
};

/* /special, by kind (names from the attribute `kinds` of /special/kind).
 * Measured maxima in the comments (all rows; with PW85_OK). */
static const Bound special_bounds[] = {
    {"coincident_centres", 0.0, 0.0, 0, 0},          /* exactly 0 */
    {"identical_ellipsoids", 1e-13, 1e-13, 0, 0},     /* 2.8e-14 */
    {"equal_spheres", 1e-15, 1e-15, 0, 0},            /* 0 */
    {"very_different_spheres", 1e-5, 0.0, 30, 0},     /* 4.8e-6, all 30 no conv. */
    {"needle_crossing_disc", 1e-5, 1e-12, 16, 0},     /* 3.0e-6; 0 with OK */
    {"parallel_needles", 1e-9, 1e-9, 0, 5},           /* 2.9e-10 */
    {"nearly_parallel_needles", 1e-9, 1e-9, 1, 5},    /* 9.3e-10 */
    {"high_aspect_spheroids", 1e-5, 1e-9, 29, 3},     /* 2.9e-6; 6.1e-10 with OK */
    {"high_aspect_ellipsoids", 1e-15, 1e-15, 0, 0},   /* 0 */
};

static void check_bounds(const Stats *s, const Bound *b) {
  g_test_message("asserted (%s): max rel. error <= %g (with PW85_OK <= %g), "
                 "PW85_ERR_NO_CONVERGENCE <= %zu, PW85_OK beyond 1e-10 <= %zu",
                 b->name, b->all, b->ok, b->max_noconv, b->max_above_ok);
  g_assert_cmpuint(s->n_other, ==, 0);
  g_assert_cmpfloat(stats_max(s), <=, b->all);
  g_assert_cmpfloat(s->max_ok, <=, b->ok);
  g_assert_cmpuint(s->n_noconv, <=, b->max_noconv);
  g_assert_cmpuint(s->above_ok, <=, b->max_above_ok);
}

static void test_contact_class(gconstpointer data) {
  int const cls = GPOINTER_TO_INT(data);
  RefPairs *p = read_group_or_skip("/contact");
  if (p == NULL) return;
  Stats s;
  stats_init(&s);
  for (gsize i = 0; i < p->n; i++)
    if (p->cls[i] == cls) run_row(p, i, &s, cls < 3 ? G_MAXINT : 10);
  g_assert_cmpuint(s.n, >, 0);
  char *what = g_strdup_printf("/contact class %d", cls);
  stats_report(what, &s);
  g_free(what);
  check_bounds(&s, &contact_bounds[cls]);
  stats_clear(&s);
  refdata_pairs_free(p);
}

static void test_near_contact_class(gconstpointer data) {
  int const cls = GPOINTER_TO_INT(data);
  RefPairs *p = read_group_or_skip("/near_contact");
  if (p == NULL) return;
  Stats s;
  stats_init(&s);
  for (gsize i = 0; i < p->n; i++)
    if (p->cls[i] == cls) run_row(p, i, &s, cls < 3 ? G_MAXINT : 5);
  g_assert_cmpuint(s.n, >, 0);
  char *what = g_strdup_printf("/near_contact class %d", cls);
  stats_report(what, &s);
  g_test_message("%s: overlap verdict (mu^2 < 1) on the wrong side of 1: %zu of %zu "
                 "(%zu rows with reference mu^2 == 1.0 exactly, not counted)",
                 what, s.wrong_side, s.n, s.tangent);
  g_free(what);
  check_bounds(&s, &near_bounds[cls]);
  stats_clear(&s);
  refdata_pairs_free(p);
}

static void test_special(void) {
  hid_t file;
  if (!refdata_open_or_skip(&file)) return;
  RefPairs *p = refdata_pairs_read(file, "/special");
  char *kinds = refdata_read_string_attribute(file, "/special/kind", "kinds");
  refdata_close(file);
  g_assert_nonnull(p);
  g_assert_nonnull(p->kind);
  g_assert_nonnull(kinds);
  char **names = g_strsplit(kinds, ",", -1);
  guint const num_kinds = g_strv_length(names);
  g_assert_cmpuint(num_kinds, >, 0);
  Stats all;
  stats_init(&all);
  gsize coincident = 0;
  for (guint k = 0; k < num_kinds; k++) {
    Stats s;
    stats_init(&s);
    for (gsize i = 0; i < p->n; i++) {
      if (p->kind[i] != (int)k) continue;
      run_row(p, i, &s, 3);
      run_row(p, i, &all, 0);
      if (p->mu2[i] == 0.0) coincident++;
    }
    char *what = g_strdup_printf("/special %s", names[k]);
    stats_report(what, &s);
    g_test_message("%s: overlap verdict on the wrong side of 1: %zu of %zu", what,
                   s.wrong_side, s.n);
    g_free(what);
    const Bound *b = NULL;
    for (gsize j = 0; j < G_N_ELEMENTS(special_bounds); j++)
      if (strcmp(special_bounds[j].name, names[k]) == 0) b = &special_bounds[j];
    if (b == NULL) g_test_message("/special: kind %s has no bound in this test", names[k]);
    g_assert_nonnull(b);
    g_assert_cmpuint(s.n, >, 0);
    check_bounds(&s, b);
    stats_clear(&s);
  }
  g_assert_cmpuint(all.n, ==, p->n);
  stats_report("/special all kinds", &all);
  g_test_message("/special: %zu rows with coincident centres gave mu^2 = 0 exactly; "
                 "overlap verdict on the wrong side of 1: %zu", coincident, all.wrong_side);
  g_assert_cmpuint(coincident, >, 0);
  g_assert_cmpuint(all.n_other, ==, 0);
  stats_clear(&all);
  g_strfreev(names);
  g_free(kinds);
  refdata_pairs_free(p);
}

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
  g_test_add_func("/f_neg/reference/F", test_f_neg_reference);
  for (int c = 0; c < 4; c++) {
    char *path = g_strdup_printf("/contact_function/reference/class%d", c);
    g_test_add_data_func(path, GINT_TO_POINTER(c), test_contact_class);
    g_free(path);
  }
  for (int c = 0; c < 4; c++) {
    char *path = g_strdup_printf("/contact_function/reference/near_contact/class%d", c);
    g_test_add_data_func(path, GINT_TO_POINTER(c), test_near_contact_class);
    g_free(path);
  }
  g_test_add_func("/contact_function/reference/special", test_special);
  return g_test_run();
}
