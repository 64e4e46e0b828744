"""Helpers of the checks of the demonstration programs (check_pw85_mc.py,
check_pw85_dynamics.py): quaternion algebra written here, and the close
pairs of a periodic configuration evaluated by the pw85 program's batch
mode (quaternion lines: centre, semi-axes, quaternion (w, x, y, z))."""
import subprocess

import numpy as np


def hamilton(p, q):
    w1, x1, y1, z1 = p
    w2, x2, y2, z2 = q
    return np.array([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2])


def rotate(q_wxyz, v):
    """q v q* for a unit quaternion q (Hamilton product)."""
    conj = np.asarray(q_wxyz) * np.array([1, -1, -1, -1])
    return hamilton(hamilton(q_wxyz, [0.0, *v]), conj)[1:]


def pair_lines(centres, radii, quats_wxyz, box, cutoff):
    """20-number batch lines (c1, radii, quat, c2 = minimum image, radii,
    quat) of the pairs i < j closer than cutoff, and the pairs."""
    lines, pairs = [], []
    n = len(centres)
    for i in range(n):
        d = centres - centres[i]
        d -= box * np.round(d / box)
        close = np.nonzero(np.einsum("ij,ij->i", d, d) < cutoff ** 2)[0]
        for j in close[close > i]:
            c2 = centres[i] + d[j]
            nums = list(centres[i]) + list(radii) + list(quats_wxyz[i]) + list(c2) + list(radii) + list(quats_wxyz[j])
            lines.append(" ".join(repr(float(x)) for x in nums))
            pairs.append((i, j))
    return lines, pairs


def batch(cli, lines):
    """Exit status of `cli --batch` and its CSV rows (line, mu2, lambda,
    overlap, status)."""
    r = subprocess.run([cli, "--batch"], input="\n".join(lines) + "\n", capture_output=True, text=True)
    rows = [l.split(",") for l in r.stdout.splitlines()[1:]]
    return r.returncode, rows
