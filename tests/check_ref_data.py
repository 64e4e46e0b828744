#!/usr/bin/python3
"""Integrity check of the libpw85 reference data set (data/pw85_ref_data.h5).

Usage::

    /usr/bin/python3 tests/check_ref_data.py PATH_TO_H5 [--samples N] [--seed S]

1. every dataset's ``sha256`` attribute is compared with the SHA-256 of its
   raw little-endian C-order bytes;
2. a random sample of /F entries is recomputed with mpmath (mp.dps = 60,
   Q^-1 r by mp.lu_solve, i.e. without the adjugate/determinant route of the
   generator); the stored float64 must be the correctly rounded value
   (|stored - exact| <= 1/2 ulp);
3. a random sample of rows of /contact, /near_contact and /special is
   recomputed (mp.dps = 80): bisection on the sign of f' followed by a
   safeguarded Newton iteration on f'(lambda) = 0, where f' and f'' are
   evaluated with mp.lu_solve; the 50-digit ``mu2_str`` must agree to 1e-40
   relative (exactly 0 when r12 = 0), ``mu2`` and ``lambda`` must be the
   correctly rounded float64 values (lambda NaN when r12 = 0).

The sample is seeded by the current time unless --seed is given; the seed is
printed.  Exit status: 0 on success, 1 on any mismatch, 77 (skip) when
mpmath, numpy or h5py is not installed.
"""

import argparse
import hashlib
import math
import sys
import time

try:
    import numpy as np
except ImportError:
    print("SKIP: python3-numpy not installed")
    sys.exit(77)
try:
    import h5py
except ImportError:
    print("SKIP: python3-h5py not installed")
    sys.exit(77)
try:
    import mpmath
    from mpmath import mp, mpf
except ImportError:
    print("SKIP: python3-mpmath not installed")
    sys.exit(77)

IDX = ((0, 1, 2), (1, 3, 4), (2, 4, 5))
REL_TOL = mpf(10) ** -40


def sym(q):
    return mpmath.matrix([[mpf(float(q[IDX[i][j]])) for j in range(3)] for i in range(3)])


def vec(r):
    return mpmath.matrix([mpf(float(x)) for x in r])


def dot(x, y):
    return sum(x[i] * y[i] for i in range(3))


def is_nearest(stored, exact):
    """True if the float64 ``stored`` is a nearest double of ``exact``."""
    stored = float(stored)
    if exact == 0:
        return stored == 0.0
    if not math.isfinite(stored):
        return False
    half_ulp = mpf(np.spacing(abs(stored))) / 2
    return abs(mpf(stored) - exact) <= half_ulp * (1 + mpf(10) ** -20)


def f_value(lam, Q1, Q2, r):
    Q = (1 - lam) * Q1 + lam * Q2
    return lam * (1 - lam) * dot(r, mpmath.lu_solve(Q, r))


def derivatives(lam, Q1, Q2, r):
    """f, f', f'' at lam (Cholesky-free formulas with s = Q^-1 r)."""
    Q = (1 - lam) * Q1 + lam * Q2
    s = mpmath.lu_solve(Q, r)
    u = (Q2 - Q1) * s
    v = mpmath.lu_solve(Q, u)
    rs, su, uv = dot(r, s), dot(s, u), dot(u, v)
    w = lam * (1 - lam)
    return (w * rs, (1 - 2 * lam) * rs - w * su,
            -2 * rs - 2 * (1 - 2 * lam) * su + 2 * w * uv)


def contact_mp(q1, q2, r12):
    """(mu2, lambda*) by bisection + safeguarded Newton on f' (mp.dps = 80)."""
    mp.dps = 80
    Q1, Q2, r = sym(q1), sym(q2), vec(r12)
    if all(float(x) == 0.0 for x in r12):
        return mpf(0), None
    lo, hi = mpf(0), mpf(1)
    lam = mpf(1) / 2
    for _ in range(20):                # coarse bisection on the sign of f'
        lam = (lo + hi) / 2
        _, fp, _ = derivatives(lam, Q1, Q2, r)
        if fp == 0:
            lo = hi = lam
            break
        if fp > 0:
            lo = lam
        else:
            hi = lam
    tol = mpf(10) ** -75
    for _ in range(200):               # safeguarded Newton
        _, fp, fpp = derivatives(lam, Q1, Q2, r)
        if fp == 0:
            break
        if fp > 0:
            lo = max(lo, lam)
        else:
            hi = min(hi, lam)
        new = lam - fp / fpp if fpp != 0 else (lo + hi) / 2
        if not (lo <= new <= hi):
            new = (lo + hi) / 2
        if abs(new - lam) <= tol * abs(lam) or hi - lo <= tol * abs(lam):
            lam = new
            break
        lam = new
    return f_value(lam, Q1, Q2, r), lam


def check_sha256(f):
    bad, n = [], [0]

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset):
            n[0] += 1
            arr = np.ascontiguousarray(obj[()])
            if arr.dtype.kind in "fiu" and arr.dtype.byteorder == ">":
                arr = arr.astype(arr.dtype.newbyteorder("<"))
            h = hashlib.sha256(arr.tobytes(order="C")).hexdigest()
            ref = obj.attrs.get("sha256")
            if isinstance(ref, bytes):
                ref = ref.decode()
            if ref != h:
                bad.append(name)
            if "description" not in obj.attrs:
                bad.append(name + " (no description)")

    f.visititems(visit)
    return n[0], bad


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("path")
    ap.add_argument("--samples", type=int, default=100,
                    help="rows sampled per mu2 group (default 100; /F: 3x as many)")
    ap.add_argument("--seed", type=int, default=None)
    args = ap.parse_args()
    seed = int(time.time()) if args.seed is None else args.seed
    print("# check_ref_data.py: %s, seed = %d (rerun with --seed %d), samples = %d"
          % (args.path, seed, seed, args.samples))
    rng = np.random.default_rng(seed)
    t0 = time.time()
    results = []

    def report(ok, name, detail=""):
        results.append(ok)
        print("%s %d - %s%s" % ("ok" if ok else "not ok", len(results), name,
                                (": " + detail) if detail else ""))
        sys.stdout.flush()

    with h5py.File(args.path, "r") as f:
        n, bad = check_sha256(f)
        report(not bad and n > 0, "sha256 of %d datasets" % n,
               ("mismatch: " + ", ".join(bad)) if bad else "")

        # ---- /F --------------------------------------------------------
        mp.dps = 60
        sph, dirs, lams = f["spheroids"][()], f["directions"][()], f["lambdas"][()]
        F = f["F"]
        shape = F.shape
        ok = shape == (len(sph), len(sph), len(dirs), len(lams))
        worst = mpf(0)
        fails = []
        for _ in range(3 * args.samples):
            i1, i2, k, l = (int(rng.integers(0, m)) for m in shape)
            lam = mpf(float(lams[l]))
            ex = f_value(lam, sym(sph[i1]), sym(sph[i2]), vec(dirs[k]))
            st = float(F[i1, i2, k, l])
            if ex != 0:
                worst = max(worst, abs(mpf(st) - ex) / abs(ex))
            if not is_nearest(st, ex):
                fails.append("F[%d,%d,%d,%d]=%r exact %s" % (i1, i2, k, l, st,
                                                              mpmath.nstr(ex, 25)))
        report(ok and not fails, "/F: %d entries correctly rounded (max rel. diff %s)"
               % (3 * args.samples, mpmath.nstr(worst, 3)), "; ".join(fails[:5]))

        # ---- mu2 groups ----------------------------------------------
        for gname in ("contact", "near_contact", "special"):
            g = f[gname]
            N = g["mu2"].shape[0]
            idx = sorted(rng.choice(N, size=min(args.samples, N), replace=False).tolist())
            q1, q2, r12 = g["q1"][()], g["q2"][()], g["r12"][()]
            mu2, lam_st, mu2s = g["mu2"][()], g["lambda"][()], g["mu2_str"][()]
            fails = []
            worst = mpf(0)
            for i in idx:
                m, lam = contact_mp(q1[i], q2[i], r12[i])
                mp.dps = 80
                s = mpf(mu2s[i].decode())
                if m == 0:
                    good = s == 0 and mu2[i] == 0.0 and math.isnan(lam_st[i])
                else:
                    err = abs(s - m) / m
                    worst = max(worst, err)
                    good = (err <= REL_TOL and is_nearest(mu2[i], m)
                            and is_nearest(lam_st[i], lam))
                if not good:
                    fails.append("%s[%d]: stored %s / %r / lambda %r, recomputed %s / %s"
                                 % (gname, i, mu2s[i].decode(), float(mu2[i]),
                                    float(lam_st[i]), mpmath.nstr(m, 50),
                                    mpmath.nstr(lam, 20) if lam is not None else "nan"))
            report(not fails, "/%s: %d rows, mu2_str rel. diff <= %s, mu2 and lambda "
                   "correctly rounded" % (gname, len(idx), mpmath.nstr(worst, 3)),
                   "; ".join(fails[:5]))

    npass = sum(results)
    print("1..%d" % len(results))
    print("# %s: %d/%d checks passed in %.1f s (seed %d)"
          % ("PASS" if npass == len(results) else "FAIL", npass, len(results),
             time.time() - t0, seed))
    sys.exit(0 if npass == len(results) else 1)


if __name__ == "__main__":
    main()
