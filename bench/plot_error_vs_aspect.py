#!/usr/bin/python3
"""Error of mu^2 against the aspect ratio, one panel per method.

    /usr/bin/python3 bench/plot_error_vs_aspect.py build/src/libpw85.so

Pairs: two needles (semi-axes 1, 1/k, 1/k) or two discs (1, 1, 1/k), or a
needle and a disc, with random orientations (seeded) and random centre
distances from overlap to apart, k = 10^(i/2), i = 0..12. Each pair goes
through pw85_contact_function_method (ctypes) with every method; the
reference mu^2 is computed with mpmath at 50 digits from the exact double
inputs (bisection on the sign of f', 120 halvings). Writes
docs/error_vs_aspect.png and docs/error_vs_aspect.csv (one row per pair and
method: method, shapes, k, status, relative error, mu2_error / mu2).
Filled markers: status PW85_OK; open markers: a non-zero status (the method
reported its failure).
"""
import csv
import ctypes
import math
import os
import random
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from mpmath import lu_solve, matrix, mp, mpf  # noqa: E402

mp.dps = 50
HERE = os.path.dirname(os.path.abspath(__file__))
DOCS = os.path.join(HERE, os.pardir, "docs")
METHODS = [("DEFAULT", 0, 1e-14), ("BRENT", 1, 1e-10), ("NEWTON", 2, 1e-12),
           ("RATIONAL", 3, 1e-12), ("ZHENG", 4, 1e-9)]
FLOOR = 1e-18


class Result(ctypes.Structure):
    _fields_ = [("mu2", ctypes.c_double), ("lambda_", ctypes.c_double),
                ("mu2_error", ctypes.c_double), ("iterations", ctypes.c_int),
                ("method", ctypes.c_int)]


def rotation(rng):
    w, x, y, z = (rng.gauss(0, 1) for _ in range(4))
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def quad_form(radii, rot):
    q = []
    for i in range(3):
        for j in range(i, 3):
            q.append(sum(radii[k] ** 2 * rot[i][k] * rot[j][k] for k in range(3)))
    return q


def ref_mu2(r, q1, q2):
    def sym(v):
        return matrix([[v[0], v[1], v[2]], [v[1], v[3], v[4]], [v[2], v[4], v[5]]])
    R = matrix([mpf(x) for x in r])
    Q1, Q2 = sym([mpf(x) for x in q1]), sym([mpf(x) for x in q2])
    D = Q2 - Q1
    lo, hi = mpf(0), mpf(1)

    def ev(lam):
        s = lu_solve((1 - lam) * Q1 + lam * Q2, R)
        phi = (R.T * s)[0]
        p = lam * (1 - lam)
        return p * phi, (1 - 2 * lam) * phi - p * (s.T * D * s)[0]
    for _ in range(120):
        m = (lo + hi) / 2
        if ev(m)[1] > 0:
            lo = m
        else:
            hi = m
    return ev((lo + hi) / 2)[0]


def main():
    lib = ctypes.CDLL(sys.argv[1])
    D3, D6 = ctypes.c_double * 3, ctypes.c_double * 6
    lib.pw85_contact_function_method.restype = ctypes.c_int
    rng = random.Random(20260521)
    rows = []
    shapes = {"needle": lambda k: (1.0, 1.0 / k, 1.0 / k), "disc": lambda k: (1.0, 1.0, 1.0 / k)}
    combos = [("needle", "needle"), ("disc", "disc"), ("needle", "disc")]
    for i in range(13):
        k = 10 ** (i / 2)
        for s1, s2 in combos:
            for rep in range(5):
                q1 = quad_form(shapes[s1](k), rotation(rng))
                q2 = quad_form(shapes[s2](k), rotation(rng))
                d = 2.0 * 10 ** rng.uniform(-2, 0.5)
                v = [rng.gauss(0, 1) for _ in range(3)]
                n = math.sqrt(sum(x * x for x in v))
                r = [d * x / n for x in v]
                ref = ref_mu2(r, q1, q2)
                for name, mid, acc in METHODS:
                    res = Result()
                    st = lib.pw85_contact_function_method(D3(*r), D6(*q1), D6(*q2), mid,
                                                          ctypes.byref(res))
                    if st == -5:
                        continue
                    err = float(abs(mpf(res.mu2) - ref) / ref) if res.mu2 == res.mu2 else float("nan")
                    rows.append((name, s1 + "-" + s2, k, st, err, res.mu2_error / res.mu2))
    with open(os.path.join(DOCS, "error_vs_aspect.csv"), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["method", "shapes", "aspect", "status", "rel_err", "rel_err_estimate"])
        w.writerows(rows)
    names = [m for m in METHODS if any(r[0] == m[0] for r in rows)]
    fig, axes = plt.subplots(1, len(names), figsize=(4 * len(names), 4), sharey=True)
    for ax, (name, _, acc) in zip(axes, names):
        for combo, marker in zip(["needle-needle", "disc-disc", "needle-disc"], "o^s"):
            sub = [r for r in rows if r[0] == name and r[1] == combo]
            ok = [r for r in sub if r[3] == 0]
            bad = [r for r in sub if r[3] != 0]
            ax.scatter([r[2] for r in ok], [max(r[4], FLOOR) for r in ok], marker=marker, s=18,
                       label=combo + " (OK)")
            ax.scatter([r[2] for r in bad], [max(r[4], FLOOR) for r in bad], marker=marker, s=26,
                       facecolors="none", edgecolors="k", label=combo + " (flagged)")
        ax.axhline(acc, color="r", ls=":", lw=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(FLOOR / 3, 10)
        ax.set_title("%s (documented accuracy %.0e, red)" % (name, acc), fontsize=9)
        ax.set_xlabel("aspect ratio k")
        ax.grid(True, which="both", lw=0.3)
    axes[0].set_ylabel("relative error of mu^2 (vs mpmath, 50 digits)")
    axes[-1].legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    out = os.path.join(DOCS, "error_vs_aspect.png")
    fig.savefig(out, dpi=100)
    print("wrote", out, "and error_vs_aspect.csv,", len(rows), "rows")


if __name__ == "__main__":
    main()
