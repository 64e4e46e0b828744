"""The frames of a GSD trajectory of ellipsoids analysed in parallel with
Dask (docs/scene.md, "From Python"): one task per frame, each opening the
file, building a pw85.Scene and returning (frame, overlapping pairs,
smallest mu^2 within s = 1.5 or NaN, mean number of neighbours within
s = 1.5).

    python3 scene_dask.py TRAJ.gsd [N_WORKERS]

starts a LocalCluster of N_WORKERS processes (default 2) and prints one
line per frame."""
import sys

import numpy as np

import pw85


def analyse_frame(path, k, s=1.5):
    import gsd.hoomd
    with gsd.hoomd.open(path, "rb") as traj:
        frame = traj[k]
    with pw85.Scene.from_gsd(frame) as scene:
        i, _ = scene.overlapping_pairs(nthreads=1)
        a, b, mu2 = scene.pairs(s, nthreads=1)
        smallest = float(mu2.min()) if mu2.size else float("nan")
        neighbours = 2.0 * a.size / max(len(scene), 1)
    return (k, int(i.size), smallest, neighbours)


def analyse(path, client):
    """One task per frame on the Dask client; the rows in frame order."""
    import gsd.hoomd
    with gsd.hoomd.open(path, "rb") as traj:
        nframes = len(traj)
    futures = client.map(analyse_frame, [path] * nframes, range(nframes))
    return client.gather(futures)


if __name__ == "__main__":
    import distributed
    workers = int(sys.argv[2]) if len(sys.argv) > 2 else 2
    with distributed.LocalCluster(n_workers=workers, threads_per_worker=1,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        for k, overlapping, smallest, neighbours in analyse(sys.argv[1], client):
            print(f"frame {k}: {overlapping} overlapping pairs, smallest mu^2 {smallest:.6g}, "
                  f"{neighbours:.3g} neighbours per particle (s = 1.5)")
