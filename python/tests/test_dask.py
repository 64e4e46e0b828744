"""The vectorised calls inside Dask: chunked arrays through blockwise and
map_blocks on a distributed LocalCluster of two worker processes (one
thread each), results identical to the in-process call. Skipped when dask
or distributed is not importable, or when the build sets
PW85_DASK_TEST_SKIP."""
import os

import numpy as np
import pytest

import pw85

if os.environ.get("PW85_DASK_TEST_SKIP"):
    pytest.skip(os.environ["PW85_DASK_TEST_SKIP"], allow_module_level=True)
da = pytest.importorskip("dask.array")
distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None, silence_logs=40)
    c = distributed.Client(cluster, timeout=120)
    yield c
    c.close()
    cluster.close()


def data(m=2000):
    rng = np.random.default_rng(5)
    axes = np.linalg.qr(rng.normal(size=(m, 3, 3)))[0]
    q1 = pw85.ellipsoid(rng.uniform(0.5, 2, (m, 3)), axes)
    q2 = pw85.ellipsoid(rng.uniform(0.5, 2, (m, 3)), axes[::-1])
    return rng.normal(size=(m, 3)) * 2, q1, q2


def mu2_block(r12, q1, q2):
    return pw85.contact_function(r12, q1, q2, nthreads=1)[0]


def test_blockwise_on_local_cluster(client):
    r12, q1, q2 = data()
    R, A, B = (da.from_array(x, chunks=(300, x.shape[1])) for x in (r12, q1, q2))
    ov = da.blockwise(pw85.overlap, "i", R, "ij", A, "ik", B, "ik", dtype=bool,
                      concatenate=True)
    mu2 = da.blockwise(mu2_block, "i", R, "ij", A, "ik", B, "ik", dtype=float,
                       concatenate=True)
    c = da.blockwise(pw85.contact, "i", R, "ij", A, "ik", B, "ik", dtype=pw85.CONTACT_DTYPE,
                     concatenate=True)
    ov_d, mu2_d, c_d = client.compute([ov, mu2, c], sync=True)
    assert np.array_equal(ov_d, pw85.overlap(r12, q1, q2))
    assert np.array_equal(mu2_d, pw85.contact_function(r12, q1, q2)[0])
    ref = pw85.contact(r12, q1, q2)
    assert all(np.array_equal(c_d[f], ref[f]) for f in ref.dtype.names)
    workers = client.run(lambda: os.getpid())
    assert len(set(workers.values()) - {os.getpid()}) == 2


def test_map_blocks_one_against_many(client):
    r12, q1, q2 = data()
    R = da.from_array(r12, chunks=(250, 3))
    ov = R.map_blocks(pw85.overlap, q1[0], q2[0], drop_axis=1, dtype=bool)
    d = R.map_blocks(pw85.dca, q1[0], q2[0], drop_axis=1, dtype=float)
    ov_d, d_d = client.compute([ov, d], sync=True)
    assert np.array_equal(ov_d, pw85.overlap(r12, q1[0], q2[0]))
    assert np.array_equal(d_d, pw85.dca(r12, q1[0], q2[0]))


def test_errors_cross_process(client):
    r12, q1, q2 = data(100)
    r12[57, 0] = np.nan
    fut = client.submit(pw85.overlap, r12, q1, q2)
    with pytest.raises(pw85.Error, match="r12") as info:
        fut.result()
    assert info.value.index == 57 and info.value.status == pw85.Status.ERR_INVALID_ARGUMENT
