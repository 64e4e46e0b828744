"""python3 -m pw85 check FILE.gsd [--s S] [--nthreads T]

For each frame of a HOOMD GSD file of ellipsoids (type_shapes 'Ellipsoid'),
prints the number of particles, the number of overlapping pairs (exact
verdicts, pw85.Scene.overlapping_pairs) and the smallest mu^2 among the
pairs within the scale factor S (default 1.5: mu^2 < 2.25; "> S^2" when no
pair is that close; S is lowered to what the box holds). Exit status: 0
when no frame has an overlapping pair, 1 when one has, 2 on a usage or file
error."""
import argparse
import sys

import numpy as np

from . import Scene, Error


def _smallest(scene, s, nthreads):
    """(mu2, i, j) of the closest pair within s (None when none), and the s
    used: s lowered while the box cannot hold the pairs at s."""
    while True:
        try:
            i, j, mu2 = scene.pairs(s, nthreads=nthreads)
            break
        except Error:
            if s <= 1.0:
                raise
            s = max(1.0, s / 1.1)
    if mu2.size == 0:
        return None, s
    k = int(np.nanargmin(mu2)) if np.any(np.isfinite(mu2)) else 0
    return (float(mu2[k]), int(i[k]), int(j[k])), s


def check(path, s=1.5, nthreads=0, out=sys.stdout):
    """Checks every frame of path; returns the exit status."""
    import gsd.hoomd
    bad_frames = 0
    with gsd.hoomd.open(path, "rb") as traj:
        for f, frame in enumerate(traj):
            scene = Scene.from_gsd(frame)
            i, _ = scene.overlapping_pairs(nthreads=nthreads)
            closest, s_used = _smallest(scene, s, nthreads)
            if closest is None:
                smallest = f"> {s_used * s_used:.6g}"
            else:
                smallest = f"{closest[0]:.17g} (pair {closest[1]}, {closest[2]})"
            print(f"frame {f}: N = {len(scene)}, overlapping pairs: {i.size}, "
                  f"smallest mu^2: {smallest}", file=out)
            bad_frames += i.size > 0
            scene.close()
    if bad_frames:
        print(f"{bad_frames} frame(s) with overlapping pairs", file=out)
    return 1 if bad_frames else 0


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m pw85")
    sub = parser.add_subparsers(dest="command", required=True)
    c = sub.add_parser("check", help="overlapping pairs and smallest mu^2 of each frame of a "
                                     "GSD file of ellipsoids")
    c.add_argument("file")
    c.add_argument("--s", type=float, default=1.5,
                   help="scale factor of the neighbour shell for the smallest mu^2 (>= 1)")
    c.add_argument("--nthreads", type=int, default=0)
    args = parser.parse_args(argv)
    try:
        return check(args.file, args.s, args.nthreads)
    except (OSError, ValueError, KeyError, RuntimeError) as e:
        print(f"python3 -m pw85 check: {args.file}: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
