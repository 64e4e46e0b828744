"""The vectorised API of pw85 (see the package docstring)."""
from __future__ import annotations

import ctypes
import math
import operator
import threading
from typing import Any, Optional, Tuple, Union

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._lib import (lib, Error, Method, Status, status_name, strerror,
                   Result, Contact, RESULT_DTYPE, CONTACT_DTYPE, DERIVATIVES_DTYPE)
from ._native import ext as _ext

FloatArray = NDArray[np.float64]
F64 = np.dtype(np.float64)
_ND = np.ndarray
_F = np.float64
_S3, _S6 = (3,), (6,)
_NAN = float("nan")
_INT_MAX = 2**31 - 1
_METHODS = {m.name.lower(): int(m) for m in Method}
_METHODS.update({int(m): int(m) for m in Method})


# ---- argument conversion --------------------------------------------------

def _aligned(x):
    """x itself when its data are aligned for its dtype, else an aligned copy
    (a view at an odd byte offset into a buffer: the C library reads the
    elements as aligned doubles)."""
    return x if x.flags.aligned else x.copy()


def _arr(x, name, last, ndim=None):
    """x as a C-contiguous, aligned float64 array whose last axis has length
    `last` (a copy only when x is not one already)."""
    if not (type(x) is np.ndarray and x.dtype is F64 and x.flags.c_contiguous
            and x.flags.aligned):
        if x is None or isinstance(x, (str, bytes)):
            raise TypeError(f"{name}: expected an array of real numbers, got {type(x).__name__}")
        try:
            a = np.asarray(x)
        except (ValueError, TypeError) as e:
            raise ValueError(f"{name}: not a regular array of numbers ({e})") from None
        if a.dtype.kind == "O":
            try:
                a = a.astype(F64)
            except (ValueError, TypeError) as e:
                raise TypeError(f"{name}: not an array of real numbers ({e})") from None
        elif a.dtype.kind not in "iuf":
            raise TypeError(f"{name}: expected real numbers, got dtype {a.dtype}")
        x = _aligned(np.asarray(a, dtype=F64, order="C"))
    if last is not None and (x.ndim == 0 or x.shape[-1] != last):
        raise ValueError(f"{name}: expected shape (..., {last}), got {x.shape}")
    if ndim is not None and x.ndim != ndim:
        raise ValueError(f"{name}: expected {ndim} dimensions, got shape {x.shape}")
    return x


def _real(x, name):
    """A scalar or array of real numbers (no trailing axis)."""
    return _arr(x, name, None)


def _broadcast(names, arrays, tails):
    """Broadcast the leading (batch) axes of arrays whose trailing axes have
    the lengths in tails (tuples); returns the batch shape and the arrays,
    each C-contiguous with that batch shape."""
    shapes = [a.shape[:a.ndim - len(t)] for a, t in zip(arrays, tails)]
    first = shapes[0]
    if all(s == first for s in shapes):
        return first, arrays
    try:
        batch = np.broadcast_shapes(*shapes)
    except ValueError:
        raise ValueError(", ".join(names) + ": batch shapes "
                         + ", ".join(str(s) for s in shapes) + " do not broadcast") from None
    out = [a if s == batch else np.ascontiguousarray(np.broadcast_to(a, batch + t))
           for a, s, t in zip(arrays, shapes, tails)]
    return batch, out


def _pairs(r12, q1, q2, rname="r12", dims=(3, 6)):
    r = _arr(r12, rname, dims[0])
    a = _arr(q1, "q1", dims[1])
    b = _arr(q2, "q2", dims[1])
    return _broadcast((rname, "q1", "q2"), [r, a, b], [(dims[0],), (dims[1],), (dims[1],)])


def _nthreads(nthreads):
    if type(nthreads) is int and 0 <= nthreads <= _INT_MAX:
        return nthreads
    if isinstance(nthreads, bool):
        raise TypeError("nthreads: expected an int, got bool")
    try:
        n = operator.index(nthreads)
    except TypeError:
        raise TypeError(f"nthreads: expected an int, got {type(nthreads).__name__}") from None
    if n < 0:
        raise ValueError(f"nthreads: must be >= 0 (0: the OpenMP default), got {n}")
    return min(n, _INT_MAX)


def _method(method):
    if isinstance(method, str):
        m = _METHODS.get(method.lower())
    elif isinstance(method, (int, np.integer)) and not isinstance(method, (bool, np.bool_)):
        m = _METHODS.get(int(method))
    else:
        raise TypeError(f"method: expected a pw85.Method, an int or a name, "
                        f"got {type(method).__name__}")
    if m is None:
        names = ", ".join(repr(m.name.lower()) for m in Method)
        raise ValueError(f"method: unknown method {method!r} (one of {names} or pw85.Method)")
    return m


def _size(batch):
    return math.prod(batch)


def _out(a, batch):
    """A result of batch shape: a NumPy scalar (or 0-d record) for one pair."""
    return a[()] if batch == () else a


# ---- error reports --------------------------------------------------------

def _not_spd(q):
    dim = 3 if q.shape[-1] == 6 else 2
    m = np.zeros((dim, dim))
    m[np.triu_indices(dim)] = q
    m = m + np.triu(m, 1).T
    try:
        np.linalg.cholesky(m)
        return False
    except np.linalg.LinAlgError:
        return True


def _reason(status, k, rows):
    """What is wrong with pair k, naming the argument: rows maps argument
    names to that pair's row of each input."""
    if status == Status.ERR_INVALID_ARGUMENT:
        for name, row in rows.items():
            if not np.all(np.isfinite(row)):
                return f"{name} holds a non-finite value {row.tolist()}"
        if "r12" in rows and not np.any(rows["r12"]):
            return "r12 = 0 (contact geometry and derivatives undefined)"
        if "u" in rows and not np.any(rows["u"]):
            return "u = 0"
    if status == Status.ERR_NOT_SPD:
        bad = [n for n, row in rows.items() if n.startswith("q") and _not_spd(row)]
        if bad:
            return " and ".join(bad) + " not positive definite"
        return "q1 or q2 not positive definite"
    return None


def _raise(func, ret, status, rows_of, batch):
    flat = status.reshape(-1)
    nz = np.flatnonzero(flat)
    if nz.size == 0:
        raise Error(f"pw85.{func}: {status_name(ret)} ({strerror(ret)})", ret, None)
    k = int(nz[0])
    s = int(flat[k])
    if len(batch) <= 1:
        where = f"pair {k}"
    else:  # Python ints: NumPy 2 writes its integers as np.int64(...)
        where = f"pair {tuple(int(i) for i in np.unravel_index(k, batch))} (flat index {k})"
    reason = rows_of(k, s)
    if isinstance(reason, dict):
        reason = _reason(s, k, reason)
    msg = f"pw85.{func}: {where}: {status_name(s)} ({strerror(s)})"
    if reason:
        msg += f": {reason}"
    raise Error(msg, s, k)


def _rows(**arrays):
    def rows_of(k, s):
        return {n: a.reshape(-1, a.shape[-1])[k] for n, a in arrays.items()}
    return rows_of


# ---- per-thread scratch for the one-pair calls -----------------------------

class _Scratch(ctypes.Structure):
    _fields_ = [("v", ctypes.c_double * 15), ("res", Result), ("contact", Contact)]


_tls = threading.local()


def _scratch():
    s = _Scratch()
    v = np.frombuffer(s, dtype=F64, count=15)
    base = ctypes.addressof(s)
    t = (s, v[0:3], v[3:9], v[9:15], base, base + 24, base + 72,
         base + _Scratch.res.offset, base + _Scratch.contact.offset,
         np.frombuffer(s, dtype=CONTACT_DTYPE, count=1, offset=_Scratch.contact.offset))
    _tls.s = t
    return t


# ---- docstrings: sections shared by the public functions, filled in by _doc

_DOC_SECTIONS = {
    "PAIR_PARAMS": """\
    r12 : array_like, shape (..., 3)
        Centre of ellipsoid 2 minus centre of ellipsoid 1.
    q1, q2 : array_like, shape (..., 6)
        Quadratic forms of the ellipsoids (upper triangle of Q row by row:
        Q00, Q01, Q02, Q11, Q12, Q22); the batch axes of r12, q1 and q2
        broadcast.""",
    "NTH": """\
    nthreads : int, default 0
        OpenMP threads of the C batch call (0: the OpenMP default).""",
    "CHECK": """\
    check : bool, default True
        False: no exception for failing pairs; their status is returned.""",
    "ARG_ERR": """\
    TypeError
        An argument that is not an array of real numbers (None, a string,
        complex or bool values), ``nthreads`` not an int.
    ValueError
        A wrong shape, batch shapes that do not broadcast, ``nthreads < 0``.""",
    "COMMON_ERR": """\
    pw85.Error
        A pair fails in the C library (non-finite value, matrix not positive
        definite, ...): ``.status``, ``.status_name``, ``.index`` (flat index
        of the first failing pair) and a message naming the argument.
        Not raised with ``check=False``.""",
    "TUT": """\
    >>> import pw85
    >>> q1 = pw85.spheroid(10., 0.1, [0., 0., 1.])
    >>> q2 = pw85.spheroid(0.5, 5., [1., 0., 0.])""",
    "SCENE_PARAMS": """\
    centres : array_like, shape (n, 3)
        Centres of the n ellipsoids.
    q : array_like, shape (n, 6) or (6,)
        Their quadratic forms, or one for all.
    pairs : array_like of int, shape (m, 2)
        Index pairs (i, j); each pair is computed with r12 = c_j − c_i (its
        periodic image in the box).
    box : array_like, shape (6,), or None
        Periodic box {Lx, Ly, Lz, xy, xz, yz} (HOOMD/GSD convention), or
        None (docs/batch.md).""",
    "SCENE_ERR": """\
    TypeError, ValueError
        A wrong type or shape of an argument, a box with lengths not finite
        and > 0.
    pw85.Error
        A pair fails (index outside [0, n), non-finite value, matrix not
        positive definite, bounding spheres larger than half the box):
        ``.index`` is the index of the pair in ``pairs``. Not raised with
        ``check=False``.""",
    "SCENE_EX": """\
    >>> import numpy as np, pw85
    >>> centres = np.array([[0., 0., 0.], [1.5, 0., 0.], [9.5, 0., 0.]])
    >>> sphere = [1., 0., 0., 1., 0., 1.]
    >>> pairs = [[0, 1], [0, 2]]""",
    "DCA_PARAMS": """\
    u : array_like, shape (..., 3)
        Directions of the line of centres (not necessarily unit, not 0).
    q1, q2 : array_like, shape (..., 6)
        Quadratic forms; the batch axes of u, q1 and q2 broadcast.""",
}


def _doc(f):
    """f with the {NAME} sections of its docstring filled in from _DOC_SECTIONS."""
    if f.__doc__:  # None under python -OO
        f.__doc__ = f.__doc__.format(**_DOC_SECTIONS)
    return f


# ---- constructors ---------------------------------------------------------

def spheroid(a: ArrayLike, c: ArrayLike, n: ArrayLike) -> FloatArray:
    """Quadratic forms of spheroids (``pw85_spheroid``).

    Q = c² n nᵀ + a² (I − n nᵀ) for the unit axis n.

    Parameters
    ----------
    a : array_like
        Equatorial radii, > 0.
    c : array_like
        Polar radii, > 0.
    n : array_like, shape (..., 3)
        Unit axes of revolution (normalised by the C call); a, c and the
        batch axes of n broadcast.

    Returns
    -------
    numpy.ndarray, shape (..., 6)
        The quadratic forms.

    Raises
    ------
    TypeError
        An argument that is not a number or array of real numbers.
    ValueError
        a or c not finite and > 0, n zero or not finite (naming the argument
        and the pair), a wrong shape.

    Examples
    --------
    >>> import pw85
    >>> print(pw85.spheroid(10., 0.1, [0., 0., 1.]))
    [ 1.e+02 -0.e+00 -0.e+00  1.e+02 -0.e+00  1.e-02]
    >>> pw85.spheroid([1., 2.], 0.5, [1., 0., 0.]).shape
    (2, 6)
    """
    a_ = _real(a, "a")
    c_ = _real(c, "c")
    n_ = _arr(n, "n", 3)
    batch, (a_, c_, n_) = _broadcast(("a", "c", "n"), [a_, c_, n_], [(), (), (3,)])
    q = np.empty(batch + (6,))
    m = _size(batch)
    af, cf = a_.reshape(-1).tolist(), c_.reshape(-1).tolist()
    pn, pq = n_.ctypes.data, q.ctypes.data
    f = lib.pw85_spheroid
    for k in range(m):
        f(af[k], cf[k], pn + 24 * k, pq + 48 * k)
    if m and np.isnan(q).any():
        k = int(np.flatnonzero(np.isnan(q).reshape(m, 6).any(axis=1))[0])
        nk = n_.reshape(-1, 3)[k]
        for name, v in (("a", af[k]), ("c", cf[k])):
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"pw85.spheroid: {name} = {v!r} (pair {k}) is not finite and > 0")
        raise ValueError(f"pw85.spheroid: n = {nk.tolist()} (pair {k}) is zero or not finite")
    return q


def _matrices(x, name):
    a = _arr(x, name, 3)
    if a.ndim < 2 or a.shape[-2] != 3:
        raise ValueError(f"{name}: expected shape (..., 3, 3), got {a.shape}")
    return a


def _build_q(func, f, radii, other, oname, otail, reason):
    """Q (..., 6) by the C constructor f(radii, other, q) over the broadcast
    batch of radii (..., 3) and other (... + otail); pw85.Error naming the
    argument of the first failure (reason(s, radii row, other row) for the
    statuses beyond a non-finite value or a radius <= 0)."""
    batch, (r, o) = _broadcast(("radii", oname), [radii, other], [(3,), otail])
    q = np.empty(batch + (6,))
    m = _size(batch)
    st = np.zeros(batch, np.intc)
    sf = st.reshape(-1)
    pr, po, pq = r.ctypes.data, o.ctypes.data, q.ctypes.data
    so = 8 * math.prod(otail)
    ret = 0
    for k in range(m):
        s = f(pr + 24 * k, po + so * k, pq + 48 * k)
        if s:
            sf[k] = s
            ret = ret or s
    if ret:
        def rows_of(k, s):
            rk, ok = r.reshape(-1, 3)[k], o.reshape(-1, so // 8)[k]
            if not np.all(np.isfinite(rk)):
                return f"radii holds a non-finite value {rk.tolist()}"
            if not np.all(np.isfinite(ok)):
                return f"{oname} holds a non-finite value {ok.tolist()}"
            if s == Status.ERR_NOT_SPD and not np.all(rk > 0):
                return f"radii = {rk.tolist()}: a radius is <= 0"
            return reason(s, rk, ok)
        _raise(func, ret, st, rows_of, batch)
    return q


def _range_reason(s, rk):
    if s == Status.ERR_RANGE:
        return f"radii = {rk.tolist()}: a radius^2 outside [DBL_MIN, DBL_MAX]"
    return None


def ellipsoid(radii: ArrayLike, axes: ArrayLike) -> FloatArray:
    """Quadratic forms of ellipsoids of given semi-axes and axes (``pw85_ellipsoid``).

    Q = Σₖ radii[k]² axes[k] axes[k]ᵀ.

    Parameters
    ----------
    radii : array_like, shape (..., 3)
        Semi-axes, finite and > 0.
    axes : array_like, shape (..., 3, 3)
        Unit axes in the ROWS (``axes[..., k, :]`` is the axis of
        ``radii[..., k]``), orthonormal to 1e-10.

    Returns
    -------
    numpy.ndarray, shape (..., 6)
        The quadratic forms, batch axes of radii and axes broadcast.

    Raises
    ------
    TypeError, ValueError
        An argument that is not an array of real numbers; a wrong shape.
    pw85.Error
        A radius not finite and > 0 (``ERR_NOT_SPD``), axes not orthonormal
        (``ERR_NOT_ORTHONORMAL``), a squared radius out of the range of
        double (``ERR_RANGE``); the message names the argument and the pair.

    Examples
    --------
    >>> import numpy as np, pw85
    >>> print(pw85.ellipsoid([1., 2., 3.], np.eye(3)))
    [1. 0. 0. 4. 0. 9.]
    """
    def reason(s, rk, ok):
        if s == Status.ERR_NOT_ORTHONORMAL:
            return "axes are not orthonormal to 1e-10"
        return _range_reason(s, rk)
    return _build_q("ellipsoid", lib.pw85_ellipsoid, _arr(radii, "radii", 3),
                    _matrices(axes, "axes"), "axes", (3, 3), reason)


def ellipsoid_rotation(radii: ArrayLike, rot: ArrayLike) -> FloatArray:
    """Quadratic forms of ellipsoids from rotation matrices (``pw85_ellipsoid_rotation``).

    Q = R diag(radii²) Rᵀ, R mapping the body frame to the lab frame.

    Parameters
    ----------
    radii : array_like, shape (..., 3)
        Semi-axes along the body axes x, y, z, finite and > 0.
    rot : array_like, shape (..., 3, 3)
        Rotation matrices whose COLUMNS are the body axes (``pw85.ellipsoid``
        takes them in rows), orthonormal to 1e-10; a reflection is accepted.

    Returns
    -------
    numpy.ndarray, shape (..., 6)
        The quadratic forms, batch axes of radii and rot broadcast.

    Raises
    ------
    TypeError, ValueError
        An argument that is not an array of real numbers; a wrong shape.
    pw85.Error
        As ``pw85.ellipsoid`` (``rot is not orthonormal to 1e-10``, ...).

    Examples
    --------
    A rotation by 90° about z: the body axis x along the lab axis y.

    >>> import numpy as np, pw85
    >>> rot = np.array([[0., -1., 0.], [1., 0., 0.], [0., 0., 1.]])
    >>> print(pw85.ellipsoid_rotation([3., 2., 1.], rot) + 0.)
    [4. 0. 0. 9. 0. 1.]
    """
    def reason(s, rk, ok):
        if s == Status.ERR_NOT_ORTHONORMAL:
            return "rot is not orthonormal to 1e-10"
        return _range_reason(s, rk)
    return _build_q("ellipsoid_rotation", lib.pw85_ellipsoid_rotation,
                    _arr(radii, "radii", 3), _matrices(rot, "rot"), "rot", (3, 3), reason)


def ellipsoid_quat(radii: ArrayLike, quat: Any, scalar_first: bool = True) -> FloatArray:
    """Quadratic forms of ellipsoids given by semi-axes and quaternions.

    Q = R diag(radii²) Rᵀ, R the rotation (body to lab frame) of the unit
    quaternion, by ``pw85_ellipsoid_quat``.

    Parameters
    ----------
    radii : array_like, shape (..., 3)
        Semi-axes along the body axes x, y, z (LAMMPS ``shape`` holds
        diameters: pass ``shape / 2``).
    quat : array_like, shape (..., 4), or scipy.spatial.transform.Rotation
        Quaternions; ``|quat|²`` within 1e-5 of 1 is accepted and normalised
        (float32 quaternions as read from a GSD file). Any object with an
        ``as_matrix()`` method, such as a SciPy ``Rotation`` (one or a
        stack), is taken as its rotation matrices (``pw85.ellipsoid_rotation``).
    scalar_first : bool, default True
        True: (w, x, y, z), the order of HOOMD-blue, GSD, LAMMPS and
        python-fcl; False: (x, y, z, w), the order of SciPy's
        ``Rotation.as_quat()`` and OVITO. Ignored for a ``Rotation``.

    Returns
    -------
    numpy.ndarray, shape (..., 6)
        The quadratic forms, batch axes of radii and quat broadcast.

    Raises
    ------
    TypeError
        scalar_first not a bool, or an argument not an array of real numbers.
    ValueError
        A wrong shape.
    pw85.Error
        A radius not finite and > 0, a quaternion not of norm 1 within 1e-5
        (``ERR_NOT_ORTHONORMAL``), a non-finite value; the message names
        the argument and the pair.

    Examples
    --------
    A rotation by 90° about z maps the body axis x onto the lab axis y:

    >>> import numpy as np, pw85
    >>> c = np.sqrt(0.5)
    >>> print(pw85.ellipsoid_quat([3., 2., 1.], [c, 0., 0., c]).round(12) + 0.)
    [4. 0. 0. 9. 0. 1.]
    >>> print(pw85.ellipsoid_quat([3., 2., 1.], [0., 0., c, c], scalar_first=False).round(12) + 0.)
    [4. 0. 0. 9. 0. 1.]
    """
    if type(scalar_first) is not bool:
        raise TypeError(f"scalar_first: expected True or False, got {type(scalar_first).__name__}")
    if callable(getattr(quat, "as_matrix", None)):
        def reason_rot(s, rk, ok):
            if s == Status.ERR_NOT_ORTHONORMAL:
                return "the rotation's as_matrix() is not orthonormal to 1e-10"
            return _range_reason(s, rk)
        return _build_q("ellipsoid_quat", lib.pw85_ellipsoid_rotation, _arr(radii, "radii", 3),
                        _matrices(quat.as_matrix(), "quat.as_matrix()"), "quat.as_matrix()",
                        (3, 3), reason_rot)
    u = _arr(quat, "quat", 4)
    if not scalar_first:
        u = np.ascontiguousarray(u[..., [3, 0, 1, 2]])

    def reason(s, rk, ok):
        if s == Status.ERR_NOT_ORTHONORMAL:
            return f"quat = {ok.tolist()}: |quat|^2 = {float(ok @ ok)!r} not within 1e-5 of 1"
        if s == Status.ERR_NOT_SPD:
            return f"radii = {rk.tolist()}: Q not positive definite once rounded"
        return _range_reason(s, rk)
    return _build_q("ellipsoid_quat", lib.pw85_ellipsoid_quat, _arr(radii, "radii", 3),
                    u, "quat", (4,), reason)


def ellipsoid_axes(q: ArrayLike) -> Tuple[FloatArray, FloatArray, FloatArray]:
    """Semi-axes and orientations of ellipsoids (``pw85_ellipsoid_axes``).

    The inverse of the constructors: ``pw85.ellipsoid_quat(radii, quat)``
    and ``pw85.ellipsoid_rotation(radii, rot)`` give q back (within a few
    ulps).

    Parameters
    ----------
    q : array_like, shape (..., 6)
        Quadratic forms, positive definite.

    Returns
    -------
    radii : numpy.ndarray, shape (..., 3)
        Semi-axes, ascending.
    rot : numpy.ndarray, shape (..., 3, 3)
        Proper rotations whose column k is the axis of ``radii[..., k]``.
    quat : numpy.ndarray, shape (..., 4)
        The same rotations as quaternions (w, x, y, z), w >= 0.

    Raises
    ------
    TypeError, ValueError
        An argument that is not an array of real numbers; a wrong shape.
    pw85.Error
        q not finite or not positive definite (naming the first such q).

    Examples
    --------
    >>> import pw85
    >>> radii, rot, quat = pw85.ellipsoid_axes([9., 0., 0., 4., 0., 1.])
    >>> print(radii, quat + 0.)
    [1. 2. 3.] [ 0.70710678  0.         -0.70710678  0.        ]
    """
    qq = _arr(q, "q", 6)
    batch = qq.shape[:-1]
    m = _size(batch)
    radii = np.empty(batch + (3,))
    rot = np.empty(batch + (3, 3))
    quat = np.empty(batch + (4,))
    st = np.zeros(batch, np.intc)
    sf = st.reshape(-1)
    pq, pr, pm, pu = qq.ctypes.data, radii.ctypes.data, rot.ctypes.data, quat.ctypes.data
    f = lib.pw85_ellipsoid_axes
    ret = 0
    for k in range(m):
        s = f(pq + 48 * k, pr + 24 * k, pm + 72 * k, pu + 32 * k)
        if s:
            sf[k] = s
            ret = ret or s
    if ret:
        _raise("ellipsoid_axes", ret, st, _rows(q=qq), batch)
    return radii, rot, quat


# ---- contact function, overlap, contact geometry over per-pair arrays ------

@_doc
def contact_function(r12: ArrayLike, q1: ArrayLike, q2: ArrayLike,
                     method: Union[Method, int, str] = "default", nthreads: int = 0,
                     check: bool = True) -> Tuple[Any, ...]:
    """Contact function μ² and maximiser λ of pairs of ellipsoids.

    μ² < 1: the ellipsoids overlap; μ² = 1: they touch; μ² > 1: they are
    apart (μ is the factor by which both, centres fixed, must be scaled to
    touch). One pair runs ``pw85_contact_function_method``, arrays of pairs
    ``pw85_contact_function_pairs``; the results are bitwise those of the C
    calls.

    Parameters
    ----------
{PAIR_PARAMS}
    method : pw85.Method, int or str, default "default"
        ``pw85.Method.DEFAULT`` (relative accuracy 1e-14, with an error
        estimate), ``BRENT`` (pw85 1.0's iteration), ``NEWTON``,
        ``RATIONAL``, ``ZHENG``; its value or its name (docs/methods.md).
{NTH}
{CHECK}

    Returns
    -------
    mu2, lambda_ : numpy.float64 or numpy.ndarray
        NumPy scalars for one pair, arrays of the batch shape otherwise.
    status : numpy.ndarray of int, only with check=False
        Per-pair status (``pw85.Status``); failing pairs have NaN results.

    Raises
    ------
{ARG_ERR}
        An unknown method.
{COMMON_ERR}

    Examples
    --------
    The tutorial pair of pw85 1.0 (the last bits of λ depend on the CPU,
    docs/api.md):

{TUT}
    >>> mu2, lambda_ = pw85.contact_function([0.7, -0.7, 1.1], q1, q2)
    >>> print(mu2, lambda_)  # doctest: +ELLIPSIS
    3.3627060406386295 0.1668589553405547...
    >>> mu2, lambda_ = pw85.contact_function([[0.7, -0.7, 1.1], [0., 0., 0.5]], q1, q2)
    >>> print(mu2.round(6))
    [3.362706 0.694444]
    """
    if _ext is not None:
        # one pair that succeeds, plain options: the result; else None
        v = _ext.contact_function1(r12, q1, q2, method, nthreads, check)
        if v is not None:
            return v
    # the one-pair path is inlined (a function call costs ~0.1 us here)
    meth = _METHODS.get(method) if type(method) is str else None
    if meth is None:
        meth = _method(method)
    nt = nthreads
    if type(nt) is not int or not 0 <= nt <= _INT_MAX:
        nt = _nthreads(nt)
    if (_ext is None and type(r12) is _ND and type(q1) is _ND and type(q2) is _ND
            and r12.shape == _S3 and q1.shape == _S6 and q2.shape == _S6
            and r12.dtype is F64 and q1.dtype is F64 and q2.dtype is F64):
        try:
            s = _tls.s
        except AttributeError:
            s = _scratch()
        s[1][...] = r12
        s[2][...] = q1
        s[3][...] = q2
        st = lib.pw85_contact_function_method(s[4], s[5], s[6], meth, s[7])
        res = s[0].res
        if st == 0:
            mu2, lam = _F(res.mu2), _F(res.lambda_)
            return (mu2, lam) if check else (mu2, lam, 0)
        if check:
            _raise("contact_function", st, np.array([st], np.intc),
                   _rows(r12=r12, q1=q1, q2=q2), ())
        return np.float64(_NAN), np.float64(_NAN), int(st)
    batch, (r, a, b) = _pairs(r12, q1, q2)
    m = _size(batch)
    if _ext is not None:
        # The statuses only for check=False, or once a pair has failed (the
        # call again: the same bits): no status array for a batch that passes.
        mu2, lam = np.empty(batch), np.empty(batch)
        st = None if check else np.empty(batch, np.intc)  # every entry written
        ret = _ext.contact_function_pairs(m, r, a, b, meth, mu2, lam, st, nt) if m else 0
        if ret and st is None:
            st = np.empty(batch, np.intc)
            ret = _ext.contact_function_pairs(m, r, a, b, meth, mu2, lam, st, nt)
    else:
        res = np.empty(batch, RESULT_DTYPE)
        st = np.zeros(batch, np.intc)
        ret = 0
        if m:
            ret = lib.pw85_contact_function_pairs(m, r.ctypes.data, a.ctypes.data, b.ctypes.data,
                                                  meth, res.ctypes.data, st.ctypes.data, nt)
        mu2 = res["mu2"].copy()
        lam = res["lambda"].copy()
    if ret:
        if check:
            _raise("contact_function", ret, st, _rows(r12=r, q1=a, q2=b), batch)
        bad = st != 0
        mu2[bad] = _NAN
        lam[bad] = _NAN
    if check:
        return _out(mu2, batch), _out(lam, batch)
    return _out(mu2, batch), _out(lam, batch), _out(st, batch)


@_doc
def overlap(r12: ArrayLike, q1: ArrayLike, q2: ArrayLike, nthreads: int = 0,
            check: bool = True) -> Any:
    """Exact overlap verdicts (μ² < 1) of pairs of ellipsoids.

    One pair runs ``pw85_overlap``, arrays of pairs ``pw85_overlap_pairs``;
    the verdict is exact (docs/overlap.md) and the same on every CPU.

    Parameters
    ----------
{PAIR_PARAMS}
{NTH}
{CHECK}

    Returns
    -------
    overlap : bool or numpy.ndarray of bool
        A bool for one pair, an array of the batch shape otherwise.
    status : int or numpy.ndarray of int, only with check=False
        Per-pair status; failing pairs are False.

    Raises
    ------
{ARG_ERR}
{COMMON_ERR}

    Examples
    --------
{TUT}
    >>> pw85.overlap([0.7, -0.7, 1.1], q1, q2)
    False
    >>> print(pw85.overlap([[0.7, -0.7, 1.1], [0., 0., 0.5]], q1, q2))
    [False  True]
    """
    if _ext is not None:
        # one pair that succeeds, plain options: the result; else None
        v = _ext.overlap1(r12, q1, q2, nthreads, check)
        if v is not None:
            return v
    nt = nthreads
    if type(nt) is not int or not 0 <= nt <= _INT_MAX:
        nt = _nthreads(nt)
    if (_ext is None and type(r12) is _ND and type(q1) is _ND and type(q2) is _ND
            and r12.shape == _S3 and q1.shape == _S6 and q2.shape == _S6
            and r12.dtype is F64 and q1.dtype is F64 and q2.dtype is F64):
        try:
            s = _tls.s
        except AttributeError:
            s = _scratch()
        s[1][...] = r12
        s[2][...] = q1
        s[3][...] = q2
        v = lib.pw85_overlap(s[4], s[5], s[6])
        if v >= 0:
            return (v == 1) if check else (v == 1, 0)
        if check:
            _raise("overlap", v, np.array([v], np.intc), _rows(r12=r12, q1=q1, q2=q2), ())
        return False, int(v)
    batch, (r, a, b) = _pairs(r12, q1, q2)
    m = _size(batch)
    if _ext is not None:
        # statuses as in contact_function
        res = np.empty(batch, bool)
        st = None if check else np.empty(batch, np.intc)  # every entry written
        ret = _ext.overlap_pairs(m, r, a, b, res, st, nt) if m else 0
        if ret and st is None:
            st = np.empty(batch, np.intc)
            ret = _ext.overlap_pairs(m, r, a, b, res, st, nt)
    else:
        ov = np.empty(batch, np.intc)
        st = np.zeros(batch, np.intc)
        ret = 0
        if m:
            ret = lib.pw85_overlap_pairs(m, r.ctypes.data, a.ctypes.data, b.ctypes.data,
                                         ov.ctypes.data, st.ctypes.data, nt)
        res = ov > 0
    if ret and check:
        _raise("overlap", ret, st, _rows(r12=r, q1=a, q2=b), batch)
    if check:
        return _out(res, batch)
    return _out(res, batch), _out(st, batch)


def _pair_records(name, cfunc, dtype, r12, q1, q2, nthreads, check):
    """A C pairs call that fills one struct per pair: a structured array of
    the batch shape (a record for one pair); check=False: (records, status),
    failing pairs NaN."""
    nt = _nthreads(nthreads)
    batch, (r, a, b) = _pairs(r12, q1, q2)
    m = _size(batch)
    out = np.empty(batch, dtype)
    st = np.zeros(batch, np.intc)
    ret = 0
    if m:
        ret = cfunc(m, r.ctypes.data, a.ctypes.data, b.ctypes.data, out.ctypes.data,
                    st.ctypes.data, nt)
    if ret:
        if check:
            _raise(name, ret, st, _rows(r12=r, q1=a, q2=b), batch)
        out[st != 0] = _NAN
    if check:
        return _out(out, batch)
    return _out(out, batch), _out(st, batch)


@_doc
def contact(r12: ArrayLike, q1: ArrayLike, q2: ArrayLike, nthreads: int = 0,
            check: bool = True) -> Any:
    """Contact geometry of pairs of ellipsoids (``pw85_contact_pairs``).

    Fields of ``pw85_contact_t`` (docs/contact_geometry.md): ``mu2``,
    ``lambda``; ``x0`` (3), the contact point of the two ellipsoids scaled
    by μ, RELATIVE TO THE CENTRE OF ELLIPSOID 1 (add c1 for lab
    coordinates); ``n`` (3), the unit normal there, pointing from ellipsoid 1
    to ellipsoid 2; ``dca``, the distance of closest approach along r12;
    ``depth`` = dca − |r12| (> 0: overlap depth along r12); ``depth_n``, the
    depth along n.

    Parameters
    ----------
{PAIR_PARAMS}
{NTH}
{CHECK}

    Returns
    -------
    contact : numpy.ndarray of dtype pw85.CONTACT_DTYPE
        A record for one pair, a structured array of the batch shape
        otherwise.
    status : numpy.ndarray of int, only with check=False
        Per-pair status; failing pairs are NaN.

    Raises
    ------
{ARG_ERR}
{COMMON_ERR}
        r12 = 0 fails (no contact geometry).

    Examples
    --------
    Two unit spheres 3 apart along x: contact point halfway, x0 = (1.5, 0, 0)
    from centre 1.

    >>> import pw85
    >>> c = pw85.contact([3., 0., 0.], [1., 0., 0., 1., 0., 1.], [1., 0., 0., 1., 0., 1.])
    >>> print(c["mu2"].round(12), c["x0"].round(12), c["n"], c["dca"].round(12), c["depth"].round(12))
    2.25 [1.5 0.  0. ] [1. 0. 0.] 2.0 -1.0
    """
    return _pair_records("contact", lib.pw85_contact_pairs, CONTACT_DTYPE, r12, q1, q2,
                         nthreads, check)


# The flags argument of the _ex derivatives calls (include/pw85.h).
_DERIVATIVES_ALL, _DERIVATIVES_FORCES = 0, 1


def _derivative_flags(forces_only):
    return _DERIVATIVES_FORCES if forces_only else _DERIVATIVES_ALL


@_doc
def contact_derivatives(r12: ArrayLike, q1: ArrayLike, q2: ArrayLike, nthreads: int = 0,
                        check: bool = True, forces_only: bool = False) -> Any:
    """Derivatives of μ² for forces, torques and the Hessian (``pw85_contact_derivatives_pairs_ex``).

    Fields of ``pw85_derivatives_t`` (docs/derivatives.md): ``mu2``,
    ``lambda``, ``d_r12`` (3) = ∂μ²/∂r12, ``d_theta1`` (3) and ``d_theta2``
    (3), the derivatives under infinitesimal rotations of each ellipsoid,
    ``d_q1`` (6) and ``d_q2`` (6), those with respect to the matrices,
    ``hess_r12`` (6), the Hessian with respect to r12.

    Parameters
    ----------
{PAIR_PARAMS}
{NTH}
{CHECK}
    forces_only : bool, optional
        True: ``PW85_DERIVATIVES_FORCES``, only ``mu2``, ``lambda``,
        ``d_r12``, ``d_theta1``, ``d_theta2`` (the same bits as the full
        call's), ``d_q1``, ``d_q2`` and ``hess_r12`` NaN.

    Returns
    -------
    derivatives : numpy.ndarray of dtype pw85.DERIVATIVES_DTYPE
        A record for one pair, a structured array of the batch shape
        otherwise.
    status : numpy.ndarray of int, only with check=False
        Per-pair status; failing pairs are NaN.

    Raises
    ------
{ARG_ERR}
{COMMON_ERR}
        r12 = 0 fails (no derivative there).

    Examples
    --------
    Unit spheres: μ² = |r12|²/4, so ∂μ²/∂r12 = r12/2.

    >>> import pw85
    >>> d = pw85.contact_derivatives([3., 0., 4.], [1., 0., 0., 1., 0., 1.], [1., 0., 0., 1., 0., 1.])
    >>> print(d["mu2"].round(12), d["d_r12"].round(12))
    6.25 [1.5 0.  2. ]
    """
    flags = _derivative_flags(forces_only)

    def pairs_ex(m, r, a, b, out, st, nt):
        return lib.pw85_contact_derivatives_pairs_ex(m, r, a, b, flags, out, st, nt)
    return _pair_records("contact_derivatives", pairs_ex, DERIVATIVES_DTYPE, r12, q1, q2,
                         nthreads, check)


@_doc
def contact_time(r12: ArrayLike, v12: ArrayLike, q1: ArrayLike, w1: ArrayLike,
                 q2: ArrayLike, w2: ArrayLike, t_max: float, nthreads: int = 0,
                 check: bool = True) -> Any:
    """First contact time of moving, spinning ellipsoids (``pw85_contact_time_pairs``).

    The pair moves as r12 + t v12 while q1 and q2 spin at the angular
    velocities w1 and w2 (docs/contact_time.md); the first t in [0, t_max]
    at which they touch, certified never to miss a collision.

    Parameters
    ----------
    r12, v12 : array_like, shape (..., 3)
        Relative position and velocity (centre 2 minus centre 1).
    q1, q2 : array_like, shape (..., 6)
        Quadratic forms at t = 0.
    w1, w2 : array_like, shape (..., 3)
        Angular velocities; the batch axes of all six broadcast.
    t_max : float
        Horizon, finite and > 0.
{NTH}
{CHECK}

    Returns
    -------
    t : numpy.float64 or numpy.ndarray
        inf: no contact in [0, t_max]; 0: overlapping or touching now.
    status : numpy.ndarray of int, only with check=False
        Per-pair status; failing pairs NaN, except ``ERR_NO_CONVERGENCE``,
        which keeps the time up to which the pair is certified free of
        contact.

    Raises
    ------
{ARG_ERR}
        t_max not finite and > 0.
{COMMON_ERR}

    Examples
    --------
    Unit spheres 4 apart closing at speed 1 touch at t = 2:

    >>> import pw85
    >>> s, w = [1., 0., 0., 1., 0., 1.], [0., 0., 0.]
    >>> print(round(float(pw85.contact_time([4., 0., 0.], [-1., 0., 0.], s, w, s, w, 10.)), 12))
    2.0
    """
    nt = _nthreads(nthreads)
    tm = float(t_max)
    if not (math.isfinite(tm) and tm > 0):
        raise ValueError(f"t_max: expected a finite number > 0, got {t_max!r}")
    names = ("r12", "v12", "q1", "w1", "q2", "w2")
    arrs = [_arr(x, n, 6 if n[0] == "q" else 3)
            for x, n in zip((r12, v12, q1, w1, q2, w2), names)]
    batch, arrs = _broadcast(names, arrs, [(a.shape[-1],) for a in arrs])
    m = _size(batch)
    t = np.empty(batch, F64)
    st = np.zeros(batch, np.intc)
    ret = 0
    if m:
        ret = lib.pw85_contact_time_pairs(m, *(a.ctypes.data for a in arrs), tm, t.ctypes.data,
                                          st.ctypes.data, nt)
    if ret:
        if check:
            rows = _rows(**dict(zip(names, arrs)))

            def rows_of(k, s):
                r = rows(k, s)
                if s == Status.ERR_INVALID_ARGUMENT and all(np.all(np.isfinite(x)) for x in r.values()):
                    return "r12 + t v12 or t w leaves the range of double within t_max"
                if s == Status.ERR_NO_CONVERGENCE:
                    return f"contact-free up to t = {float(t.reshape(-1)[k])!r} only"
                return r
            _raise("contact_time", ret, st, rows_of, batch)
        bad = (st != 0) & (st != Status.ERR_NO_CONVERGENCE)
        t[bad] = _NAN
    if check:
        return _out(t, batch)
    return _out(t, batch), _out(st, batch)


# ---- scenes ---------------------------------------------------------------

def _scene(centres, q, pairs, box):
    c = _arr(centres, "centres", 3, ndim=2)
    n = c.shape[0]
    qq = _arr(q, "q", 6)
    if qq.ndim == 1:
        qq = np.ascontiguousarray(np.broadcast_to(qq, (n, 6)))
    elif qq.shape != (n, 6):
        raise ValueError(f"q: expected shape ({n}, 6) or (6,) for the {n} centres, got {qq.shape}")
    if pairs is None or isinstance(pairs, (str, bytes)):
        raise TypeError(f"pairs: expected an array of integer index pairs, got {type(pairs).__name__}")
    try:
        p = np.asarray(pairs)
    except (ValueError, TypeError) as e:
        raise ValueError(f"pairs: not a regular array of integers ({e})") from None
    if p.size == 0 and p.ndim == 1:
        p = np.zeros((0, 2), np.int64)
    if p.dtype.kind not in "iu":
        raise TypeError(f"pairs: expected integers, got dtype {p.dtype}")
    if p.ndim != 2 or p.shape[1] != 2:
        raise ValueError(f"pairs: expected shape (m, 2), got {p.shape}")
    p = _aligned(np.ascontiguousarray(p, dtype=np.int64))
    bx = _box(box)
    return c, qq, p, bx, None if bx is None else bx.ctypes.data


def _box(box):
    """A periodic box {Lx, Ly, Lz, xy, xz, yz} as a float64 array (6,), or
    None; ValueError for lengths not finite and > 0 or tilts not finite."""
    if box is None:
        return None
    bx = _arr(box, "box", 6, ndim=1)
    L, t = bx[:3], bx[3:]
    with np.errstate(over="ignore", invalid="ignore"):
        tilts_ok = np.all(np.isfinite(t * np.array([L[1], L[2], L[2]])))
    if not (np.all(np.isfinite(bx)) and np.all(L > 0) and tilts_ok):
        raise ValueError(f"box: expected {{Lx, Ly, Lz, xy, xz, yz}} with finite lengths > 0 "
                         f"and finite tilts, got {bx.tolist()}")
    return bx


def _scene_rows(c, qq, p, bx):
    n = c.shape[0]

    def rows_of(k, s):
        i, j = (int(v) for v in p[k])
        if not (0 <= i < n and 0 <= j < n):
            return f"pairs[{k}] = ({i}, {j}) outside [0, {n})"
        rows = {f"centres[{i}]": c[i], f"centres[{j}]": c[j], f"q[{i}]": qq[i], f"q[{j}]": qq[j]}
        if s == Status.ERR_INVALID_ARGUMENT:
            r = _reason(s, k, rows)
            if r:
                return r
            if bx is not None:
                return (f"ellipsoids {i} and {j}: bounding spheres exceed min(Lx, Ly, Lz)/2 "
                        "of the box")
            return None
        return _reason(s, k, rows)
    return rows_of


@_doc
def scene_overlap(centres: ArrayLike, q: ArrayLike, pairs: ArrayLike,
                  box: Optional[ArrayLike] = None, nthreads: int = 0,
                  check: bool = True) -> Any:
    """Overlap verdicts of index pairs of a scene (``pw85_scene_overlap``).

    Parameters
    ----------
{SCENE_PARAMS}
{NTH}
{CHECK}

    Returns
    -------
    overlap : numpy.ndarray of bool, shape (m,)
    status : numpy.ndarray of int, shape (m,), only with check=False

    Raises
    ------
{SCENE_ERR}

    Examples
    --------
{SCENE_EX}
    >>> print(pw85.scene_overlap(centres, sphere, pairs))
    [ True False]
    >>> print(pw85.scene_overlap(centres, sphere, pairs, box=[10., 10., 10., 0., 0., 0.]))
    [ True  True]
    """
    nt = _nthreads(nthreads)
    c, qq, p, bx, pbox = _scene(centres, q, pairs, box)
    m = p.shape[0]
    ov = np.empty(m, np.intc)
    st = np.zeros(m, np.intc)
    ret = 0
    if m:
        ret = lib.pw85_scene_overlap(c.shape[0], c.ctypes.data, qq.ctypes.data, pbox, m,
                                     p.ctypes.data, ov.ctypes.data, st.ctypes.data, nt)
    if ret and check:
        _raise("scene_overlap", ret, st, _scene_rows(c, qq, p, bx), (m,))
    res = ov > 0
    return res if check else (res, st)


@_doc
def scene_contact_function(centres: ArrayLike, q: ArrayLike, pairs: ArrayLike,
                           box: Optional[ArrayLike] = None,
                           method: Union[Method, int, str] = "default", nthreads: int = 0,
                           check: bool = True) -> Tuple[FloatArray, ...]:
    """μ² and λ of index pairs of a scene (``pw85_scene_contact_function``).

    Parameters
    ----------
{SCENE_PARAMS}
    method : pw85.Method, int or str, default "default"
        As ``pw85.contact_function``.
{NTH}
{CHECK}

    Returns
    -------
    mu2, lambda_ : numpy.ndarray, shape (m,)
    status : numpy.ndarray of int, shape (m,), only with check=False
        Failing pairs have NaN results.

    Raises
    ------
{SCENE_ERR}

    Examples
    --------
{SCENE_EX}
    >>> mu2, lambda_ = pw85.scene_contact_function(centres, sphere, pairs)
    >>> print(mu2.round(12), lambda_)
    [ 0.5625 22.5625] [0.5 0.5]
    """
    meth = _method(method)
    nt = _nthreads(nthreads)
    c, qq, p, bx, pbox = _scene(centres, q, pairs, box)
    m = p.shape[0]
    res = np.empty(m, RESULT_DTYPE)
    st = np.zeros(m, np.intc)
    ret = 0
    if m:
        ret = lib.pw85_scene_contact_function(c.shape[0], c.ctypes.data, qq.ctypes.data, pbox,
                                              m, p.ctypes.data, meth, res.ctypes.data,
                                              st.ctypes.data, nt)
    mu2 = res["mu2"].copy()
    lam = res["lambda"].copy()
    if ret:
        if check:
            _raise("scene_contact_function", ret, st, _scene_rows(c, qq, p, bx), (m,))
        bad = st != 0
        mu2[bad] = _NAN
        lam[bad] = _NAN
    return (mu2, lam) if check else (mu2, lam, st)


def _scene_records(name, cfunc, dtype, centres, q, pairs, box, nthreads, check):
    """A C scene call that fills one struct per index pair: a structured
    array (m,); check=False: (records, status), failing pairs NaN."""
    nt = _nthreads(nthreads)
    c, qq, p, bx, pbox = _scene(centres, q, pairs, box)
    m = p.shape[0]
    out = np.empty(m, dtype)
    st = np.zeros(m, np.intc)
    ret = 0
    if m:
        ret = cfunc(c.shape[0], c.ctypes.data, qq.ctypes.data, pbox, m, p.ctypes.data,
                    out.ctypes.data, st.ctypes.data, nt)
    if ret:
        if check:
            _raise(name, ret, st, _scene_rows(c, qq, p, bx), (m,))
        out[st != 0] = _NAN
    return out if check else (out, st)


@_doc
def scene_contact(centres: ArrayLike, q: ArrayLike, pairs: ArrayLike,
                  box: Optional[ArrayLike] = None, nthreads: int = 0,
                  check: bool = True) -> Any:
    """Contact geometry of index pairs of a scene (``pw85_scene_contact``).

    Fields as ``pw85.contact``; x0 is relative to the centre of ellipsoid i
    of the pair (i, j).

    Parameters
    ----------
{SCENE_PARAMS}
{NTH}
{CHECK}

    Returns
    -------
    contact : numpy.ndarray of dtype pw85.CONTACT_DTYPE, shape (m,)
    status : numpy.ndarray of int, shape (m,), only with check=False
        Failing pairs are NaN.

    Raises
    ------
{SCENE_ERR}

    Examples
    --------
{SCENE_EX}
    >>> c = pw85.scene_contact(centres, sphere, pairs)
    >>> print(c["x0"][0], c["depth"])
    [0.75 0.   0.  ] [ 0.5 -7.5]
    """
    return _scene_records("scene_contact", lib.pw85_scene_contact, CONTACT_DTYPE, centres, q,
                          pairs, box, nthreads, check)


@_doc
def scene_contact_derivatives(centres: ArrayLike, q: ArrayLike, pairs: ArrayLike,
                              box: Optional[ArrayLike] = None, nthreads: int = 0,
                              check: bool = True, forces_only: bool = False) -> Any:
    """Derivatives of μ² for index pairs of a scene (``pw85_scene_contact_derivatives_ex``).

    Fields as ``pw85.contact_derivatives``, with respect to r12 = c_j − c_i
    (or its periodic image), q_i (``d_q1``, ``d_theta1``) and q_j (``d_q2``,
    ``d_theta2``).

    Parameters
    ----------
{SCENE_PARAMS}
{NTH}
{CHECK}
    forces_only : bool, optional
        As ``pw85.contact_derivatives``.

    Returns
    -------
    derivatives : numpy.ndarray of dtype pw85.DERIVATIVES_DTYPE, shape (m,)
    status : numpy.ndarray of int, shape (m,), only with check=False
        Failing pairs are NaN.

    Raises
    ------
{SCENE_ERR}

    Examples
    --------
{SCENE_EX}
    >>> d = pw85.scene_contact_derivatives(centres, sphere, pairs)
    >>> print(d["d_r12"][0])
    [0.75 0.   0.  ]
    """
    flags = _derivative_flags(forces_only)

    def scene_ex(n, c, qq, pbox, m, p, out, st, nt):
        return lib.pw85_scene_contact_derivatives_ex(n, c, qq, pbox, m, p, flags, out, st, nt)
    return _scene_records("scene_contact_derivatives", scene_ex, DERIVATIVES_DTYPE, centres, q,
                          pairs, box, nthreads, check)


# ---- distance of closest approach and 2D functions (a loop of one-pair calls)

def _loop(func, name, r12, q1, q2, rname, dims, nout, call, check):
    batch, (r, a, b) = _pairs(r12, q1, q2, rname, dims)
    m = _size(batch)
    outs = [np.empty(batch + ((k,) if k > 1 else ()), dt) for k, dt in nout]
    st = np.zeros(batch, np.intc)
    sf = st.reshape(-1)
    pr, pa, pb = r.ctypes.data, a.ctypes.data, b.ctypes.data
    po = [o.ctypes.data for o in outs]
    sr, sq = 8 * dims[0], 8 * dims[1]
    ret = 0
    for k in range(m):
        s = call(pr + sr * k, pa + sq * k, pb + sq * k, *[p + o.itemsize * (o.size // max(m, 1)) * k
                                                          for p, o in zip(po, outs)])
        if s:
            sf[k] = s
            ret = ret or s
    if ret:
        if check:
            _raise(name, ret, st, _rows(**{rname: r, "q1": a, "q2": b}), batch)
        bad = st != 0
        for o in outs:
            if o.dtype.kind == "f":
                o[bad] = _NAN
    return batch, outs, st


@_doc
def dca(u: ArrayLike, q1: ArrayLike, q2: ArrayLike, method: Union[Method, int, str] = "default",
        check: bool = True) -> Any:
    """Distance of closest approach of ellipsoids along u (``pw85_dca``).

    The centre distance at which the ellipsoids, centres on a line of
    direction u, touch (docs/dca.md).

    Parameters
    ----------
{DCA_PARAMS}
    method : pw85.Method, int or str, default "default"
        ``ZHENG``: rotation of a plane (Zheng, Iglesias & Palffy-Muhoray);
        any other method: 1/sqrt(F(u/|u|)) with F by that method.
{CHECK}

    Returns
    -------
    d : numpy.float64 or numpy.ndarray
    status : numpy.ndarray of int, only with check=False

    Raises
    ------
    TypeError, ValueError
        A wrong type or shape of an argument, an unknown method.
{COMMON_ERR}

    Examples
    --------
    >>> import pw85
    >>> print(round(float(pw85.dca([1., 0., 0.], [4., 0., 0., 1., 0., 1.], [1., 0., 0., 1., 0., 1.])), 12))
    3.0
    """
    meth = _method(method)
    f = lib.pw85_dca
    batch, (d,), st = _loop(f, "dca", u, q1, q2, "u", (3, 6), [(1, F64)],
                            lambda pu, pa, pb, pd: f(pu, pa, pb, meth, pd), check)
    return _out(d, batch) if check else (_out(d, batch), _out(st, batch))


@_doc
def dca_ex(u: ArrayLike, q1: ArrayLike, q2: ArrayLike, theta_tol: float = 0.0,
           check: bool = True) -> Tuple[Any, ...]:
    """Distance of closest approach by plane rotation with a tolerance (``pw85_dca_ex``).

    Parameters
    ----------
{DCA_PARAMS}
    theta_tol : float, default 0.0
        Tolerance (radians, >= 0) on the angle of the optimal plane; 0:
        ``PW85_DCA_THETA_TOL`` (1e-8).
{CHECK}

    Returns
    -------
    d : numpy.float64 or numpy.ndarray
    evaluations : numpy.intc or numpy.ndarray
        Number of 2D problems solved.
    status : numpy.ndarray of int, only with check=False

    Raises
    ------
    TypeError, ValueError
        A wrong type or shape of an argument, theta_tol not finite and >= 0.
{COMMON_ERR}

    Examples
    --------
    >>> import pw85
    >>> d, evaluations = pw85.dca_ex([1., 0., 0.], [4., 0., 0., 1., 0., 1.], [1., 0., 0., 1., 0., 1.])
    >>> print(round(float(d), 12))
    3.0
    """
    try:
        tol = float(theta_tol)
    except (TypeError, ValueError):
        raise TypeError(f"theta_tol: expected a real number, got {type(theta_tol).__name__}") from None
    if not (math.isfinite(tol) and tol >= 0):
        raise ValueError(f"theta_tol: must be finite and >= 0, got {theta_tol!r}")
    f = lib.pw85_dca_ex
    batch, (d, ev), st = _loop(f, "dca_ex", u, q1, q2, "u", (3, 6),
                               [(1, F64), (1, np.dtype(np.intc))],
                               lambda pu, pa, pb, pd, pe: f(pu, pa, pb, tol, pd, pe), check)
    if check:
        return _out(d, batch), _out(ev, batch)
    return _out(d, batch), _out(ev, batch), _out(st, batch)


@_doc
def dca_2d(u: ArrayLike, q1: ArrayLike, q2: ArrayLike, check: bool = True) -> Any:
    """Distance of closest approach of ellipses along u (``pw85_dca_2d``, closed form).

    Parameters
    ----------
    u : array_like, shape (..., 2)
        Directions of the line of centres (not 0).
    q1, q2 : array_like, shape (..., 3)
        Quadratic forms of the ellipses {{Q00, Q01, Q11}}; batch axes broadcast.
{CHECK}

    Returns
    -------
    d : numpy.float64 or numpy.ndarray
    status : numpy.ndarray of int, only with check=False

    Raises
    ------
    TypeError, ValueError
        A wrong type or shape of an argument.
{COMMON_ERR}

    Examples
    --------
    >>> import pw85
    >>> print(round(float(pw85.dca_2d([0., 1.], [1., 0., 4.], [1., 0., 1.])), 12))
    3.0
    """
    f = lib.pw85_dca_2d
    batch, (d,), st = _loop(f, "dca_2d", u, q1, q2, "u", (2, 3), [(1, F64)], f, check)
    return _out(d, batch) if check else (_out(d, batch), _out(st, batch))


@_doc
def contact_function_2d(r12: ArrayLike, q1: ArrayLike, q2: ArrayLike,
                        check: bool = True) -> Tuple[Any, ...]:
    """Contact function μ² and λ of ellipses (``pw85_contact_function_2d``).

    Parameters
    ----------
    r12 : array_like, shape (..., 2)
        Centre of ellipse 2 minus centre of ellipse 1.
    q1, q2 : array_like, shape (..., 3)
        Quadratic forms {{Q00, Q01, Q11}}; batch axes broadcast.
{CHECK}

    Returns
    -------
    mu2, lambda_ : numpy.float64 or numpy.ndarray
    status : numpy.ndarray of int, only with check=False

    Raises
    ------
    TypeError, ValueError
        A wrong type or shape of an argument.
{COMMON_ERR}

    Examples
    --------
    Unit circles 3 apart: μ² = 9/4, λ = 1/2.

    >>> import pw85
    >>> mu2, lambda_ = pw85.contact_function_2d([3., 0.], [1., 0., 1.], [1., 0., 1.])
    >>> print(round(float(mu2), 12), round(float(lambda_), 12))
    2.25 0.5
    """
    f = lib.pw85_contact_function_2d
    batch, (out,), st = _loop(f, "contact_function_2d", r12, q1, q2, "r12", (2, 3),
                              [(2, F64)], f, check)
    mu2, lam = out[..., 0].copy(), out[..., 1].copy()
    if check:
        return _out(mu2, batch), _out(lam, batch)
    return _out(mu2, batch), _out(lam, batch), _out(st, batch)
