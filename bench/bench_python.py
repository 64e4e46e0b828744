#!/usr/bin/env python3
"""Cost of the Python API (package pw85) against the C calls it runs.

usage: PYTHONPATH=python PW85_LIBRARY=build/src/libpw85.so.1 \\
       [PW85_EXTENSION=build/python/_ext.cpython-311-x86_64-linux-gnu.so] \\
       /usr/bin/python3 bench/bench_python.py [--n 1000000] [--reps 7] [--pairs 1000]
       [--c-bench build/bench/bench_one_pair]
(or, after pip install ., the venv's python with no variable.)

n pairs of class-0 ellipsoids (semi-axes uniform in [0.5, 2], random
orientations; r12 normal with a scale uniform in [0.2, 3], so that about
half of the pairs overlap) held in NumPy arrays.

Per-pair calls: each round times, one thread, in the same process: the C
per-pair batch call through ctypes with raw pointers and preallocated
outputs (pw85_overlap_pairs, pw85_contact_function_pairs with
PW85_METHOD_DEFAULT), then the Python call (pw85.overlap,
pw85.contact_function with nthreads=1: argument checks, output allocation,
result conversion). Thread CPU time (time.thread_time, so that time the
machine gives to other processes is not counted) and wall time; one untimed
round, then --reps rounds; medians over the rounds and the median of the
per-round ratios Python / C.

One-pair calls: the first --pairs pairs, each a row (3,) and (6,) of the
arrays; the C program bench_one_pair (bench/bench_one_pair.c, run here on a
file of those pairs) times pw85_overlap and pw85_contact_function_method
over them, --reps passes after an untimed one; then the same passes of
Python loops `for k in range(pairs): f(r12[k], q1[k], q2[k])` calling
pw85.overlap, pw85.contact_function (through the compiled module when
present, then through ctypes), the bare ctypes calls, pypw85's
contact_function (Brent) and a no-op function (the cost of the loop and of
a Python call). The overhead of a Python call is its time per call minus
the C call's, pass by pass (median, min-max). Prints Markdown tables
(docs/performance.md). Never run by the tests (only compiled).
"""
import argparse
import ctypes
import os
import platform
import statistics
import subprocess
import tempfile
import time

import numpy as np

import pw85
import pypw85
from pw85 import _api, _lib, _native


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


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1000000)
    ap.add_argument("--reps", type=int, default=7)
    ap.add_argument("--pairs", type=int, default=1000)
    ap.add_argument("--c-bench", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                      "..", "build", "bench", "bench_one_pair"))
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
    print(f"# bench_python: n = {n}, reps = {args.reps}, pairs = {args.pairs}; "
          f"{platform.python_implementation()} {platform.python_version()}, NumPy {np.__version__}, "
          f"libpw85 {pw85.__version__} ({_lib.library_path}); compiled module: "
          f"{_native.ext.__file__ if _native.ext is not None else 'none (ctypes)'}; CPU: {cpu_model()}; "
          f"load average {', '.join(f'{x:.2f}' for x in os.getloadavg())}")
    print()
    print("| call (1 thread) | C batch call, ns/pair | Python API, ns/pair | ratio (min-max) | ratio, wall time |")
    print("|---|---|---|---|---|")
    for name, c, py, rat, lo, hi, wr in rows:
        print(f"| {name} | {c:.1f} | {py:.1f} | {rat:.3f} ({lo:.3f}-{hi:.3f}) | {wr:.3f} |")
    print()

    k = args.pairs
    c_times = c_one_pair(args.c_bench, r12[:k], q1[:k], q2[:k], args.reps)
    rs, As, Bs = list(r12[:k]), list(q1[:k]), list(q2[:k])
    resc = _lib.Result()
    byref = ctypes.byref(resc)
    raw = [(r.ctypes.data, a.ctypes.data, b.ctypes.data) for r, a, b in zip(rs, As, Bs)]
    cf_method = lib.pw85_contact_function_method
    ov_c = lib.pw85_overlap

    def loop(f):
        def run():
            for j in range(k):
                f(rs[j], As[j], Bs[j])
        return run

    def loop_raw(f):
        def run():
            for p in raw:
                f(*p)
        return run

    def ctypes_path(run):
        def without_module():
            saved, _api._ext = _api._ext, None
            try:
                run()
            finally:
                _api._ext = saved
        return without_module

    one = [
        ("pw85.overlap", "pw85_overlap", loop(pw85.overlap)),
        ("pw85.contact_function", "pw85_contact_function_method", loop(pw85.contact_function)),
        ("pw85.overlap, ctypes path", "pw85_overlap", ctypes_path(loop(pw85.overlap))),
        ("pw85.contact_function, ctypes path", "pw85_contact_function_method",
         ctypes_path(loop(pw85.contact_function))),
        ("bare ctypes pw85_overlap", "pw85_overlap", loop_raw(ov_c)),
        ("bare ctypes pw85_contact_function_method", "pw85_contact_function_method",
         loop_raw(lambda r, a, b: cf_method(r, a, b, 0, byref))),
        ("pypw85.contact_function (Brent)", None, loop(pypw85.contact_function)),
        ("no-op Python function (loop and call)", None, loop(lambda r, a, b: None)),
    ]
    print("| one-pair call | C call, ns | Python, ns per call | overhead over C, ns (min-max) |")
    print("|---|---|---|---|")
    for name, cname, run in one:
        run()
        times = []
        for _ in range(args.reps):
            t0 = time.thread_time()
            run()
            times.append((time.thread_time() - t0) / k * 1e9)
        if cname is None:
            print(f"| {name} | | {statistics.median(times):.0f} | |")
            continue
        over = [t - c for t, c in zip(times, c_times[cname])]
        print(f"| {name} | {statistics.median(c_times[cname]):.0f} | {statistics.median(times):.0f} | "
              f"{statistics.median(over):.0f} ({min(over):.0f}-{max(over):.0f}) |")
    print()
    print(f"load average at the end: {', '.join(f'{x:.2f}' for x in os.getloadavg())}")


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def c_one_pair(program, r12, q1, q2, reps):
    """ns per call of each pass of bench_one_pair over these pairs."""
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "pairs.bin")
        with open(path, "wb") as f:
            f.write(np.int64(len(r12)).tobytes())
            for x in (r12, q1, q2):
                f.write(np.ascontiguousarray(x, dtype=np.float64).tobytes())
        out = subprocess.run([program, path, str(reps)], check=True, capture_output=True,
                             text=True).stdout
    return {line.split()[0]: [float(x) for x in line.split()[1:]] for line in out.splitlines()}


if __name__ == "__main__":
    main()
