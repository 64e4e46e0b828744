#!/usr/bin/env python3
"""Writes the seed corpus of the fuzz target (tests/fuzz/corpus/), in the
input layout of fuzz_pw85.cpp: mode byte, method byte, 17 doubles (r12[3],
q1[6], q2[6], lambda, theta_tol), then (seeds of the scene, derivative and
contact-time calls) 17 more (box[6], v12[3], w1[3], w2[3], t_max, s).

usage: make_corpus.py REF_DATA.h5 OUTPUT_DIR

Seeds: 12 pairs of the reference data (/contact and /near_contact), each
also at scales 2^-900 and 2^900; r12 = 0; NaN, Inf; a non-SPD matrix;
spheres and needles of aspect 1e8 and 1e16; the constructed-matrix mode
(squared radii and angles) at scales 1, 1e-300, 1e300; every method number -1..5; periodic boxes (orthorhombic, tilted, the
extreme boxes of the red-team report: tilt 2^60, centres 2^53 apart);
contact-point and derivative pairs at size ratios 2^104..2^300 and
distances 2^499..2^512; contact times (ordinary, rotating, head-on from
2^996 and 2^997); the constructors' boundary radii; nearly singular
matrices; the scale factor of pw85_configuration_pairs below 1 and NaN."""
import math
import os
import struct
import sys

import h5py


def seed(mode, method, r, q1, q2, lam=0.5, theta=0.0, box=None, v12=(0, 0, 0),
         w1=(0, 0, 0), w2=(0, 0, 0), t_max=0.0, scale=0.0):
    vals = list(r) + list(q1) + list(q2) + [lam, theta]
    assert len(vals) == 17
    data = struct.pack("<Bb17d", mode, method, *vals)
    if box is None and mode < 16:
        return data
    more = list(box or [0] * 6) + list(v12) + list(w1) + list(w2) + [t_max, scale]
    assert len(more) == 17
    return data + struct.pack("<17d", *more)


# mode bits of fuzz_pw85.cpp
BOX, TILT, ON_X, TIME = 16, 32, 64, 128


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

    # Periodic scenes: a reference pair shifted by lattice vectors.
    with h5py.File(ref, "r") as f:
        g = f["contact"]
        r, q1, q2 = list(g["r12"][13]), list(g["q1"][13]), list(g["q2"][13])
    box = [8.0, 9.0, 10.0, 0.0, 0.0, 0.0]
    shifted = [r[0] + 16.0, r[1] - 18.0, r[2] + 30.0]
    seeds["box-orthorhombic"] = seed(BOX, 0, shifted, q1, q2, box=box, scale=1.5)
    seeds["box-tilted"] = seed(BOX | TILT, 2, shifted, q1, q2, box=[8.0, 9.0, 10.0, 0.5, -0.25, 1.0],
                               scale=2.0)
    seeds["box-tilted-on-x"] = seed(BOX | TILT | ON_X, 0, [r[0] + 24.0, 0, 0], q1, q2,
                                    box=[8.0, 9.0, 10.0, 0.5, -0.25, 1.0], scale=1.0)
    seeds["box-spheres-too-large"] = seed(BOX, 0, r, [9, 0, 0, 9, 0, 9], sphere,
                                          box=[5.0, 6.0, 7.0, 0, 0, 0], scale=1.0)
    seeds["box-invalid"] = seed(BOX | TILT, 0, r, sphere, sphere, box=[1.0, -1.0, 1.0, 0, 0, 0])
    seeds["box-tilt-overflow"] = seed(BOX | TILT, 0, r, sphere, sphere,
                                      box=[1.0, 1e300, 1.0, 1e300, 0, 0])
    # The red-team report's extreme boxes (tilt 2^60; centres 2^53 apart).
    small = [float.fromhex("0x1.d7dbf487fcb92p-9"), 0, 0, float.fromhex("0x1.d7dbf487fcb92p-9"),
             0, float.fromhex("0x1.d7dbf487fcb92p-9")]
    far = [float.fromhex("0x1.3333333333333p-2"), float.fromhex("0x1.ccccccccccccdp-1"), 0.0]
    for e in (20, 52, 60):
        seeds[f"box-tilt-pow2-{e}"] = seed(BOX | TILT, 0, far, small, small,
                                        box=[1.0, 1.0, 1.0, 2.0 ** e, 0, 0], scale=1.0)
    ball = [0.32, 0, 0, 0.32, 0, 0.32]  # the report's pair: mu^2 = 1.5625 at the image (-1, 0, 0)
    seeds["box-centres-pow2-53"] = seed(BOX | ON_X, 0, [2.0 ** 53, 0, 0], ball, ball,
                                     box=[3.0, 3.0, 3.0, 0, 0, 0], scale=1.0)
    seeds["box-tilt-100-far"] = seed(BOX | TILT, 0, [1.3e6 + 0.3, -2.1e6 - 0.1, 0.7e6 + 0.2], small, small,
                                     box=[1.0, 1.0, 1.0, 100.0, -100.0, 100.0], scale=1.0)

    # Tilts that make the wrap need more than 2^50 lattice vectors along a2
    # (a refused pair, PW85_ERR_INVALID_ARGUMENT).
    seeds["box-tilt-count-limit"] = seed(BOX | TILT, 0, [1.3e6 + 0.3, -2.1e6 - 0.1, 0.7e6 + 0.2],
                                         small, small,
                                         box=[1.0, 1.0, 1.0, 100.0, 1.8e11, 1.7e69], scale=1.0)

    # Contact point and derivatives at size ratios 2^k (the report's r12).
    r4 = [float.fromhex("-0x1.603d97098ec97p-3"), float.fromhex("0x1.087c848e777b7p-1"),
          float.fromhex("-0x1.0cdcb891621c6p+1")]
    for k in (104, 150, 300):
        seeds[f"ratio-pow2-{k}"] = seed(0, 0, r4, q1, [x * 2.0 ** k for x in q2])
    # Unit spheres far apart: the derivatives' far-pair range.
    for k in (499, 512, 1000):
        seeds[f"spheres-pow2-{k}"] = seed(0, 0, [2.0 ** k, 0, 0], sphere, sphere)

    # Contact times: ordinary, rotating, head-on from far away.
    seeds["time-approach"] = seed(TIME, 0, r, q1, q2, v12=[-x for x in r], t_max=2.0)
    seeds["time-rotating"] = seed(TIME, 0, [2.5, 0.3, -0.2], [4, 0, 0, 0.25, 0, 1], sphere,
                                  v12=[-1.0, 0, 0], w1=[0, 0, 3.0], w2=[1.0, 0, 0], t_max=3.0)
    seeds["time-invalid-horizon"] = seed(TIME, 0, r, sphere, sphere, v12=[-1, 0, 0], t_max=-1.0)
    for e in (996, 997):
        seeds[f"time-head-on-pow2-{e}"] = seed(TIME, 0, [2.0 ** e, 0, 0], sphere, sphere,
                                            v12=[-1.0, 0, 0], t_max=2.0 ** 998)

    # Constructors (r12 = radii, q1 and q2[0:3] = axes, q2[0:4] = quaternion):
    # positive radii whose Q does not round to positive definite; radii
    # 2^500, 2^-500, 1 with the identity.
    axes_q1, axes_q2 = [1.0, 0, 0, 0, 1.0, 0], [0, 0, 1.0, 0, 0, 0]
    tiny = [float.fromhex("0x1.9c77c2b8fa4bcp-106"), float.fromhex("0x1.367e751f48531p+0"),
            float.fromhex("0x1.5b45212ad5b4cp+4")]
    seeds["radii-tiny"] = seed(0, 0, tiny, axes_q1, axes_q2)
    seeds["radii-pow2-500"] = seed(0, 0, [2.0 ** 500, 2.0 ** -500, 1.0], axes_q1, axes_q2)

    # Nearly singular matrices (the report's q1, det = +2.8e-35; v v^T + eps I).
    q_det = [float.fromhex(x) for x in ("0x1.3d309aa66da1cp-1", "-0x1.b79b0ccb151b3p-2",
                                        "-0x1.d0635705bd7b9p-3", "0x1.30a21b072a3bcp-2",
                                        "0x1.41ce80f19c03p-3", "0x1.53f2beafea01dp-4")]
    seeds["nearly-singular-report"] = seed(0, 0, [0.3, -0.2, 0.9], q_det, [1, 0.2, 0, 0.5, 0, 0.7])
    v = [0.6, -0.48, 0.64]
    for e in (-15, -17, -20):
        qs = [v[i] * v[j] + (10.0 ** e if i == j else 0.0) for i in range(3) for j in range(i, 3)]
        seeds[f"nearly-singular-1e{e}"] = seed(0, 0, [0.1, 0.8, -0.3], qs, sphere)

    # Overlapping pairs whose support values overflow in the configuration's
    # plane test (k = 341 ... 500 of test-configuration's huge_matrices).
    base1, base2 = [2.0, -1.0, 0.5, 2.0, -0.7, 2.0], [1.5, 0.6, -0.4, 2.5, 0.3, 1.0]
    for k in (341, 400):
        seeds[f"configuration-huge-pow2-{k}"] = seed(0, 0, [1.0, 2.0, 0.0],
                                                     [x * 2.0 ** k for x in base1],
                                                     [x * 2.0 ** k for x in base2])

    # pw85_configuration_pairs: s below 1 and NaN (call errors).
    seeds["configuration-scale-below-1"] = seed(BOX, 0, r, q1, q2, box=box, scale=0.5)
    seeds["configuration-scale-nan"] = seed(BOX, 0, r, q1, q2, box=box, scale=math.nan)
    for name, data in seeds.items():
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)
    print(f"{len(seeds)} seeds written to {out}")


if __name__ == "__main__":
    main()
