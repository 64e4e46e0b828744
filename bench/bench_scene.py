#!/usr/bin/env python3
"""Overlapping pairs of N ellipsoids in a periodic box from Python:
pw85.Scene against scipy's cKDTree (docs/performance.md, section "Scene").

usage: PYTHONPATH=python PW85_LIBRARY=build/src/libpw85.so.1 \\
       /usr/bin/python3 bench/bench_scene.py [--n 10000,100000] [--reps 5] [--sweeps 3]

Configuration (no overlapping pair): spheroids of semi-axes (1, 1, 3) on a
face-centred cubic lattice stretched by 3 along z at volume fraction 0.45
in an orthorhombic periodic box, then --sweeps Monte Carlo sweeps through
pw85.Scene.test_move and move (as bench/bench_scene.c). Each round, one
thread, the same NumPy arrays:
  - scene: pw85.Scene(centres, q, box).overlapping_pairs(nthreads=1)
    (construction included);
  - kdtree: scipy.spatial.cKDTree(centres wrapped into [0, L), boxsize=L)
    .query_pairs(2 R) (R the largest semi-axis), then pw85.scene_overlap
    on those pairs (nthreads=1).
Both give the same pairs (none); thread CPU time per particle, median (min,
max) of --reps rounds after one untimed round, and the median of the
per-round ratios kdtree / scene. Needs scipy (Debian python3-scipy).
"""
import argparse
import os
import platform
import statistics
import time

import numpy as np

import pw85


def lattice(nwant, aspect=3.0, phi=0.45, sweeps=3, seed=1):
    m = max(2, round((nwant / 4) ** (1 / 3)))
    d = (16 * np.pi / (3 * phi)) ** (1 / 3)
    basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]]) + 0.25
    cells = np.stack(np.meshgrid(*(np.arange(m),) * 3, indexing="ij"), -1).reshape(-1, 1, 3)
    f = (cells + basis).reshape(-1, 3)
    centres = f * np.array([d, d, d * aspect])
    box = np.array([m * d, m * d, m * d * aspect, 0, 0, 0])
    n = len(centres)
    radii = np.array([1.0, 1.0, aspect])
    quat = np.tile([1.0, 0, 0, 0], (n, 1))
    scene = pw85.Scene.from_axes(centres, radii, quat, box)
    rng = np.random.default_rng(seed)
    step = 0.3 * (d - 2) + 0.05
    for _ in range(sweeps):
        dc = step * (rng.random((n, 3)) - 0.5)
        dq = 0.3 * (rng.random((n, 4)) - 0.5)
        for i in range(n):
            qn = quat[i] + dq[i]
            qn /= np.linalg.norm(qn)
            qi = pw85.ellipsoid_quat(radii, qn)
            c = scene.centres[i] + dc[i]
            if scene.test_move(i, c, qi) < 0:
                scene.move(i, c, qi)
                quat[i] = qn
    return np.array(scene.centres), np.array(scene.q), box, aspect


def run_scene(centres, q, box):
    with pw85.Scene(centres, q, box) as s:
        i, j = s.overlapping_pairs(nthreads=1)
    return len(i)


def run_kdtree(centres, q, box, reach):
    from scipy.spatial import cKDTree
    L = box[:3]
    wrapped = centres - np.floor(centres / L) * L
    wrapped[wrapped >= L] = 0.0  # floor rounding at the upper face
    tree = cKDTree(wrapped, boxsize=L)
    pairs = tree.query_pairs(reach, output_type="ndarray")
    if len(pairs) == 0:
        return 0
    return int(np.count_nonzero(pw85.scene_overlap(centres, q, pairs, box, nthreads=1)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", default="10000,100000")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--sweeps", type=int, default=3)
    args = ap.parse_args()
    print(f"CPU: {platform.processor() or platform.machine()}, load {os.getloadavg()}")
    print("| N | pw85.Scene (ns/particle) | cKDTree + scene_overlap (ns/particle) | ratio |")
    print("|---|---|---|---|")
    for n in (int(x) for x in args.n.split(",")):
        centres, q, box, aspect = lattice(n, sweeps=args.sweeps)
        reach = 2 * aspect
        ts, tk, ratio = [], [], []
        for r in range(args.reps + 1):
            t0 = time.thread_time()
            a = run_scene(centres, q, box)
            t1 = time.thread_time()
            b = run_kdtree(centres, q, box, reach)
            t2 = time.thread_time()
            assert a == b, (a, b)
            if r == 0:
                continue
            ts.append((t1 - t0) / len(centres) * 1e9)
            tk.append((t2 - t1) / len(centres) * 1e9)
            ratio.append((t2 - t1) / (t1 - t0))
        fmt = lambda v: f"{statistics.median(v):.0f} ({min(v):.0f}-{max(v):.0f})"
        print(f"| {len(centres)} | {fmt(ts)} | {fmt(tk)} | "
              f"{statistics.median(ratio):.2f} ({min(ratio):.2f}-{max(ratio):.2f}) |")
    print(f"load after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
