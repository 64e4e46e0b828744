/* Force loop with pw85_contact_derivatives (docs/derivatives.md): pair
 * potential U = eps (1 - mu)^2 for mu < 1, zero beyond. With
 * dU/dmu^2 = -eps (1 - mu) / mu, the pair (i, j), r12 = c_j - c_i, gives
 *   F_j = -dU/dmu^2 d_r12,  F_i = -F_j,
 *   tau_i = -dU/dmu^2 d_theta1,  tau_j = -dU/dmu^2 d_theta2.
 * The program checks that the total force and the total torque
 * sum(c x F + tau) vanish, and one force against a central difference. */
#include <math.h>
#include <pw85.h>
#include <stdio.h>

#define N 3

static double energy(const double c[N][3], const double q[N][6], double eps) {
  double u = 0.0;
  for (int i = 0; i < N; i++)
    for (int j = i + 1; j < N; j++) {
      double r[3] = {c[j][0] - c[i][0], c[j][1] - c[i][1], c[j][2] - c[i][2]}, out[2];
      pw85_contact_function(r, q[i], q[j], out);
      double mu = sqrt(out[0]);
      if (mu < 1.0) u += eps * (1.0 - mu) * (1.0 - mu);
    }
  return u;
}

int main(void) {
  const double eps = 1.0;
  double c[N][3] = {{0.0, 0.0, 0.0}, {1.2, 0.3, 0.1}, {0.4, 1.1, -0.2}};
  double q[N][6];
  const double radii[N][3] = {{1.0, 0.5, 0.3}, {0.8, 0.6, 0.4}, {0.9, 0.3, 0.3}};
  const double s = sqrt(0.5);
  const double axes[N][9] = {{1, 0, 0, 0, 1, 0, 0, 0, 1},
                             {s, s, 0, -s, s, 0, 0, 0, 1},
                             {1, 0, 0, 0, s, s, 0, -s, s}};
  for (int i = 0; i < N; i++)
    if (pw85_ellipsoid(radii[i], axes[i], q[i]) != PW85_OK) return 1;
  double f[N][3] = {{0}}, tau[N][3] = {{0}};
  for (int i = 0; i < N; i++)
    for (int j = i + 1; j < N; j++) {
      double r[3] = {c[j][0] - c[i][0], c[j][1] - c[i][1], c[j][2] - c[i][2]};
      pw85_derivatives_t d;
      if (pw85_contact_derivatives(r, q[i], q[j], &d) != PW85_OK) return 1;
      double mu = sqrt(d.mu2);
      if (mu >= 1.0) continue;
      double dudm2 = -eps * (1.0 - mu) / mu;
      for (int k = 0; k < 3; k++) {
        f[j][k] -= dudm2 * d.d_r12[k];
        f[i][k] += dudm2 * d.d_r12[k];
        tau[i][k] -= dudm2 * d.d_theta1[k];
        tau[j][k] -= dudm2 * d.d_theta2[k];
      }
    }
  double fnet[3] = {0}, lnet[3] = {0}, fbig = 0.0;
  for (int i = 0; i < N; i++)
    for (int k = 0; k < 3; k++) {
      int a = (k + 1) % 3, b = (k + 2) % 3;
      fnet[k] += f[i][k];
      lnet[k] += c[i][a] * f[i][b] - c[i][b] * f[i][a] + tau[i][k];
      fbig = fmax(fbig, fabs(f[i][k]));
    }
  printf("U = %.6f\n", energy(c, q, eps));
  printf("net force and torque vanish: %s\n",
         fabs(fnet[0]) + fabs(fnet[1]) + fabs(fnet[2]) <= 1e-14 * fbig &&
                 fabs(lnet[0]) + fabs(lnet[1]) + fabs(lnet[2]) <= 1e-13 * fbig
             ? "yes" : "no");
  /* F_1 (x component) against -(U(c + h) - U(c - h)) / 2h */
  const double h = 1e-6;
  c[1][0] += h;
  double up = energy(c, q, eps);
  c[1][0] -= 2 * h;
  double um = energy(c, q, eps);
  c[1][0] += h;
  double fd = -(up - um) / (2 * h);
  printf("force matches finite difference: %s\n",
         fabs(fd - f[1][0]) <= 1e-7 * fbig ? "yes" : "no");
  return 0;
}
