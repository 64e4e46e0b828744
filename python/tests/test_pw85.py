"""pw85: the vectorised API against the one-pair calls, the reference data
and NumPy; broadcasting, conversions, scenes, periodic boxes, 2D and DCA."""
import pickle
import re
import os

import numpy as np
import pytest

import pw85
import pypw85
from conftest import MU2_TUTORIAL, LAMBDA_TUTORIAL, within_ulps

R12 = np.array([0.7, -0.7, 1.1])
Q1 = pw85.spheroid(10., 0.1, [0., 0., 1.])
Q2 = pw85.spheroid(0.5, 5., [1., 0., 0.])


def random_pairs(m, seed=0, lo=0.5, hi=2.0):
    rng = np.random.default_rng(seed)
    def ell(k):
        axes = np.linalg.qr(rng.normal(size=(k, 3, 3)))[0]
        return pw85.ellipsoid(rng.uniform(lo, hi, size=(k, 3)), axes)
    r12 = rng.normal(size=(m, 3)) * rng.uniform(0.2, 3, size=(m, 1))
    return r12, ell(m), ell(m)


def test_version_and_names():
    header = os.path.join(os.path.dirname(__file__), "..", "..", "include", "pw85.h")
    with open(header) as f:
        v = re.search(r'#define PW85_VERSION "(.*)"', f.read()).group(1)
    assert pw85.__version__ == v == pypw85.__version__
    assert [int(m) for m in pw85.Method] == [0, 1, 2, 3, 4]
    assert pw85.Method.DEFAULT == 0 and pw85.Method.ZHENG == 4
    assert pw85.status_name(-7) == "PW85_ERR_RANGE"
    assert pw85.status_name(-99) == "status -99"
    assert pw85.Status.ERR_NOT_SPD == -2


def test_tutorial_one_pair():
    mu2, lam = pw85.contact_function(R12, Q1, Q2, method="brent")
    assert within_ulps(mu2, MU2_TUTORIAL) and within_ulps(lam, LAMBDA_TUTORIAL)
    assert isinstance(mu2, np.float64) and np.ndim(mu2) == 0
    mu2d, _ = pw85.contact_function(R12, Q1, Q2)
    assert abs(mu2d - MU2_TUTORIAL) <= 1e-14 * MU2_TUTORIAL
    ov = pw85.overlap(R12, Q1, Q2)
    assert ov is False or ov == np.False_
    c = pw85.contact(R12, Q1, Q2)
    assert c["mu2"] == mu2d and c["x0"].shape == (3,) and c["n"].shape == (3,)
    assert np.allclose(c["n"], [3.64031943e-04, -3.82067448e-04, 9.99999861e-01], atol=1e-10)


def test_spheroid_ellipsoid_vectorised():
    rng = np.random.default_rng(1)
    a, c = rng.uniform(0.1, 10, 50), rng.uniform(0.1, 10, 50)
    n = rng.normal(size=(50, 3))
    n /= np.linalg.norm(n, axis=1)[:, None]
    q = pw85.spheroid(a, c, n)
    assert q.shape == (50, 6)
    for k in range(50):
        assert np.array_equal(q[k], pypw85.spheroid(a[k], c[k], n[k]))
    assert pw85.spheroid(2., 3., n).shape == (50, 6)
    assert pw85.spheroid(a[:, None], c[:, None], n[:4]).shape == (50, 4, 6)
    axes = np.linalg.qr(rng.normal(size=(50, 3, 3)))[0]
    radii = rng.uniform(0.1, 10, (50, 3))
    q = pw85.ellipsoid(radii, axes)
    for k in range(50):
        m = axes[k].T @ np.diag(radii[k] ** 2) @ axes[k]
        assert np.allclose(q[k], m[np.triu_indices(3)], rtol=1e-13, atol=1e-13 * radii[k].max() ** 2)
    assert pw85.ellipsoid([1, 2, 3], np.eye(3)).tolist() == [1, 0, 0, 4, 0, 9]


@pytest.mark.parametrize("method", list(pw85.Method))
def test_contact_function_against_one_pair(method):
    r12, q1, q2 = random_pairs(300, seed=int(method))
    mu2, lam = pw85.contact_function(r12, q1, q2, method=method, nthreads=2)
    assert mu2.shape == lam.shape == (300,)
    for k in range(0, 300, 7):
        m1, l1 = pw85.contact_function(r12[k], q1[k], q2[k], method=method.name.lower())
        assert m1 == mu2[k] and l1 == lam[k]  # bitwise
    if method == pw85.Method.BRENT:
        for k in range(0, 300, 31):
            ref = pypw85.contact_function(r12[k], q1[k], q2[k])
            assert ref[0] == mu2[k] and ref[1] == lam[k]


def test_reference_data(refdata):
    g = refdata["contact"]
    for cls in range(4):
        sel = g["class"] == cls
        mu2, lam = pw85.contact_function(g["r12"][sel], g["q1"][sel], g["q2"][sel])
        err = np.abs(mu2 - g["mu2"][sel]) / g["mu2"][sel]
        assert err.max() <= 1e-14, (cls, err.max())
    h = refdata["near_contact"]
    ref = h["mu2"]
    ov = pw85.overlap(h["r12"], h["q1"], h["q2"])
    decided = ref != 1.0
    assert np.array_equal(ov[decided], ref[decided] < 1)


def test_overlap_and_contact_vectorised():
    r12, q1, q2 = random_pairs(500, seed=7)
    ov = pw85.overlap(r12, q1, q2, nthreads=2)
    assert ov.dtype == bool and ov.shape == (500,)
    mu2, _ = pw85.contact_function(r12, q1, q2)
    assert np.array_equal(ov, mu2 < 1)
    c = pw85.contact(r12, q1, q2)
    assert c.dtype == pw85.CONTACT_DTYPE and c.shape == (500,)
    assert np.array_equal(c["mu2"], mu2)
    for k in range(0, 500, 50):
        assert pw85.overlap(r12[k], q1[k], q2[k]) == ov[k]
        ck = pw85.contact(r12[k], q1[k], q2[k])
        assert all(np.array_equal(ck[f], c[k][f]) for f in c.dtype.names)
    assert np.allclose(c["dca"], np.linalg.norm(r12, axis=1) / np.sqrt(mu2))


def test_contact_derivatives():
    r12, q1, q2 = random_pairs(300, seed=11)
    d = pw85.contact_derivatives(r12, q1, q2, nthreads=2)
    assert d.dtype == pw85.DERIVATIVES_DTYPE and d.shape == (300,)
    mu2, _ = pw85.contact_function(r12, q1, q2)
    assert np.array_equal(d["mu2"], mu2)
    # bitwise against the C one-pair call through bare ctypes
    one = np.zeros(1, pw85.DERIVATIVES_DTYPE)
    for k in range(0, 300, 13):
        rk, ak, bk = (np.ascontiguousarray(x[k]) for x in (r12, q1, q2))
        st = pw85._clib.pw85_contact_derivatives(rk.ctypes.data, ak.ctypes.data, bk.ctypes.data,
                                                 one.ctypes.data)
        assert st == 0 and one.tobytes() == d[k:k + 1].tobytes()
        dk = pw85.contact_derivatives(r12[k], q1[k], q2[k])
        assert dk.dtype == pw85.DERIVATIVES_DTYPE and dk.tobytes() == one.tobytes()
    # Euler's identity for mu^2, homogeneous of degree 2 in r12: g.r12 = 2 mu^2
    euler = np.einsum("ij,ij->i", d["d_r12"], r12)
    assert np.all(np.abs(euler - 2 * mu2) <= 1e-13 * 2 * mu2)
    # the gradient against a central difference of mu^2 along r12's first axis
    h = 1e-6
    e0 = np.array([h, 0.0, 0.0])
    fd = (pw85.contact_function(r12 + e0, q1, q2)[0]
          - pw85.contact_function(r12 - e0, q1, q2)[0]) / (2 * h)
    assert np.allclose(fd, d["d_r12"][:, 0], rtol=1e-6, atol=1e-8 * np.abs(d["d_r12"]).max())
    # r12 = 0: no derivative there
    bad = r12.copy()
    bad[4] = 0.0
    with pytest.raises(pw85.Error, match="pair 4.*r12 = 0"):
        pw85.contact_derivatives(bad, q1, q2)
    d2, st = pw85.contact_derivatives(bad, q1, q2, check=False)
    assert st[4] == pw85.Status.ERR_INVALID_ARGUMENT and st[3] == 0
    assert all(np.isnan(d2[4][f]).all() for f in d2.dtype.names)
    assert d2[3].tobytes() == d[3].tobytes()


def test_contact_derivatives_forces_only():
    # forces_only: mu2, lambda, gradient and torques bitwise the full call's
    # (pw85_contact_derivatives through bare ctypes), the rest NaN
    r12, q1, q2 = random_pairs(300, seed=17)
    full = pw85.contact_derivatives(r12, q1, q2)
    light = pw85.contact_derivatives(r12, q1, q2, nthreads=2, forces_only=True)
    assert light.dtype == pw85.DERIVATIVES_DTYPE and light.shape == (300,)
    forces = ("mu2", "lambda", "d_r12", "d_theta1", "d_theta2")
    for f in forces:
        assert light[f].tobytes() == full[f].tobytes()
    for f in ("d_q1", "d_q2", "hess_r12"):
        assert np.isnan(light[f]).all()
    one = np.zeros(1, pw85.DERIVATIVES_DTYPE)
    for k in range(0, 300, 29):
        rk, ak, bk = (np.ascontiguousarray(x[k]) for x in (r12, q1, q2))
        assert pw85._clib.pw85_contact_derivatives(rk.ctypes.data, ak.ctypes.data,
                                                   bk.ctypes.data, one.ctypes.data) == 0
        assert one.tobytes()[:88] == light[k:k + 1].tobytes()[:88]
        lk = pw85.contact_derivatives(r12[k], q1[k], q2[k], forces_only=True)
        assert lk.tobytes() == light[k:k + 1].tobytes()
    # flags other than 0 and 1 are invalid (the C calls)
    assert pw85._clib.pw85_contact_derivatives_ex(rk.ctypes.data, ak.ctypes.data, bk.ctypes.data,
                                                  2, one.ctypes.data) == pw85.Status.ERR_INVALID_ARGUMENT
    assert np.isnan(one["mu2"][0])
    # the scene form: pairs (0, 1), (2, 3), ... of 2 m ellipsoids
    centres = np.zeros((600, 3))
    centres[1::2] = r12
    q = np.empty((600, 6))
    q[0::2], q[1::2] = q1, q2
    pairs = np.arange(600).reshape(300, 2)
    sl = pw85.scene_contact_derivatives(centres, q, pairs, forces_only=True)
    assert sl.tobytes() == light.tobytes()
    # failing pairs: NaN everywhere, status as the full call's
    bad = r12.copy()
    bad[4] = 0.0
    d2, st = pw85.contact_derivatives(bad, q1, q2, check=False, forces_only=True)
    assert st[4] == pw85.Status.ERR_INVALID_ARGUMENT and st[3] == 0
    assert all(np.isnan(d2[4][f]).all() for f in d2.dtype.names)


def test_broadcasting():
    r12, q1, q2 = random_pairs(40, seed=3)
    # one q1 against many q2
    mu2, lam = pw85.contact_function(r12, q1[0], q2)
    ref = pw85.contact_function(r12, np.repeat(q1[:1], 40, axis=0), q2)
    assert np.array_equal(mu2, ref[0]) and np.array_equal(lam, ref[1])
    # one r12 against many pairs, and a 2-D batch (5, 8)
    assert np.array_equal(pw85.overlap(r12[0], q1, q2),
                          pw85.overlap(np.tile(r12[0], (40, 1)), q1, q2))
    mu2b, _ = pw85.contact_function(r12.reshape(5, 8, 3), q1.reshape(5, 8, 6), q2.reshape(5, 8, 6))
    assert mu2b.shape == (5, 8) and np.array_equal(mu2b.ravel(), pw85.contact_function(r12, q1, q2)[0])
    # outer product: r12 (40, 1, 3) against q2 (3, 6)
    out = pw85.contact_function(r12[:, None, :], q1[0], q2[:3])[0]
    assert out.shape == (40, 3)
    assert out[5, 2] == pw85.contact_function(r12[5], q1[0], q2[2])[0]
    c = pw85.contact(r12[:, None, :], q1[0], q2[:3])
    assert c.shape == (40, 3) and c["x0"].shape == (40, 3, 3)
    # empty batches
    e = pw85.contact_function(np.zeros((0, 3)), q1[0], q2[0])
    assert e[0].shape == (0,) and pw85.overlap(np.zeros((0, 3)), q1[0], q2[0]).shape == (0,)


def test_conversions_one_copy_never_misread():
    r12, q1, q2 = random_pairs(30, seed=4)
    ref = pw85.contact_function(r12, q1, q2)[0]
    big = np.zeros((30, 12))
    big[:, ::2] = q1  # non-contiguous view
    assert np.array_equal(pw85.contact_function(r12, big[:, ::2], q2)[0], ref)
    assert np.array_equal(pw85.contact_function(r12.tolist(), q1.tolist(), q2)[0], ref)
    assert np.array_equal(pw85.contact_function(r12.astype(">f8"), q1, np.asfortranarray(q2))[0], ref)
    f32 = pw85.contact_function(r12.astype(np.float32), q1, q2)[0]
    assert np.array_equal(f32, pw85.contact_function(r12.astype(np.float32).astype(float), q1, q2)[0])
    ints = pw85.contact_function(np.array([1, 2, 3]), np.array([1, 0, 0, 1, 0, 1]),
                                 np.array([1, 0, 0, 1, 0, 1]))[0]
    assert within_ulps(ints, 14 / 4)
    # one pair given as non-contiguous views takes the one-pair path
    assert pw85.contact_function(r12[3], big[3, ::2], q2[3])[0] == ref[3]
    assert pw85.overlap(np.asfortranarray(r12)[3], q1[3], q2[3]) == (ref[3] < 1)
    # inputs are never modified
    q1c = q1.copy()
    pw85.contact(r12, q1, q2)
    assert np.array_equal(q1, q1c)


def min_image(d, box):
    Lx, Ly, Lz, xy, xz, yz = box
    d = d.copy()
    a1, a2, a3 = np.array([Lx, 0, 0]), np.array([xy * Ly, Ly, 0]), np.array([xz * Lz, yz * Lz, Lz])
    def rnd(x):
        return np.where(x >= 0, np.floor(x + 0.5), -np.floor(-x + 0.5))
    d -= rnd(d[:, 2] * (1 / Lz))[:, None] * a3
    d -= rnd(d[:, 1] * (1 / Ly))[:, None] * a2
    d -= rnd(d[:, 0] * (1 / Lx))[:, None] * a1
    return d


# Centres on a grid of 2^-20 and dyadic tilts: every operation of min_image
# above is exact, so it gives the exact image the library computes.
@pytest.mark.parametrize("box", [None, [20., 25., 30., 0.3125, -0.1875, 0.125]])
def test_scenes_against_per_pair_arrays(box):
    rng = np.random.default_rng(8)
    n, m = 200, 1000
    centres = np.ldexp(np.round(np.ldexp(rng.uniform(-15, 15, (n, 3)), 20)), -20)
    q = pw85.ellipsoid(rng.uniform(0.5, 2, (n, 3)), np.linalg.qr(rng.normal(size=(n, 3, 3)))[0])
    pairs = rng.integers(0, n, (m, 2))
    pairs = pairs[pairs[:, 0] != pairs[:, 1]]
    d = centres[pairs[:, 1]] - centres[pairs[:, 0]]
    r12 = d if box is None else min_image(d, box)
    q1, q2 = q[pairs[:, 0]], q[pairs[:, 1]]
    mu2, lam = pw85.scene_contact_function(centres, q, pairs, box=box, nthreads=2)
    ref = pw85.contact_function(r12, q1, q2)
    assert np.array_equal(mu2, ref[0]) and np.array_equal(lam, ref[1])
    assert np.array_equal(pw85.scene_overlap(centres, q, pairs, box), pw85.overlap(r12, q1, q2))
    c = pw85.scene_contact(centres, q, pairs.astype(np.int32), box)
    cr = pw85.contact(r12, q1, q2)
    assert all(np.array_equal(c[f], cr[f]) for f in c.dtype.names)
    dd = pw85.scene_contact_derivatives(centres, q, pairs, box, nthreads=2)
    assert dd.tobytes() == pw85.contact_derivatives(r12, q1, q2).tobytes()
    mb, _ = pw85.scene_contact_function(centres, q, pairs, box, method=pw85.Method.BRENT)
    assert np.array_equal(mb, pw85.contact_function(r12, q1, q2, method="BRENT")[0])
    # one matrix for every ellipsoid
    assert np.array_equal(pw85.scene_overlap(centres, q[0], pairs, box),
                          pw85.overlap(r12, q[0], q[0]))


def test_dca_and_2d():
    r12, q1, q2 = random_pairs(20, seed=9)
    mu2 = pw85.contact_function(r12 / np.linalg.norm(r12, axis=1)[:, None], q1, q2)[0]
    d = pw85.dca(r12, q1, q2)
    assert d.shape == (20,) and np.allclose(d, 1 / np.sqrt(mu2), rtol=1e-14)
    dz, ev = pw85.dca_ex(r12, q1, q2)
    assert np.allclose(dz, d, rtol=1e-9) and ev.dtype == np.intc and np.all(ev > 0)
    assert np.allclose(pw85.dca(r12, q1, q2, method="zheng"), dz, rtol=1e-12)
    assert pw85.dca(r12[0], q1[0], q2[0]) == d[0]
    # 2D: circles of radii 1 and 2, ellipses
    assert within_ulps(pw85.dca_2d([1., 0.], [1., 0., 1.], [4., 0., 4.]), 3.0)
    mu2_2d, lam = pw85.contact_function_2d([3., 0.], [1., 0., 1.], [4., 0., 4.])
    assert within_ulps(mu2_2d, 1.0) and abs(lam - 1 / 3) < 1e-15
    rng = np.random.default_rng(10)
    u = rng.normal(size=(10, 2))
    a = np.array([[1., 0.2, 2.]] * 10)
    b = np.array([[3., -0.5, 1.]] * 10)
    mu2u = pw85.contact_function_2d(u / np.linalg.norm(u, axis=1)[:, None], a, b)[0]
    assert np.allclose(pw85.dca_2d(u, a, b), 1 / np.sqrt(mu2u), rtol=1e-12)


def test_check_false_returns_statuses():
    r12, q1, q2 = random_pairs(10, seed=11)
    r12[3, 1] = np.nan
    q2[6] = [1, 0, 0, -1, 0, 1]
    mu2, lam, st = pw85.contact_function(r12, q1, q2, check=False)
    assert st.tolist() == [0, 0, 0, -1, 0, 0, -2, 0, 0, 0]
    assert np.isnan(mu2[[3, 6]]).all() and np.isnan(lam[[3, 6]]).all()
    assert np.isfinite(np.delete(mu2, [3, 6])).all()
    ov, st2 = pw85.overlap(r12, q1, q2, check=False)
    assert st2.tolist() == st.tolist() and not ov[3] and not ov[6]
    c, st3 = pw85.contact(r12, q1, q2, check=False)
    assert st3.tolist() == st.tolist() and np.isnan(c["x0"][3]).all()
    m1 = pw85.contact_function(r12[3], q1[3], q2[3], check=False)
    assert np.isnan(m1[0]) and m1[2] == -1
    assert pw85.overlap(r12[6], q1[6], q2[6], check=False) == (False, -2)
    d, st4 = pw85.dca(r12, q1, q2, check=False)
    assert st4[3] == -1 and np.isnan(d[3])


def test_pickle():
    for f in (pw85.contact_function, pw85.overlap, pw85.scene_contact, pw85.Method.ZHENG):
        assert pickle.loads(pickle.dumps(f)) is f
    e = pw85.Error("message", -2, 5)
    e2 = pickle.loads(pickle.dumps(e))
    assert (str(e2), e2.status, e2.index, e2.status_name) == ("message", -2, 5, "PW85_ERR_NOT_SPD")
    c = pw85.contact(*random_pairs(3))
    assert np.array_equal(pickle.loads(pickle.dumps(c)), c)


def test_contact_time():
    # unit spheres 3 apart closing at unit speed touch at t = 1 (spins change
    # nothing); receding: inf; broadcasting against the one-pair C call
    unit = pw85.spheroid(1., 1., [0., 0., 1.])
    t = pw85.contact_time([3., 0, 0], [-1., 0, 0], unit, [0, 0, 5.], unit, [1., 0, 0], 2.0)
    assert abs(t - 1.0) <= 1e-14
    v = np.array([[-1., 0, 0], [1., 0, 0], [0., 1, 0]])
    ts = pw85.contact_time([3., 0, 0], v, unit, np.zeros(3), unit, np.zeros(3), 3.0)
    assert ts.shape == (3,) and ts[0] == t and np.isinf(ts[1]) and np.isinf(ts[2])
    r12, q1, q2 = random_pairs(20, seed=3)
    rng = np.random.default_rng(4)
    v12 = -r12 * rng.uniform(0.5, 2, size=(20, 1))
    w1 = rng.normal(size=(20, 3))
    ts = pw85.contact_time(r12, v12, q1, w1, q2, np.zeros(3), 1.0, nthreads=2)
    for k in range(20):
        assert pw85.contact_time(r12[k], v12[k], q1[k], w1[k], q2[k], np.zeros(3), 1.0) == ts[k]
    with pytest.raises(ValueError, match="t_max"):
        pw85.contact_time(r12, v12, q1, w1, q2, w1, 0.0)
    bad = v12.copy()
    bad[5, 1] = np.nan
    with pytest.raises(pw85.Error, match="pair 5.*v12 holds a non-finite"):
        pw85.contact_time(r12, bad, q1, w1, q2, w1, 1.0)
    t2, st = pw85.contact_time(r12, bad, q1, w1, q2, w1, 1.0, check=False)
    assert st[5] == pw85.Status.ERR_INVALID_ARGUMENT and np.isnan(t2[5]) and st[4] == 0
