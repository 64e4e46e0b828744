"""Bad input and extreme overlaps. An atom that is not an ellipsoid (a point
particle, shape 0) in the pair style and in the compute: lmp stops with an
error naming the atom, never a crash. A negative shape: LAMMPS's own check
of the data file stops lmp with an error. A position that is not finite
(set between two steps, after LAMMPS's own check of the coordinates): lmp
stops with an error naming the atom. Deep overlaps: centres 1e-9 apart
(mu^2 ~ 1e-18) and coincident centres give finite forces and torques and
U = epsilon per pair (to 1e-12)."""
import sys
import tempfile

import numpy as np

import lammps_run as lr

# id, ellipsoid flag, position, diameters, quaternion
GOOD = [(1, 1, (5.0, 5.0, 5.0), (2.0, 1.2, 0.8), (0.9, 0.1, -0.3, 0.2)),
        (2, 1, (5.0 + 1e-9, 5.0, 5.0), (2.0, 0.9, 0.9), (0.2, 0.7, 0.1, -0.4)),
        (3, 1, (12.0, 12.0, 12.0), (2.0, 1.2, 0.8), (0.5, 0.5, 0.5, 0.5)),
        (4, 1, (12.0, 12.0, 12.0), (1.0, 2.0, 3.0), (1.0, 0.0, 0.0, 0.0)),
        (5, 1, (18.0, 5.0, 12.0), (2.0, 1.2, 0.8), (1.0, 0.0, 0.0, 0.0))]


def write_data(path, atoms):
    lines = ["LAMMPS data file: pw85 plugin error test", "", f"{len(atoms)} atoms", "1 atom types",
             f"{sum(a[1] for a in atoms)} ellipsoids", "", "0 20 xlo xhi", "0 20 ylo yhi",
             "0 20 zlo zhi", "", "Atoms # ellipsoid", ""]
    lines += [f"{a[0]} 1 {a[1]} 1.0 {a[2][0]!r} {a[2][1]!r} {a[2][2]!r}" for a in atoms]
    lines += ["", "Ellipsoids", ""]
    lines += [f"{a[0]} " + " ".join(map(repr, a[3])) + " " + " ".join(map(repr, a[4]))
              for a in atoms if a[1]]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def expect_error(lmp, plugin, tmp, name, atoms, what, needle):
    write_data(f"{tmp}/{name}.data", atoms)
    rc, out = lr.run_lmp(lmp, plugin, "errors.in", {"data": f"{tmp}/{name}.data", "what": what,
                                                   "dump": f"{tmp}/{name}.dump"}, tmp, check=False)
    err = [l for l in out.splitlines() if "ERROR" in l]
    return lr.report(name, 0 < rc < 128 and any(needle in l for l in err),
                     f"exit {rc}, {err[0] if err else 'no ERROR line'!r} (expected {needle!r})")


def main():
    lmp, plugin, _ = lr.args()
    ok = True
    with tempfile.TemporaryDirectory() as tmp:
        point = GOOD[:2] + [(3, 0, (12.0, 12.0, 12.0), (0, 0, 0), None)] + GOOD[3:]
        ok &= expect_error(lmp, plugin, tmp, "point-particle-pair", point, "pair",
                           "pair pw85/soft: atom 3 is not an ellipsoid")
        ok &= expect_error(lmp, plugin, tmp, "point-particle-compute", point, "compute",
                           "compute pw85/overlap: atom 3 is not an ellipsoid")
        negative = GOOD[:3] + [(4, 1, (12.0, 12.0, 12.0), (1.0, -2.0, 3.0), (1, 0, 0, 0))] + GOOD[4:]
        ok &= expect_error(lmp, plugin, tmp, "negative-shape", negative, "pair", "shape")
        ok &= expect_error(lmp, plugin, tmp, "nan-position", GOOD, "nan",
                           "pair pw85/soft: atom 5 has a position that is not finite")

        write_data(f"{tmp}/deep.data", GOOD)
        _, out = lr.run_lmp(lmp, plugin, "errors.in", {"data": f"{tmp}/deep.data", "what": "overlap",
                                                      "dump": f"{tmp}/deep.dump"}, tmp)
        th = lr.thermo(out)[-1]
        frame, _ = lr.read_dump(f"{tmp}/deep.dump")
        ft = np.stack([frame[k] for k in ("fx", "fy", "fz", "tqx", "tqy", "tqz")], axis=1)
        pe = th["PotEng"][-1]
        ok &= lr.report("deep-overlaps", np.all(np.isfinite(ft)) and abs(pe - 2.0) <= 2e-12
                        and np.all(ft[4] == 0) and np.all(ft[2:4] == 0),
                        f"U = {pe!r} (2 pairs at mu^2 ~ 0), largest |F|, |torque| "
                        f"{np.max(np.abs(ft)):.3g}; coincident centres: no force")
        ok &= lr.report("deep-overlaps-compute", th["c_overlap[1]"][-1] == 2
                        and th["c_overlap[2]"][-1] < 1e-15,
                        f"{th['c_overlap[1]'][-1]:g} overlapping pairs, smallest mu^2"
                        f" {th['c_overlap[2]'][-1]!r}")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
