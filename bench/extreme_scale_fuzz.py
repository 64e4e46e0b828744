#!/usr/bin/python3
"""PW85_METHOD_DEFAULT on pairs of extreme scale against an exact reference.

    /usr/bin/python3 bench/extreme_scale_fuzz.py [--small-angles] build/src/libpw85.so [pairs] [seed] [csv]
    /usr/bin/python3 bench/extreme_scale_fuzz.py --reference < pairs.txt

Pairs (seeded): six semi-axes log-uniform in [1e-37, 1e37], random
orientations, drawn again until both matrices are positive definite, exactly
and by the library's test (about 1 draw in 30: the rounded matrix of
semi-axes further apart than ~1e8 is not); the centre distance either log-uniform in [1e-45, 1e45]
independently of the shapes (even pairs) or 10^U(-4, 4) times the sum of the
support radii along r (odd pairs): from deep overlap to far apart. Each pair
goes through pw85_contact_function_method with PW85_METHOD_DEFAULT (ctypes).
--small-angles: each orientation a rotation by an angle log-uniform in
[2^-60, 1] about a random axis instead, so that semi-axes far apart still
give positive definite matrices, rotated by less than their rounding can
resolve: matrices far more ill-conditioned than double precision (the
numerically singular shapes of docs/stability.md).

Reference, from the exact double inputs (no rounding anywhere): with
Q(t) = (1 - t) Q1 + t Q2, f(t) = t (1 - t) N(t) / D(t), N = r^T adj(Q(t)) r
(quadratic), D = det Q(t) (cubic), coefficients in rational arithmetic
(fractions). The maximiser of f on [0, 1] (f concave, docs/methods.md (M3))
is bracketed to 2^-200 of min(lambda, 1 - lambda) by bisection on the exact sign of the numerator of
f' at dyadic points; mu^2 lies between max(f(lo), f(hi)) and
f(lo) + f'(lo) (hi - lo) (concavity), both exact: the reference is exact
to far below a double's rounding (the bracket width is printed).

--reference reads pairs (three lines each: r12, q1, q2 as 3 and 6 doubles
in C99 hex or decimal notation) and prints mu^2 rounded to double (hex and
decimal), the relative width of the exact bracket, the maximiser, and mu^2
recomputed with mpmath at 2000 bits (LU solve of Q(lambda) r at the
maximiser, an independent check of the rational form); the expected values
of tests/test-reliability-methods.c come from this.

Prints the pairs with status PW85_OK whose relative error exceeds 1e-14
(the documented accuracy) or 10 times mu2_error / mu2 ("silent"), counts per
status and the largest error of the OK results; csv: one row per pair
(inputs in hex, status, mu2, lambda, mu2_error, reference, relative error).
"""
import ctypes
import math
import random
import sys
from fractions import Fraction

ACCURACY = 1e-14
NAMES = {0: "OK", -3: "NO_CONVERGENCE", -6: "INACCURATE", -7: "RANGE"}


class Result(ctypes.Structure):
    _fields_ = [("mu2", ctypes.c_double), ("lambda_", ctypes.c_double),
                ("mu2_error", ctypes.c_double), ("iterations", ctypes.c_int),
                ("method", ctypes.c_int)]


def _mul(a, b):
    r = [Fraction(0)] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            r[i + j] += x * y
    return r


def _add(*ps):
    r = [Fraction(0)] * max(len(p) for p in ps)
    for p in ps:
        for i, x in enumerate(p):
            r[i] += x
    return r


def _neg(p):
    return [-x for x in p]


def _eval(p, x):
    s = Fraction(0)
    for c in reversed(p):
        s = s * x + c
    return s


def _full(q):
    a, b, c, d, e, f = (Fraction(x) for x in q)
    return [[a, b, c], [b, d, e], [c, e, f]]


def reference(r, q1, q2, bits=200):
    """Exact bounds (lo, hi) on mu^2 and the maximiser, as Fractions."""
    r = [Fraction(x) for x in r]
    a, b = _full(q1), _full(q2)
    m = [[[a[i][j], b[i][j] - a[i][j]] for j in range(3)] for i in range(3)]

    def cof(i, j):
        rw = [k for k in range(3) if k != i]
        cl = [k for k in range(3) if k != j]
        c = _add(_mul(m[rw[0]][cl[0]], m[rw[1]][cl[1]]),
                 _neg(_mul(m[rw[0]][cl[1]], m[rw[1]][cl[0]])))
        return c if (i + j) % 2 == 0 else _neg(c)

    cof_ = [[cof(i, j) for j in range(3)] for i in range(3)]
    det = _add(*[_mul(m[0][j], cof_[0][j]) for j in range(3)])
    num = _add(*[[x * r[i] * r[j] for x in cof_[i][j]] for i in range(3) for j in range(3)])
    dnum = [i * num[i] for i in range(1, len(num))]
    ddet = [i * det[i] for i in range(1, len(det))]
    p, dp = [Fraction(0), Fraction(1), Fraction(-1)], [Fraction(1), Fraction(-2)]
    # f' = P / D^2, P = (p' N + p N') D - p N D'
    big_p = _add(_mul(_add(_mul(dp, num), _mul(p, dnum)), det), _neg(_mul(_mul(p, num), ddet)))
    den = 1
    for c in big_p:
        den = den * c.denominator // math.gcd(den, c.denominator)
    ip = [int(c * den) for c in big_p]
    n = len(ip) - 1

    def sign(k, e):  # sign of P(k / 2^e)
        s = sum(c * k ** i << (e * (n - i)) for i, c in enumerate(ip))
        return (s > 0) - (s < 0)

    lo, hi, e = 0, 1, 0  # bracket [lo, hi] / 2^e of the root of f'
    # until the bracket is 2^-bits of lambda and of 1 - lambda (at most
    # 4000 halvings: lambda within 2^-4000 of 0 or 1 is not met in doubles)
    while e < 4000 and not (lo > 0 and hi < 2 ** e and (hi - lo) << bits <= min(lo, 2 ** e - hi)):
        lo, hi, e = 2 * lo, 2 * hi, e + 1
        s = sign(lo + 1, e)
        if s == 0:
            lo = hi = lo + 1
            break
        if s > 0:
            lo += 1
        else:
            hi -= 1
    t0, t1 = Fraction(lo, 2 ** e), Fraction(hi, 2 ** e)

    def f(t):
        return t * (1 - t) * _eval(num, t) / _eval(det, t)

    def fprime(t):
        return _eval(big_p, t) / _eval(det, t) ** 2

    f0, f1 = f(t0), f(t1)
    upper = min(f0 + fprime(t0) * (t1 - t0), f1 - fprime(t1) * (t1 - t0))
    return max(f0, f1), max(upper, max(f0, f1)), (t0 + t1) / 2


def exactly_spd(q):
    """Leading minors of the exact (rational) matrix all > 0."""
    a, b, c, d, e, f = (Fraction(x) for x in q)
    return a > 0 and a * d - b * b > 0 and a * (d * f - e * e) - b * (b * f - e * c) + c * (b * e - d * c) > 0


def rotation(rng, small_angles=False):
    w, x, y, z = (rng.gauss(0, 1) for _ in range(4))
    if small_angles:  # angle 2^-U(0, 60) about the axis (x, y, z)
        half = 2.0 ** -rng.uniform(0, 60) / 2
        n = math.sqrt(x * x + y * y + z * z)
        w, x, y, z = math.cos(half), *(math.sin(half) * c / n for c in (x, y, z))
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def quad_form(radii, rot):
    return [math.fsum(radii[k] ** 2 * rot[i][k] * rot[j][k] for k in range(3))
            for i in range(3) for j in range(i, 3)]


def support(q, u):
    full = [[q[0], q[1], q[2]], [q[1], q[3], q[4]], [q[2], q[4], q[5]]]
    return math.sqrt(max(sum(u[i] * full[i][j] * u[j] for i in range(3) for j in range(3)), 0.0))


def gen(rng, k, small_angles):
    q1 = quad_form([10 ** rng.uniform(-37, 37) for _ in range(3)], rotation(rng, small_angles))
    q2 = quad_form([10 ** rng.uniform(-37, 37) for _ in range(3)], rotation(rng, small_angles))
    u = [rng.gauss(0, 1) for _ in range(3)]
    nu = math.sqrt(sum(x * x for x in u))
    u = [x / nu for x in u]
    if k % 2 == 0:
        d = 10 ** rng.uniform(-45, 45)
    else:
        d = (support(q1, u) + support(q2, u)) * 10 ** rng.uniform(-4, 4)
    return [d * x for x in u], q1, q2


def print_reference(lines):
    from mpmath import lu_solve, matrix, mp, mpf

    mp.prec = 2000
    vals = [[float.fromhex(x) if "0x" in x else float(x) for x in line.replace(",", " ").split()]
            for line in lines if line.strip()]
    for r, q1, q2 in zip(vals[0::3], vals[1::3], vals[2::3]):
        lo, hi, t = reference(r, q1, q2)
        full = [[matrix([[q[0], q[1], q[2]], [q[1], q[3], q[4]], [q[2], q[4], q[5]]])]
                for q in ([mpf(x) for x in q1], [mpf(x) for x in q2])]
        lam = mpf(t.numerator) / t.denominator
        s = lu_solve((1 - lam) * full[0][0] + lam * full[1][0], matrix([mpf(x) for x in r]))
        check = lam * (1 - lam) * sum(mpf(x) * s[i] for i, x in enumerate(r))
        print("mu2 %s = %.17g  bracket %.1e  lambda %.17g  1 - lambda %.3e  mpmath %s" % (
            float(lo).hex(), float(lo), float((hi - lo) / lo), float(t), float(1 - t),
            float(check).hex()))


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--reference":
        print_reference(sys.stdin.readlines())
        return
    small_angles = "--small-angles" in sys.argv
    argv = [a for a in sys.argv if a != "--small-angles"]
    lib = ctypes.CDLL(argv[1] if len(argv) > 1 else "build/src/libpw85.so")
    n = int(argv[2]) if len(argv) > 2 else 6000
    seed = int(argv[3]) if len(argv) > 3 else 1
    out = open(argv[4], "w") if len(argv) > 4 else None
    d3, d6 = ctypes.c_double * 3, ctypes.c_double * 6
    f = lib.pw85_contact_function_method
    f.argtypes = [d3, d6, d6, ctypes.c_int, ctypes.POINTER(Result)]
    rng = random.Random(seed)
    counts, silent, worst, width = {}, 0, 0.0, 0.0
    if out:
        out.write("r12,q1,q2,status,mu2,lambda,mu2_error,iterations,reference,rel_error\n")
    for k in range(n):
        while True:
            r, q1, q2 = gen(rng, k, small_angles)
            res = Result()
            s = f(d3(*r), d6(*q1), d6(*q2), 0, ctypes.byref(res))
            if s != -2 and exactly_spd(q1) and exactly_spd(q2):  # -2: PW85_ERR_NOT_SPD
                break
        counts[s] = counts.get(s, 0) + 1
        if s not in (0, -3, -6, -7):
            continue
        lo, hi, _ = reference(r, q1, q2)
        width = max(width, float((hi - lo) / lo))
        ref = float(lo)
        err = abs(res.mu2 - ref) / ref if ref > 0 else math.inf
        if s == 0:
            worst = max(worst, err)
            if err > ACCURACY or err > 10 * res.mu2_error / res.mu2:
                silent += 1
                print("silent: pair %d rel. error %.3e estimate %.3e lambda %r iterations %d"
                      % (k, err, res.mu2_error / res.mu2, res.lambda_, res.iterations))
                print("  r12 = (%s)\n  q1 = (%s)\n  q2 = (%s)" % tuple(
                    ", ".join(x.hex() for x in v) for v in (r, q1, q2)))
        if out:
            out.write("%s,%s,%s,%d,%r,%r,%r,%d,%r,%.3e\n" % (
                " ".join(x.hex() for x in r), " ".join(x.hex() for x in q1),
                " ".join(x.hex() for x in q2), s, res.mu2, res.lambda_, res.mu2_error,
                res.iterations, ref, err))
    print("%d pairs (seed %d%s); statuses: %s" % (n, seed, ", small angles" * small_angles, ", ".join(
        "%s %d" % (NAMES.get(s, str(s)), c) for s, c in sorted(counts.items(), reverse=True))))
    print("silent (OK, error > %g or > 10 x estimate): %d; largest OK error %.3e; "
          "reference bracket width %.1e" % (ACCURACY, silent, worst, width))


if __name__ == "__main__":
    main()
