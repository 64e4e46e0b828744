#!/usr/bin/env python3
"""Options and GSD trajectories of pw85_md and pw85_edmd (docs/usage.md).

usage: check_pw85_dynamics.py PW85_MD PW85_EDMD PW85

--help: exit 0, every option of the synopsis described on a line of its
own; bad options: exit 2 and a message. The trajectories are read back
with python3-gsd (gsd.hoomd): steps, box, N, type_shapes, unit
quaternions. pw85_md: the first frame's centres are the program's starting
lattice (computed here); the potential energy logged with each frame is
recomputed here from the frame's float32 positions and quaternions, with
mu^2 of every pair closer than 2 from the pw85 program's batch mode
(U = sum (1 - mu^2)^3 over mu^2 < 1); the logged total energy is the one
printed. pw85_edmd: the first frame has the identity orientation, time
0; no pair of any frame overlaps (mu^2 > 1 - 1e-4: float32 rounding of
pairs in contact); the time increases to the one printed.
"""
import os
import re
import subprocess
import sys
import tempfile

import numpy as np
import gsd.hoomd

from demo_pairs import batch, pair_lines

MD, EDMD, CLI = sys.argv[1:4]
FAILURES = []


def check(cond, what):
    if not cond:
        FAILURES.append(what)
        print("FAIL:", what)


def run(prog, args):
    r = subprocess.run([prog] + args, capture_output=True, text=True)
    return r.returncode, r.stdout, r.stderr


def check_options(prog, name, bad_args):
    rc, out, err = run(prog, ["--help"])
    check(rc == 0 and out.startswith(f"usage: {name} ") and err == "", f"{name} --help: exit 0, usage on stdout")
    synopsis = out.split("\n\n")[0].split("\n")
    options = sorted(set(re.findall(r"--[a-z-]+", "\n".join(l for l in synopsis if l.startswith(("usage", " " * 8))))))
    described = set(re.findall(r"^  (--[a-z-]+)", out, re.M))
    check(len(options) >= 6 and set(options) <= described,
          f"{name} --help: every option described (undescribed: {sorted(set(options) - described)})")
    for bad in bad_args:
        rc, out, err = run(prog, bad)
        check(rc == 2 and err.startswith(f"{name}: "), f"{name} {bad}: exit 2 and a message (got {rc}, {err[:80]!r})")


def energy_from_frame(frame, radii):
    """sum over pairs with mu^2 < 1 of (1 - mu^2)^3, mu^2 from the pw85 program."""
    pos = np.array(frame.particles.position, float)
    quat = np.array(frame.particles.orientation, float)
    box = float(frame.configuration.box[0])
    lines, _ = pair_lines(pos, radii, quat, box, 2.0)
    rc, rows = batch(CLI, lines)
    mu2 = np.array([float(r[1]) for r in rows])
    return rc, float(np.sum(np.where(mu2 < 1, (1 - mu2) ** 3, 0.0)))


def check_md(d):
    check_options(MD, "pw85_md", [["--bogus"], ["--n"], ["--n", "x"], ["--n", "42"], ["--steps", "5"],
                                  ["--dt", "-1"], ["--seed", "-3"], ["--gsd-every", "0"], ["--gsd"],
                                  ["--n", "64", "--steps", "10", "--gsd", "/nonexistent/dir/t.gsd"]])
    path = os.path.join(d, "md.gsd")
    rc, out, err = run(MD, ["--n", "64", "--steps", "200", "--dt", "0.008", "--gsd", path, "--gsd-every", "50"])
    check(rc == 0, f"pw85_md --gsd: exit 0 (got {rc}: {err})")
    printed = {int(m[0]): float(m[1]) for m in re.findall(r"^step (\d+)  t \S+  E (\S+)", out, re.M)}
    radii = [1.0, 0.6, 0.4]
    with gsd.hoomd.open(path, "rb") as traj:
        frames = [traj[k] for k in range(len(traj))]
    steps = [int(f.configuration.step) for f in frames]
    check(steps == [0, 50, 100, 150, 200], f"pw85_md GSD: frames at steps 0, 50, ..., 200 (got {steps})")
    f0 = frames[0]
    box = float(f0.configuration.box[0])
    check(f0.particles.N == 64 and f0.particles.types == ["E"]
          and f0.particles.type_shapes == [{"type": "Ellipsoid", "a": 1.0, "b": 0.6, "c": 0.4}],
          f"pw85_md GSD: N, types, type_shapes ({f0.particles.type_shapes})")
    L = (64 * 4 / 3 * np.pi * 0.24 / 0.2) ** (1 / 3)
    check(abs(box - L) <= 1e-6 * L and list(f0.configuration.box[3:]) == [0, 0, 0], f"pw85_md GSD: cubic box {L}")
    side = 4
    lattice = np.array([[(i % side + 0.5) * L / side, (i // side % side + 0.5) * L / side,
                         (i // side ** 2 + 0.5) * L / side] for i in range(64)]) - L / 2
    check(np.max(np.abs(f0.particles.position - lattice)) <= 1e-6 * L, "pw85_md GSD: frame 0 on the starting lattice")
    for f in frames:
        q = np.array(f.particles.orientation, float)
        pos = np.array(f.particles.position, float)
        step = int(f.configuration.step)
        check(np.max(np.abs(np.linalg.norm(q, axis=1) - 1)) < 3e-7 and np.all(q[:, 0] >= 0),
              f"pw85_md GSD step {step}: unit quaternions, w >= 0")
        check(np.all((pos >= -box / 2) & (pos < box / 2)), f"pw85_md GSD step {step}: positions in [-L/2, L/2)")
        u_log = f.log.get("pw85/potential_energy")
        e_log = f.log.get("pw85/total_energy")
        check(u_log is not None and e_log is not None and u_log.dtype == np.float64,
              f"pw85_md GSD step {step}: potential and total energy logged (float64)")
        if u_log is None or e_log is None:
            continue
        rc, u = energy_from_frame(f, radii)
        check(rc == 0 and abs(u - u_log[0]) <= 1e-4 * max(1.0, u_log[0]),
              f"pw85_md GSD step {step}: logged U {u_log[0]!r} vs recomputed from the frame {u!r}")
        if step in printed:
            check(abs(e_log[0] - printed[step]) <= 1e-11 * abs(printed[step]),
                  f"pw85_md GSD step {step}: logged E {e_log[0]!r} vs printed {printed[step]!r}")
        print(f"pw85_md step {step}: U logged {u_log[0]:.6f}, recomputed {u:.6f}")
    check(frames[-1].log["pw85/potential_energy"][0] > 0.1, "pw85_md GSD: the ellipsoids interact by the end")
    check(sum(s in printed for s in steps) >= 2, "pw85_md: total energy printed at two frames or more")


def check_edmd(d):
    check_options(EDMD, "pw85_edmd", [["--bogus"], ["--n"], ["--n", "x"], ["--phi", "0.6"], ["--shape", "cube"],
                                      ["--axes", "1", "2"], ["--axes", "1", "2", "0"], ["--blocks", "1"],
                                      ["--collisions", "5"], ["--seed", "-1"], ["--gsd"],
                                      ["--collisions", "20", "--gsd", "/nonexistent/dir/t.gsd"]])
    path = os.path.join(d, "edmd.gsd")
    rc, out, err = run(EDMD, ["--n", "256", "--collisions", "2000", "--blocks", "4", "--check", "--gsd", path])
    check(rc == 0 and out.rstrip().endswith("OK"), f"pw85_edmd --gsd: exit 0, checks passed (got {rc}: {err})")
    t_end = float(re.search(r"re-predictions \d+, time (\S+)", out).group(1))
    with gsd.hoomd.open(path, "rb") as traj:
        frames = [traj[k] for k in range(len(traj))]
    steps = [int(f.configuration.step) for f in frames]
    times = [float(f.log["pw85/time"][0]) for f in frames]
    check(steps == [0, 500, 1000, 1500, 2000], f"pw85_edmd GSD: frames at collisions 0, 500, ..., 2000 ({steps})")
    check(times[0] == 0 and all(a < b for a, b in zip(times, times[1:])) and abs(times[-1] - t_end) <= 1e-5 * t_end,
          f"pw85_edmd GSD: time from 0, increasing, to the printed {t_end} ({times})")
    f0 = frames[0]
    check(f0.particles.N == 256 and f0.particles.type_shapes == [{"type": "Ellipsoid", "a": 0.5, "b": 0.5, "c": 1}],
          f"pw85_edmd GSD: N, type_shapes ({f0.particles.type_shapes})")
    check(np.all(np.array(f0.particles.orientation) == [1, 0, 0, 0]), "pw85_edmd GSD: frame 0, aligned lattice")
    moved = np.mean(np.any(np.array(frames[-1].particles.orientation) != f0.particles.orientation, axis=1))
    check(moved > 0.9, f"pw85_edmd GSD: the ellipsoids turned by the last frame ({moved})")
    for f in frames:
        pos, q = np.array(f.particles.position, float), np.array(f.particles.orientation, float)
        box = float(f.configuration.box[0]) if f.configuration.box is not None else float(f0.configuration.box[0])
        lines, _ = pair_lines(pos, [0.5, 0.5, 1.0], q, box, 2.0)
        rc, rows = batch(CLI, lines)
        mu2 = [float(r[1]) for r in rows]
        check(rc == 0 and len(rows) > 100 and min(mu2) > 1 - 1e-4,
              f"pw85_edmd GSD step {int(f.configuration.step)}: no pair with mu^2 < 1 - 1e-4 "
              f"({len(rows)} pairs, min {min(mu2):.7f})")


def main():
    with tempfile.TemporaryDirectory() as d:
        check_md(d)
        check_edmd(d)
    if FAILURES:
        print(f"{len(FAILURES)} failures")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
