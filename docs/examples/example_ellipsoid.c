/* example_ellipsoid.c - general ellipsoids with pw85_ellipsoid(), checking
 * every status.
 *
 * The pair of the tutorial (tutorial.c) is rotated as a whole by 30 degrees
 * about the z axis: each ellipsoid is given by its three semi-axes and unit
 * axes, and the centre-to-centre vector is rotated too. The contact function
 * is invariant under a common rotation, so this prints the tutorial values
 * again (mu^2 = 3.36271, lambda = 0.166859). Then it shows the error path:
 * axes that are not orthonormal are refused.
 * Build: cc example_ellipsoid.c $(pkg-config --cflags --libs pw85) -lm
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <pw85.h>

/* v <- R v, R the rotation by angle t about z. */
static void rotate_z(double t, double const v[PW85_DIM], double w[PW85_DIM]) {
  w[0] = cos(t) * v[0] - sin(t) * v[1];
  w[1] = sin(t) * v[0] + cos(t) * v[1];
  w[2] = v[2];
}

int main(void) {
  double const pi = 3.14159265358979323846;
  double const t = pi / 6.;

  /* Semi-axes and unit axes (one axis per row) before the rotation. */
  double const radii1[PW85_DIM] = {10., 10., 0.1};
  double const radii2[PW85_DIM] = {5., 0.5, 0.5};
  double const identity[PW85_DIM * PW85_DIM] = {1., 0., 0., 0., 1., 0., 0., 0., 1.};
  double const r12_unrotated[PW85_DIM] = {0.7, -0.7, 1.1};

  double axes[PW85_DIM * PW85_DIM], r12[PW85_DIM];
  for (int i = 0; i < PW85_DIM; i++) rotate_z(t, identity + 3 * i, axes + 3 * i);
  rotate_z(t, r12_unrotated, r12);

  double q1[PW85_SYM], q2[PW85_SYM];
  int status = pw85_ellipsoid(radii1, axes, q1);
  if (status != PW85_OK) {
    fprintf(stderr, "pw85_ellipsoid (first): %s\n", pw85_strerror(status));
    return EXIT_FAILURE;
  }
  status = pw85_ellipsoid(radii2, axes, q2);
  if (status != PW85_OK) {
    fprintf(stderr, "pw85_ellipsoid (second): %s\n", pw85_strerror(status));
    return EXIT_FAILURE;
  }

  double out[2];
  status = pw85_contact_function(r12, q1, q2, out);
  if (status != PW85_OK) {
    fprintf(stderr, "pw85_contact_function: %s\n", pw85_strerror(status));
    return EXIT_FAILURE;
  }
  printf("mu^2 = %g\n", out[0]);
  printf("lambda = %g\n", out[1]);
  printf("%s\n", out[0] < 1. ? "overlap" : out[0] > 1. ? "no overlap" : "contact");

  /* Error path: skewed axes are refused and q1 is NaN-filled. */
  axes[1] += 0.1;
  status = pw85_ellipsoid(radii1, axes, q1);
  printf("skewed axes: %s\n", pw85_strerror(status));
  if (status != PW85_ERR_NOT_ORTHONORMAL || !isnan(q1[0])) return EXIT_FAILURE;
  return EXIT_SUCCESS;
}
