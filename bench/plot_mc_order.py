#!/usr/bin/python3
"""Nematic order parameter S2 of pw85_mc runs against the number of sweeps,
one curve per packing fraction.

    /usr/bin/python3 bench/plot_mc_order.py build/src/tools/pw85_mc

Runs pw85_mc with 500 prolate spheroids of aspect 3 (semi-axes 0.5, 0.5,
1.5), seed 1, 20 equilibration sweeps (steps tuned to acceptance 0.3) and
3000 production sweeps in 60 blocks, at packing fractions 0.1, 0.2, 0.3,
0.35 and 0.4, each from the aligned lattice (S2 = 1). Plots the S2 of each
block (mean over its 50 sweeps) against the last sweep of the block, and
the level 1/sqrt(N) of N random axes. Writes docs/mc_order.png and
docs/mc_order.csv (phi, last sweep of the block, S2, acceptance of the
translations and rotations). About 3 minutes on the 2-core machine of
docs/guide.md.
"""
import csv
import os
import re
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DOCS = os.path.join(HERE, os.pardir, "docs")
N, ASPECT, EQUIL, SWEEPS, BLOCKS = 500, 3, 20, 3000, 60
PHIS = [0.1, 0.2, 0.3, 0.35, 0.4]
BLOCK = re.compile(r"^block \d+: sweeps \d+-(\d+), acceptance translation (\S+) rotation (\S+), "
                   r"S2 = (\S+) ", re.M)


def main():
    program = sys.argv[1] if len(sys.argv) > 1 else "build/src/tools/pw85_mc"
    rows = []
    for phi in PHIS:
        run = subprocess.run([program, "--n", str(N), "--aspect", str(ASPECT), "--phi", str(phi),
                              "--equil", str(EQUIL), "--sweeps", str(SWEEPS), "--blocks", str(BLOCKS),
                              "--seed", "1"], capture_output=True, text=True, check=False)
        if run.returncode != 0:
            sys.exit(f"pw85_mc at phi {phi} exited with status {run.returncode}: {run.stderr}")
        for m in BLOCK.finditer(run.stdout):
            rows.append((phi, int(m.group(1)), float(m.group(4)), float(m.group(2)), float(m.group(3))))
        print(f"phi {phi}: S2 of the last block {rows[-1][2]:.4f}")
    with open(os.path.join(DOCS, "mc_order.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["phi", "sweep", "S2", "acceptance_translation", "acceptance_rotation"])
        w.writerows(rows)
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for phi in PHIS:
        pts = [(r[1], r[2]) for r in rows if r[0] == phi]
        ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", ms=3, label=f"$\\phi$ = {phi}")
    ax.axhline(N ** -0.5, color="grey", ls=":", label="$1/\\sqrt{N}$")
    ax.set_xscale("log")
    ax.set_ylim(0, 1)
    ax.set_xlabel("production sweeps (end of block)")
    ax.set_ylabel("nematic order $S_2$ (block mean)")
    ax.set_title(f"pw85_mc: {N} hard spheroids, aspect {ASPECT}, from the aligned lattice")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(DOCS, "mc_order.png"), dpi=110)


if __name__ == "__main__":
    main()
