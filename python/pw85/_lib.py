"""Loading of libpw85 and libpw85_legacy, C declarations, statuses, errors.

Library search order: the environment variable (PW85_LIBRARY,
PW85_LEGACY_LIBRARY), then the paths recorded by `meson install` in
_config.py (the library relative to this package, then its absolute path),
then the soname through the dynamic loader's search path.
"""
from __future__ import annotations

import ctypes
import enum
import os

import numpy as np

try:
    from . import _config
except ImportError:  # source tree: no install-time configuration
    _config = None

_HERE = os.path.dirname(os.path.abspath(__file__))


def _find(env, key, soname):
    path = os.environ.get(env)
    if path:
        return path
    if _config is not None:
        rel = getattr(_config, key + "_RELATIVE", None)
        if rel:
            cand = os.path.normpath(os.path.join(_HERE, rel))
            if os.path.exists(cand):
                return cand
        absolute = getattr(_config, key, None)
        if absolute and os.path.exists(absolute):
            return absolute
    return soname


def _load(env, key, soname):
    path = _find(env, key, soname)
    try:
        return ctypes.CDLL(path), path
    except OSError as e:
        raise ImportError(
            f"cannot load {soname} ({path}): {e}; set {env} to its path") from None


lib, library_path = _load("PW85_LIBRARY", "LIBPW85", "libpw85.so.1")
_legacy = None
legacy_library_path = None


def legacy():
    """libpw85_legacy, loaded on first use (after libpw85, whose soname
    then satisfies its dependency)."""
    global _legacy, legacy_library_path
    if _legacy is None:
        _legacy, legacy_library_path = _load(
            "PW85_LEGACY_LIBRARY", "LIBPW85_LEGACY", "libpw85_legacy.so.1")
        _declare_legacy(_legacy)
    return _legacy


P = ctypes.c_void_p
D = ctypes.c_double
I = ctypes.c_int
LL = ctypes.c_longlong
U = ctypes.c_uint


class Result(ctypes.Structure):
    """struct pw85_result."""
    _fields_ = [("mu2", D), ("lambda_", D), ("mu2_error", D),
                ("iterations", I), ("method", I)]


class Contact(ctypes.Structure):
    """struct pw85_contact_t."""
    _fields_ = [("mu2", D), ("lambda_", D), ("x0", D * 3), ("n", D * 3),
                ("dca", D), ("depth", D), ("depth_n", D)]


RESULT_DTYPE = np.dtype([("mu2", "f8"), ("lambda", "f8"), ("mu2_error", "f8"),
                         ("iterations", "i4"), ("method", "i4")])
CONTACT_DTYPE = np.dtype([("mu2", "f8"), ("lambda", "f8"), ("x0", "f8", (3,)),
                          ("n", "f8", (3,)), ("dca", "f8"), ("depth", "f8"),
                          ("depth_n", "f8")])
# struct pw85_derivatives_t: 29 doubles (docs/derivatives.md).
DERIVATIVES_DTYPE = np.dtype([("mu2", "f8"), ("lambda", "f8"), ("d_r12", "f8", (3,)),
                              ("d_theta1", "f8", (3,)), ("d_theta2", "f8", (3,)),
                              ("d_q1", "f8", (6,)), ("d_q2", "f8", (6,)),
                              ("hess_r12", "f8", (6,))])
assert RESULT_DTYPE.itemsize == ctypes.sizeof(Result)
assert CONTACT_DTYPE.itemsize == ctypes.sizeof(Contact)
assert DERIVATIVES_DTYPE.itemsize == 29 * ctypes.sizeof(D)


def _sig(f, argtypes, restype=I):
    f.argtypes = argtypes
    f.restype = restype
    return f


_sig(lib.pw85_version, [], ctypes.c_char_p)
_sig(lib.pw85_strerror, [I], ctypes.c_char_p)
_sig(lib.pw85__cholesky_decomp, [P, P], None)
_sig(lib.pw85__cholesky_solve, [P, P, P], None)
_sig(lib.pw85_spheroid, [D, D, P, P], None)
_sig(lib.pw85_ellipsoid, [P, P, P])
_sig(lib.pw85_ellipsoid_quat, [P, P, P])
_sig(lib.pw85_ellipsoid_rotation, [P, P, P])
_sig(lib.pw85_ellipsoid_axes, [P, P, P, P])
_sig(lib.pw85_f_neg, [D, P], D)
_sig(lib.pw85__residual, [D, P, P, P, P], None)
_sig(lib.pw85_contact_function, [P, P, P, P])
_sig(lib.pw85_contact_function_method, [P, P, P, I, P])
_sig(lib.pw85_overlap, [P, P, P])
_sig(lib.pw85_contact, [P, P, P, P])
_sig(lib.pw85_contact_derivatives, [P, P, P, P])
_sig(lib.pw85_contact_derivatives_ex, [P, P, P, U, P])
_sig(lib.pw85_dca, [P, P, P, I, P])
_sig(lib.pw85_dca_ex, [P, P, P, D, P, P])
_sig(lib.pw85_dca_2d, [P, P, P, P])
_sig(lib.pw85_contact_function_2d, [P, P, P, P])
_sig(lib.pw85_overlap_pairs, [LL, P, P, P, P, P, I])
_sig(lib.pw85_contact_function_pairs, [LL, P, P, P, I, P, P, I])
_sig(lib.pw85_contact_pairs, [LL, P, P, P, P, P, I])
_sig(lib.pw85_contact_derivatives_pairs, [LL, P, P, P, P, P, I])
_sig(lib.pw85_contact_derivatives_pairs_ex, [LL, P, P, P, U, P, P, I])
_sig(lib.pw85_contact_time_pairs, [LL, P, P, P, P, P, P, D, P, P, I])
_sig(lib.pw85_scene_overlap, [LL, P, P, P, LL, P, P, P, I])
_sig(lib.pw85_scene_contact_function, [LL, P, P, P, LL, P, I, P, P, I])
_sig(lib.pw85_scene_contact, [LL, P, P, P, LL, P, P, P, I])
_sig(lib.pw85_scene_contact_derivatives, [LL, P, P, P, LL, P, P, P, I])
_sig(lib.pw85_scene_contact_derivatives_ex, [LL, P, P, P, LL, P, U, P, P, I])


def _declare_legacy(leg):
    _sig(leg.pw85_legacy__det_sym, [P], D)
    _sig(leg.pw85_legacy__xT_adjA_x, [P, P], D)
    _sig(leg.pw85_legacy__rT_adjQ_r_as_poly, [P, P, P, P, P], None)
    _sig(leg.pw85_legacy__detQ_as_poly, [P, P, P, P, P], None)
    _sig(leg.pw85_legacy_f1, [D, P, P, P, P], D)
    _sig(leg.pw85_legacy_f2, [D, P, P, P, P], D)
    _sig(leg.pw85_legacy_contact_function1, [P, P, P, P])
    _sig(leg.pw85_legacy_contact_function2, [P, P, P, P])


class Method(enum.IntEnum):
    """The PW85_METHOD_* values of pw85.h."""
    DEFAULT = 0
    BRENT = 1
    NEWTON = 2
    RATIONAL = 3
    ZHENG = 4


class Status(enum.IntEnum):
    """The status codes of pw85.h (PW85_OK, PW85_ERR_*)."""
    OK = 0
    ERR_INVALID_ARGUMENT = -1
    ERR_NOT_SPD = -2
    ERR_NO_CONVERGENCE = -3
    ERR_NOT_ORTHONORMAL = -4
    ERR_UNKNOWN_METHOD = -5
    ERR_INACCURATE = -6
    ERR_RANGE = -7
    ERR_CAPACITY = -8
    ERR_NO_MEMORY = -9


def status_name(status: int) -> str:
    """Name of a status code of pw85.h.

    Parameters
    ----------
    status : int
        A status code (``pw85.Status`` or its value).

    Returns
    -------
    str
        ``'PW85_OK'``, ``'PW85_ERR_...'``, or ``'status <n>'`` for a code
        this module does not know.

    Raises
    ------
    TypeError
        status not an integer.

    Examples
    --------
    >>> import pw85
    >>> pw85.status_name(-2), pw85.status_name(pw85.Status.OK), pw85.status_name(-99)
    ('PW85_ERR_NOT_SPD', 'PW85_OK', 'status -99')
    """
    try:
        return "PW85_" + Status(status).name
    except ValueError:
        return f"status {int(status)}"


def strerror(status: int) -> str:
    """Description of a status code (``pw85_strerror`` of the loaded library).

    Parameters
    ----------
    status : int
        A status code (``pw85.Status`` or its value).

    Returns
    -------
    str
        The library's one-line description (a generic one for an unknown
        code).

    Raises
    ------
    TypeError
        status not an integer.

    Examples
    --------
    >>> import pw85
    >>> pw85.strerror(pw85.Status.ERR_NOT_SPD)
    'matrix not symmetric positive definite (or radius not > 0)'
    """
    return lib.pw85_strerror(int(status)).decode()


class Error(ValueError):
    """A pair failed in the C library.

    Attributes: ``.status`` (a ``pw85.Status``, or an int for a code this
    module does not know), ``.status_name``, ``.index`` (flat C-order index
    of the first failing pair, None for a call error); the message names the
    argument.

    Examples
    --------
    >>> import pw85
    >>> try:
    ...     pw85.contact_function([1., 0., 0.], [1., 0., 0., -1., 0., 1.], [1., 0., 0., 1., 0., 1.])
    ... except pw85.Error as e:
    ...     print(e.status_name, e.index)
    ...     print(e)
    PW85_ERR_NOT_SPD 0
    pw85.contact_function: pair 0: PW85_ERR_NOT_SPD (matrix not symmetric positive definite (or radius not > 0)): q1 not positive definite
    """

    def __init__(self, message, status, index=None):
        super().__init__(message)
        try:
            status = Status(status)
        except ValueError:
            status = int(status)
        self.status = status
        self.status_name = status_name(status)
        self.index = index

    def __reduce__(self):
        return (type(self), (self.args[0], int(self.status), self.index))


for _c in (Error, Method, Status):
    _c.__module__ = "pw85"
