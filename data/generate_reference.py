#!/usr/bin/python3
"""Generate the high-precision reference data set ``pw85_ref_data.h5`` of libpw85.

Usage::

    /usr/bin/python3 data/generate_reference.py [-o data/pw85_ref_data.h5]
                                                [--seed 314159265] [--workers 2]
                                                [--quick]

Requirements (Debian): python3-numpy python3-h5py python3-gmpy2 python3-mpmath.

Everything is computed from the *exact* float64 values that are stored in the
output file:

* every stored double is converted exactly to a rational number
  (``gmpy2.mpq``);
* the polynomials a(lambda) = r^T adj(Q(lambda)) r (degree 2),
  b(lambda) = det Q(lambda) (degree 3) and the numerator
  c(lambda) = p'(lambda) b(lambda) - p(lambda) b'(lambda) of f'(lambda),
  with p(lambda) = lambda (1 - lambda) a(lambda), are formed with exact
  rational coefficients;
* the maximiser lambda* of f is the unique root of c in (0, 1); it is isolated
  with exact sign evaluations at dyadic points (bisection down to 2^-52, then
  a safeguarded Newton iteration on the integer lattice 2^-400 Z), so that
  the final bracket [lo, hi] has width <= 2 * 2^-400 and the sign change
  c(lo) > 0 > c(hi) is verified exactly;
* mu^2 = f(lambda*) is evaluated exactly at the dyadic lambda*, then rounded
  to 400 bits (about 120 decimal digits; the error coming from lambda* is of
  order 2^-800), from which the 50-significant-digit string and the correctly
  rounded float64 are derived;
* an independent cross-check (mpmath, mp.dps = 80, f evaluated with
  mp.lu_solve, golden-section maximisation) is run on a sample and must agree
  to 1e-40 relative.

The output is reproducible: fixed seed, no dates, HDF5 object time stamps
disabled.
"""

import argparse
import hashlib
import math
import multiprocessing
import os
import sys
import time

import numpy as np

import gmpy2
from gmpy2 import mpq, mpz, mpfr
import h5py
import mpmath

GENERATOR = "data/generate_reference.py (libpw85)"
DEFAULT_SEED = 314159265
NBITS = 400          # lattice 2^-NBITS for lambda*, precision of mpfr results
MP_DPS_CHECK = 80    # mpmath working precision of the independent cross-check
DIGITS = 50          # significant digits stored in mu2_str
STR_LEN = 64         # fixed length of the mu2_str byte strings

# Upper triangle, row-major: [Q00, Q01, Q02, Q11, Q12, Q22]
IDX = ((0, 1, 2), (1, 3, 4), (2, 4, 5))

CLASS_BOUNDS = [(0.5, 2.0), (0.1, 10.0), (0.01, 100.0), (0.001, 1000.0)]

SPECIAL_KINDS = [
    "coincident_centres",            # 0
    "identical_ellipsoids",          # 1
    "equal_spheres",                 # 2
    "very_different_spheres",        # 3
    "needle_crossing_disc",          # 4
    "parallel_needles",              # 5
    "nearly_parallel_needles",       # 6
    "high_aspect_spheroids",         # 7
    "high_aspect_ellipsoids",        # 8
]


# ---------------------------------------------------------------------------
# Small helpers
# ---------------------------------------------------------------------------

class Progress:
    """Minimal progress display on stderr."""

    def __init__(self, label, total):
        self.label, self.total, self.done = label, total, 0
        self.t0 = time.time()
        self.last = 0.0
        self.show(force=True)

    def update(self, k=1):
        self.done += k
        self.show()

    def show(self, force=False):
        now = time.time()
        if not force and now - self.last < 0.5 and self.done < self.total:
            return
        self.last = now
        el = now - self.t0
        eta = el / self.done * (self.total - self.done) if self.done else float("nan")
        sys.stderr.write("\r  %-28s %7d/%-7d  %6.1f s elapsed  ETA %6.1f s   "
                         % (self.label, self.done, self.total, el, eta))
        if self.done >= self.total:
            sys.stderr.write("\n")
        sys.stderr.flush()


def to_float(x):
    """Correctly rounded (nearest-even) float64 of an exact rational or mpfr."""
    return float(mpfr(x, 53))


def to_str(x):
    """50 significant digits, scientific notation."""
    if x == 0:
        return "0." + "0" * (DIGITS - 1) + "e+00"
    return "{:.{}e}".format(mpfr(x, NBITS), DIGITS - 1)


def spheroid(a, c, n):
    """Same float64 operations as the C function pw85_spheroid.

    a2 = a*a, c2 = c*c, and (c2 - a2) is evaluated first; each product is
    evaluated left to right: q[0] = a2 + ((c2 - a2) * n0) * n0, etc.
    (no fused multiply-add).
    """
    a2 = a * a
    c2 = c * c
    c2_a2 = c2 - a2
    n0, n1, n2 = float(n[0]), float(n[1]), float(n[2])
    return [a2 + c2_a2 * n0 * n0,
            c2_a2 * n0 * n1,
            c2_a2 * n0 * n2,
            a2 + c2_a2 * n1 * n1,
            c2_a2 * n1 * n2,
            a2 + c2_a2 * n2 * n2]


def is_spd_exact(q):
    """Exact Sylvester criterion on the stored doubles."""
    Q = [mpq(float(x)) for x in q]
    m1 = Q[0]
    m2 = Q[0] * Q[3] - Q[1] * Q[1]
    det = (Q[0] * (Q[3] * Q[5] - Q[4] * Q[4])
           - Q[1] * (Q[1] * Q[5] - Q[4] * Q[2])
           + Q[2] * (Q[1] * Q[4] - Q[3] * Q[2]))
    return m1 > 0 and m2 > 0 and det > 0


# ---------------------------------------------------------------------------
# Exact polynomial machinery
# ---------------------------------------------------------------------------

def pmul(p, q):
    r = [mpq(0)] * (len(p) + len(q) - 1)
    for i, x in enumerate(p):
        if x == 0:
            continue
        for j, y in enumerate(q):
            r[i + j] += x * y
    return r


def padd(p, q):
    n = max(len(p), len(q))
    return [(p[i] if i < len(p) else 0) + (q[i] if i < len(q) else 0) for i in range(n)]


def psub(p, q):
    n = max(len(p), len(q))
    return [(p[i] if i < len(p) else 0) - (q[i] if i < len(q) else 0) for i in range(n)]


def pscale(p, s):
    return [x * s for x in p]


def pder(p):
    return [i * p[i] for i in range(1, len(p))] or [mpq(0)]


def peval(p, x):
    acc = mpq(0)
    for c in reversed(p):
        acc = acc * x + c
    return acc


def ab_polys(q1, q2, r):
    """Exact coefficients (lowest degree first) of a(lambda) and b(lambda)."""
    A = [mpq(float(x)) for x in q1]
    B = [mpq(float(y)) - mpq(float(x)) for x, y in zip(q1, q2)]
    M = [[[A[IDX[i][j]], B[IDX[i][j]]] for j in range(3)] for i in range(3)]
    R = [mpq(float(x)) for x in r]
    c00 = psub(pmul(M[1][1], M[2][2]), pmul(M[1][2], M[1][2]))
    c01 = psub(pmul(M[0][2], M[1][2]), pmul(M[0][1], M[2][2]))
    c02 = psub(pmul(M[0][1], M[1][2]), pmul(M[0][2], M[1][1]))
    c11 = psub(pmul(M[0][0], M[2][2]), pmul(M[0][2], M[0][2]))
    c12 = psub(pmul(M[0][1], M[0][2]), pmul(M[0][0], M[1][2]))
    c22 = psub(pmul(M[0][0], M[1][1]), pmul(M[0][1], M[0][1]))
    a = pscale(c00, R[0] * R[0])
    a = padd(a, pscale(c11, R[1] * R[1]))
    a = padd(a, pscale(c22, R[2] * R[2]))
    a = padd(a, pscale(c01, 2 * R[0] * R[1]))
    a = padd(a, pscale(c02, 2 * R[0] * R[2]))
    a = padd(a, pscale(c12, 2 * R[1] * R[2]))
    b = padd(padd(pmul(M[0][0], c00), pmul(M[0][1], c01)), pmul(M[0][2], c02))
    return a, b


def contact(q1, q2, r):
    """Return (mu2 as mpq, lambda* as mpq or None, stats) from exact doubles."""
    if all(float(x) == 0.0 for x in r):
        return mpq(0), None, 0
    a, b = ab_polys(q1, q2, r)
    # p = lambda (1 - lambda) a
    p = pmul([mpq(0), mpq(1), mpq(-1)], a)
    c = psub(pmul(pder(p), b), pmul(p, pder(b)))
    c = (c + [mpq(0)] * 7)[:7]
    # integer coefficients with the same sign behaviour
    den = mpz(1)
    for x in c:
        den = gmpy2.lcm(den, x.denominator)
    C = [mpz(x * den) for x in c]
    D = [(i + 1) * C[i + 1] for i in range(6)]
    n = NBITS

    def ev(K):      # c(K 2^-n) * 2^(6n)
        acc = C[6]
        for i in range(5, -1, -1):
            acc = acc * K + (C[i] << (n * (6 - i)))
        return acc

    def evd(K):     # c'(K 2^-n) * 2^(5n)
        acc = D[5]
        for i in range(4, -1, -1):
            acc = acc * K + (D[i] << (n * (5 - i)))
        return acc

    lo, hi = mpz(0), mpz(1) << n
    if not (ev(lo) > 0 and ev(hi) < 0):
        raise ArithmeticError("no sign change of c on [0, 1]")
    its = 0
    root = None
    while hi - lo > (mpz(1) << (n - 52)):
        mid = (lo + hi) >> 1
        v = ev(mid)
        its += 1
        if v == 0:
            root = mid
            break
        if v > 0:
            lo = mid
        else:
            hi = mid
    if root is None:
        K = (lo + hi) >> 1
        for _ in range(200):
            v = ev(K)
            its += 1
            if v == 0:
                root = K
                break
            if v > 0:
                lo = max(lo, K)
            else:
                hi = min(hi, K)
            if hi - lo <= 2:
                break
            d = evd(K)
            if d == 0:
                K = (lo + hi) >> 1
                continue
            # Newton iterate K - v/d, floored to the lattice (exact)
            Kf = (K * d - v) // d
            if abs(Kf - K) <= 8:
                # converged to within a few lattice steps: test both
                # lattice points around the Newton iterate
                for cand in (Kf, Kf + 1):
                    w = ev(cand)
                    its += 1
                    if w == 0:
                        root = cand
                        break
                    if w > 0:
                        lo = max(lo, cand)
                    else:
                        hi = min(hi, cand)
                if root is not None or hi - lo <= 2:
                    break
            Kn = Kf
            if not (lo < Kn < hi):
                Kn = (lo + hi) >> 1
            K = Kn
        else:
            raise ArithmeticError("root finding did not converge")
        if root is None:
            # final verified bracket: c(lo) > 0 > c(hi), hi - lo <= 2
            assert ev(lo) > 0 and ev(hi) < 0 and hi - lo <= 2
            root = (lo + hi) >> 1
    lam = mpq(root, mpz(1) << n)
    mu2 = peval(p, lam) / peval(b, lam)
    return mu2, lam, its


def contact_row(args):
    """Worker: (q1, q2, r) -> (mu2 float, lambda float, mu2 string, its)."""
    q1, q2, r = args
    mu2, lam, its = contact(q1, q2, r)
    return (to_float(mu2), float("nan") if lam is None else to_float(lam),
            to_str(mu2), its)


def near_contact_row(args):
    """Worker: rescale r so that mu2 ~ target, round to doubles, recompute."""
    q1, q2, u, target = args
    mu2u, _, _ = contact(q1, q2, u)
    s = gmpy2.sqrt(mpfr(mpq(target) / mu2u, NBITS))
    r = [to_float(mpfr(s * mpfr(mpq(float(x)), NBITS), NBITS)) for x in u]
    mu2, lam, its = contact(q1, q2, r)
    return (r, to_float(mu2), to_float(lam), to_str(mu2), its)


# ---------------------------------------------------------------------------
# /F
# ---------------------------------------------------------------------------

_F_DATA = {}


def _f_init(spheroids, directions, lambdas):
    _F_DATA["S"] = [[mpq(float(x)) for x in row] for row in spheroids]
    rr = []
    for d in directions:
        r0, r1, r2 = (mpq(float(x)) for x in d)
        rr.append([r0 * r0, 2 * r0 * r1, 2 * r0 * r2, r1 * r1, 2 * r1 * r2, r2 * r2])
    _F_DATA["rr"] = rr
    _F_DATA["lam"] = [mpq(float(x)) for x in lambdas]


def f_block(i1):
    """F[i1, :, :, :] exactly: f = lam (1 - lam) r^T adj(Q) r / det(Q)."""
    S, rr, lams = _F_DATA["S"], _F_DATA["rr"], _F_DATA["lam"]
    n2, nd, nl = len(S), len(rr), len(lams)
    out = np.zeros((n2, nd, nl))
    Q1 = S[i1]
    for i2 in range(n2):
        Q2 = S[i2]
        for l, lam in enumerate(lams):
            w = lam * (1 - lam)
            if w == 0:
                continue            # f(0) = f(1) = 0 exactly
            m = [(1 - lam) * x + lam * y for x, y in zip(Q1, Q2)]
            m00, m01, m02, m11, m12, m22 = m
            c00 = m11 * m22 - m12 * m12
            c01 = m02 * m12 - m01 * m22
            c02 = m01 * m12 - m02 * m11
            c11 = m00 * m22 - m02 * m02
            c12 = m01 * m02 - m00 * m12
            c22 = m00 * m11 - m01 * m01
            det = m00 * c00 + m01 * c01 + m02 * c02
            fac = w / det
            for k in range(nd):
                x = rr[k]
                a = (c00 * x[0] + c01 * x[1] + c02 * x[2]
                     + c11 * x[3] + c12 * x[4] + c22 * x[5])
                out[i2, k, l] = to_float(fac * a)
    return i1, out


# ---------------------------------------------------------------------------
# Independent cross-check (mpmath, lu_solve, golden section)
# ---------------------------------------------------------------------------

def mp_f(lam, Q1, Q2, r):
    Q = (1 - lam) * Q1 + lam * Q2
    s = mpmath.lu_solve(Q, r)
    return lam * (1 - lam) * (r.T * s)[0]


def golden_mu2(args):
    """Independent route: golden-section maximisation of f (mp.dps = 80)."""
    q1, q2, r = args
    mpmath.mp.dps = MP_DPS_CHECK
    Q1 = mpmath.matrix([[mpmath.mpf(float(q1[IDX[i][j]])) for j in range(3)] for i in range(3)])
    Q2 = mpmath.matrix([[mpmath.mpf(float(q2[IDX[i][j]])) for j in range(3)] for i in range(3)])
    R = mpmath.matrix([mpmath.mpf(float(x)) for x in r])
    if all(float(x) == 0 for x in r):
        return "0", "nan"
    g = (mpmath.sqrt(5) - 1) / 2
    lo, hi = mpmath.mpf(0), mpmath.mpf(1)
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    f1, f2 = mp_f(x1, Q1, Q2, R), mp_f(x2, Q1, Q2, R)
    tol = mpmath.mpf(10) ** -38
    while hi - lo > tol:
        if f1 < f2:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + g * (hi - lo)
            f2 = mp_f(x2, Q1, Q2, R)
        else:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - g * (hi - lo)
            f1 = mp_f(x1, Q1, Q2, R)
    best = max(f1, f2)
    return mpmath.nstr(best, 70), mpmath.nstr((lo + hi) / 2, 30)


# ---------------------------------------------------------------------------
# Random sampling (parent process only, reproducible)
# ---------------------------------------------------------------------------

def random_rotation(rng):
    q = rng.standard_normal(4)
    q = q / np.sqrt(np.dot(q, q))
    w, x, y, z = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def ellipsoid_q(radii, R):
    """Q = R diag(radii^2) R^T in float64, upper triangle only."""
    s = [float(x) * float(x) for x in radii]
    q = []
    for i in range(3):
        for j in range(i, 3):
            q.append(float(R[i, 0] * s[0] * R[j, 0] + R[i, 1] * s[1] * R[j, 1]
                           + R[i, 2] * s[2] * R[j, 2]))
    return q


def random_ellipsoid(rng, lo, hi):
    while True:
        radii = np.exp(rng.uniform(math.log(lo), math.log(hi), 3))
        if len(set(radii.tolist())) < 3:
            continue
        q = ellipsoid_q(radii, random_rotation(rng))
        if is_spd_exact(q):
            return radii, q


def random_unit(rng):
    u = rng.standard_normal(3)
    return u / np.sqrt(np.dot(u, u))


# ---------------------------------------------------------------------------
# Special cases
# ---------------------------------------------------------------------------

def special_cases(rng):
    """Rows (kind, q1, q2, r or None, radii1, radii2, target or None).

    r = None means: r12 = scale * u with u random unit and the scale chosen
    so that mu2 ~ target (near contact); computed by near_contact_row.
    """
    rows = []
    ez = np.array([0.0, 0.0, 1.0])

    def sph(a, c, n):
        return spheroid(float(a), float(c), n)

    def add(kind, q1, q2, r, r1, r2, target=None, u=None):
        assert is_spd_exact(q1) and is_spd_exact(q2)
        rows.append((SPECIAL_KINDS.index(kind), q1, q2, r, list(r1), list(r2), target, u))

    # 0: coincident centres
    for cls in range(4):
        for _ in range(5):
            ra1, q1 = random_ellipsoid(rng, *CLASS_BOUNDS[cls])
            ra2, q2 = random_ellipsoid(rng, *CLASS_BOUNDS[cls])
            add("coincident_centres", q1, q2, [0.0, 0.0, 0.0], ra1, ra2)
    # 1: identical ellipsoids
    for cls in range(4):
        for _ in range(10):
            ra1, q1 = random_ellipsoid(rng, *CLASS_BOUNDS[cls])
            d = math.exp(rng.uniform(math.log(0.01), math.log(10.0))) * 2 * max(ra1)
            add("identical_ellipsoids", q1, list(q1), list(d * random_unit(rng)), ra1, ra1)
    # 2: equal spheres (including exact contact / far / deep overlap)
    for rad in (1e-6, 1e-3, 0.5, 1.0, 3.0, 1e3, 1e6):
        q = [rad * rad, 0.0, 0.0, rad * rad, 0.0, rad * rad]
        for fac in (0.0625, 0.5, 1.0, 2.0, 10.0):
            add("equal_spheres", q, list(q), [0.0, 0.0, 2 * rad * fac], [rad] * 3, [rad] * 3)
            add("equal_spheres", q, list(q), list(2 * rad * fac * random_unit(rng)),
                [rad] * 3, [rad] * 3)
    # 3: very different spheres
    for r1, r2 in ((1e-6, 1e6), (1e6, 1e-6), (1e-6, 1.0), (1.0, 1e6), (1e-3, 1e3)):
        qa = [r1 * r1, 0.0, 0.0, r1 * r1, 0.0, r1 * r1]
        qb = [r2 * r2, 0.0, 0.0, r2 * r2, 0.0, r2 * r2]
        for fac in (0.01, 0.5, 1.0, 1.0 + 1e-9, 2.0, 100.0):
            add("very_different_spheres", qa, qb, list((r1 + r2) * fac * random_unit(rng)),
                [r1] * 3, [r2] * 3)
    # 4: needle crossing a disc at right angles (needle axis = disc normal)
    for eps in (1e-2, 1e-3, 1e-4, 1e-6):
        for _ in range(2):
            n = random_unit(rng)
            needle = sph(eps, 1.0, n)
            disc = sph(1.0, eps, n)
            t = random_unit(rng)
            t = t - np.dot(t, n) * n
            t = t / np.sqrt(np.dot(t, t))
            # along the common axis, laterally, and obliquely
            for dist in ([0.5 * n, 1.5 * n, (1 + eps) * 0.999 * n, 0.5 * t,
                          (1 + eps) * t, 2 * t, 0.3 * t + 0.3 * n]):
                add("needle_crossing_disc", needle, disc, [float(x) for x in dist],
                    [eps, eps, 1.0], [1.0, 1.0, eps])
            add("needle_crossing_disc", needle, disc, None,
                [eps, eps, 1.0], [1.0, 1.0, eps], target=1 - 1e-10, u=t)
            add("needle_crossing_disc", needle, disc, None,
                [eps, eps, 1.0], [1.0, 1.0, eps], target=1 + 1e-10, u=n)
    # 5: exactly parallel needles ; 6: nearly parallel needles
    for eps in (1e-2, 1e-3, 1e-4, 1e-6):
        n = random_unit(rng)
        nd = sph(eps, 1.0, n)
        t = random_unit(rng)
        t = t - np.dot(t, n) * n
        t = t / np.sqrt(np.dot(t, t))
        for dist in (0.5 * eps * t, 2 * eps * t, 3 * eps * t, 0.5 * n, 2.5 * n,
                     eps * t + 1.0 * n, 10 * t):
            add("parallel_needles", nd, list(nd), [float(x) for x in dist],
                [eps, eps, 1.0], [eps, eps, 1.0])
        for ang in (1e-2, 1e-4, 1e-6, 1e-8):
            m = math.cos(ang) * n + math.sin(ang) * t
            m = m / np.sqrt(np.dot(m, m))
            nd2 = sph(eps, 1.0, m)
            w = np.cross(n, t)
            for dist in (2 * eps * w, 0.5 * eps * w, 2 * eps * t + 0.5 * n):
                add("nearly_parallel_needles", nd, nd2, [float(x) for x in dist],
                    [eps, eps, 1.0], [eps, eps, 1.0])
            add("nearly_parallel_needles", nd, nd2, None, [eps, eps, 1.0], [eps, eps, 1.0],
                target=1 + 1e-8, u=w)
    # 7: high aspect ratio spheroids (prolate and oblate)
    for rho in (10.0, 100.0, 1e3, 1e4, 1e5, 1e6):
        for kind_p in range(2):
            for _ in range(2):
                n1, n2 = random_unit(rng), random_unit(rng)
                if kind_p == 0:     # prolate: c = 1, a = 1/rho
                    qa, ra = sph(1.0 / rho, 1.0, n1), [1.0 / rho, 1.0 / rho, 1.0]
                else:               # oblate: a = 1, c = 1/rho
                    qa, ra = sph(1.0, 1.0 / rho, n1), [1.0, 1.0, 1.0 / rho]
                qb, rb = sph(1.0 / rho, 1.0, n2), [1.0 / rho, 1.0 / rho, 1.0]
                for fac in (0.01, 0.5, 1.0, 3.0):
                    add("high_aspect_spheroids", qa, qb, list(fac * random_unit(rng)), ra, rb)
                for tgt in (1 - 1e-12, 1 - 1e-6, 1 + 1e-6, 1 + 1e-12):
                    add("high_aspect_spheroids", qa, qb, None, ra, rb, target=tgt,
                        u=random_unit(rng))
    # 8: high aspect ratio general ellipsoids: semi-axes 1, rho^-1/2, rho^-1
    for rho in (10.0, 100.0, 1e3, 1e4, 1e5, 1e6):
        for _ in range(3):
            ra = [1.0, 1.0 / math.sqrt(rho), 1.0 / rho]
            rb = [1.0 / math.sqrt(rho), 1.0 / rho, 1.0]
            qa = ellipsoid_q(ra, random_rotation(rng))
            qb = ellipsoid_q(rb, random_rotation(rng))
            if not (is_spd_exact(qa) and is_spd_exact(qb)):
                continue
            for fac in (0.01, 0.5, 1.0, 3.0):
                add("high_aspect_ellipsoids", qa, qb, list(fac * random_unit(rng)), ra, rb)
            for tgt in (1 - 1e-12, 1 - 1e-6, 1 + 1e-6, 1 + 1e-12):
                add("high_aspect_ellipsoids", qa, qb, None, ra, rb, target=tgt,
                    u=random_unit(rng))
    return rows


# ---------------------------------------------------------------------------
# HDF5 output
# ---------------------------------------------------------------------------

def le_bytes(arr):
    arr = np.ascontiguousarray(arr)
    if arr.dtype.kind in "fi" and arr.dtype.byteorder == ">":
        arr = arr.astype(arr.dtype.newbyteorder("<"))
    return arr.tobytes(order="C")


def write_dset(parent, name, arr, description):
    arr = np.ascontiguousarray(arr)
    if arr.dtype.kind == "f":
        arr = arr.astype("<f8")
    elif arr.dtype.kind == "i":
        arr = arr.astype("<i4")
    kw = dict(compression="gzip", compression_opts=9, fletcher32=True, shuffle=True,
              track_times=False)
    if arr.ndim == 0 or arr.size < 2:
        kw = dict(track_times=False)
    d = parent.create_dataset(name, data=arr, **kw)
    d.attrs["description"] = description
    d.attrs["sha256"] = hashlib.sha256(le_bytes(arr)).hexdigest()
    return d


def create_group(f, name):
    gcpl = h5py.h5p.create(h5py.h5p.GROUP_CREATE)
    gcpl.set_obj_track_times(False)
    h5py.h5g.create(f.id, name.encode(), gcpl=gcpl)
    return f[name]


# ---------------------------------------------------------------------------
# Main
# ---------------------------------------------------------------------------

def run_rows(pool, func, tasks, label, chunksize=16):
    prog = Progress(label, len(tasks))
    out = []
    for res in pool.imap(func, tasks, chunksize=chunksize):
        out.append(res)
        prog.update()
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("-o", "--output",
                    default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                         "pw85_ref_data.h5"))
    ap.add_argument("--seed", type=int, default=DEFAULT_SEED)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--per-class", type=int, default=5000,
                    help="/contact pairs per class (default 5000)")
    ap.add_argument("--near-per-class", type=int, default=2000,
                    help="/near_contact pairs per class (default 2000)")
    ap.add_argument("--check-samples", type=int, default=200,
                    help="rows per group cross-checked by golden section (default 200)")
    ap.add_argument("--quick", action="store_true",
                    help="tiny sizes, for testing the generator only")
    args = ap.parse_args()
    if args.quick:
        args.per_class, args.near_per_class, args.check_samples = 50, 20, 4

    t_start = time.time()
    rng = np.random.default_rng(args.seed)
    print("generate_reference.py: seed=%d workers=%d output=%s"
          % (args.seed, args.workers, args.output), file=sys.stderr)

    # ---- pw85 layout -------------------------------------------------------
    radii = np.array([0.01999, 1.999, 9.999])
    phi = (1.0 + math.sqrt(5.0)) / 2.0
    nrm = math.sqrt(1.0 + phi * phi)
    dirs = []
    for form in range(3):
        for s1, s2 in ((1, 1), (1, -1), (-1, 1), (-1, -1)):
            v = [0.0, s1 * 1.0, s2 * phi]          # (0, +-1, +-phi)
            v = v[-form:] + v[:-form] if form else v   # cyclic shift to the right
            dirs.append([x / nrm for x in v])
    directions = np.array(dirs)
    spheroids = np.array([spheroid(float(a), float(c), n)
                          for a in radii for c in radii for n in directions])
    for q in spheroids:
        assert is_spd_exact(q)
    lambdas = np.linspace(0.0, 1.0, 11)

    ns = len(spheroids)
    F = np.empty((ns, ns, len(directions), len(lambdas)))
    fpool = multiprocessing.Pool(args.workers, initializer=_f_init,
                                 initargs=(spheroids.tolist(), directions.tolist(),
                                           lambdas.tolist()))
    prog = Progress("/F (rows i1)", ns)
    for i1, block in fpool.imap_unordered(f_block, range(ns)):
        F[i1] = block
        prog.update()
    fpool.close()
    fpool.join()
    pool = multiprocessing.Pool(args.workers)

    # ---- /contact ---------------------------------------------------------
    c_rows = []
    for cls, (lo, hi) in enumerate(CLASS_BOUNDS):
        for _ in range(args.per_class):
            ra1, q1 = random_ellipsoid(rng, lo, hi)
            ra2, q2 = random_ellipsoid(rng, lo, hi)
            scale = max(ra1) + max(ra2)
            d = math.exp(rng.uniform(math.log(0.01), math.log(10.0))) * scale
            r = [float(x) for x in d * random_unit(rng)]
            c_rows.append((cls, q1, q2, r, ra1, ra2))
    res = run_rows(pool, contact_row, [(q1, q2, r) for _, q1, q2, r, _, _ in c_rows],
                   "/contact")
    contact_data = dict(
        r12=np.array([row[3] for row in c_rows]),
        q1=np.array([row[1] for row in c_rows]),
        q2=np.array([row[2] for row in c_rows]),
        mu2=np.array([x[0] for x in res]),
        **{"lambda": np.array([x[1] for x in res])},
        mu2_str=np.array([x[2].encode() for x in res], dtype="S%d" % STR_LEN),
        **{"class": np.array([row[0] for row in c_rows], dtype=np.int32)},
        radii1=np.array([row[4] for row in c_rows]),
        radii2=np.array([row[5] for row in c_rows]))
    its = [x[3] for x in res]
    print("  /contact: %d rows, exact sign evaluations per root: mean %.1f, max %d"
          % (len(res), np.mean(its), max(its)), file=sys.stderr)

    # ---- /near_contact ----------------------------------------------------
    n_rows = []
    for cls, (lo, hi) in enumerate(CLASS_BOUNDS):
        for k in range(args.near_per_class):
            ra1, q1 = random_ellipsoid(rng, lo, hi)
            ra2, q2 = random_ellipsoid(rng, lo, hi)
            eps = 10.0 ** rng.uniform(-15.0, -2.0)
            side = -1 if k % 2 == 0 else 1
            u = [float(x) for x in random_unit(rng)]
            n_rows.append((cls, q1, q2, u, ra1, ra2, eps, side))
    res = run_rows(pool, near_contact_row,
                   [(q1, q2, u, (mpq(1) + side * mpq(eps)))
                    for _, q1, q2, u, _, _, eps, side in n_rows], "/near_contact")
    near_data = dict(
        r12=np.array([x[0] for x in res]),
        q1=np.array([row[1] for row in n_rows]),
        q2=np.array([row[2] for row in n_rows]),
        mu2=np.array([x[1] for x in res]),
        **{"lambda": np.array([x[2] for x in res])},
        mu2_str=np.array([x[3].encode() for x in res], dtype="S%d" % STR_LEN),
        **{"class": np.array([row[0] for row in n_rows], dtype=np.int32)},
        radii1=np.array([row[4] for row in n_rows]),
        radii2=np.array([row[5] for row in n_rows]),
        eps_target=np.array([row[6] for row in n_rows]),
        side_target=np.array([row[7] for row in n_rows], dtype=np.int32))
    # side statistics, from the exact (50-digit) values
    mpmath.mp.dps = 60
    wrong = []
    for i, (row, x) in enumerate(zip(n_rows, res)):
        dev = mpmath.mpf(x[3]) - 1
        if dev == 0 or (dev > 0) != (row[7] > 0):
            wrong.append((i, row[0], row[6], row[7], mpmath.nstr(dev, 5)))
    print("  /near_contact: %d rows; %d on the intended side of 1, %d not "
          "(after rounding r12 to doubles)" % (len(res), len(res) - len(wrong), len(wrong)),
          file=sys.stderr)
    for i, cls, eps, side, dev in wrong[:20]:
        print("    row %d (class %d): eps_target=%.3e, intended side %+d, mu2-1=%s"
              % (i, cls, eps, side, dev), file=sys.stderr)
    near_wrong = wrong
    rel_dev = []
    for row, x in zip(n_rows, res):
        dev = abs(mpmath.mpf(x[3]) - 1)
        rel_dev.append(float(abs(dev - row[6]) / row[6]))
    print("  /near_contact: | |mu2-1| - eps | / eps: median %.2e, max %.2e"
          % (np.median(rel_dev), max(rel_dev)), file=sys.stderr)

    # ---- /special ---------------------------------------------------------
    s_rows = special_cases(rng)
    tasks_direct = [(i, (row[1], row[2], row[3])) for i, row in enumerate(s_rows)
                    if row[3] is not None]
    tasks_near = [(i, (row[1], row[2], [float(x) for x in row[7]], mpq(row[6])))
                  for i, row in enumerate(s_rows) if row[3] is None]
    res_d = run_rows(pool, contact_row, [t for _, t in tasks_direct], "/special (direct)", 1)
    res_n = run_rows(pool, near_contact_row, [t for _, t in tasks_near],
                     "/special (near contact)", 1)
    ns_rows = len(s_rows)
    s_r12 = np.zeros((ns_rows, 3))
    s_mu2 = np.zeros(ns_rows)
    s_lam = np.zeros(ns_rows)
    s_str = [None] * ns_rows
    for (i, t), x in zip(tasks_direct, res_d):
        s_r12[i] = t[2]
        s_mu2[i], s_lam[i], s_str[i] = x[0], x[1], x[2]
    for (i, t), x in zip(tasks_near, res_n):
        s_r12[i] = x[0]
        s_mu2[i], s_lam[i], s_str[i] = x[1], x[2], x[3]
    special_data = dict(
        r12=s_r12,
        q1=np.array([row[1] for row in s_rows]),
        q2=np.array([row[2] for row in s_rows]),
        mu2=s_mu2,
        **{"lambda": s_lam},
        mu2_str=np.array([x.encode() for x in s_str], dtype="S%d" % STR_LEN),
        **{"class": np.full(ns_rows, -1, dtype=np.int32)},
        radii1=np.array([row[4] for row in s_rows]),
        radii2=np.array([row[5] for row in s_rows]),
        kind=np.array([row[0] for row in s_rows], dtype=np.int32),
        mu2_target=np.array([np.nan if row[6] is None else float(row[6]) for row in s_rows]))

    # analytic checks on /special
    mpmath.mp.dps = 80
    worst = mpmath.mpf(0)
    nsph = 0
    for i, row in enumerate(s_rows):
        kind = SPECIAL_KINDS[row[0]]
        if kind in ("equal_spheres", "very_different_spheres"):
            r = [mpmath.mpf(float(x)) for x in s_r12[i]]
            rr = sum(x * x for x in r)
            ex = rr / (mpmath.sqrt(mpmath.mpf(float(row[1][0])))
                       + mpmath.sqrt(mpmath.mpf(float(row[2][0])))) ** 2
            worst = max(worst, abs(mpmath.mpf(s_str[i]) - ex) / ex)
            nsph += 1
        if kind == "identical_ellipsoids":
            assert s_lam[i] == 0.5, s_lam[i]
        if kind == "coincident_centres":
            assert s_mu2[i] == 0.0 and math.isnan(s_lam[i])
    print("  /special: %d rows; sphere rows vs |r|^2/(sqrt(Q1_00)+sqrt(Q2_00))^2: "
          "%d rows, max rel. diff %s; identical ellipsoids: lambda* = 1/2 exactly"
          % (ns_rows, nsph, mpmath.nstr(worst, 3)), file=sys.stderr)
    assert worst < mpmath.mpf(10) ** -45

    # ---- independent cross-check (golden section, lu_solve) -------------
    srng = np.random.default_rng(args.seed + 1)
    check_tasks = []
    for gname, data in (("contact", contact_data), ("near_contact", near_data),
                        ("special", special_data)):
        n = len(data["mu2"])
        idx = srng.choice(n, size=min(args.check_samples, n), replace=False)
        for i in sorted(idx.tolist()):
            check_tasks.append((gname, i, data))
    gres = run_rows(pool, golden_mu2,
                    [(d["q1"][i].tolist(), d["q2"][i].tolist(), d["r12"][i].tolist())
                     for _, i, d in check_tasks], "cross-check (golden)", 1)
    mpmath.mp.dps = 80
    worst = mpmath.mpf(0)
    nfail = 0
    for (gname, i, d), (gm, gl) in zip(check_tasks, gres):
        ref = mpmath.mpf(d["mu2_str"][i].decode())
        gm = mpmath.mpf(gm)
        err = abs(gm - ref) / ref if ref != 0 else abs(gm)
        worst = max(worst, err)
        if err > mpmath.mpf(10) ** -40:
            nfail += 1
            print("    MISMATCH %s[%d]: %s vs %s" % (gname, i, d["mu2_str"][i].decode(),
                                                  mpmath.nstr(gm, 50)), file=sys.stderr)
    print("  cross-check: %d rows (golden section on f via mp.lu_solve, dps=%d): "
          "max rel. diff %s, %d beyond 1e-40"
          % (len(check_tasks), MP_DPS_CHECK, mpmath.nstr(worst, 3), nfail), file=sys.stderr)
    if nfail:
        sys.exit("cross-check failed")
    pool.close()
    pool.join()

    # ---- write -------------------------------------------------------------
    tmp = args.output + ".tmp"
    with h5py.File(tmp, "w", libver=("earliest", "v110"), track_order=False) as f:
        f.attrs["generator"] = GENERATOR
        f.attrs["seed"] = np.int64(args.seed)
        f.attrs["mp_dps"] = np.int64(MP_DPS_CHECK)
        f.attrs["exact_arithmetic"] = (
            "polynomial coefficients and all values exact rationals (gmpy2.mpq) of the "
            "stored doubles; lambda* on the dyadic lattice 2^-%d with verified sign "
            "change; results rounded from %d-bit values" % (NBITS, NBITS))
        f.attrs["description"] = (
            "High-precision reference values of the Perram-Wertheim contact function "
            "of two ellipsoids for libpw85. Ellipsoid {m : (m-c)^T Q^-1 (m-c) <= 1}; Q "
            "stored as its upper triangle, row-major [Q00,Q01,Q02,Q11,Q12,Q22]. "
            "f(lambda) = lambda (1-lambda) r^T Q(lambda)^-1 r, Q(lambda) = (1-lambda) Q1 + "
            "lambda Q2; mu2 = max over [0,1] of f. All results computed from the exact "
            "float64 values stored in this file. See data/README.md.")
        f.attrs["mu2_str_digits"] = np.int64(DIGITS)
        f.attrs["special_kinds"] = ",".join(SPECIAL_KINDS)

        write_dset(f, "radii", radii, "Radii used to build /spheroids, length units, "
                   "float64: [0.01999, 1.999, 9.999].")
        write_dset(f, "directions", directions,
                   "12 x 3, float64, unit vectors: vertices of a regular icosahedron. Row "
                   "4*k + j, k = 0, 1, 2 (cyclic shift of (0, s1, s2*phi) by k places to "
                   "the right: (0,s1,s2 phi), (s2 phi,0,s1), (s1,s2 phi,0)), j = 0..3 "
                   "for (s1,s2) = (+,+),(+,-),(-,+),(-,-); phi = (1+sqrt(5))/2, each "
                   "component divided by sqrt(1+phi^2) in float64.")
        write_dset(f, "spheroids", spheroids,
                   "108 x 6, float64, length^2: Q of pw85_spheroid(a, c, n) for a in "
                   "/radii (outermost), c in /radii, n in /directions (innermost): row = "
                   "36*ia + 12*ic + in. Computed in float64 exactly as the C code: "
                   "a2=a*a, c2=c*c, d=c2-a2 (evaluated first), q[0]=a2+d*n0*n0, "
                   "q[1]=d*n0*n1, q[2]=d*n0*n2, q[3]=a2+d*n1*n1, q[4]=d*n1*n2, "
                   "q[5]=a2+d*n2*n2 (products left to right, no FMA).")
        write_dset(f, "lambdas", lambdas, "11, float64, dimensionless: np.linspace(0, 1, 11).")
        write_dset(f, "F", F,
                   "108 x 108 x 12 x 11, float64, dimensionless: F[i1,i2,k,l] = "
                   "f(lambda) = lambda (1-lambda) r^T Q^-1 r with Q = (1-lambda) Q1 + "
                   "lambda Q2, Q1 = /spheroids[i1], Q2 = /spheroids[i2], r = "
                   "/directions[k], lambda = /lambdas[l]; C order. Computed in exact "
                   "rational arithmetic from the stored doubles (1-lambda exact, not "
                   "rounded) as lambda(1-lambda) r^T adj(Q) r / det(Q), then correctly "
                   "rounded to float64 (round to nearest even).")

        common = {
            "r12": "N x 3, float64, length: r12 = c2 - c1 (exact doubles used).",
            "q1": "N x 6, float64, length^2: Q1 upper triangle row-major "
                  "[Q00,Q01,Q02,Q11,Q12,Q22] (exact doubles used).",
            "q2": "N x 6, float64, length^2: Q2, same storage as q1.",
            "mu2": "N, float64, dimensionless: contact function mu^2 = max_[0,1] f, "
                   "correctly rounded (nearest even) from a 400-bit value computed from "
                   "the stored doubles.",
            "lambda": "N, float64: maximiser lambda* of f (unique root in (0,1) of the "
                      "numerator of f'), correctly rounded; NaN where r12 = 0 "
                      "(f identically 0, maximiser undefined).",
            "mu2_str": "N, fixed-length ASCII (S%d, NUL padded): mu^2 with %d "
                       "significant digits, format '%%.%de' (correctly rounded)."
                       % (STR_LEN, DIGITS, DIGITS - 1),
            "class": "N, int32: size class of the semi-axes, 0: [0.5,2], 1: [0.1,10], "
                     "2: [0.01,100], 3: [0.001,1000] (log-uniform), -1: not applicable.",
            "radii1": "N x 3, float64, length: semi-axes used to build Q1 (nominal; "
                      "Q1 itself is rounded to float64). Spheroids: (a, a, c) with a "
                      "equatorial and c polar radius.",
            "radii2": "N x 3, float64, length: semi-axes used to build Q2.",
        }
        gdesc = {
            "contact": "Random pairs of general ellipsoids (three distinct semi-axes "
                       "log-uniform in the class interval, uniform random rotation from a "
                       "normalised Gaussian quaternion, Q = R diag(a^2) R^T in float64, "
                       "exactly positive definite), %d per class; r12 = d u, u uniform "
                       "random unit vector, d log-uniform in [0.01, 10] x (max semi-axis "
                       "of 1 + max semi-axis of 2)." % args.per_class,
            "near_contact": "Random pairs as in /contact, %d per class; target mu^2 = "
                            "1 - eps (even rows) or 1 + eps (odd rows), eps log-uniform "
                            "in [1e-15, 1e-2]; r12 = s u, u random unit, s = sqrt(target/"
                            "mu2(u)) at 400 bits, each component rounded to float64; "
                            "mu2 recomputed from the stored doubles." % args.near_per_class,
            "special": "Hand-built cases (kind dataset), see its attribute 'kinds'.",
        }
        for gname, data in (("contact", contact_data), ("near_contact", near_data),
                            ("special", special_data)):
            g = create_group(f, gname)
            g.attrs["description"] = gdesc[gname]
            for key, arr in data.items():
                if key == "eps_target":
                    desc = ("N, float64: target |mu^2 - 1| (before rounding r12 to "
                            "doubles).")
                elif key == "side_target":
                    desc = "N, int32: intended side of 1: -1 (mu^2 < 1) or +1 (mu^2 > 1)."
                elif key == "kind":
                    desc = ("N, int32: kind of special case, index into the attribute "
                            "'kinds' (comma separated): " + ",".join(
                                "%d=%s" % (i, k) for i, k in enumerate(SPECIAL_KINDS)))
                elif key == "mu2_target":
                    desc = ("N, float64: target mu^2 used to scale r12 for near-contact "
                            "rows (NaN: r12 given directly).")
                else:
                    desc = common[key]
                d = write_dset(g, key, arr, desc)
                if key == "kind":
                    d.attrs["kinds"] = ",".join(SPECIAL_KINDS)
    os.replace(tmp, args.output)
    size = os.path.getsize(args.output)
    print("wrote %s (%.2f MB)" % (args.output, size / 1e6), file=sys.stderr)
    if near_wrong:
        print("note: %d near_contact rows ended on the other side of 1" % len(near_wrong),
              file=sys.stderr)
    print("total wall time: %.1f s" % (time.time() - t_start), file=sys.stderr)


if __name__ == "__main__":
    main()
