/* Reading a group of data/pw85_ref_data.h5 (r12, q1, q2, mu2, class) for the
 * tests of issue 6. */
#ifndef PW85_REFGROUP_H
#define PW85_REFGROUP_H

#include <stddef.h>

typedef struct {
  size_t n;
  double *r12, *q1, *q2, *mu2;
  int *cls;
} ref_group;

/* Loads group name (e.g. "/near_contact") from the reference file; returns
 * FALSE (and calls g_test_skip) when the file or group is absent. */
int ref_group_load(const char *name, ref_group *g);
void ref_group_free(ref_group *g);

#endif
