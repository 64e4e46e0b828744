/* tutorial.c - the pw85 tutorial problem, written against the pw85 1.0 API.
 *
 * Two spheroids: E1 centred at (-0.5, 0.4, -0.7), equatorial radius 10,
 * polar radius 0.1, axis of revolution z; E2 centred at (0.2, -0.3, 0.4),
 * equatorial radius 0.5, polar radius 5, axis of revolution x. Prints their
 * contact function mu^2 and the maximiser lambda.
 *
 * Uses only what pw85 1.0 offered (pw85_spheroid, pw85_contact_function, the
 * header <pw85.h>) and ignores the returned status as 1.0 programs did, so
 * it checks that such programs still compile and give the same numbers.
 * Build: cc tutorial.c $(pkg-config --cflags --libs pw85)
 */
#include <pw85.h>
#include <stdio.h>

int main() {
    double centre1[] = {-0.5, 0.4, -0.7}, axis1[] = {0., 0., 1.};
    double centre2[] = {0.2, -0.3, 0.4}, axis2[] = {1., 0., 0.};
    double q1[6], q2[6], r12[3], out[2];

    pw85_spheroid(10., 0.1, axis1, q1);
    pw85_spheroid(0.5, 5., axis2, q2);
    for (int i = 0; i < 3; i++) {
        r12[i] = centre2[i] - centre1[i];
    }
    pw85_contact_function(r12, q1, q2, out);
    printf("mu^2 = %g\n", out[0]);
    printf("lambda = %g\n", out[1]);
    return 0;
}
