"""Domain decomposition: the thermo output (potential, kinetic and rotational
energy, total energy, pressure) of 100 NVE steps (nve.in) on two MPI ranks,
with newton_pair on and off, and on one rank with newton_pair off, within
1e-10 relative of one rank with newton_pair on (ghost atoms, periodic images
and the reverse communication of forces and torques)."""
import sys
import tempfile

import numpy as np

import lammps_run as lr

N, PHI, SEED, TOL = 512, 0.3, 11, 1e-10
COLUMNS = ("PotEng", "KinEng", "c_rot", "v_etotal", "Press")


def main():
    lmp, plugin, _ = lr.args()
    ok = True
    with tempfile.TemporaryDirectory() as tmp:
        lr.write_config(f"{tmp}/mpi.data", N, PHI, SEED)
        runs = {}
        for ranks, newton in ((1, "on"), (1, "off"), (2, "on"), (2, "off")):
            _, out = lr.run_lmp(lmp, plugin, "nve.in",
                                {"data": f"{tmp}/mpi.data", "dt": 0.002, "steps": 100,
                                 "every": 10, "newton": newton}, tmp, ranks=ranks)
            runs[ranks, newton] = lr.thermo(out)[0]
            if ranks == 2:
                ok &= lr.report(f"two ranks, newton {newton}", "2 by 1 by 1" in out
                                or "1 by 2 by 1" in out or "1 by 1 by 2" in out,
                                "the box is split between the two ranks")
    ref = runs[1, "on"]
    for key, run in runs.items():
        if key == (1, "on"):
            continue
        err = max(np.max(np.abs(run[c] - ref[c]) / np.abs(ref[c])) for c in COLUMNS)
        ok &= lr.report(f"ranks {key[0]}, newton {key[1]}", len(run["Step"]) == 11 and err <= TOL,
                        f"largest relative difference {err:.2e} over 11 thermo lines"
                        f" (<= {TOL:g})")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
