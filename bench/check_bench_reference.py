#!/usr/bin/python3
"""Checks the __float128 reference of bench/bench_contact.cpp against mpmath.

    bench_contact --dump K dump.txt out.csv
    /usr/bin/python3 bench/check_bench_reference.py dump.txt

Each line of dump.txt: class, r12 (3), q1 (6), q2 (6) as %.17g (so the
doubles are exact), and the __float128 reference mu2 with 36 digits. For each pair, mu2 is recomputed at 50
digits: f(lambda) = lambda (1 - lambda) r^T Q(lambda)^{-1} r with
Q(lambda) = (1 - lambda) Q1 + lambda Q2 (mpmath matrices, lu_solve), and its
maximum found by bisection on the sign of f' (f' = (1 - 2 lambda) phi
- lambda (1 - lambda) s^T (Q2 - Q1) s, s = Q^{-1} r), 120 halvings. Prints
the relative difference with the float128 reference; exits 1 if one exceeds
1e-24 (the float128 reference has ~1e-34 rounding times kappa(Q(lambda)),
kappa up to ~1e12 in the last class).
"""
import sys

from mpmath import mp, mpf, matrix, lu_solve

mp.dps = 50


def sym(v):
    a00, a01, a02, a11, a12, a22 = v
    return matrix([[a00, a01, a02], [a01, a11, a12], [a02, a12, a22]])


def mu2(r, q1, q2):
    # float() first: the %.17g strings round-trip to the exact doubles, which
    # mpf(str) would not reproduce (it reads the decimal, not the double).
    r = matrix([mpf(float(x)) for x in r])
    Q1 = sym([mpf(float(x)) for x in q1])
    Q2 = sym([mpf(float(x)) for x in q2])
    D = Q2 - Q1

    def derivs(lam):
        Q = (1 - lam) * Q1 + lam * Q2
        s = lu_solve(Q, r)
        phi = (r.T * s)[0]
        sds = (s.T * D * s)[0]
        p = lam * (1 - lam)
        return p * phi, (1 - 2 * lam) * phi - p * sds

    lo, hi = mpf(0), mpf(1)
    for _ in range(120):
        mid = (lo + hi) / 2
        if derivs(mid)[1] > 0:
            lo = mid
        else:
            hi = mid
    return derivs((lo + hi) / 2)[0]


def main():
    worst = 0.0
    with open(sys.argv[1]) as fh:
        for line in fh:
            v = line.split()
            cls = int(v[0])
            r, q1, q2, ref = v[1:4], v[4:10], v[10:16], mpf(v[16])
            m = mu2(r, q1, q2)
            rel = abs(m - ref) / m
            worst = max(worst, float(rel))
            print("class %d  mu2 = %s  rel. diff. float128 vs mpmath = %.2e"
                  % (cls, mp.nstr(m, 20), float(rel)))
    print("max relative difference: %.2e" % worst)
    return 0 if worst < 1e-24 else 1


if __name__ == "__main__":
    sys.exit(main())
