"""pw85: every error path raises TypeError or ValueError naming the argument
(pw85.Error, with the status and the index of the first failing pair, for
what the C library reports per pair); nothing crashes."""
import numpy as np
import pytest

import pw85
from conftest import misaligned

R12 = np.array([0.7, -0.7, 1.1])
Q1 = pw85.spheroid(10., 0.1, [0., 0., 1.])
Q2 = pw85.spheroid(0.5, 5., [1., 0., 0.])
NOT_SPD = np.array([1., 0., 0., -1., 0., 1.])
PAIR_CALLS = [pw85.contact_function, pw85.overlap, pw85.contact]


@pytest.mark.parametrize("call", PAIR_CALLS + [pw85.dca])
@pytest.mark.parametrize("bad, name, exc", [
    (("r12", None), "r12", TypeError),
    (("q1", None), "q1", TypeError),
    (("q2", "abc"), "q2", TypeError),
    (("q1", b"123456"), "q1", TypeError),
    (("q2", np.array(["a"] * 6)), "q2", TypeError),
    (("q2", np.ones(6, dtype=complex)), "q2", TypeError),
    (("q1", np.ones(6, dtype=bool)), "q1", TypeError),
    (("q1", [object()] * 6), "q1", TypeError),
    (("r12", [[1, 2, 3], [1, 2]]), "r12", ValueError),
    (("r12", np.zeros(2)), "r12", ValueError),
    (("r12", 1.0), "r12", ValueError),
    (("q1", np.zeros((4, 5))), "q1", ValueError),
    (("q2", np.zeros((3, 6))), None, ValueError),  # batch shapes (2,), (), (3,)
])
def test_bad_arguments(call, bad, name, exc):
    args = {"r12": np.array([R12, R12]), "q1": Q1, "q2": Q2}
    key, value = bad
    args[key] = value
    r = args.pop("r12")
    if name == "r12" and call is pw85.dca:
        name = "u"
    with pytest.raises(exc, match=name or "broadcast"):
        call(r, args["q1"], args["q2"])


@pytest.mark.parametrize("call", PAIR_CALLS)
@pytest.mark.parametrize("where, value, name, status", [
    ("r12", [0.7, np.nan, 1.1], "r12", -1),
    ("r12", [np.inf, 0., 1.], "r12", -1),
    ("q1", [1., 0., 0., 1., np.nan, 1.], "q1", -1),
    ("q2", [1., 0., 0., 1., 0., -np.inf], "q2", -1),
    ("q1", NOT_SPD, "q1 not positive definite", -2),
    ("q2", NOT_SPD, "q2 not positive definite", -2),
])
def test_failing_pair(call, where, value, name, status):
    args = {"r12": np.tile(R12, (5, 1)), "q1": np.tile(Q1, (5, 1)), "q2": np.tile(Q2, (5, 1))}
    args[where][2] = value
    args[where][4] = value
    with pytest.raises(pw85.Error, match=name) as info:
        call(args["r12"], args["q1"], args["q2"])
    e = info.value
    assert isinstance(e, ValueError)
    assert e.status == status and e.index == 2
    assert e.status_name == pw85.status_name(status) and e.status_name in str(e)
    # one pair: same error, index 0
    with pytest.raises(pw85.Error, match=name) as info:
        call(args["r12"][2], args["q1"][2], args["q2"][2])
    assert info.value.index == 0 and info.value.status == status


def test_contact_r12_zero_and_2d_index():
    with pytest.raises(pw85.Error, match="r12 = 0") as info:
        pw85.contact(np.zeros((2, 3, 3)), Q1, Q2)
    assert info.value.index == 0 and "(0, 0)" in str(info.value)
    r = np.tile(R12, (2, 3, 1))
    r[1, 2, 0] = np.nan
    with pytest.raises(pw85.Error, match=r"\(1, 2\)") as info:
        pw85.overlap(r, Q1, Q2)
    assert info.value.index == 5


@pytest.mark.parametrize("method, exc", [
    ("foo", ValueError), ("", ValueError), (7, ValueError), (-1, ValueError),
    (None, TypeError), (1.5, TypeError), (1.0, TypeError), (True, TypeError),
    (np.bool_(False), TypeError), ([0], TypeError), (np.array(0), TypeError)])
def test_bad_method(method, exc):
    with pytest.raises(exc, match="method"):
        pw85.contact_function(R12, Q1, Q2, method=method)
    with pytest.raises(exc, match="method"):
        pw85.scene_contact_function(np.zeros((2, 3)), Q1, [[0, 1]], method=method)
    with pytest.raises(exc, match="method"):
        pw85.dca(R12, Q1, Q2, method=method)


def test_methods_by_name_value_enum():
    ref = pw85.contact_function(R12, Q1, Q2, method=pw85.Method.NEWTON)
    for m in ("newton", "NEWTON", "Newton", 2, np.int64(2)):
        assert pw85.contact_function(R12, Q1, Q2, method=m) == ref


@pytest.mark.parametrize("nthreads, exc", [
    (-1, ValueError), (-2**40, ValueError), (1.0, TypeError), ("2", TypeError),
    (None, TypeError), (True, TypeError)])
def test_bad_nthreads(nthreads, exc):
    for call in PAIR_CALLS:
        with pytest.raises(exc, match="nthreads"):
            call(R12, Q1, Q2, nthreads=nthreads)
        with pytest.raises(exc, match="nthreads"):
            call(np.tile(R12, (3, 1)), Q1, Q2, nthreads=nthreads)


def test_huge_nthreads_is_clamped():
    r = np.tile(R12, (3, 1))
    for n in (2**31 - 1, 2**40, np.int64(100000)):
        assert pw85.overlap(r, Q1, Q2, nthreads=n).tolist() == [False] * 3


def test_scene_errors():
    c = np.array([[0., 0., 0.], [1., 0., 0.], [3., 0., 0.]])
    q = np.tile(pw85.spheroid(0.4, 0.4, [0., 0., 1.]), (3, 1))
    with pytest.raises(pw85.Error, match=r"pairs\[1\] = \(1, 3\) outside \[0, 3\)") as info:
        pw85.scene_overlap(c, q, [[0, 1], [1, 3]])
    assert info.value.index == 1 and info.value.status == -1
    with pytest.raises(pw85.Error, match="outside"):
        pw85.scene_contact(c, q, np.array([[0, -1]]))
    ov, st = pw85.scene_overlap(c, q, [[0, 1], [1, 3], [0, 2]], check=False)
    assert ov.tolist() == [False, False, False] and st.tolist() == [0, -1, 0]
    cc = c.copy()
    cc[2, 1] = np.nan
    with pytest.raises(pw85.Error, match=r"centres\[2\]"):
        pw85.scene_contact_function(cc, q, [[0, 2]])
    qq = q.copy()
    qq[1] = NOT_SPD
    with pytest.raises(pw85.Error, match=r"q\[1\] not positive definite"):
        pw85.scene_contact_function(c, qq, [[0, 1]])
    with pytest.raises(pw85.Error, match="bounding spheres"):
        pw85.scene_overlap(c, q, [[0, 1]], box=[1.5, 10, 10, 0, 0, 0])
    for box, exc in [([0, 1, 1, 0, 0, 0], ValueError), ([1, 1, np.inf, 0, 0, 0], ValueError),
                     ([1, 1, 1, np.nan, 0, 0], ValueError), ([1, 1, 1e300, 0, 0, 1e300], ValueError),
                     ([1, 1, 1], ValueError), ("box", TypeError), ([[1] * 6], ValueError)]:
        with pytest.raises(exc, match="box"):
            pw85.scene_overlap(c, q, [[0, 1]], box=box)
    for pairs, exc in [([[0.0, 1.0]], TypeError), ([0, 1], ValueError), ([[0, 1, 2]], ValueError),
                       (None, TypeError), ("01", TypeError), ([[0, 1], [2]], ValueError),
                       (np.array([[True, False]]), TypeError)]:
        with pytest.raises(exc, match="pairs"):
            pw85.scene_overlap(c, q, pairs)
    with pytest.raises(ValueError, match="centres"):
        pw85.scene_overlap(c[0], q, [[0, 1]])
    with pytest.raises(ValueError, match="q"):
        pw85.scene_overlap(c, q[:2], [[0, 1]])
    assert pw85.scene_overlap(c, q, np.zeros((0, 2), int)).shape == (0,)
    assert pw85.scene_contact_function(c, q, [])[0].shape == (0,)


def test_constructor_errors():
    with pytest.raises(ValueError, match="a = -1"):
        pw85.spheroid(-1., 1., [0., 0., 1.])
    with pytest.raises(ValueError, match="c = nan"):
        pw85.spheroid([1., 1.], [1., np.nan], [0., 0., 1.])
    with pytest.raises(ValueError, match="n = "):
        pw85.spheroid(1., 1., [0., 0., 0.])
    with pytest.raises(TypeError, match="a"):
        pw85.spheroid(None, 1., [0., 0., 1.])
    with pytest.raises(ValueError, match="n"):
        pw85.spheroid(1., 1., [0., 1.])
    with pytest.raises(pw85.Error, match="not orthonormal") as info:
        pw85.ellipsoid([[1, 2, 3], [1, 2, 3]], [np.eye(3), 2 * np.eye(3)])
    assert info.value.status == -4 and info.value.index == 1
    with pytest.raises(pw85.Error, match="radius is <= 0"):
        pw85.ellipsoid([1, 0, 3], np.eye(3))
    with pytest.raises(pw85.Error, match="radii holds a non-finite"):
        pw85.ellipsoid([1, np.nan, 3], np.eye(3))
    with pytest.raises(ValueError, match="axes"):
        pw85.ellipsoid([1, 2, 3], np.eye(3)[:2])


def test_dca_2d_errors():
    with pytest.raises(pw85.Error, match="u = 0"):
        pw85.dca([0., 0., 0.], Q1, Q2)
    with pytest.raises(pw85.Error, match="u = 0"):
        pw85.dca_2d([0., 0.], [1., 0., 1.], [1., 0., 1.])
    with pytest.raises(pw85.Error, match="q2 not positive definite"):
        pw85.contact_function_2d([1., 0.], [1., 0., 1.], [1., 0., -1.])
    with pytest.raises(ValueError, match="q1"):
        pw85.dca_2d([1., 0.], Q1, [1., 0., 1.])
    for tol, exc in [(-1., ValueError), (np.nan, ValueError), ("x", TypeError), (None, TypeError)]:
        with pytest.raises(exc, match="theta_tol"):
            pw85.dca_ex(R12, Q1, Q2, theta_tol=tol)


def test_misaligned_arrays_are_copied():
    from pw85 import _api
    import pypw85
    rng = np.random.default_rng(11)
    r12 = rng.normal(size=(40, 3))
    q1 = np.tile(Q1, (40, 1))
    q2 = np.tile(Q2, (40, 1))
    for x, last in ((r12, 3), (q1, 6)):
        a = _api._arr(misaligned(x), "x", last)
        assert a.flags.aligned and a.flags.c_contiguous and np.array_equal(a, x)
    assert pypw85._in(misaligned(R12), "r12", 3).flags.aligned
    bad = [misaligned(x) for x in (r12, q1, q2)]
    assert np.array_equal(pw85.overlap(*bad), pw85.overlap(r12, q1, q2))
    for got, ref in zip(pw85.contact_function(*bad), pw85.contact_function(r12, q1, q2)):
        assert np.array_equal(got, ref)
    assert np.array_equal(pw85.contact(*bad), pw85.contact(r12, q1, q2))
    assert np.array_equal(pw85.dca(*bad), pw85.dca(r12, q1, q2))
    assert pw85.contact_function(*(x[0] for x in bad)) == pw85.contact_function(r12[0], q1[0], q2[0])
    # Scenes: centres, q and the int64 index pairs.
    centres = rng.uniform(0, 5, (10, 3))
    pairs = np.array([[i, j] for i in range(10) for j in range(i + 1, 10)], dtype=np.int64)
    ref = pw85.scene_contact_function(centres, q1[:10], pairs)
    got = pw85.scene_contact_function(misaligned(centres), misaligned(q1[:10]), misaligned(pairs))
    assert all(np.array_equal(g, r) for g, r in zip(got, ref))
    # pypw85 (pw85 1.0's API), inputs and a misaligned output array.
    ref = pypw85.contact_function(R12, Q1, Q2)
    out = misaligned(np.zeros(2))
    got = pypw85.contact_function(misaligned(R12), misaligned(Q1), misaligned(Q2), out)
    assert got is out and np.array_equal(out, ref)
