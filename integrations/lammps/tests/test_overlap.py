"""compute pw85/overlap against brute force over all pairs: a configuration
of hard spheroids written by the project's pw85_mc (--gsd; float32
positions and quaternions), as written and compressed by 3 % (positions and
box), read by LAMMPS; the count of overlapping pairs equals that of
pw85.scene_overlap over all N (N - 1) / 2 pairs (minimum image) of the
positions and quaternions LAMMPS holds (dumped with 17 digits), and the
smallest mu^2 equals the smallest of pw85.scene_contact_function over those
pairs (1e-12 relative); on one and on two MPI ranks."""
import subprocess
import sys
import tempfile

import gsd.hoomd
import numpy as np

import lammps_run as lr
import pw85

N, TOL = 600, 1e-12


def write_data(path, frame, scale):
    """A LAMMPS data file of the GSD frame, positions and box scaled by
    `scale`."""
    shape = frame.particles.type_shapes[0]  # {"type": "Ellipsoid", "a", "b", "c"}
    radii = [shape["a"], shape["b"], shape["c"]]
    L = np.asarray(frame.configuration.box[:3], float) * scale
    pos = np.asarray(frame.particles.position, float) * scale
    quat = np.asarray(frame.particles.orientation, float)
    n = len(pos)
    lines = ["LAMMPS data file: pw85_mc configuration", "", f"{n} atoms", "1 atom types",
             f"{n} ellipsoids", ""]
    lines += [f"{-L[d] / 2!r} {L[d] / 2!r} {a}lo {a}hi" for d, a in enumerate("xyz")]
    lines += ["", "Atoms # ellipsoid", ""]
    lines += [f"{i + 1} 1 1 1.0 " + " ".join(repr(float(c)) for c in pos[i]) for i in range(n)]
    lines += ["", "Ellipsoids", ""]
    lines += [f"{i + 1} " + " ".join(repr(2 * float(r)) for r in radii) + " "
              + " ".join(repr(float(c)) for c in quat[i]) for i in range(n)]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def brute_force(dump, bounds):
    L = bounds[:, 1] - bounds[:, 0]
    centres = np.stack([dump["x"], dump["y"], dump["z"]], axis=1)
    quat = np.stack([dump[k] for k in ("quatw", "quati", "quatj", "quatk")], axis=1)
    radii = np.stack([dump["shapex"], dump["shapey"], dump["shapez"]], axis=1) / 2
    q = pw85.ellipsoid_quat(radii, quat)
    i, j = np.triu_indices(len(centres), 1)
    pairs = np.stack([i, j], axis=1)
    box = [*L, 0, 0, 0]
    count = int(np.sum(pw85.scene_overlap(centres, q, pairs, box=box)))
    mu2, _ = pw85.scene_contact_function(centres, q, pairs, box=box)
    return count, float(mu2.min())


def main():
    lmp, plugin, rest = lr.args()
    pw85_mc = rest[0]
    ok = True
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([pw85_mc, "--n", str(N), "--phi", "0.35", "--aspect", "2", "--equil", "10",
                        "--sweeps", "10", "--blocks", "1", "--threads", "1", "--seed", "4",
                        "--gsd", f"{tmp}/mc.gsd"], check=True, stdout=subprocess.DEVNULL)
        with gsd.hoomd.open(f"{tmp}/mc.gsd", "rb") as traj:
            frame = traj[len(traj) - 1]  # later frames inherit the box and shapes
        for scale in (1.0, 0.97):
            write_data(f"{tmp}/mc.data", frame, scale)
            for ranks in (1, 2):
                dump = f"{tmp}/overlap-{ranks}.dump"
                _, out = lr.run_lmp(lmp, plugin, "overlap.in",
                                    {"data": f"{tmp}/mc.data", "dump": dump}, tmp, ranks=ranks)
                th = lr.thermo(out)[-1]
                count, mu2_min = int(th["c_overlap[1]"][-1]), th["c_overlap[2]"][-1]
                ref_count, ref_mu2 = brute_force(*lr.read_dump(dump))
                ok &= lr.report(f"scale {scale}, ranks {ranks}",
                                count == ref_count and abs(mu2_min - ref_mu2) <= TOL * ref_mu2,
                                f"{count} overlapping pairs (brute force {ref_count}), smallest"
                                f" mu^2 {mu2_min!r} (brute force {ref_mu2!r})")
                if scale < 1:
                    ok &= lr.report("overlaps", ref_count > 0, "the compressed configuration"
                                    " has overlapping pairs")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
