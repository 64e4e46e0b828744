#!/usr/bin/env python3
"""Cost of the Python API (package pw85) against the C batch call it runs.

usage: PYTHONPATH=python PW85_LIBRARY=build/src/libpw85.so.1 \\
       /usr/bin/python3 bench/bench_python.py [--n 1000000] [--reps 7] [--calls 20000]

n pairs of class-0 ellipsoids (semi-axes uniform in [0.5, 2], random
orientations; r12 normal with a scale uniform in [0.2, 3], so that about
half of the pairs overlap) held in NumPy arrays. Each round times, one
thread, in the same process: the C per-pair batch call through ctypes with
raw pointers and preallocated outputs (pw85_overlap_pairs,
pw85_contact_function_pairs with PW85_METHOD_DEFAULT), then the Python call
(pw85.overlap, pw85.contact_function with nthreads=1: argument checks,
output allocation, result conversion). Thread CPU time (time.thread_time,
so that time the machine gives to other processes is not counted) and wall
time; one untimed round, then --reps rounds; medians over the rounds and the
median of the per-round ratios Python / C. Then the cost of one-pair calls
(--calls calls, thread CPU time per call, best of 5 passes) of pw85 and
pypw85, and of the bare ctypes call for reference. Prints a Markdown table
(docs/python.md). Never run by the tests (only compiled).
"""
import argparse
import ctypes
import os
import platform
import statistics
import time

import numpy as np

import pw85
import pypw85
from pw85 import _lib


def pairs(n, seed=1):
    rng = np.random.default_rng(seed)

    def ell():
        axes = np.linalg.qr(rng.normal(size=(n, 3, 3)))[0]
        return pw85.ellipsoid(rng.uniform(0.5, 2, (n, 3)), axes)
    r12 = rng.normal(size=(n, 3)) * rng.uniform(0.2, 3, (n, 1))
    return np.ascontiguousarray(r12), ell(), ell()


def timed(f):
    c0, w0 = time.thread_time(), time.perf_counter()
    f()
    return time.thread_time() - c0, time.perf_counter() - w0


def per_call(f, calls):
    best = float("inf")
    for _ in range(5):
        c0 = time.thread_time()
        for _ in range(calls):
            f()
        best = min(best, (time.thread_time() - c0) / calls)
    return best * 1e6


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1000000)
    ap.add_argument("--reps", type=int, default=7)
    ap.add_argument("--calls", type=int, default=20000)
    args = ap.parse_args()
    n = args.n
    r12, q1, q2 = pairs(n)
    lib = _lib.lib
    ov = np.empty(n, np.intc)
    st = np.empty(n, np.intc)
    res = np.empty(n, pw85.RESULT_DTYPE)
    p = [x.ctypes.data for x in (r12, q1, q2, ov, st, res)]
    groups = {
        "overlap": (lambda: lib.pw85_overlap_pairs(n, p[0], p[1], p[2], p[3], p[4], 1),
                    lambda: pw85.overlap(r12, q1, q2, nthreads=1)),
        "contact_function (DEFAULT)": (
            lambda: lib.pw85_contact_function_pairs(n, p[0], p[1], p[2], 0, p[5], p[4], 1),
            lambda: pw85.contact_function(r12, q1, q2, nthreads=1)),
    }
    rows = []
    for name, (c_call, py_call) in groups.items():
        assert c_call() == 0
        py_out = py_call()
        if name == "overlap":
            assert np.array_equal(py_out, ov > 0)
        else:
            assert np.array_equal(py_out[0], res["mu2"])
        cpu = {"C": [], "Python": []}
        wall = {"C": [], "Python": []}
        for rnd in range(args.reps + 1):
            for label, f in (("C", c_call), ("Python", py_call)):
                c, w = timed(f)
                if rnd:
                    cpu[label].append(c / n * 1e9)
                    wall[label].append(w / n * 1e9)
        ratios = [b / a for a, b in zip(cpu["C"], cpu["Python"])]
        wratios = [b / a for a, b in zip(wall["C"], wall["Python"])]
        rows.append((name, statistics.median(cpu["C"]), statistics.median(cpu["Python"]),
                     statistics.median(ratios), min(ratios), max(ratios),
                     statistics.median(wratios)))
    r, a, b = r12[0], q1[0], q2[0]
    raw = [x.ctypes.data for x in (r, a, b)]
    resc = _lib.Result()
    one = [
        ("pw85.overlap, one pair", lambda: pw85.overlap(r, a, b)),
        ("pw85.contact_function, one pair", lambda: pw85.contact_function(r, a, b)),
        ("pypw85.contact_function (Brent)", lambda: pypw85.contact_function(r, a, b)),
        ("bare ctypes pw85_overlap", lambda: lib.pw85_overlap(*raw)),
        ("bare ctypes pw85_contact_function_method", lambda: lib.pw85_contact_function_method(
            raw[0], raw[1], raw[2], 0, ctypes.byref(resc))),
    ]
    print(f"# bench_python: n = {n}, reps = {args.reps}, calls = {args.calls}; "
          f"{platform.python_implementation()} {platform.python_version()}, NumPy {np.__version__}, "
          f"libpw85 {pw85.__version__} ({_lib.library_path}); load average "
          f"{', '.join(f'{x:.2f}' for x in os.getloadavg())}")
    print()
    print("| call (1 thread) | C batch call, ns/pair | Python API, ns/pair | ratio (min-max) | ratio, wall time |")
    print("|---|---|---|---|---|")
    for name, c, py, rat, lo, hi, wr in rows:
        print(f"| {name} | {c:.1f} | {py:.1f} | {rat:.3f} ({lo:.3f}-{hi:.3f}) | {wr:.3f} |")
    print()
    print("| one-pair call | µs per call |")
    print("|---|---|")
    for name, f in one:
        print(f"| {name} | {per_call(f, args.calls):.2f} |")


if __name__ == "__main__":
    main()
