"""The compiled module pw85._ext (python/ext/_ext.cpp): pw85.overlap and
pw85.contact_function give, for one pair and for arrays of pairs, the bits
of the C calls (pw85_overlap, pw85_contact_function_method and their pair
calls, made here through ctypes with raw pointers), for NumPy arrays of any
strides or alignment and for lists; the ctypes path of the package
(pw85._ext absent) gives the same bits. Skipped when the module was not
built (meson build without nanobind), unless PW85_REQUIRE_EXTENSION is set
(.ci/pip-check: pip install . always builds it)."""
import ctypes
import os

import numpy as np
import pytest

import pw85
from pw85 import _api, _lib, _native
from conftest import misaligned

if _native.ext is None:
    if os.environ.get("PW85_REQUIRE_EXTENSION"):
        raise ImportError("pw85._ext is not installed (PW85_REQUIRE_EXTENSION is set)")
    pytest.skip("pw85._ext not built (nanobind not found by meson for this interpreter; "
                "pip install . builds it): the ctypes path is tested by the other files",
                allow_module_level=True)

LIB = _lib.lib
N = 3000


def pairs(n, seed):
    """Class-0 pairs (semi-axes in [0.5, 2]) with r12 scaled so that about
    half overlap, plus spheroids of aspect ratio up to 1e3."""
    rng = np.random.default_rng(seed)
    axes = np.linalg.qr(rng.normal(size=(2, n, 3, 3)))[0]
    radii = rng.uniform(0.5, 2, (2, n, 3))
    radii[:, : n // 10] *= np.array([1e-3, 1, 1])
    q1, q2 = (pw85.ellipsoid(radii[k], axes[k]) for k in range(2))
    r12 = rng.normal(size=(n, 3)) * rng.uniform(0.2, 3, (n, 1))
    return r12, q1, q2


R12, Q1, Q2 = pairs(N, 53)


def c_overlap(r, a, b):
    return LIB.pw85_overlap(r.ctypes.data, a.ctypes.data, b.ctypes.data)


def c_contact_function(r, a, b, method):
    res = _lib.Result()
    st = LIB.pw85_contact_function_method(r.ctypes.data, a.ctypes.data, b.ctypes.data,
                                          method, ctypes.byref(res))
    return st, res.mu2, res.lambda_


def bits(x):
    return np.asarray(x, dtype=np.float64).view(np.int64)


def test_module_in_use():
    assert _api._ext is _native.ext
    assert {"overlap1", "contact_function1", "overlap_pairs",
            "contact_function_pairs"} <= set(dir(_native.ext))
    # NumPy's array fields read directly (checked at import against the
    # buffer protocol); else every array goes through the buffer protocol.
    assert _native.ext.numpy_fields is True


@pytest.mark.parametrize("method", list(pw85.Method))
def test_one_pair_bitwise(method):
    for k in range(0, N, 7 if method == pw85.Method.DEFAULT else 37):
        r, a, b = R12[k], Q1[k], Q2[k]
        st, mu2, lam = c_contact_function(r, a, b, int(method))
        if st != 0:
            with pytest.raises(pw85.Error):
                pw85.contact_function(r, a, b, method=method)
            continue
        out = pw85.contact_function(r, a, b, method=method)
        assert type(out[0]) is np.float64 and type(out[1]) is np.float64
        assert bits(out).tolist() == bits([mu2, lam]).tolist(), k
        v = pw85.overlap(r, a, b)
        assert type(v) is bool and v == (c_overlap(r, a, b) == 1)


def test_batch_bitwise():
    mu2, lam, st = pw85.contact_function(R12, Q1, Q2, check=False)
    ov, st_ov = pw85.overlap(R12, Q1, Q2, check=False)
    ref = np.empty(N, pw85.RESULT_DTYPE)
    ref_st = np.empty(N, np.intc)
    ref_ov = np.empty(N, np.intc)
    args = [x.ctypes.data for x in (R12, Q1, Q2)]
    LIB.pw85_contact_function_pairs(N, *args, 0, ref.ctypes.data, ref_st.ctypes.data, 1)
    LIB.pw85_overlap_pairs(N, *args, ref_ov.ctypes.data, st_ov.ctypes.data, 1)
    ok = ref_st == 0
    assert np.array_equal(st, ref_st) and ok.sum() > N // 2
    assert np.array_equal(bits(mu2[ok]), bits(ref["mu2"][ok]))
    assert np.array_equal(bits(lam[ok]), bits(ref["lambda"][ok]))
    assert np.array_equal(ov, ref_ov == 1)
    assert 0.2 * N < ov.sum() < 0.8 * N


def test_ctypes_path_same_bits(monkeypatch):
    with_ext = [pw85.contact_function(R12[k], Q1[k], Q2[k]) for k in range(200)]
    batch = pw85.contact_function(R12, Q1, Q2)
    verdicts = pw85.overlap(R12, Q1, Q2)
    monkeypatch.setattr(_api, "_ext", None)
    assert [pw85.contact_function(R12[k], Q1[k], Q2[k]) for k in range(200)] == with_ext
    assert np.array_equal(bits(pw85.contact_function(R12, Q1, Q2)), bits(batch))
    assert np.array_equal(pw85.overlap(R12, Q1, Q2), verdicts)


def test_one_pair_inputs():
    # Lists, tuples, strided views, misaligned views, read-only arrays: the
    # values of the float64 array.
    r, a, b = R12[5], Q1[5], Q2[5]
    ref = pw85.contact_function(r, a, b)
    wide = np.zeros((3, 12))
    wide[0, ::2] = a
    ro = b.copy()
    ro.flags.writeable = False
    for args in [(r.tolist(), a.tolist(), b.tolist()), (tuple(r), tuple(a), tuple(b)),
                 (misaligned(r), misaligned(a), misaligned(b)), (r, wide[0, ::2], ro),
                 (memoryview(r), memoryview(a), memoryview(b))]:
        assert pw85.contact_function(*args) == ref
        assert pw85.overlap(*args) == pw85.overlap(r, a, b)
    # Integers are converted; a list with an int past the range of double,
    # float32, big-endian and 2D arrays go through NumPy's conversion.
    assert pw85.contact_function([1, 0, 0], [1, 0, 0, 1, 0, 1], [1, 0, 0, 1, 0, 1]) == (
        pw85.contact_function(np.array([1., 0, 0]), np.array([1., 0, 0, 1, 0, 1]),
                              np.array([1., 0, 0, 1, 0, 1])))
    assert pw85.contact_function(r.astype(">f8"), a, b) == ref
    assert pw85.contact_function(r.astype(np.float32), a, b) == pw85.contact_function(
        r.astype(np.float32).astype(np.float64), a, b)
    assert np.array_equal(pw85.contact_function(r[None], a, b)[0], [ref[0]])
    ext = _native.ext
    assert ext.contact_function1("abc", a, b, 0, 0, True) is None
    assert ext.overlap1(r, a, [1.0] * 5, 0, True) is None
    assert ext.overlap1([True, 0., 0.], a, b, 0, True) is None
    # Options the module leaves to the Python function (which converts or
    # rejects them): the same results or errors as without the module.
    assert ext.overlap1(r, a, b, 0, 1) is None and ext.overlap1(r, a, b, True, True) is None
    assert ext.overlap1(r, a, b, -1, True) is None and ext.overlap1(r, a, b, 2**31, True) is None
    assert ext.contact_function1(r, a, b, "Brent", 0, True) is None
    assert ext.contact_function1(r, a, b, 5, 0, True) is None
    assert ext.contact_function1(r, a, b, True, 0, True) is None
    assert pw85.contact_function(r, a, b, method="Brent", nthreads=np.int64(2), check=1) == (
        pw85.contact_function(r, a, b, method=pw85.Method.BRENT))
    for method in ("brent", 1, pw85.Method.BRENT):
        assert ext.contact_function1(r, a, b, method, 3, True) == pw85.contact_function(
            r, a, b, method="brent")
    assert pw85.overlap(r, a, b, nthreads=np.int32(1), check=0) == (pw85.overlap(r, a, b), 0)
    with pytest.raises(TypeError, match="nthreads"):
        pw85.overlap(r, a, b, nthreads=True)
    with pytest.raises(ValueError, match="method"):
        pw85.contact_function(r, a, b, method="fast")


def test_one_pair_errors():
    # A failing pair: None from the module, the error or status from the
    # Python function (argument named).
    bad = np.array([1., 0., 0., -1., 0., 1.])
    assert _native.ext.overlap1(R12[0], bad, Q2[0], 0, True) is None
    assert _native.ext.contact_function1(R12[0], Q1[0], bad, 0, 0, False) is None
    with pytest.raises(pw85.Error, match="q2 not positive definite"):
        pw85.contact_function(R12[0], Q1[0], bad)
    with pytest.raises(pw85.Error, match="r12 holds a non-finite"):
        pw85.overlap([np.nan, 0., 0.], Q1[0], Q2[0])
    mu2, lam, st = pw85.contact_function(R12[0], Q1[0], bad, check=False)
    assert np.isnan(mu2) and np.isnan(lam) and st == pw85.Status.ERR_NOT_SPD
    assert pw85.overlap(R12[0], bad, Q2[0], check=False) == (False, pw85.Status.ERR_NOT_SPD)
    assert pw85.overlap(R12[0], Q1[0], Q2[0], check=False)[1] == 0
    assert pw85.contact_function(R12[0], Q1[0], Q2[0], check=False)[2] == 0


def test_pair_calls_check_their_buffers():
    out, st = np.empty(4, bool), np.empty(4, np.intc)
    with pytest.raises(ValueError, match="r12"):
        _native.ext.overlap_pairs(4, R12[:3], Q1[:4], Q2[:4], out, st, 1)
    with pytest.raises(ValueError, match="q1"):
        _native.ext.overlap_pairs(4, R12[:4], misaligned(Q1[:4]), Q2[:4], out, st, 1)
    with pytest.raises(ValueError, match="overlap"):
        _native.ext.overlap_pairs(4, R12[:4], Q1[:4], Q2[:4], st, st, 1)
    with pytest.raises((TypeError, BufferError, ValueError)):
        _native.ext.overlap_pairs(4, R12[:4], Q1[:4], Q2[:4], out, R12[:4, 0], 1)
    with pytest.raises(ValueError, match="mu2"):
        _native.ext.contact_function_pairs(4, R12[:4], Q1[:4], Q2[:4], 0, st, st, st, 1)


def test_batch_over_chunks():
    # More pairs than one chunk of the module's pair calls (32768), the
    # first failing pair in the second chunk: its status and index.
    m = 70000
    r = np.tile(R12[:7], (m // 7, 1))
    a = np.tile(Q1[:7], (m // 7, 1))
    b = np.tile(Q2[:7], (m // 7, 1))
    a[40000] = [1., 0., 0., -1., 0., 1.]
    b[60000] = np.nan
    mu2, lam, st = pw85.contact_function(r, a, b, check=False)
    ov, st_ov = pw85.overlap(r, a, b, check=False)
    assert np.flatnonzero(st).tolist() == [40000, 60000] == np.flatnonzero(st_ov).tolist()
    assert np.isnan(mu2[40000]) and not ov[40000] and not ov[60000]
    ref_mu2, ref_lam = pw85.contact_function(R12[:7], Q1[:7], Q2[:7])
    keep = st == 0
    assert np.array_equal(mu2[keep], np.tile(ref_mu2, m // 7)[keep])
    assert np.array_equal(ov[keep], np.tile(pw85.overlap(R12[:7], Q1[:7], Q2[:7]), m // 7)[keep])
    # check=True runs the pair call without statuses, then again with them
    # once it reports a failure.
    for call in (pw85.contact_function, pw85.overlap):
        with pytest.raises(pw85.Error) as info:
            call(r, a, b)
        assert info.value.index == 40000 and info.value.status == pw85.Status.ERR_NOT_SPD
    assert _native.ext.overlap_pairs(m, r, a, b, np.empty(m, bool), None, 1) == (
        pw85.Status.ERR_NOT_SPD)
