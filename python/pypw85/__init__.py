"""Overlap test of two ellipsoids: the Python API of pw85 1.0 on libpw85.

Same names, arguments, optional output arrays and return values as pw85
1.0's pypw85, so that its programs run unchanged; no configuration file
(the library is found as by the package pw85: docs/python.md). A vector is
a double[3] array, a symmetric matrix the double[6] array of its upper
triangle row by row; array-likes are accepted and converted. As in pw85
1.0, a numerical failure gives NaN (or pw85 1.0's best estimate), never an
exception; an argument of the wrong size or type raises ValueError or
TypeError naming it. For arrays of pairs, threads and status codes use the
package pw85.
"""
import numpy as np

from pw85 import _lib
from pw85._lib import lib as _clib

__version__ = _clib.pw85_version().decode()
__all__ = ["spheroid", "f", "contact_function", "_cholesky_decomp", "_cholesky_solve"]

_F64 = np.dtype(np.float64)


def _in(x, name, size):
    """x as a C-contiguous double[size] array (converted when needed)."""
    if not (type(x) is np.ndarray and x.dtype is _F64 and x.flags.c_contiguous
            and x.flags.aligned):
        if x is None or isinstance(x, (str, bytes)):
            raise TypeError(f"{name}: expected a double[{size}] array, got {type(x).__name__}")
        try:
            a = np.asarray(x)
        except (ValueError, TypeError) as e:
            raise ValueError(f"{name}: not a double[{size}] array ({e})") from None
        if a.dtype.kind not in "iufO":
            raise TypeError(f"{name}: expected real numbers, got dtype {a.dtype}")
        try:
            x = np.asarray(a, dtype=_F64, order="C")
        except (ValueError, TypeError) as e:
            raise TypeError(f"{name}: not an array of real numbers ({e})") from None
        if not x.flags.aligned:  # a view at an odd byte offset: the C library reads aligned doubles
            x = x.copy()
    if x.shape != (size,):
        raise ValueError(f"{name}: expected a double[{size}] array (shape ({size},)), got shape {x.shape}")
    return x


def _outarr(x, name, size, sizes=None):
    """(array to return, buffer the C function writes): a new double[size]
    array when x is None; x itself when it is a writeable C-contiguous
    aligned double array of an accepted size; otherwise a temporary whose
    values _copy_back puts into x."""
    if x is None:
        a = np.empty(size)
        return a, a
    if not isinstance(x, np.ndarray):
        raise TypeError(f"{name}: expected a pre-allocated NumPy array, got {type(x).__name__}")
    if x.dtype.kind != "f" or x.size not in (sizes or (size,)) or x.ndim != 1:
        raise ValueError(f"{name}: expected a pre-allocated double[{size}] array, "
                         f"got shape {x.shape} and dtype {x.dtype}")
    if not x.flags.writeable:
        raise ValueError(f"{name}: the array is read-only")
    if x.dtype is _F64 and x.flags.c_contiguous and x.flags.aligned and x.size >= size:
        return x, x
    return x, np.empty(size)


def _copy_back(x, buf):
    if x is not buf:
        x[...] = buf[:x.size]


def _real(x, name):
    if isinstance(x, (str, bytes)) or x is None:
        raise TypeError(f"{name}: expected a real number, got {type(x).__name__}")
    try:
        return float(x)
    except (TypeError, ValueError) as e:
        raise TypeError(f"{name}: expected a real number ({e})") from None


def _cholesky_decomp(a, l=None):
    """Compute the Cholesky decomposition A = L⋅Lᵀ of a 3×3 matrix.

    A is a symmetric matrix, L is a lower matrix, both represented by
    double[6] arrays. Returns l, updated with the coefficients of the
    decomposition (a new array when l is None); NaN when A is not positive
    definite.
    """
    a = _in(a, "a", 6)
    ret, buf = _outarr(l, "l", 6)
    _clib.pw85__cholesky_decomp(a.ctypes.data, buf.ctypes.data)
    _copy_back(ret, buf)
    return ret


def _cholesky_solve(l, b, x=None):
    """Compute the solution of the 3×3 linear system L⋅Lᵀ⋅x = b.

    L is a lower matrix, represented by the double[6] array l; x and b are
    vectors (double[3] arrays). Returns x, updated with the solution (a new
    array when x is None).
    """
    l = _in(l, "l", 6)
    b = _in(b, "b", 3)
    ret, buf = _outarr(x, "x", 3)
    _clib.pw85__cholesky_solve(l.ctypes.data, b.ctypes.data, buf.ctypes.data)
    _copy_back(ret, buf)
    return ret


def spheroid(a, c, n, q=None):
    """Return the quadratic form associated to a spheroid.

    The spheroid is defined by its equatorial radius a, its polar radius c
    and the direction of its axis of revolution, n (double[3] array, a unit
    vector). If q is not None, it must be a pre-allocated double[6] array;
    it is modified in place and returned. NaN when a or c is not > 0 or n
    is zero.
    """
    a = _real(a, "a")
    c = _real(c, "c")
    n = _in(n, "n", 3)
    ret, buf = _outarr(q, "q", 6)
    _clib.pw85_spheroid(a, c, n.ctypes.data, buf.ctypes.data)
    _copy_back(ret, buf)
    return ret


def f(lambda_, r12, q1, q2):
    """Return f(λ) = λ(1-λ) r₁₂ᵀ⋅Q⁻¹⋅r₁₂ with Q = (1-λ)Q₁ + λQ₂.

    r12 = c₂ - c₁ (double[3]) joins the centres, q1 and q2 (double[6]) are
    the quadratic forms; λ is lambda_. NaN on bad input.
    """
    lam = _real(lambda_, "lambda_")
    params = np.empty(15)
    params[0:3] = _in(r12, "r12", 3)
    params[3:9] = _in(q1, "q1", 6)
    params[9:15] = _in(q2, "q2", 6)
    return -_clib.pw85_f_neg(lam, params.ctypes.data)


def contact_function(r12, q1, q2, out=None):
    """Return the value of the contact function of two ellipsoids.

    See f() for r12, q1 and q2. Returns the double[2] array (μ², λ), μ² the
    maximum over [0, 1] of f and λ its maximiser (pw85 1.0's algorithm,
    pw85_contact_function). If out is not None, it must be a pre-allocated
    double[2] array; it is updated and returned. NaN on bad input.
    """
    r12 = _in(r12, "r12", 3)
    q1 = _in(q1, "q1", 6)
    q2 = _in(q2, "q2", 6)
    ret, buf = _outarr(out, "out", 2)
    _clib.pw85_contact_function(r12.ctypes.data, q1.ctypes.data, q2.ctypes.data,
                                buf.ctypes.data)
    _copy_back(ret, buf)
    return ret
