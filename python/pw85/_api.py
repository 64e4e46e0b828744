"""The vectorised API of pw85 (see the package docstring)."""
import ctypes
import math
import operator
import threading

import numpy as np

from ._lib import (lib, Error, Method, Status, status_name, strerror,
                   Result, Contact, RESULT_DTYPE, CONTACT_DTYPE, DERIVATIVES_DTYPE)

F64 = np.dtype(np.float64)
_ND = np.ndarray
_F = np.float64
_S3, _S6 = (3,), (6,)
_NAN = float("nan")
_INT_MAX = 2**31 - 1
_METHODS = {m.name.lower(): int(m) for m in Method}
_METHODS.update({int(m): int(m) for m in Method})


# ---- argument conversion --------------------------------------------------

def _arr(x, name, last, ndim=None):
    """x as a C-contiguous float64 array whose last axis has length `last`
    (a copy only when x is not one already)."""
    if not (type(x) is np.ndarray and x.dtype is F64 and x.flags.c_contiguous):
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
        x = np.asarray(a, dtype=F64, order="C")
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
    where = f"pair {k}" if len(batch) <= 1 else f"pair {np.unravel_index(k, batch)} (flat index {k})"
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


# ---- constructors ---------------------------------------------------------

def spheroid(a, c, n):
    """Quadratic form of spheroids: equatorial radius a, polar radius c, unit
    axis n (shape (..., 3)); a, c and the batch axes of n broadcast; returns
    shape (..., 6). ValueError naming the argument when pw85_spheroid fails
    (a or c not finite and > 0, n = 0 or not finite)."""
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


def ellipsoid(radii, axes):
    """Quadratic form of ellipsoids: semi-axes radii (..., 3), unit axes in
    the rows of axes (..., 3, 3); returns shape (..., 6). pw85.Error naming
    the argument on failure (a radius not finite and > 0: radii; axes not
    orthonormal to 1e-10 or not finite: axes)."""
    def reason(s, rk, ok):
        if s == Status.ERR_NOT_ORTHONORMAL:
            return "axes are not orthonormal to 1e-10"
        return _range_reason(s, rk)
    return _build_q("ellipsoid", lib.pw85_ellipsoid, _arr(radii, "radii", 3),
                    _matrices(axes, "axes"), "axes", (3, 3), reason)


def ellipsoid_rotation(radii, rot):
    """Quadratic form of ellipsoids: semi-axes radii (..., 3), rotation
    matrices rot (..., 3, 3) whose COLUMNS are the body axes (R mapping body
    to lab frame; pw85.ellipsoid takes the rows); Q = R diag(radii^2) R^T,
    shape (..., 6). pw85.Error naming the argument on failure (rot not
    orthonormal to 1e-10; a reflection is accepted)."""
    def reason(s, rk, ok):
        if s == Status.ERR_NOT_ORTHONORMAL:
            return "rot is not orthonormal to 1e-10"
        return _range_reason(s, rk)
    return _build_q("ellipsoid_rotation", lib.pw85_ellipsoid_rotation,
                    _arr(radii, "radii", 3), _matrices(rot, "rot"), "rot", (3, 3), reason)


def ellipsoid_quat(radii, quat):
    """Quadratic form of ellipsoids: semi-axes radii (..., 3) rotated by the
    quaternions quat (..., 4) = (w, x, y, z) (HOOMD-blue, GSD, LAMMPS order;
    body to lab frame). |quat|^2 within 1e-5 of 1 is accepted and normalised
    (float32 quaternions as read from a GSD file); returns shape (..., 6).
    LAMMPS shape (diameters): radii = shape / 2. OVITO's (x, y, z, w):
    quat[..., [3, 0, 1, 2]]. pw85.Error naming the argument on failure."""
    def reason(s, rk, ok):
        if s == Status.ERR_NOT_ORTHONORMAL:
            return f"quat = {ok.tolist()}: |quat|^2 = {float(ok @ ok)!r} not within 1e-5 of 1"
        if s == Status.ERR_NOT_SPD:
            return f"radii = {rk.tolist()}: Q not positive definite once rounded"
        return _range_reason(s, rk)
    return _build_q("ellipsoid_quat", lib.pw85_ellipsoid_quat, _arr(radii, "radii", 3),
                    _arr(quat, "quat", 4), "quat", (4,), reason)


def ellipsoid_axes(q):
    """Semi-axes and orientations of ellipsoids of quadratic forms q (..., 6):
    returns (radii (..., 3) ascending, rot (..., 3, 3) proper rotations whose
    column k is the axis of radii[..., k], quat (..., 4) = (w, x, y, z) with
    w >= 0), so that pw85.ellipsoid_quat(radii, quat) and
    pw85.ellipsoid_rotation(radii, rot) give q back. pw85.Error naming the
    first failing q (not finite, not positive definite)."""
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

def contact_function(r12, q1, q2, method="default", nthreads=0, check=True):
    """mu^2 and lambda of pairs (r12 (..., 3), q1 (..., 6), q2 (..., 6),
    batch axes broadcast) by pw85_contact_function_pairs with `method`
    (a pw85.Method, its value or its name). Returns (mu2, lambda_): NumPy
    scalars for one pair, arrays of the batch shape otherwise. check=True:
    pw85.Error on the first pair whose status is not PW85_OK; check=False:
    returns (mu2, lambda_, status), failing pairs NaN."""
    # the one-pair path is inlined (a function call costs ~0.1 us here)
    meth = _METHODS.get(method) if type(method) is str else None
    if meth is None:
        meth = _method(method)
    nt = nthreads
    if type(nt) is not int or not 0 <= nt <= _INT_MAX:
        nt = _nthreads(nt)
    if (type(r12) is _ND and type(q1) is _ND and type(q2) is _ND
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


def overlap(r12, q1, q2, nthreads=0, check=True):
    """Exact overlap verdicts (mu^2 < 1) of pairs, by pw85_overlap_pairs;
    shapes as contact_function. Returns a bool (one pair) or bool array.
    check=False: returns (overlap, status), failing pairs False."""
    nt = nthreads
    if type(nt) is not int or not 0 <= nt <= _INT_MAX:
        nt = _nthreads(nt)
    if (type(r12) is _ND and type(q1) is _ND and type(q2) is _ND
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
    ov = np.empty(batch, np.intc)
    st = np.zeros(batch, np.intc)
    ret = 0
    if m:
        ret = lib.pw85_overlap_pairs(m, r.ctypes.data, a.ctypes.data, b.ctypes.data,
                                     ov.ctypes.data, st.ctypes.data, nt)
    if ret and check:
        _raise("overlap", ret, st, _rows(r12=r, q1=a, q2=b), batch)
    res = ov > 0
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


def contact(r12, q1, q2, nthreads=0, check=True):
    """Contact geometry of pairs by pw85_contact_pairs: a structured array of
    the batch shape (a record for one pair) with the fields of pw85_contact_t
    (mu2, lambda, x0 (3), n (3), dca, depth, depth_n). check=False: returns
    (contact, status), failing pairs NaN."""
    return _pair_records("contact", lib.pw85_contact_pairs, CONTACT_DTYPE, r12, q1, q2,
                         nthreads, check)


def contact_derivatives(r12, q1, q2, nthreads=0, check=True):
    """Derivatives of mu^2 for forces, torques and the Hessian
    (docs/derivatives.md) by pw85_contact_derivatives_pairs: a structured
    array of the batch shape (a record for one pair) with the fields of
    pw85_derivatives_t (mu2, lambda, d_r12 (3), d_theta1 (3), d_theta2 (3),
    d_q1 (6), d_q2 (6), hess_r12 (6)). r12 = 0 is an error (no derivative
    there). check=False: returns (derivatives, status), failing pairs NaN."""
    return _pair_records("contact_derivatives", lib.pw85_contact_derivatives_pairs,
                         DERIVATIVES_DTYPE, r12, q1, q2, nthreads, check)


def contact_time(r12, v12, q1, w1, q2, w2, t_max, nthreads=0, check=True):
    """First contact time in [0, t_max] of pairs moving as r12 + t v12 with
    q1, q2 spinning at angular velocities w1, w2 (docs/contact_time.md), by
    pw85_contact_time_pairs; r12, v12, w1, w2 (..., 3), q1, q2 (..., 6),
    batch axes broadcast; t_max one positive number. Returns t (inf: no
    contact; 0: overlapping or touching now): a NumPy scalar for one pair,
    an array of the batch shape otherwise. check=False: returns (t, status);
    failing pairs NaN, except PW85_ERR_NO_CONVERGENCE, which keeps the time
    up to which the pair is certified free of contact."""
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
                    return f"contact-free up to t = {t.reshape(-1)[k]!r} only"
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
    p = np.ascontiguousarray(p, dtype=np.int64)
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


def scene_overlap(centres, q, pairs, box=None, nthreads=0, check=True):
    """Overlap verdicts of the index pairs (m, 2) of a scene of n ellipsoids
    (centres (n, 3), q (n, 6) or one (6,) for all), box {Lx, Ly, Lz, xy, xz,
    yz} or None, by pw85_scene_overlap. Returns a bool array (m,);
    check=False: (overlap, status)."""
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


def scene_contact_function(centres, q, pairs, box=None, method="default", nthreads=0,
                           check=True):
    """mu^2 and lambda of the index pairs of a scene (as scene_overlap), by
    pw85_scene_contact_function. Returns (mu2, lambda_) arrays (m,);
    check=False: (mu2, lambda_, status), failing pairs NaN."""
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


def scene_contact(centres, q, pairs, box=None, nthreads=0, check=True):
    """Contact geometry of the index pairs of a scene (as scene_overlap), by
    pw85_scene_contact: a structured array (m,) as contact();
    check=False: (contact, status), failing pairs NaN."""
    return _scene_records("scene_contact", lib.pw85_scene_contact, CONTACT_DTYPE, centres, q,
                          pairs, box, nthreads, check)


def scene_contact_derivatives(centres, q, pairs, box=None, nthreads=0, check=True):
    """Derivatives of mu^2 for the index pairs (i, j) of a scene (as
    scene_overlap), by pw85_scene_contact_derivatives: a structured array
    (m,) as contact_derivatives(), with respect to r12 = c_j - c_i (or its
    periodic image), q_i (d_q1, d_theta1) and q_j (d_q2, d_theta2).
    check=False: (derivatives, status), failing pairs NaN."""
    return _scene_records("scene_contact_derivatives", lib.pw85_scene_contact_derivatives,
                          DERIVATIVES_DTYPE, centres, q, pairs, box, nthreads, check)


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


def dca(u, q1, q2, method="default", check=True):
    """Distance of closest approach along u (..., 3) by pw85_dca with
    `method`. Returns d; check=False: (d, status)."""
    meth = _method(method)
    f = lib.pw85_dca
    batch, (d,), st = _loop(f, "dca", u, q1, q2, "u", (3, 6), [(1, F64)],
                            lambda pu, pa, pb, pd: f(pu, pa, pb, meth, pd), check)
    return _out(d, batch) if check else (_out(d, batch), _out(st, batch))


def dca_ex(u, q1, q2, theta_tol=0.0, check=True):
    """pw85_dca_ex: plane rotation with angle tolerance theta_tol (0: 1e-8).
    Returns (d, evaluations); check=False: (d, evaluations, status)."""
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


def dca_2d(u, q1, q2, check=True):
    """Distance of closest approach of ellipses along u (..., 2), q1, q2
    (..., 3) = {Q00, Q01, Q11}, by pw85_dca_2d. Returns d;
    check=False: (d, status)."""
    f = lib.pw85_dca_2d
    batch, (d,), st = _loop(f, "dca_2d", u, q1, q2, "u", (2, 3), [(1, F64)], f, check)
    return _out(d, batch) if check else (_out(d, batch), _out(st, batch))


def contact_function_2d(r12, q1, q2, check=True):
    """mu^2 and lambda of ellipses (r12 (..., 2), q1, q2 (..., 3)) by
    pw85_contact_function_2d. Returns (mu2, lambda_);
    check=False: (mu2, lambda_, status)."""
    f = lib.pw85_contact_function_2d
    batch, (out,), st = _loop(f, "contact_function_2d", r12, q1, q2, "r12", (2, 3),
                              [(2, F64)], f, check)
    mu2, lam = out[..., 0].copy(), out[..., 1].copy()
    if check:
        return _out(mu2, batch), _out(lam, batch)
    return _out(mu2, batch), _out(lam, batch), _out(st, batch)
