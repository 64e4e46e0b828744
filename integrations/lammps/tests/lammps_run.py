"""Helpers of the LAMMPS plugin's tests (integrations/lammps/README.md, "Tests"): running
lmp (on one rank, or on several under mpirun), the thermo table, dumps, and
the random ellipsoid configurations written as LAMMPS data files.

Every test script takes the lmp executable and the plugin as its first two
arguments (the two lines printed by integrations/lammps/build.sh)."""
import math
import os
import re
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))

# OpenMPI under root in a container: allowed explicitly; ranks may outnumber
# the cores; shared memory without CMA (ptrace is often forbidden).
MPI_ENV = {
    "OMPI_ALLOW_RUN_AS_ROOT": "1",
    "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
    "OMPI_MCA_rmaps_base_oversubscribe": "1",
    "OMPI_MCA_btl_vader_single_copy_mechanism": "none",
    "OMPI_MCA_btl": "self,vader",
}


def args():
    if len(sys.argv) < 3:
        sys.exit(f"usage: {sys.argv[0]} LMP PLUGIN [more]")
    return sys.argv[1], sys.argv[2], sys.argv[3:]


def run_lmp(lmp, plugin, deck, variables, cwd, ranks=1, check=True):
    """Runs lmp on `deck` (a file of this folder) with `-var` variables (the
    plugin's path is the variable `plugin`); returns (exit status, output)."""
    cmd = [lmp, "-in", os.path.join(HERE, deck), "-log", "none", "-nocite",
           "-var", "plugin", plugin]
    for k, v in variables.items():
        cmd += ["-var", k, str(v)]
    if ranks > 1:
        cmd = ["mpirun", "-np", str(ranks)] + cmd
    env = dict(os.environ, **MPI_ENV)
    p = subprocess.run(cmd, cwd=cwd, env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=1200)
    if check and p.returncode != 0:
        print(p.stdout[-4000:])
        raise SystemExit(f"lmp failed (exit {p.returncode}): {' '.join(cmd)}")
    return p.returncode, p.stdout


def thermo(output):
    """The thermo table of each run in the output: a list of dicts column ->
    numpy array."""
    runs, lines = [], output.splitlines()
    k = 0
    while k < len(lines):
        if lines[k].split()[:1] == ["Step"]:
            cols = lines[k].split()
            rows = []
            k += 1
            while k < len(lines) and not lines[k].startswith("Loop time"):
                f = lines[k].split()
                if len(f) == len(cols) and re.match(r"^-?\d", f[0]):
                    rows.append([float(x) for x in f])
                k += 1
            a = np.array(rows)
            runs.append({c: a[:, i] for i, c in enumerate(cols)})
        k += 1
    return runs


def read_dump(path):
    """The last frame of a `dump custom` text file: dict column -> array,
    sorted by id, and the box bounds (3 x 2)."""
    with open(path) as f:
        lines = f.read().splitlines()
    start = max(i for i, l in enumerate(lines) if l.startswith("ITEM: TIMESTEP"))
    n = int(lines[start + 3])
    bounds = np.array([[float(x) for x in lines[start + 5 + d].split()[:2]] for d in range(3)])
    cols = lines[start + 8].split()[2:]
    a = np.array([[float(x) for x in l.split()] for l in lines[start + 9:start + 9 + n]])
    a = a[np.argsort(a[:, cols.index("id")])]
    # compute property/atom quatw quati quatj quatk shapex shapey shapez
    # (shapes: diameters) dumped as c_p[1..7]
    names = dict(zip([f"c_p[{k}]" for k in range(1, 8)],
                     ["quatw", "quati", "quatj", "quatk", "shapex", "shapey", "shapez"]))
    return {names.get(c, c): a[:, i] for i, c in enumerate(cols)}, bounds


def quat_matrix(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


# Semi-axes of the two types of the random configurations: a prolate
# spheroid and a general ellipsoid (that of pw85_md).
SEMI_AXES = {1: (1.0, 0.45, 0.45), 2: (1.0, 0.6, 0.4)}


def write_config(path, n, phi, seed, kT=0.5, jitter=0.3):
    """A LAMMPS data file (atom_style ellipsoid) of n ellipsoids, types 1 and
    2 alternating (SEMI_AXES), mass 1 each, on a simple cubic lattice
    (displaced by up to `jitter` spacings) in a cubic box of packing fraction
    phi, uniformly random orientations, Maxwell velocities and body angular
    momenta of temperature kT. Every number is written with 17 digits."""
    rng = np.random.default_rng(seed)
    types = np.array([1 + i % 2 for i in range(n)])
    vols = np.array([4 / 3 * math.pi * np.prod(SEMI_AXES[t]) for t in types])
    side = math.ceil(n ** (1 / 3))
    L = (vols.sum() / phi) ** (1 / 3)
    h = L / side
    lines = ["LAMMPS data file: pw85 plugin test configuration", "",
             f"{n} atoms", "2 atom types", f"{n} ellipsoids", "",
             f"0 {L!r} xlo xhi", f"0 {L!r} ylo yhi", f"0 {L!r} zlo zhi", "", "Atoms # ellipsoid", ""]
    quats, pos = [], []
    for i in range(n):
        cell = np.array([i % side, (i // side) % side, i // (side * side)])
        x = (cell + 0.5 + jitter * rng.uniform(-1, 1, 3)) * h
        pos.append(x % L)
        q = rng.normal(size=4)
        quats.append(q / np.linalg.norm(q))
        lines.append(f"{i + 1} {types[i]} 1 {1 / vols[i]!r} " + " ".join(repr(float(c)) for c in pos[i]))
    lines += ["", "Ellipsoids", ""]
    for i in range(n):
        d = " ".join(repr(2 * r) for r in SEMI_AXES[types[i]])
        lines.append(f"{i + 1} {d} " + " ".join(repr(float(c)) for c in quats[i]))
    lines += ["", "Velocities", ""]
    v = rng.normal(size=(n, 3)) * math.sqrt(kT)
    v -= v.mean(axis=0)
    for i in range(n):
        a = np.array(SEMI_AXES[types[i]])
        inertia = 0.2 * np.array([a[1] ** 2 + a[2] ** 2, a[0] ** 2 + a[2] ** 2, a[0] ** 2 + a[1] ** 2])
        l_body = rng.normal(size=3) * np.sqrt(kT * inertia)
        l_lab = quat_matrix(quats[i]) @ l_body
        lines.append(f"{i + 1} " + " ".join(repr(float(c)) for c in v[i]) + " "
                     + " ".join(repr(float(c)) for c in l_lab))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return L


def report(name, ok, detail):
    print(f"{name}: {'ok' if ok else 'FAILED'}: {detail}")
    return ok
