"""The GIL is released during the C calls: while one Python thread is inside
a long C call, another Python thread keeps running. Robust to a loaded
machine with any number of cores: the main thread timestamps each iteration
of a pure-Python loop, and the test asserts that it made progress all along
the C call (no pause longer than half the call; a held GIL would pause it
for the whole call)."""
import threading
import time

import numpy as np
import pytest

import pw85


def pairs(m):
    rng = np.random.default_rng(0)
    axes = np.linalg.qr(rng.normal(size=(2, 3, 3)))[0]
    q = pw85.ellipsoid(rng.uniform(0.5, 2, (2, 3)), axes)
    return rng.normal(size=(m, 3)), q[0], q[1]


R12, QA, QB = pairs(100000)
R12_BIG = np.concatenate([R12] * 10)
QA_BIG = np.tile(QA, (len(R12_BIG), 1))
QB_BIG = np.tile(QB, (len(R12_BIG), 1))
N = 50
CENTRES = np.random.default_rng(1).uniform(0, 10, (N, 3))
SCENE_PAIRS = np.random.default_rng(2).integers(0, N, (200000, 2))
CALLS = {
    "contact_function": lambda: pw85.contact_function(R12, QA, QB, method="brent", nthreads=1),
    "overlap": lambda: pw85.overlap(R12_BIG, QA_BIG, QB_BIG, nthreads=1),
    "scene_contact": lambda: pw85.scene_contact(CENTRES, QA, SCENE_PAIRS, check=False,
                                                nthreads=1),
}


@pytest.mark.parametrize("name", list(CALLS))
def test_other_thread_runs_during_call(name):
    call = CALLS[name]
    call()  # warm up
    window = {}

    def worker():
        window["t0"] = time.perf_counter()
        call()
        window["t1"] = time.perf_counter()

    stamps = []
    t = threading.Thread(target=worker)
    t.start()
    while t.is_alive():
        stamps.append(time.perf_counter())
    t.join()
    t0, t1 = window["t0"], window["t1"]
    inside = [s for s in stamps if t0 < s < t1]
    assert t1 - t0 > 0.02, "the call is too short to tell"
    assert inside, f"{name}: the main thread never ran during the {t1 - t0:.3f} s call"
    gaps = np.diff([t0] + inside + [t1])
    assert gaps.max() < 0.5 * (t1 - t0), (
        f"{name}: the main thread paused {gaps.max():.3f} s of a {t1 - t0:.3f} s call")


def test_two_threads_same_results():
    """Concurrent calls from two threads give the single-thread results."""
    ref = pw85.contact_function(R12[:20000], QA, QB)[0]
    out = [None, None]

    def worker(i):
        out[i] = pw85.contact_function(R12[:20000], QA, QB, nthreads=1)[0]

    ts = [threading.Thread(target=worker, args=(i,)) for i in range(2)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    assert np.array_equal(out[0], ref) and np.array_equal(out[1], ref)
