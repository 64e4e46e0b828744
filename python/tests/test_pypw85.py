"""pypw85: the Python API of pw85 1.0 (chapter 8 of its documentation),
its tutorial (chapter 2.1), and each function against independently
computed values (reference data, mpmath, NumPy)."""
import contextlib
import io

import numpy as np
import pytest

import pypw85
import pypw85.legacy
from conftest import MU2_TUTORIAL, LAMBDA_TUTORIAL, MU2_PW85_DOC, LAMBDA_PW85_DOC, DOC_RTOL, within_ulps

mpmath = pytest.importorskip("mpmath")
mpmath.mp.dps = 50


def sym(q):
    """3x3 from the upper triangle q."""
    i, j = np.triu_indices(3)
    m = np.zeros((3, 3))
    m[i, j] = q
    m[j, i] = q
    return m


def mp_sym(q):
    i, j = np.triu_indices(3)
    m = mpmath.matrix(3, 3)
    for a, b, v in zip(i, j, q):
        m[a, b] = m[b, a] = mpmath.mpf(float(v))
    return m


def mp_f(lam, r, q1, q2):
    lam = mpmath.mpf(lam)
    Q = (1 - lam) * mp_sym(q1) + lam * mp_sym(q2)
    rv = mpmath.matrix([mpmath.mpf(float(x)) for x in r])
    return lam * (1 - lam) * (rv.T * mpmath.lu_solve(Q, rv))[0]


def test_tutorial():
    """Chapter 2.1, unchanged; the printed values to a few ulps."""
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        x1 = np.array([-0.5, 0.4, -0.7])
        n1 = np.array([0., 0., 1.])
        a1, c1 = 10, 0.1
        x2 = np.array([0.2, -0.3, 0.4])
        n2 = np.array([1., 0., 0.])
        a2, c2 = 0.5, 5.
        r12 = x2-x1
        q1 = pypw85.spheroid(a1, c1, n1)
        q2 = pypw85.spheroid(a2, c2, n2)
        mu2, lambda_ = pypw85.contact_function(r12, q1, q2)
        print('μ² = {}'.format(mu2))
        print('λ = {}'.format(lambda_))
    # the documented arrays, as printed, and to a few ulps of the largest
    # entry (pw85 1.0 computed q1[5] = 100 + (0.01 - 100) = 0.010000000000005116)
    assert repr(q1) == "array([ 1.e+02, -0.e+00, -0.e+00,  1.e+02, -0.e+00,  1.e-02])"
    assert np.allclose(q1, [1.e+02, -0.e+00, -0.e+00, 1.e+02, -0.e+00, 1.e-02],
                       rtol=0, atol=4 * np.spacing(100.))
    assert np.allclose(q2, [25., 0., 0., 0.25, 0., 0.25], rtol=0, atol=4 * np.spacing(25.))
    lines = buf.getvalue().splitlines()
    assert lines[0].startswith("μ² = ") and lines[1].startswith("λ = ")
    assert within_ulps(float(lines[0][5:]), MU2_TUTORIAL)
    assert within_ulps(float(lines[1][4:]), LAMBDA_TUTORIAL)
    assert abs(float(lines[0][5:]) / MU2_PW85_DOC - 1) <= DOC_RTOL
    assert abs(float(lines[1][4:]) / LAMBDA_PW85_DOC - 1) <= DOC_RTOL

    # 2.1.1 Checking the output
    Q1 = np.zeros((3, 3), dtype=np.float64)
    i, j = np.triu_indices_from(Q1)
    Q1[i, j] = q1
    Q1[j, i] = q1
    Q2 = np.zeros_like(Q1)
    Q2[i, j] = q2
    Q2[j, i] = q2
    Q1_inv = np.linalg.inv(Q1)
    Q2_inv = np.linalg.inv(Q2)
    Q = (1-lambda_)*Q1+lambda_*Q2
    x = np.linalg.solve(Q, r12)
    x0a = x1+(1-lambda_)*np.dot(Q1, x)
    x0b = x2-lambda_*np.dot(Q2, x)
    assert np.allclose(x0a, [0.16662271, -0.29964969, -0.51687799], atol=1e-8)
    assert np.allclose(x0a, x0b, atol=1e-12)
    x0 = x0a
    Q1_inv /= mu2
    Q2_inv /= mu2
    assert abs((x0-x1) @ Q1_inv @ (x0-x1) - 1) < 1e-9
    assert abs((x0-x2) @ Q2_inv @ (x0-x2) - 1) < 1e-9
    nn1 = Q1_inv.dot(x0-x1)
    nn1 /= np.linalg.norm(nn1)
    nn2 = Q2_inv.dot(x0-x2)
    nn2 /= np.linalg.norm(nn2)
    assert np.allclose(nn1, [3.64031943e-04, -3.82067448e-04, 9.99999861e-01], atol=1e-10)
    assert np.allclose(nn1, -nn2, atol=1e-9)


def test_optional_outputs_updated_in_place():
    n = np.array([0., 0., 1.])
    q = np.zeros(6)
    assert pypw85.spheroid(10, 0.1, n, q) is q
    assert np.array_equal(q, pypw85.spheroid(10, 0.1, n))
    out = np.zeros(2)
    q2 = pypw85.spheroid(0.5, 5., np.array([1., 0., 0.]))
    res = pypw85.contact_function(np.array([0.7, -0.7, 1.1]), q, q2, out)
    assert res is out and within_ulps(out[0], MU2_TUTORIAL)
    l = np.zeros(6)
    assert pypw85._cholesky_decomp(q, l) is l
    x = np.zeros(3)
    assert pypw85._cholesky_solve(l, np.array([1., 2., 3.]), x) is x
    # a strided float64 view is written through
    big = np.zeros(12)
    pypw85.spheroid(10, 0.1, n, big[::2])
    assert np.array_equal(big[::2], q)


def test_spheroid_reference(refdata):
    radii, dirs, ref = refdata["radii"], refdata["directions"], refdata["spheroids"]
    for ia, a in enumerate(radii):
        for ic, c in enumerate(radii):
            for k, n in enumerate(dirs):
                q = pypw85.spheroid(a, c, n)
                r = ref[36 * ia + 12 * ic + k]
                scale = max(a, c) ** 2
                assert np.all(np.abs(q - r) <= 4 * np.spacing(scale)), (a, c, n, q, r)


def test_f_reference(refdata):
    sph, dirs, lams = refdata["spheroids"], refdata["directions"], refdata["lambdas"]
    i1, i2, k, l = refdata["F_index"]
    for t in range(len(i1)):
        val = pypw85.f(lams[l[t]], dirs[k[t]], sph[i1[t]], sph[i2[t]])
        ref = refdata["F"][t]
        assert abs(val - ref) <= 1e-10 * abs(ref) + 1e-300, (t, val, ref)


def test_f_mpmath():
    rng = np.random.default_rng(2)
    for _ in range(50):
        r = rng.normal(size=3)
        q1 = pypw85.spheroid(rng.uniform(0.5, 2), rng.uniform(0.5, 2), unit(rng))
        q2 = pypw85.spheroid(rng.uniform(0.5, 2), rng.uniform(0.5, 2), unit(rng))
        lam = rng.uniform()
        ref = float(mp_f(lam, r, q1, q2))
        assert abs(pypw85.f(lam, r, q1, q2) - ref) <= 1e-13 * ref


def unit(rng):
    n = rng.normal(size=3)
    return n / np.linalg.norm(n)


def test_contact_function_reference(refdata):
    g = refdata["contact"]
    sel = np.flatnonzero(g["class"] <= 1)[::20]
    for t in sel:
        mu2, lam = pypw85.contact_function(g["r12"][t], g["q1"][t], g["q2"][t])
        assert abs(mu2 - g["mu2"][t]) <= 1e-9 * g["mu2"][t], t


def test_cholesky_against_numpy():
    rng = np.random.default_rng(3)
    for _ in range(50):
        q = pypw85.spheroid(rng.uniform(0.5, 2), rng.uniform(0.5, 2), unit(rng))
        l = pypw85._cholesky_decomp(q)
        L = np.linalg.cholesky(sym(q))
        assert np.allclose(l, [L[0, 0], L[1, 0], L[2, 0], L[1, 1], L[2, 1], L[2, 2]],
                           rtol=1e-14, atol=1e-14)
        b = rng.normal(size=3)
        x = pypw85._cholesky_solve(l, b)
        assert np.allclose(sym(q) @ x, b, rtol=1e-13, atol=1e-13)
    assert np.all(np.isnan(pypw85._cholesky_decomp(np.array([1., 0, 0, -1, 0, 1]))))


def test_legacy_algebra_mpmath():
    rng = np.random.default_rng(4)
    L = pypw85.legacy
    for _ in range(30):
        a = rng.normal(size=6)
        x = rng.normal(size=3)
        A = mp_sym(a)
        assert abs(L._det_sym(a) - float(mpmath.det(A))) <= 1e-13 * float(mpmath.mnorm(A, 1)) ** 3
        adj = mpmath.inverse(A) * mpmath.det(A)
        xv = mpmath.matrix(list(map(float, x)))
        ref = float((xv.T * adj * xv)[0])
        assert abs(L._xT_adjA_x(x, a) - ref) <= 1e-12 * (1 + abs(ref)) * 10
        q1 = pypw85.spheroid(rng.uniform(0.5, 2), rng.uniform(0.5, 2), unit(rng))
        q2 = pypw85.spheroid(rng.uniform(0.5, 2), rng.uniform(0.5, 2), unit(rng))
        b = L._detQ_as_poly(q1, q2)
        av = L._rT_adjQ_r_as_poly(x, q1, q2)
        for lam in (0.0, 0.3, 0.8, 1.0):
            Q = (1 - lam) * mp_sym(q1) + lam * mp_sym(q2)
            detq = float(mpmath.det(Q))
            assert abs(np.polyval(b[::-1], lam) - detq) <= 1e-12 * 100
            adjq = mpmath.inverse(Q) * mpmath.det(Q)
            ra = float((xv.T * adjq * xv)[0])
            assert abs(np.polyval(av[::-1], lam) - ra) <= 1e-12 * 100
        # q3, q4 and the output arrays given explicitly
        bb = np.zeros(4)
        assert L._detQ_as_poly(q1, q2, 2 * q1 - q2, 0.5 * (q1 + q2), bb) is bb
        assert np.array_equal(bb, b)
        aa = np.zeros(3)
        assert L._rT_adjQ_r_as_poly(x, q1, q2, 2 * q1 - q2, aa) is aa
        assert np.array_equal(aa, av)


def test_legacy_f_and_contact():
    rng = np.random.default_rng(5)
    L = pypw85.legacy
    for _ in range(20):
        r = rng.normal(size=3)
        q1 = pypw85.spheroid(rng.uniform(0.5, 2), rng.uniform(0.5, 2), unit(rng))
        q2 = pypw85.spheroid(rng.uniform(0.5, 2), rng.uniform(0.5, 2), unit(rng))
        lam = rng.uniform(0.05, 0.95)
        ref = float(mp_f(lam, r, q1, q2))
        d1 = float(mpmath.diff(lambda t: mp_f(t, r, q1, q2), lam))
        d2 = float(mpmath.diff(lambda t: mp_f(t, r, q1, q2), lam, 2))
        out = np.zeros(3)
        assert abs(L.f1(lam, r, q1, q2) - ref) <= 1e-12 * ref
        assert abs(L.f1(lam, r, q1, q2, out) - ref) <= 1e-12 * ref
        assert np.allclose(out, [ref, d1, d2], rtol=1e-9, atol=1e-9 * ref)
        assert abs(L.f2(lam, r, q1, q2) - ref) <= 1e-9 * ref
        one = np.zeros(1)  # pw85 1.0 passed a double[1]
        v = L.f2(lam, r, q1, q2, one)
        assert one[0] == v and abs(v - ref) <= 1e-9 * ref
        three = np.zeros(3)
        L.f2(lam, r, q1, q2, three)
        assert np.allclose(three, [ref, d1, d2], rtol=1e-7, atol=1e-7 * ref)
        mu2 = pypw85.contact_function(r, q1, q2)[0]
        for cf in (L.contact_function1, L.contact_function2):
            res = cf(r, q1, q2)
            assert res.shape == (2,) and abs(res[0] - mu2) <= 1e-8 * mu2
        o = np.zeros(2)
        assert L.contact_function1(r, q1, q2, o) is o


def test_bad_input_nan_or_exception():
    q = pypw85.spheroid(1., 2., np.array([0., 0., 1.]))
    # numerical failures: NaN, as pw85 1.0's C functions, never an exception
    assert np.all(np.isnan(pypw85.spheroid(-1., 2., np.array([0., 0., 1.]))))
    assert np.all(np.isnan(pypw85.contact_function(np.array([np.nan, 0, 0]), q, q)))
    assert np.isnan(pypw85.f(0.5, np.array([1., 0, 0]), q, np.array([1., 0, 0, -1, 0, 1])))
    assert np.isnan(pypw85.legacy.f1(0.5, np.array([np.inf, 0, 0]), q, q))
    # arguments that would be misread: exceptions naming them
    for call, name in [
            (lambda: pypw85.contact_function(np.zeros(2), q, q), "r12"),
            (lambda: pypw85.contact_function(np.zeros(3), q[:5], q), "q1"),
            (lambda: pypw85.contact_function(np.zeros(3), q, q, np.zeros(1)), "out"),
            (lambda: pypw85.spheroid(1., 1., np.zeros((3, 1))), "n"),
            (lambda: pypw85.legacy.f1(0.5, np.zeros(3), q, q, np.zeros(2)), "out"),
            (lambda: pypw85.legacy._det_sym(np.zeros(9)), "a"),
            (lambda: pypw85._cholesky_solve(q, np.zeros(4)), "b")]:
        with pytest.raises(ValueError, match=name):
            call()
    for call, name in [
            (lambda: pypw85.contact_function(None, q, q), "r12"),
            (lambda: pypw85.contact_function("abc", q, q), "r12"),
            (lambda: pypw85.spheroid("1", 1., np.zeros(3)), "a"),
            (lambda: pypw85.f(None, np.zeros(3), q, q), "lambda_"),
            (lambda: pypw85.contact_function(np.zeros(3), q, q, [0., 0.]), "out"),
            (lambda: pypw85.legacy._xT_adjA_x(np.array(["a", "b", "c"]), q), "x")]:
        with pytest.raises(TypeError, match=name):
            call()
    with pytest.raises(ValueError, match="r12"):
        pypw85.contact_function([[1, 2, 3], [1, 2]], q, q)
    with pytest.raises(ValueError, match="read-only"):
        ro = np.zeros(2)
        ro.flags.writeable = False
        pypw85.contact_function(np.ones(3), q, q, ro)


def test_array_likes_and_dtypes():
    q1 = pypw85.spheroid(10, 0.1, [0, 0, 1])
    q2 = pypw85.spheroid(0.5, 5., np.array([1, 0, 0], dtype=np.int32))
    res = pypw85.contact_function([0.7, -0.7, 1.1], list(q1), q2.astype(np.float32).astype(">f8"))
    assert within_ulps(res[0], MU2_TUTORIAL)
    strided = np.repeat(q1, 2)[::2]
    assert np.array_equal(pypw85.contact_function([0.7, -0.7, 1.1], strided, q2), res)
