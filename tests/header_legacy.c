/* pw85_legacy.h compiles as strict C99 (-pedantic -Werror) and a program
 * written for pw85 1.0's legacy API (non-const arrays, out of f2 a double[3]
 * here) compiles and links unchanged. Exit status 0 when the calls return
 * what two spheres of radii 1 and 2, centres 3 apart, give: mu^2 = 1. */
#include <math.h>
#include <stddef.h>

#include <pw85_legacy.h>

int main(void) {
  double q1[PW85_SYM] = {1.0, 0.0, 0.0, 1.0, 0.0, 1.0};
  double q2[PW85_SYM] = {4.0, 0.0, 0.0, 4.0, 0.0, 4.0};
  double q3[PW85_SYM], q4[PW85_SYM], a[PW85_DIM], b[PW85_DIM + 1];
  double r12[PW85_DIM] = {3.0, 0.0, 0.0};
  double out[3], contact[2];
  int i, status1, status2;
  for (i = 0; i < PW85_SYM; ++i) {
    q3[i] = 2.0 * q1[i] - q2[i];
    q4[i] = 0.5 * (q1[i] + q2[i]);
  }
  pw85_legacy__rT_adjQ_r_as_poly(r12, q1, q2, q3, a);
  pw85_legacy__detQ_as_poly(q1, q2, q3, q4, b);
  if (pw85_legacy__det_sym(q1) != 1.0 || pw85_legacy__xT_adjA_x(r12, q1) != 9.0) return 1;
  if (fabs(pw85_legacy_f1(0.5, r12, q1, q2, out) - 0.9) > 1e-15) return 2;
  if (fabs(pw85_legacy_f2(0.5, r12, q1, q2, NULL) - 0.9) > 1e-14) return 3;
  status1 = pw85_legacy_contact_function1(r12, q1, q2, contact);
  if (status1 != PW85_OK || fabs(contact[0] - 1.0) > 1e-14) return 4;
  status2 = pw85_legacy_contact_function2(r12, q1, q2, contact);
  if (status2 != PW85_OK || fabs(contact[0] - 1.0) > 1e-14) return 5;
  return 0;
}
