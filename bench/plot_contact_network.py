#!/usr/bin/python3
"""A snapshot of a pw85_mc configuration and its contact network coloured
by mu^2.

    /usr/bin/python3 bench/plot_contact_network.py build/src/tools/pw85_mc

Runs pw85_mc (300 prolate spheroids of semi-axes 0.5, 0.5, 1.5, packing
fraction 0.3, seed 3, 200 equilibration and 1000 production sweeps: past
the relaxation of the aligned start, docs/usage.md) with --xyz, reads its
last frame (doubles), finds the pairs whose centres are closer than 2 c = 3
(brute force over the minimum images) and evaluates their mu^2 with
pw85.scene_contact_function (periodic box). The pairs with mu^2 < 1.44
(mu < 1.2: the two spheroids, each scaled by 1.2 about its centre, would
overlap) form the contact network. Left: the spheroids whose centres lie
in a slab through the middle of the box, normal to the view, of depth half
the box side (orthographic view; outlines exact: the outline of an
ellipsoid of matrix Q seen along z is the ellipse of the upper-left 2x2
block of Q), drawn from back to front, translucent, and the network's
bonds between them, from each centre to the nearest image of the other,
coloured by mu^2. Right: the distribution of mu^2 over all the pairs, the
shell coloured. Writes docs/contact_network.png. About 10 s.

pw85 is imported as installed, else from python/ of this source tree with
the library next to the program (PW85_LIBRARY = BUILD/src/libpw85.so.1).
"""
import os
import re
import subprocess
import sys
import tempfile

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.colors import LinearSegmentedColormap, Normalize  # noqa: E402
from matplotlib.patches import Ellipse  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.join(HERE, os.pardir)
DOCS = os.path.join(SOURCE, "docs")
N, PHI, SEED, EQUIL, SWEEPS = 300, 0.3, 3, 200, 1000
SEMI_AXES = np.array([0.5, 0.5, 1.5])
SHELL = 1.44  # mu^2 < SHELL: a bond of the network
SLAB = 0.5  # the slab drawn: centres within SLAB * box / 2 of the box centre along the view


def import_pw85(program):
    try:
        import pw85
        return pw85
    except ImportError:
        build = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(program))))
        os.environ.setdefault("PW85_LIBRARY", os.path.join(build, "src", "libpw85.so.1"))
        sys.path.insert(0, os.path.join(SOURCE, "python"))
        import pw85
        return pw85


def last_xyz_frame(path):
    """Box side, S2, centres (n, 3), quaternions (w, x, y, z) (n, 4) of the
    last frame of pw85_mc's extended XYZ file."""
    lines = open(path).read().splitlines()
    k, start = 0, 0
    while k < len(lines):
        start = k
        k += 2 + int(lines[k])
    n, header = int(lines[start]), lines[start + 1]
    box = float(re.search(r'Lattice="(\S+) ', header).group(1))
    s2 = float(re.search(r" S2=(\S+)", header).group(1))
    rows = np.array([[float(x) for x in l.split()[1:]] for l in lines[start + 2:start + 2 + n]])
    return box, s2, rows[:, 0:3], rows[:, [6, 3, 4, 5]]


def rotation(q):
    """Rotation matrix of the unit quaternion (w, x, y, z), columns the body
    axes."""
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def view_matrix(elevation, azimuth):
    """Rows: screen x, screen y, towards the viewer (orthographic)."""
    e, a = np.radians(elevation), np.radians(azimuth)
    toward = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    right = np.cross([0.0, 0.0, 1.0], toward)
    right /= np.linalg.norm(right)
    return np.array([right, np.cross(toward, right), toward])


def main():
    program = sys.argv[1] if len(sys.argv) > 1 else "build/src/tools/pw85_mc"
    pw85 = import_pw85(program)
    with tempfile.TemporaryDirectory() as d:
        xyz = os.path.join(d, "c.xyz")
        run = subprocess.run([program, "--n", str(N), "--phi", str(PHI), "--seed", str(SEED),
                              "--equil", str(EQUIL), "--sweeps", str(SWEEPS), "--blocks", "1",
                              "--xyz", xyz], capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(f"{program} failed ({run.returncode}): {run.stderr}")
        box, s2, centres, quats = last_xyz_frame(xyz)
    rot = np.array([rotation(q) for q in quats])
    q_full = np.einsum("nij,j,nkj->nik", rot, SEMI_AXES ** 2, rot)
    q6 = q_full[:, [0, 0, 0, 1, 1, 2], [0, 1, 2, 1, 2, 2]]

    # pairs closer than 2 c (minimum image), then mu^2 of each
    d = centres[None, :, :] - centres[:, None, :]
    d -= box * np.round(d / box)
    i, j = np.nonzero(np.triu(np.einsum("ijk,ijk->ij", d, d) < (2 * SEMI_AXES.max()) ** 2, k=1))
    pairs = np.stack([i, j], axis=1)
    mu2, _ = pw85.scene_contact_function(centres, q6, pairs, box=[box, box, box, 0, 0, 0])
    bonds = mu2 < SHELL
    print(f"{N} spheroids, box {box:.4f}, S2 {s2:.3f}: {len(pairs)} pairs closer than "
          f"{2 * SEMI_AXES.max()}, min mu^2 {mu2.min():.6f}, {bonds.sum()} with mu^2 < {SHELL} "
          f"({2 * bonds.sum() / N:.2f} per spheroid)")

    view = view_matrix(22, 35)
    screen = (centres - box / 2) @ view.T
    q_screen = np.einsum("ij,njk,lk->nil", view, q_full, view)
    cmap = LinearSegmentedColormap.from_list("bond", plt.get_cmap("plasma")(np.linspace(0, 0.82, 256)))
    norm = Normalize(1.0, SHELL)

    fig, (ax, hx) = plt.subplots(1, 2, figsize=(13, 6.6), gridspec_kw={"width_ratios": [1.6, 1]})
    depth = screen[:, 2]
    in_slab = np.abs(depth) < SLAB * box / 2
    near, far = depth[in_slab].max(), depth[in_slab].min()
    for k in np.argsort(depth):  # back to front
        if not in_slab[k]:
            continue
        evals, evecs = np.linalg.eigh(q_screen[k, :2, :2])
        t = (depth[k] - far) / (near - far)  # 0 at the back, 1 at the front
        ax.add_patch(Ellipse(screen[k, :2], 2 * np.sqrt(evals[1]), 2 * np.sqrt(evals[0]),
                             angle=np.degrees(np.arctan2(evecs[1, 1], evecs[0, 1])),
                             facecolor=(0.62 + 0.33 * t, 0.66 + 0.31 * t, 0.74 + 0.24 * t),
                             edgecolor=(0.3, 0.32, 0.4), linewidth=0.5, alpha=0.8))
    shown = bonds & in_slab[pairs[:, 0]] & in_slab[pairs[:, 1]]
    b_i, b_j, b_mu2 = pairs[shown, 0], pairs[shown, 1], mu2[shown]
    ends = np.stack([screen[b_i, :2], screen[b_i, :2] + (d[b_i, b_j] @ view.T)[:, :2]], axis=1)
    order = np.argsort(-b_mu2)  # the closest contacts on top
    ax.add_collection(LineCollection(ends[order], colors=cmap(norm(b_mu2[order])),
                                     linewidths=0.8 + 2.0 * (SHELL - b_mu2[order]) / (SHELL - 1)))
    corners = np.array([[x, y, z] for x in (0, box) for y in (0, box) for z in (0, box)]) - box / 2
    for a in range(8):
        for b in range(a + 1, 8):
            if np.sum(corners[a] != corners[b]) == 1:
                p = corners[[a, b]] @ view.T
                ax.plot(p[:, 0], p[:, 1], color="0.6", linewidth=0.6, zorder=0)
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_axis_off()
    ax.set_title(f"pw85_mc: {N} spheroids (aspect 3), packing fraction {PHI}, S2 = {s2:.2f},\n"
                 f"{bonds.sum()} pairs with $\\mu^2 < {SHELL}$; drawn: the {in_slab.sum()} in a slab "
                 f"of depth {SLAB:g} L and their {shown.sum()} pairs", fontsize=11)
    sm = plt.cm.ScalarMappable(norm=norm, cmap=cmap)
    fig.colorbar(sm, ax=ax, fraction=0.035, pad=0.01, label=r"$\mu^2$ of the pair")

    edges = np.linspace(1.0, 4.0, 61)
    counts, _ = np.histogram(mu2, edges)
    centres_h = 0.5 * (edges[1:] + edges[:-1])
    colours = [cmap(norm(c)) if c < SHELL else (0.75, 0.75, 0.78) for c in centres_h]
    hx.bar(centres_h, counts, width=edges[1] - edges[0], color=colours, edgecolor="white", linewidth=0.3)
    hx.axvline(SHELL, color="0.3", linestyle="--", linewidth=0.8)
    hx.text(SHELL + 0.02, counts.max() * 0.95, f"shell $\\mu^2 < {SHELL}$\n($\\mu$ < 1.2)", fontsize=9,
            va="top")
    hx.set_xlabel(r"$\mu^2$ (pw85.scene_contact_function)")
    hx.set_ylabel(f"pairs with centres closer than {2 * SEMI_AXES.max():g}")
    hx.set_title(f"{len(pairs)} neighbour pairs, min $\\mu^2$ = {mu2.min():.4f}\n"
                 f"({np.sum(mu2 >= edges[-1])} with $\\mu^2 \\geq$ {edges[-1]:g} not shown)", fontsize=11)
    fig.tight_layout()
    out = os.path.join(DOCS, "contact_network.png")
    fig.savefig(out, dpi=110)
    print(f"wrote {os.path.relpath(out)}")


if __name__ == "__main__":
    main()
