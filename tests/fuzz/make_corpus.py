#!/usr/bin/env python3
"""Writes the seed corpus of the fuzz target (tests/fuzz/corpus/), in the
input layout of fuzz_pw85.cpp: mode byte, method byte, 17 doubles (r12[3],
q1[6], q2[6], lambda, theta_tol).

usage: make_corpus.py REF_DATA.h5 OUTPUT_DIR

Seeds: 12 pairs of the reference data (/contact and /near_contact), each
also at scales 2^-900 and 2^900; r12 = 0; NaN, Inf; a non-SPD matrix;
spheres and needles of aspect 1e8 and 1e16; the constructed-matrix mode
(squared radii and angles) at scales 1, 1e-300, 1e300; every method number -1..5."""
import math
import os
import struct
import sys

import h5py


def seed(mode, method, r, q1, q2, lam=0.5, theta=0.0):
    vals = list(r) + list(q1) + list(q2) + [lam, theta]
    assert len(vals) == 17
    return struct.pack("<Bb17d", mode, method, *vals)


def main():
    ref, out = sys.argv[1:3]
    os.makedirs(out, exist_ok=True)
    seeds = {}
    with h5py.File(ref, "r") as f:
        for group in ("contact", "near_contact"):
            g = f[group]
            n = g["r12"].shape[0]
            for k in range(6):
                i = (k * 7919 + 13) % n
                r, q1, q2 = g["r12"][i], g["q1"][i], g["q2"][i]
                seeds[f"{group}-{i}"] = seed(0, k % 5, r, q1, q2, 0.25, 1e-6)
                if k < 2:
                    for e in (-900, 900):
                        s, t = 2.0 ** e, 2.0 ** (e // 2)
                        seeds[f"{group}-{i}-scale{e}"] = seed(
                            0, 0, [x * t for x in r], [x * s for x in q1], [x * s for x in q2])
    sphere = [1.0, 0.0, 0.0, 1.0, 0.0, 1.0]
    r = [0.7, -0.7, 1.1]
    seeds["r12-zero"] = seed(4, 0, r, sphere, [25, 0, 0, 0.25, 0, 0.25])
    seeds["nan-r12"] = seed(0, 0, [math.nan, 0, 0], sphere, sphere)
    seeds["nan-q2"] = seed(0, 1, r, sphere, [1, math.nan, 0, 1, 0, 1])
    seeds["inf-q1"] = seed(0, 2, r, [math.inf, 0, 0, 1, 0, 1], sphere)
    seeds["nan-lambda"] = seed(0, 3, r, sphere, sphere, math.nan, math.nan)
    seeds["not-spd"] = seed(0, 0, r, [1, 2, 0, 1, 0, 1], sphere)
    seeds["tangent-spheres"] = seed(0, 0, [2.0, 0, 0], sphere, sphere)
    for a in (1e8, 1e16):
        needle = [a * a, 0, 0, 1, 0, 1]
        disc = [1 / (a * a), 0, 0, 1, 0, 1]
        seeds[f"needle-disc-{a:g}"] = seed(0, 0, [0.5, 0.5, 0.5], needle, disc)
        seeds[f"needles-{a:g}"] = seed(8, 4, [0.5, 1e-3, 0], needle, needle)
    for e, name in ((1.0, "unit"), (1e-300, "tiny"), (1e300, "huge")):
        # constructed mode: squared radii, then three angles
        seeds[f"built-{name}"] = seed(3, 0, [1.0, 2.0, 3.0],
                                      [e, 2.0 * e, 0.5 * e, 0.3, 1.1, 2.0],
                                      [e, 4.0 * e, e, 2.5, 0.1, 0.7])
    for m in range(-1, 6):
        seeds[f"method{m}"] = seed(0, m, r, [100, 0, 0, 100, 0, 0.01], [25, 0, 0, 0.25, 0, 0.25])
    seeds["short"] = b"\x00"
    for name, data in seeds.items():
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)
    print(f"{len(seeds)} seeds written to {out}")


if __name__ == "__main__":
    main()
