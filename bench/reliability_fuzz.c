/* Extreme pairs through the five methods of pw85_contact_function_method
 * and pw85_contact (docs/stability.md, "Failing evaluations"): magnitudes
 * 1e-300 to 1e300, aspect ratios to 1e16, diagonal matrices with entries
 * from DBL_MAX to 4.9e-324, near-singular and identical shapes, semi-axes
 * 1e-37 to 1e37. Each pair is computed twice, after filling the stack with
 * two different bytes and after a different other call: counts results
 * that differ (bitwise), statuses that write an estimate with a NaN (or
 * negative) mu2, mu2 = +inf, lambda outside [0, 1] or NaN, and statuses
 * outside the documented list. DUMP=file writes every result, to compare
 * builds (e.g. -ftrivial-auto-var-init=pattern against =zero).
 * Built by bench/meson.build:  build/bench/reliability_fuzz 200000 [seed] */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "pw85.h"
static uint64_t rs = 88172645463325252ull;
static double urand(void) { rs ^= rs << 13; rs ^= rs >> 7; rs ^= rs << 17; return (rs >> 11) * 0x1p-53; }
static void rot(double R[9]) { double w=urand()-.5,x=urand()-.5,y=urand()-.5,z=urand()-.5,n=sqrt(w*w+x*x+y*y+z*z); w/=n;x/=n;y/=n;z/=n;
  double m[9]={1-2*(y*y+z*z),2*(x*y-w*z),2*(x*z+w*y),2*(x*y+w*z),1-2*(x*x+z*z),2*(y*z-w*x),2*(x*z-w*y),2*(y*z+w*x),1-2*(x*x+y*y)}; for(int i=0;i<9;i++)R[i]=m[i]; }
static void mkq(double a, double b, double c, double q[6]) { double R[9]; rot(R); double s[3]={a*a,b*b,c*c}; int k=0;
  for(int i=0;i<3;i++)for(int j=i;j<3;j++){ double t=0; for(int l=0;l<3;l++) t+=s[l]*R[3*i+l]*R[3*j+l]; q[k++]=t; } }
static double lu(double lo, double hi) { return pow(10, lo + (hi - lo) * urand()); }
static void gen(double r[3], double q1[6], double q2[6]) {
  int mode = (int)(urand() * 5);
  double sc = lu(-150, 150);
  if (mode == 0) { /* rotated, aspect ratios to 1e16 */
    double a = lu(0, 16); mkq(sc, sc / sqrt(a) * (urand() + .5), sc / a, q1);
    double b = lu(0, 16), s2 = sc * lu(-4, 4); mkq(s2 / b, s2 * (urand() + .1), s2, q2);
  } else if (mode == 1) { /* diagonal, entries from DBL_MAX to 4.9e-324 */
    static const double v[] = {DBL_MAX, 1e300, 1e200, 1e16, 1, 1e-16, 1e-200, 1e-300, 4.9e-324, 2.2e-308};
    memset(q1, 0, 6 * sizeof *q1); memset(q2, 0, 6 * sizeof *q2);
    for (int i = 0; i < 6; i += i == 0 ? 3 : 2) q1[i] = v[(int)(urand() * 10)];
    if (urand() < .5) q2[0] = q2[3] = q2[5] = lu(-5, 5);
    else for (int i = 0; i < 6; i += i == 0 ? 3 : 2) q2[i] = v[(int)(urand() * 10)];
    double d = lu(-300, 300); for (int i = 0; i < 3; i++) r[i] = d * (urand() < .3 ? 0 : (urand() - .5));
    if (r[0] == 0 && r[1] == 0 && r[2] == 0) r[0] = d;
    return;
  } else if (mode == 2) { /* near singular */
    double a = lu(0, 16); mkq(sc, sc / a, sc / a, q1); mkq(sc, sc / a * (1 + urand()), sc * urand(), q2);
  } else if (mode == 3) { /* identical shapes */
    double a = lu(0, 16); mkq(sc, sc / a, sc * (urand() + 1e-3), q1); memcpy(q2, q1, 6 * sizeof *q1);
  } else { /* semi-axes 1e-37 to 1e37 */
    mkq(lu(-37, 37), lu(-37, 37), lu(-37, 37), q1); mkq(lu(-37, 37), lu(-37, 37), lu(-37, 37), q2); sc = lu(-37, 37);
  }
  double d = sc * lu(-8, 8); for (int i = 0; i < 3; i++) r[i] = d * (urand() - .5);
}
static __attribute__((noinline)) void scribble(unsigned char b) { volatile unsigned char buf[1 << 13]; for (size_t i = 0; i < sizeof buf; i++) buf[i] = b; }
static const double other_r[3] = {1, 2, 3}, other_q1[6] = {1, 0, 0, 1, 0, 1}, other_q2[6] = {4, 0, 0, 9, 0, 1};
static int call(int m, const double r[3], const double q1[6], const double q2[6], double out[11], int *it) {
  if (m < 5) { pw85_result res; int s = pw85_contact_function_method(r, q1, q2, m, &res);
    out[0] = res.mu2; out[1] = res.lambda; out[2] = res.mu2_error; *it = res.iterations; return s; }
  pw85_contact_t c; int s = pw85_contact(r, q1, q2, &c); memcpy(out, &c, sizeof c); *it = 0; return s;
}
int main(int argc, char **argv) {
  long n = argc > 1 ? atol(argv[1]) : 200000; rs += argc > 2 ? atol(argv[2]) : 0;
  FILE *dump = getenv("DUMP") ? fopen(getenv("DUMP"), "w") : NULL;
  long differ[6] = {0}, nan_est[6] = {0}, inf_mu2[6] = {0}, lam_out[6] = {0}, undoc[6] = {0};
  for (long k = 0; k < n; k++) {
    double r[3], q1[6], q2[6]; gen(r, q1, q2);
    for (int m = 0; m < 6; m++) {
      int nv = m < 5 ? 3 : 11, ia, ib; double a[11], b[11], t[11];
      scribble(0x00); int sa = call(m, r, q1, q2, a, &ia);
      call(m, other_r, other_q1, other_q2, t, &ib); scribble(0xef); int sb = call(m, r, q1, q2, b, &ib);
      if (sa != sb || ia != ib || memcmp(a, b, nv * sizeof *a)) differ[m]++;
      if (dump) { fprintf(dump, "%ld %d %d %d", k, m, sa, ia); for (int i = 0; i < nv; i++) fprintf(dump, " %a", a[i]); fprintf(dump, "\n"); }
      if (!(sa == PW85_OK || sa == PW85_ERR_INACCURATE || sa == PW85_ERR_NO_CONVERGENCE || sa == PW85_ERR_NOT_SPD ||
            sa == PW85_ERR_INVALID_ARGUMENT)) undoc[m]++;
      if (sa == PW85_OK || sa == PW85_ERR_INACCURATE || sa == PW85_ERR_NO_CONVERGENCE) {
        if (a[0] == INFINITY) inf_mu2[m]++; else if (!(a[0] >= 0)) nan_est[m]++;
        if (!(a[1] >= 0 && a[1] <= 1)) lam_out[m]++;
      }
    }
  }
  static const char *const name[] = {"DEFAULT", "BRENT", "NEWTON", "RATIONAL", "ZHENG", "pw85_contact"};
  printf("%ld pairs\n", n);
  for (int m = 0; m < 6; m++)
    printf("%-13s differ %ld  NaN estimate %ld  mu2 = inf %ld  lambda not in [0,1] %ld  undocumented status %ld\n",
           name[m], differ[m], nan_est[m], inf_mu2[m], lam_out[m], undoc[m]);
  if (dump) fclose(dump);
  return 0;
}
