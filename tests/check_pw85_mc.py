#!/usr/bin/env python3
"""Outputs of pw85_mc (docs/usage.md): options, XYZ and GSD files, step
tuning, nematic order parameter.

usage: check_pw85_mc.py PW85_MC PW85

The GSD file (a frame at sweep 0 and one per block, S2 logged as
log/pw85/S2) is read back with python3-gsd (its C reader gsd.fl through
gsd.hoomd, and its pure-Python reader gsd.pygsd); the XYZ file is parsed
here. No pair of the last XYZ frame (doubles) may overlap, checked by the
pw85 program's batch mode (exact predicate, mu^2 >= 1); the GSD frame
(float32, positions rounded to about 4e-7 relative to the box) must give
mu^2 > 1 - 1e-4. S2 is recomputed from the XYZ orientations with
numpy.linalg.eigvalsh; the symmetry axes come from rotating z by the
quaternions with the Hamilton product, independently of the program.
General ellipsoids (--axes): semi-axes in both files, no overlap. Start
from a GSD frame (--from, --frame): files written here with python3-gsd
(gsd.hoomd, its own writer), chunks carried over from frame 0; the
program's sweep-0 XYZ frame equals the chosen frame exactly (positions
shifted by L/2 into [0, L), quaternions normalised with w >= 0, semi-axes
from type_shapes); malformed, non-cubic, non-ellipsoid, mixed-shape and
overlapping frames refused with exit 2; pw85_mc's own GSD file as a start.
"""
import os
import re
import subprocess
import sys
import tempfile

import numpy as np
import gsd.fl
import gsd.hoomd
import gsd.pygsd

from demo_pairs import batch, pair_lines, rotate

MC, CLI = sys.argv[1], sys.argv[2]
FAILURES = []


def check(cond, what):
    if not cond:
        FAILURES.append(what)
        print("FAIL:", what)


def run(args):
    r = subprocess.run([MC] + args, capture_output=True, text=True)
    return r.returncode, r.stdout, r.stderr


def axis(q_wxyz):
    """The body z axis q e_z q* in the lab frame."""
    return rotate(q_wxyz, [0.0, 0.0, 1.0])


def s2_of(quats_wxyz):
    u = np.array([axis(q) for q in quats_wxyz])
    qt = 1.5 * (u.T @ u) / len(u) - 0.5 * np.eye(3)
    return np.linalg.eigvalsh(qt)[-1]


def read_xyz(path):
    frames = []
    with open(path) as f:
        lines = f.read().splitlines()
    k = 0
    while k < len(lines):
        n = int(lines[k])
        header = lines[k + 1]
        rows = [l.split() for l in lines[k + 2:k + 2 + n]]
        frames.append((header, rows))
        k += 2 + n
    return frames


def block_lines(out):
    return re.findall(r"^block (\d+): sweeps (\d+)-(\d+), acceptance translation (\S+) rotation (\S+), "
                      r"S2 = (\S+) \(mean over the block; last sweep (\S+)\)$", out, re.M)


def production_acceptance(out):
    return float(re.search(r"acceptance rate (\S+),", out).group(1))


def check_general_ellipsoids():
    axes = [0.4, 0.7, 1.0]
    with tempfile.TemporaryDirectory() as d:
        xyz, gsdf = os.path.join(d, "e.xyz"), os.path.join(d, "e.gsd")
        rc, out, err = run(["--n", "300", "--axes", *map(str, axes), "--phi", "0.35", "--equil", "6",
                            "--sweeps", "4", "--seed", "2", "--xyz", xyz, "--gsd", gsdf])
        check(rc == 0 and "300 ellipsoids (semi-axes 0.4 0.7 1)" in out and "OK: no overlapping pair" in out,
              f"--axes 0.4 0.7 1: exit 0 (got {rc}: {err})")
        header, rows = read_xyz(xyz)[-1]
        a = np.array([[float(x) for x in r[1:]] for r in rows])
        pos, q_wxyz, shape = a[:, 0:3], a[:, [6, 3, 4, 5]], a[:, 7:10]
        box = float(re.match(r'Lattice="(\S+) ', header).group(1))
        check(np.all(shape == axes), "--axes: XYZ aspherical_shape = (0.4, 0.7, 1)")
        turned = np.mean(np.abs(q_wxyz[:, 0]) < 0.999)
        check(turned > 0.5, f"--axes: most ellipsoids turned away from the lattice orientation ({turned})")
        rc, rows = batch(CLI, pair_lines(pos, axes, q_wxyz, box, 2.0)[0])
        check(rc == 0 and len(rows) > 300 and all(r[3] == "0" and float(r[1]) >= 1.0 for r in rows),
              f"--axes: no overlap among {len(rows)} close pairs of the last XYZ frame (exit {rc})")
        with gsd.hoomd.open(gsdf, "rb") as traj:
            shapes = traj[0].particles.type_shapes
        check(shapes == [{"type": "Ellipsoid", "a": 0.4, "b": 0.7, "c": 1.0}], f"--axes: GSD type_shapes {shapes}")


def write_gsd(path, frames):
    """frames: dicts of gsd.hoomd.Frame attributes (None: not written, the
    reader takes frame 0's)."""
    with gsd.hoomd.open(path, "wb") as f:
        for attrs in frames:
            fr = (getattr(gsd.hoomd, "Frame", None) or gsd.hoomd.Snapshot)()
            for key, value in attrs.items():
                obj, name = key.split(".")
                setattr(getattr(fr, obj), name, value)
            f.append(fr)


def lattice_frame(rng, side=6, spacing=2.1, axes=(0.4, 0.7, 1.0)):
    """side^3 ellipsoids at random orientations on a cubic lattice of
    spacing > 2 max(axes) (no overlap), box side * spacing, centred."""
    L = side * spacing
    g = (np.arange(side) + 0.5) * spacing - L / 2
    pos = np.array(np.meshgrid(g, g, g, indexing="ij")).reshape(3, -1).T + rng.uniform(-0.04, 0.04, (side ** 3, 3))
    quat = rng.normal(size=(side ** 3, 4))
    quat *= rng.uniform(0.5, 2.0, (side ** 3, 1))  # not unit: the program normalises
    shape = {"type": "Ellipsoid", "a": axes[0], "b": axes[1], "c": axes[2]}
    return {"configuration.step": 5, "configuration.box": [L, L, L, 0, 0, 0], "particles.N": side ** 3,
            "particles.types": ["A"], "particles.typeid": np.zeros(side ** 3, np.uint32),
            "particles.type_shapes": [shape], "particles.position": pos.astype(np.float32),
            "particles.orientation": quat.astype(np.float32)}


def expected_start(frame):
    """The centres in [0, L) and the unit quaternions (w >= 0) pw85_mc makes
    of a frame, in double as the program computes them."""
    L = float(np.float32(frame["configuration.box"][0]))
    x = np.asarray(frame["particles.position"], np.float64) + 0.5 * L
    x = np.fmod(x, L)
    x = np.where(x < 0, x + L, x)
    x = np.where(x >= L, x - L, x)
    q = np.asarray(frame["particles.orientation"], np.float64)
    norm = np.sqrt(q[:, 0] * q[:, 0] + q[:, 1] * q[:, 1] + q[:, 2] * q[:, 2] + q[:, 3] * q[:, 3])
    norm = np.where(q[:, 0] < 0, -norm, norm)
    return L, x, q / norm[:, None]


def check_from_gsd():
    rng = np.random.default_rng(12)
    with tempfile.TemporaryDirectory() as d:
        f0 = lattice_frame(rng)
        f1 = lattice_frame(rng)  # frame 1: new positions and orientations
        f1["configuration.step"] = 9
        path = os.path.join(d, "start.gsd")
        write_gsd(path, [f0, f1])
        # gsd.hoomd leaves out of frame 1 the chunks equal to frame 0's: the
        # reader must take them from frame 0.
        with gsd.fl.open(name=path, mode="rb") as g:
            carried = [not g.chunk_exists(frame=1, name=c) for c in
                       ("configuration/box", "particles/N", "particles/type_shapes", "particles/typeid")]
            check(all(carried) and g.chunk_exists(frame=1, name="particles/position"),
                  f"--from test file: frame 1 without box, N, type_shapes, typeid ({carried})")
        for frame_args, frame in (([], f1), (["--frame", "0"], f0), (["--frame", "-1"], f1), (["--frame", "1"], f1)):
            xyz = os.path.join(d, "s.xyz")
            rc, out, err = run(["--from", path, *frame_args, "--equil", "0", "--sweeps", "0", "--xyz", xyz])
            check(rc == 0 and "216 ellipsoids (semi-axes 0.4 0.7 1)" in out and "start from a GSD frame" in out,
                  f"--from {frame_args}: exit 0 (got {rc}: {err})")
            if rc != 0:
                continue
            header, rows = read_xyz(xyz)[0]
            a = np.array([[float(x) for x in r[1:]] for r in rows])
            L, x, q = expected_start(frame)
            check(float(re.match(r'Lattice="(\S+) ', header).group(1)) == L, f"--from {frame_args}: box {L}")
            check(np.array_equal(a[:, 0:3], x), f"--from {frame_args}: centres = the frame's positions + L/2, exactly")
            check(np.max(np.abs(a[:, [6, 3, 4, 5]] - q)) <= 4e-16, f"--from {frame_args}: quaternions normalised, w >= 0")
            check(np.all(a[:, 7:10] == [0.4, 0.7, 1.0]), f"--from {frame_args}: semi-axes from type_shapes")
        rc, out, err = run(["--from", path, "--equil", "4", "--sweeps", "4", "--seed", "3"])
        check(rc == 0 and "OK: no overlapping pair" in out, f"--from, 8 sweeps: exit 0, no overlap (got {rc}: {err})")

        # two types of the same shape: accepted
        f2 = lattice_frame(rng)
        f2["particles.types"] = ["A", "B"]
        f2["particles.type_shapes"] = [f2["particles.type_shapes"][0]] * 2
        f2["particles.typeid"] = (np.arange(216) % 2).astype(np.uint32)
        write_gsd(os.path.join(d, "two.gsd"), [f2])
        rc, out, err = run(["--from", os.path.join(d, "two.gsd"), "--equil", "1", "--sweeps", "1"])
        check(rc == 0, f"--from: two types of one shape accepted (got {rc}: {err})")

        # refused frames: exit 2, a message naming the problem
        bad = []
        f = lattice_frame(rng); f["configuration.box"] = [12.6, 12.6, 13.0, 0, 0, 0]; bad.append(("not cubic", f))
        f = lattice_frame(rng); f["configuration.box"] = [12.6, 12.6, 12.6, 0.1, 0, 0]; bad.append(("not cubic", f))
        f = lattice_frame(rng); f["particles.type_shapes"] = [{"type": "Sphere", "diameter": 1.0}]
        bad.append(("no Ellipsoid", f))
        f = lattice_frame(rng); f["particles.type_shapes"] = [{}]; bad.append(("no Ellipsoid", f))
        f = lattice_frame(rng)
        f["particles.types"] = ["A", "B"]
        f["particles.type_shapes"] = [f["particles.type_shapes"][0], {"type": "Ellipsoid", "a": 0.4, "b": 0.7, "c": 0.9}]
        f["particles.typeid"] = (np.arange(216) % 2).astype(np.uint32)
        bad.append(("shapes differ", f))
        f = lattice_frame(rng); f["particles.position"][1] = f["particles.position"][0]
        bad.append(("overlapping pairs", f))
        bad.append(("too small", lattice_frame(rng, spacing=0.8)))
        for k, (what, frame) in enumerate(bad):
            p = os.path.join(d, f"bad{k}.gsd")
            write_gsd(p, [frame])
            rc, out, err = run(["--from", p, "--equil", "1", "--sweeps", "1"])
            check(rc == 2 and what in err, f"--from, {what}: exit 2 and a message (got {rc}: {err.strip()})")
        # malformed files
        good = open(path, "rb").read()
        malformed = {"truncated": good[:len(good) // 2], "header only": good[:256], "empty": b"",
                     "magic": b"\0" * 8 + good[8:], "index": good[:8] + (2 ** 62).to_bytes(8, "little") + good[16:]}
        for what, data in malformed.items():
            p = os.path.join(d, "bad.gsd")
            open(p, "wb").write(data)
            rc, out, err = run(["--from", p])
            check(rc == 2 and err.startswith("pw85_mc: --from"), f"--from, {what} file: exit 2 and a message (got {rc}: {err.strip()})")
        for args in (["--from", path, "--n", "300"], ["--from", path, "--axes", "1", "1", "1"], ["--frame", "1"],
                     ["--from", path, "--frame", "2"], ["--from", os.path.join(d, "missing.gsd")]):
            rc, out, err = run(args)
            check(rc == 2 and err.startswith("pw85_mc: "), f"{args}: exit 2 and a message (got {rc}: {err.strip()})")

        # pw85_mc's own file as a start
        own = os.path.join(d, "own.gsd")
        rc, out, _ = run(["--n", "300", "--aspect", "3", "--phi", "0.3", "--equil", "5", "--sweeps", "2", "--gsd", own])
        rc2, out2, err2 = run(["--from", own, "--equil", "2", "--sweeps", "2"])
        check(rc == 0 and rc2 == 0 and "300 prolate spheroids (semi-axes 0.5 0.5 1.5)" in out2,
              f"--from a file of pw85_mc: exit 0 (got {rc2}: {err2})")


def main():
    rc, out, err = run(["--help"])
    check(rc == 0 and out.startswith("usage: pw85_mc"), "--help: exit 0, usage on stdout")
    for bad in (["--bogus"], ["--n"], ["--n", "x"], ["--n", "1"], ["--phi", "0.7"], ["--sweeps", "-1"],
                ["--aspect", "0"], ["--target", "1.5"], ["--seed", "-3"], ["--axes", "1", "2"], ["--axes", "0", "1", "1"], ["--n", "300", "--xyz",
                "/nonexistent/dir/c.xyz"], ["--n", "300", "--gsd", "/nonexistent/dir/c.gsd"]):
        rc, out, err = run(bad)
        check(rc == 2 and "pw85_mc: " in err, f"{bad}: exit 2 and a message (got {rc})")

    with tempfile.TemporaryDirectory() as d:
        xyz, gsdf = os.path.join(d, "c.xyz"), os.path.join(d, "c.gsd")
        args = ["--n", "300", "--equil", "10", "--sweeps", "8", "--blocks", "4", "--seed", "7",
                "--phi", "0.3", "--xyz", xyz, "--gsd", gsdf, "--progress"]
        rc, out, err = run(args)
        check(rc == 0 and "OK: no overlapping pair" in out, f"run with --xyz --gsd: exit 0 (got {rc}: {err})")
        check("pw85_mc: sweep 18/18, acceptance" in err, "--progress: progress lines on stderr")
        blocks = block_lines(out)
        check([b[1:3] for b in blocks] == [("1", "2"), ("3", "4"), ("5", "6"), ("7", "8")],
              f"4 blocks of 2 sweeps reported (got {blocks})")
        for b in blocks:
            check(0.0 <= float(b[5]) <= 1.0 and 0.0 <= float(b[6]) <= 1.0, f"block {b[0]}: S2 in [0, 1]")
        rc2, out2, _ = run(args[:-5])
        check(block_lines(out2) == blocks, "same seed, same blocks")

        # XYZ
        frames = read_xyz(xyz)
        check(len(frames) == 5 and [h.split("sweep=")[1].split()[0] for h, _ in frames] == ["0", "2", "4", "6", "8"],
              f"XYZ: 5 frames, sweep 0 and 4 blocks (got {len(frames)})")
        xyz_s2 = [float(re.search(r" S2=(\S+)$", h).group(1)) for h, _ in frames]
        header, rows = frames[-1]
        m = re.match(r'Lattice="(\S+) 0 0 0 (\S+) 0 0 0 (\S+)" pbc="T T T" '
                     r"Properties=species:S:1:pos:R:3:orientation:R:4:aspherical_shape:R:3 "
                     r"sweep=(\d+) S2=(\S+)$", header)
        check(m is not None, f"XYZ: extended XYZ comment line ({header!r})")
        box = float(m.group(1))
        check(m.group(1) == m.group(2) == m.group(3) and int(m.group(4)) == 8, "XYZ: cubic box, sweep 8")
        check(len(rows) == 300 and all(len(r) == 11 and r[0] == "E" for r in rows), "XYZ: 300 rows of 11 columns")
        a = np.array([[float(x) for x in r[1:]] for r in rows])
        pos, q_xyzw, shape = a[:, 0:3], a[:, 3:7], a[:, 7:10]
        q_wxyz = q_xyzw[:, [3, 0, 1, 2]]
        check(np.all((pos >= 0) & (pos < box)), "XYZ: positions in [0, L)")
        check(np.max(np.abs(np.linalg.norm(q_xyzw, axis=1) - 1)) < 1e-15, "XYZ: unit quaternions")
        check(np.all(shape == [0.5, 0.5, 1.5]), "XYZ: aspherical_shape = semi-axes (0.5, 0.5, 1.5)")
        s2 = s2_of(q_wxyz)
        check(abs(s2 - float(m.group(5))) < 1e-12, f"XYZ: S2 of the frame {m.group(5)} vs numpy {s2}")
        check(abs(s2 - float(blocks[-1][6])) <= 6e-5, f"printed S2 of the last sweep {blocks[-1][6]} vs numpy {s2}")

        # GSD, C reader through gsd.hoomd and pure-Python reader
        with gsd.hoomd.open(gsdf, "rb") as traj:
            check(len(traj) == 5, f"GSD: 5 frames, sweep 0 and 4 blocks (got {len(traj)})")
            f0, f3 = traj[0], traj[4]
            logged_s2 = [traj[k].log.get("pw85/S2") for k in range(len(traj))]
            frame_s2 = [s2_of(np.array(traj[k].particles.orientation, float)) for k in range(len(traj))]
            steps = [int(traj[k].configuration.step) for k in range(len(traj))]
            gpos, gq = np.array(f3.particles.position, float), np.array(f3.particles.orientation, float)
            gbox = np.array(f3.configuration.box, float)
            shapes, types, typeid, n = f3.particles.type_shapes, f3.particles.types, f3.particles.typeid, f3.particles.N
            moved = np.mean(np.any(np.array(f0.particles.position) != f3.particles.position, axis=1)
                            | np.any(np.array(f0.particles.orientation) != f3.particles.orientation, axis=1))
        with gsd.pygsd.GSDFile(open(gsdf, "rb")) as g:
            py = gsd.hoomd.HOOMDTrajectory(g)
            check(len(py) == 5 and np.array_equal(py[4].particles.position, gpos.astype(np.float32))
                  and g.schema == "hoomd" and g.gsd_version == (2, 0),
                  "GSD: the pure-Python reader reads the same file")
        check(steps == [0, 2, 4, 6, 8], f"GSD: steps {steps}")
        check(all(v is not None and v.shape == (1,) and v.dtype == np.float64 for v in logged_s2),
              "GSD: log/pw85/S2 in every frame, one float64")
        if all(v is not None for v in logged_s2):
            check([float(v[0]) for v in logged_s2] == xyz_s2, f"GSD log/pw85/S2 = XYZ S2= ({xyz_s2})")
            check(max(abs(float(v[0]) - f) for v, f in zip(logged_s2, frame_s2)) < 1e-6,
                  "GSD log/pw85/S2 vs numpy over the frame's (float32) orientations")
        check(n == 300 and types == ["E"] and np.all(np.asarray(typeid) == 0), "GSD: N, types, typeid")
        check(np.allclose(gbox, [box, box, box, 0, 0, 0], rtol=1e-7, atol=0), f"GSD: box {gbox} vs {box}")
        check(shapes == [{"type": "Ellipsoid", "a": 0.5, "b": 0.5, "c": 1.5}], f"GSD: type_shapes {shapes}")
        check(np.all((gpos >= -gbox[0] / 2) & (gpos < gbox[0] / 2)), "GSD: positions in [-L/2, L/2)")
        check(np.max(np.abs(np.linalg.norm(gq, axis=1) - 1)) < 3e-7, "GSD: unit quaternions (float32)")
        dpos = gpos - (pos - box / 2)
        dpos -= box * np.round(dpos / box)
        check(np.max(np.abs(dpos)) < 1e-6 * box, "GSD positions = XYZ positions - L/2 (float32)")
        check(np.max(np.abs(gq - q_wxyz)) < 1e-7, "GSD orientation (w, x, y, z) = XYZ (x, y, z, w) reordered")
        check(moved > 0.5, f"GSD: most particles moved or turned between the first and last frame ({moved})")

        # no overlapping pair: exact on the XYZ doubles, loosely on the GSD floats
        cutoff = 2 * 1.5
        rc, rows = batch(CLI, pair_lines(pos, [0.5, 0.5, 1.5], q_wxyz, box, cutoff)[0])
        check(rc == 0 and len(rows) > 300 and all(r[4] == "0" and r[3] == "0" and float(r[1]) >= 1.0 for r in rows),
              f"XYZ: no overlap among {len(rows)} close pairs (exit {rc})")
        print(f"XYZ: {len(rows)} pairs closer than {cutoff}, min mu^2 {min(float(r[1]) for r in rows):.6f}")
        rc, rows = batch(CLI, pair_lines(gpos, [0.5, 0.5, 1.5], gq, gbox[0], cutoff)[0])
        check(rc == 0 and all(float(r[1]) > 1 - 1e-4 for r in rows), "GSD: no pair with mu^2 < 1 - 1e-4")

    # --sweeps 0: one frame, sweep 0, the configuration after equilibration
    with tempfile.TemporaryDirectory() as d:
        gsdf = os.path.join(d, "c.gsd")
        rc, out, _ = run(["--n", "300", "--equil", "3", "--sweeps", "0", "--gsd", gsdf])
        with gsd.hoomd.open(gsdf, "rb") as traj:
            steps = [int(f.configuration.step) for f in traj]
            s2 = [float(f.log["pw85/S2"][0]) for f in traj]
            orientation = np.array(traj[0].particles.orientation, float)
        check(rc == 0 and steps == [0] and abs(s2[0] - s2_of(orientation)) < 1e-6
              and np.any(np.abs(orientation[:, 1:]) > 1e-3),
              f"--sweeps 0: one frame at sweep 0, after the equilibration turned the axes (steps {steps})")

    # step tuning reaches the target acceptance
    for target in ("0.3", "0.5"):
        rc, out, _ = run(["--n", "300", "--phi", "0.4", "--equil", "40", "--sweeps", "20", "--seed", "3",
                          "--target", target])
        acc = production_acceptance(out)
        check(rc == 0 and abs(acc - float(target)) <= 0.05, f"phi 0.4, target {target}: acceptance {acc}")
    # S2: near 0 for an isotropic dilute run (about 1/sqrt(N)), near 1 near the aligned start
    rc, out, _ = run(["--n", "300", "--phi", "0.02", "--equil", "20", "--sweeps", "20", "--seed", "5"])
    s2 = [float(b[5]) for b in block_lines(out)]
    check(rc == 0 and len(s2) == 4 and all(0 <= x < 0.2 for x in s2), f"isotropic run: S2 {s2} < 0.2")
    rc, out, _ = run(["--n", "300", "--phi", "0.4", "--equil", "2", "--sweeps", "2", "--seed", "5"])
    s2 = [float(b[5]) for b in block_lines(out)]
    check(rc == 0 and all(x > 0.8 for x in s2), f"dense run from the aligned lattice: S2 {s2} > 0.8")
    rc, out, _ = run(["--n", "300", "--equil", "0", "--sweeps", "2", "--blocks", "9"])
    check(rc == 0 and re.search(r"^equilibration: none;.*\nblock 1: sweeps 1-1,.*\nblock 2: sweeps 2-2,", out, re.M)
          is not None, "--equil 0: fixed steps reported first; --blocks above --sweeps: one block per sweep")
    rc, out, _ = run(["--n", "300", "--aspect", "0.3", "--phi", "0.3", "--equil", "4", "--sweeps", "4"])
    check(rc == 0 and "oblate" in out and "OK: no overlapping pair" in out, "oblate spheroids: exit 0")

    check_general_ellipsoids()
    check_from_gsd()

    if FAILURES:
        print(f"{len(FAILURES)} failures")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
