"""pw85.Scene against brute force (pw85.scene_overlap and
pw85.scene_contact_function over every pair i < j), its trial moves, its
errors, the GSD constructor, `python3 -m pw85 check` on GSD files (one
written here, one written by pw85_mc when the program is built), and the
frames of a trajectory analysed in parallel on a Dask LocalCluster."""
import os
import subprocess
import sys

import numpy as np
import pytest

import pw85


def config(n, aspect, box_scale, periodic=True, tilted=True, seed=0):
    rng = np.random.default_rng(seed)
    quat = rng.normal(size=(n, 4))
    quat /= np.linalg.norm(quat, axis=1)[:, None]
    radii = np.array([1.0, 1.0, aspect]) if aspect > 0 else rng.uniform(0.3, 1.5, (n, 3))
    q = pw85.ellipsoid_quat(np.broadcast_to(radii, (n, 3)), quat)
    rb = max(aspect, 1.0) if aspect > 0 else 1.5
    L = box_scale * rb * np.sqrt(3)
    box = np.array([L, 0.9 * L, 1.1 * L, 0.3, -0.2, 0.4] if tilted else [L, 0.9 * L, 1.1 * L, 0, 0, 0])
    f = rng.uniform(-0.5, 0.5, (n, 3)) + rng.integers(-2, 3, (n, 3)) * (rng.random((n, 1)) < 0.2)
    h = np.array([[box[0], box[3] * box[1], box[4] * box[2]],
                  [0, box[1], box[5] * box[2]],
                  [0, 0, box[2]]])
    centres = f @ h.T
    return centres, q, (box if periodic else None), radii, quat


def brute(centres, q, box, s):
    n = len(centres)
    i, j = np.triu_indices(n, 1)
    pairs = np.stack([i, j], axis=1)
    ov = pw85.scene_overlap(centres, (s * s) * q, pairs, box)
    sel = pairs[ov]
    mu2 = pw85.scene_contact_function(centres, q, sel, box, check=False)[0] if len(sel) else np.empty(0)
    return sel[:, 0], sel[:, 1], mu2


@pytest.mark.parametrize("aspect", [0.1, 1.0, 3.0, 10.0, 0.0])
@pytest.mark.parametrize("periodic", [False, True])
def test_pairs_brute_force(aspect, periodic):
    centres, q, box, _, _ = config(400, aspect, 8, periodic, seed=int(aspect * 10) + periodic)
    scene = pw85.Scene(centres, q, box)
    for s in (1.0, 1.2):
        bi, bj, bmu2 = brute(centres, q, box, s)
        assert bi.size > 0
        for nthreads in (1, 2):
            if s == 1.0:
                i, j = scene.overlapping_pairs(nthreads=nthreads)
            else:
                i, j, mu2 = scene.pairs(s, nthreads=nthreads)
                assert np.array_equal(mu2, bmu2, equal_nan=True)
            assert np.array_equal(i, bi) and np.array_equal(j, bj)


def test_test_move_and_move():
    centres, q, box, radii, quat = config(300, 3.0, 9, True, seed=3)
    scene = pw85.Scene(centres, q, box)
    rng = np.random.default_rng(4)
    cc, qq = centres.copy(), q.copy()
    hits = 0
    for t in range(150):
        i = int(rng.integers(len(cc)))
        c = cc[i] + rng.uniform(-1, 1, 3)
        u = rng.normal(size=4)
        qt = pw85.ellipsoid_quat(radii, u / np.linalg.norm(u))
        k = scene.test_move(i, c, qt)
        c2, q2 = cc.copy(), qq.copy()
        c2[i], q2[i] = c, qt
        others = np.array([j for j in range(len(cc)) if j != i])
        pairs = np.stack([np.minimum(i, others), np.maximum(i, others)], axis=1)
        ov = pw85.scene_overlap(c2, q2, pairs, box)
        expect = int(others[ov][0]) if ov.any() else -1
        assert k == expect
        hits += k >= 0
        if k < 0:
            scene.move(i, c, qt)
            cc, qq = c2, q2
    assert 5 < hits < 145
    assert np.array_equal(scene.centres, cc) and np.array_equal(scene.q, qq)
    bi, bj, _ = brute(cc, qq, box, 1.0)
    i, j = scene.overlapping_pairs()
    assert np.array_equal(i, bi) and np.array_equal(j, bj)


@pytest.mark.parametrize("periodic", [False, True])
def test_neighbours_brute_force(periodic):
    centres, q, box, _, _ = config(300, 0.0, 6, periodic, seed=11)
    scene = pw85.Scene(centres, q, box)
    if box is not None:
        h = np.array([[box[0], box[3] * box[1], box[4] * box[2]],
                      [0, box[1], box[5] * box[2]],
                      [0, 0, box[2]]])
        images = np.array([[u, v, w] for u in range(-2, 3) for v in range(-2, 3) for w in range(-2, 3)]) @ h.T
    lmin = 6 * 1.5 * np.sqrt(3) * 0.9
    listed = 0
    for t, i in enumerate(range(0, 300, 7)):
        distance = [0.1, 0.25, 0.4, 0.499][t % 4] * lmin
        j = scene.neighbours(i, distance)
        r = centres - centres[i]
        if box is not None:  # nearest image: fractional coordinates rounded, then 5^3 images
            f = np.linalg.solve(h, r.T).T
            r = r - np.rint(f) @ h.T
            d = np.min(np.linalg.norm(r[:, None, :] - images[None, :, :], axis=2), axis=1)
        else:
            d = np.linalg.norm(r, axis=1)
        d[i] = np.inf
        inside = np.flatnonzero(d < distance * (1 - 1e-9))
        outside = d >= distance * (1 + 1e-9)
        assert np.all(np.diff(j) > 0) and set(inside) <= set(j) and not np.any(outside[j])
        listed += len(j)
    assert listed > 500
    with pytest.raises(IndexError):
        scene.neighbours(300, 1.0)
    with pytest.raises(ValueError, match="distance"):
        scene.neighbours(0, -1.0)
    if box is not None:
        with pytest.raises(pw85.Error, match="exceeds"):
            scene.neighbours(0, 0.5 * lmin * 1.01)


def test_errors():
    centres, q, box, _, _ = config(50, 3.0, 9, True, seed=5)
    c = centres.copy()
    c[17, 1] = np.nan
    with pytest.raises(pw85.Error, match=r"particle 17: centres\[17\] holds a non-finite") as e:
        pw85.Scene(c, q, box)
    assert e.value.index == 17 and e.value.status == pw85.Status.ERR_INVALID_ARGUMENT
    qb = q.copy()
    qb[9] = [1, 0, 0, 1, 0, -1]
    with pytest.raises(pw85.Error, match=r"q\[9\] not positive definite") as e:
        pw85.Scene(centres, qb, box)
    assert e.value.status == pw85.Status.ERR_NOT_SPD
    with pytest.raises(pw85.Error, match="too large for the box"):
        pw85.Scene(centres, q, [5, 5, 5, 0, 0, 0])
    with pytest.raises(ValueError, match="box"):
        pw85.Scene(centres, q, [0, 5, 5, 0, 0, 0])
    with pytest.raises(ValueError, match="q: expected shape"):
        pw85.Scene(centres, q[:10], box)
    scene = pw85.Scene(centres, q, box)
    assert len(pw85.Scene(np.empty((0, 3)), np.empty((0, 6))).overlapping_pairs()[0]) == 0
    with pytest.raises(IndexError):
        scene.test_move(50, [0, 0, 0], q[0])
    with pytest.raises(pw85.Error, match="not positive definite"):
        scene.move(3, [0, 0, 0], [1, 0, 0, 1, 0, -1])
    with pytest.raises(pw85.Error, match="too far"):
        scene.move(3, [0, 0, 1e30], q[0])
    assert np.array_equal(scene.centres, centres)
    with pytest.raises(ValueError, match="s:"):
        scene.pairs(0.5)
    with pytest.raises(pw85.Error, match="cannot hold"):
        scene.pairs(10.0)
    with pytest.raises(ValueError):
        scene.centres[0, 0] = 1.0  # read-only


def gsd_frames(path, frames):
    gsd_hoomd = pytest.importorskip("gsd.hoomd")
    make = getattr(gsd_hoomd, "Frame", None) or gsd_hoomd.Snapshot
    with gsd_hoomd.open(path, "wb") as f:
        for centres, quat, radii, box in frames:
            fr = make()
            fr.particles.N = len(centres)
            fr.particles.position = centres.astype(np.float32)
            fr.particles.orientation = quat.astype(np.float32)
            fr.particles.types = ["A"]
            fr.particles.typeid = np.zeros(len(centres), np.uint32)
            fr.particles.type_shapes = [{"type": "Ellipsoid", "a": float(radii[0]),
                                         "b": float(radii[1]), "c": float(radii[2])}]
            fr.configuration.box = box.astype(np.float32)
            f.append(fr)


def sparse_frame(seed, overlap):
    """A lattice of spheroids (1, 1, 3) with no overlap, or with particles
    0 and 1 overlapping."""
    m = 5
    x = np.arange(m) * 7.0
    centres = np.stack(np.meshgrid(x, x, x * 1.0, indexing="ij"), -1).reshape(-1, 3)
    centres -= centres.mean(axis=0)
    rng = np.random.default_rng(seed)
    quat = rng.normal(size=(len(centres), 4))
    quat /= np.linalg.norm(quat, axis=1)[:, None]
    if overlap:
        centres[1] = centres[0] + [0.5, 0, 0]
    box = np.array([m * 7.0] * 3 + [0, 0, 0])
    return centres, quat, np.array([1.0, 1.0, 3.0]), box


def test_from_gsd_and_check(tmp_path):
    path = str(tmp_path / "t.gsd")
    frames = [sparse_frame(1, False), sparse_frame(2, True), sparse_frame(3, False)]
    gsd_frames(path, frames)
    import gsd.hoomd
    with gsd.hoomd.open(path, "rb") as traj:
        for frame, (centres, quat, radii, box) in zip(traj, frames):
            scene = pw85.Scene.from_gsd(frame)
            c32 = centres.astype(np.float32).astype(np.float64)
            q32 = quat.astype(np.float32).astype(np.float64)
            q = pw85.ellipsoid_quat(np.broadcast_to(radii, (len(c32), 3)),
                                    q32 / np.linalg.norm(q32, axis=1)[:, None])
            assert np.array_equal(scene.centres, c32) and np.array_equal(scene.q, q)
            bi, bj, _ = brute(c32, q, box, 1.0)
            i, j = scene.overlapping_pairs()
            assert np.array_equal(i, bi) and np.array_equal(j, bj)
    env = dict(os.environ)
    r = subprocess.run([sys.executable, "-m", "pw85", "check", path], capture_output=True,
                       text=True, env=env, timeout=120)
    assert r.returncode == 1, r.stderr
    lines = r.stdout.splitlines()
    assert lines[0].startswith("frame 0: N = 125, overlapping pairs: 0, smallest mu^2: ")
    assert lines[1].startswith("frame 1: N = 125, overlapping pairs: 1, smallest mu^2: ")
    assert "(pair 0, 1)" in lines[1]
    assert float(lines[0].split("smallest mu^2: ")[1].split()[0]) > 1
    clean = str(tmp_path / "clean.gsd")
    gsd_frames(clean, [sparse_frame(1, False)])
    r = subprocess.run([sys.executable, "-m", "pw85", "check", clean], capture_output=True,
                       text=True, env=env, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    r = subprocess.run([sys.executable, "-m", "pw85", "check", str(tmp_path / "none.gsd")],
                       capture_output=True, text=True, env=env, timeout=120)
    assert r.returncode == 2 and "none.gsd" in r.stderr


def test_check_on_pw85_mc_output(tmp_path):
    """A file written by pw85_mc (PW85_MC: its path, set by the build)."""
    mc = os.environ.get("PW85_MC")
    if not mc or not os.path.exists(mc):
        pytest.skip("pw85_mc not built (PW85_MC unset)")
    pytest.importorskip("gsd.hoomd")
    out = str(tmp_path / "mc.gsd")
    r = subprocess.run([mc, "--n", "300", "--sweeps", "5", "--gsd", out], capture_output=True,
                       text=True, timeout=300)
    if r.returncode != 0 or not os.path.exists(out):
        pytest.skip(f"pw85_mc did not write a GSD file here: {r.stderr.strip()[:200]}")
    r = subprocess.run([sys.executable, "-m", "pw85", "check", out], capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "overlapping pairs: 0" in r.stdout


def test_dask_frames_in_parallel(tmp_path):
    """docs/examples/scene_dask.py: the frames of a trajectory on a Dask
    LocalCluster of two worker processes, results equal to the in-process
    analysis."""
    if os.environ.get("PW85_DASK_TEST_SKIP"):
        pytest.skip(os.environ["PW85_DASK_TEST_SKIP"])
    pytest.importorskip("dask")
    distributed = pytest.importorskip("distributed")
    pytest.importorskip("gsd.hoomd")
    examples = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs",
                            "examples")
    sys.path.insert(0, examples)
    try:
        import scene_dask
    finally:
        sys.path.pop(0)
    path = str(tmp_path / "traj.gsd")
    gsd_frames(path, [sparse_frame(k, k % 3 == 1) for k in range(6)])
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None, silence_logs=40)
    client = distributed.Client(cluster, timeout=120)
    try:
        client.upload_file(os.path.join(examples, "scene_dask.py"))
        rows = scene_dask.analyse(path, client)
        workers = client.run(lambda: os.getpid())
        assert len(set(workers.values()) - {os.getpid()}) == 2
    finally:
        client.close()
        cluster.close()
    assert [r[0] for r in rows] == list(range(6))
    assert [r[1] for r in rows] == [0, 1, 0, 0, 1, 0]
    local = [scene_dask.analyse_frame(path, k) for k in range(6)]
    assert rows == local
