"""Python wrapper to the legacy API of PW85 (libpw85_legacy).

Implementations of f and of the contact function that pw85 discarded for
accuracy reasons, kept for reference (docs/legacy.md). Arguments as in
pypw85: double[3] vectors, double[6] symmetric matrices; NaN on bad input.
"""
import numpy as np

from pw85 import _lib
from pypw85 import _in, _outarr, _copy_back, _real

__all__ = ["_detQ_as_poly", "_det_sym", "_rT_adjQ_r_as_poly", "_xT_adjA_x",
           "f1", "f2", "contact_function1", "contact_function2"]


def _det_sym(a):
    """Return the determinant of A, given by the double[6] array a."""
    a = _in(a, "a", 6)
    return _lib.legacy().pw85_legacy__det_sym(a.ctypes.data)


def _xT_adjA_x(x, a):
    """Return xᵀ⋅adj(A)⋅x, x a double[3] array, A the double[6] array a."""
    x = _in(x, "x", 3)
    a = _in(a, "a", 6)
    return _lib.legacy().pw85_legacy__xT_adjA_x(x.ctypes.data, a.ctypes.data)


def _rT_adjQ_r_as_poly(r, q1, q2, q3=None, a=None):
    """Coefficients of λ ↦ rᵀ⋅adj[(1-λ)Q₁+λQ₂]⋅r = a₀ + a₁λ + a₂λ².

    q3, when not None, holds 2Q₁-Q₂. If a is not None, it must be a
    pre-allocated double[3] array, updated in place with a[i] = aᵢ; a new
    array otherwise. Returns a.
    """
    r = _in(r, "r", 3)
    q1 = _in(q1, "q1", 6)
    q2 = _in(q2, "q2", 6)
    q3 = 2 * q1 - q2 if q3 is None else _in(q3, "q3", 6)
    ret, buf = _outarr(a, "a", 3)
    _lib.legacy().pw85_legacy__rT_adjQ_r_as_poly(r.ctypes.data, q1.ctypes.data, q2.ctypes.data,
                                                 q3.ctypes.data, buf.ctypes.data)
    _copy_back(ret, buf)
    return ret


def _detQ_as_poly(q1, q2, q3=None, q4=None, b=None):
    """Coefficients of λ ↦ det[(1-λ)Q₁+λQ₂] = b₀ + b₁λ + b₂λ² + b₃λ³.

    q3, q4, when not None, hold 2Q₁-Q₂ and (Q₁+Q₂)/2. If b is not None, it
    must be a pre-allocated double[4] array, updated in place with
    b[i] = bᵢ; a new array otherwise. Returns b.
    """
    q1 = _in(q1, "q1", 6)
    q2 = _in(q2, "q2", 6)
    q3 = 2 * q1 - q2 if q3 is None else _in(q3, "q3", 6)
    q4 = 0.5 * (q1 + q2) if q4 is None else _in(q4, "q4", 6)
    ret, buf = _outarr(b, "b", 4)
    _lib.legacy().pw85_legacy__detQ_as_poly(q1.ctypes.data, q2.ctypes.data, q3.ctypes.data,
                                            q4.ctypes.data, buf.ctypes.data)
    _copy_back(ret, buf)
    return ret


def _f(cname, lambda_, r12, q1, q2, out, sizes):
    lam = _real(lambda_, "lambda_")
    r12 = _in(r12, "r12", 3)
    q1 = _in(q1, "q1", 6)
    q2 = _in(q2, "q2", 6)
    fn = getattr(_lib.legacy(), cname)
    if out is None:
        return fn(lam, r12.ctypes.data, q1.ctypes.data, q2.ctypes.data, None)
    ret, buf = _outarr(out, "out", 3, sizes)
    if buf.size < 3:  # the C function writes three doubles
        buf = np.empty(3)
    val = fn(lam, r12.ctypes.data, q1.ctypes.data, q2.ctypes.data, buf.ctypes.data)
    _copy_back(ret, buf)
    return val


def f1(lambda_, r12, q1, q2, out=None):
    """Return f(λ) (see pypw85.f) through Cholesky decompositions. If out is
    not None, it must be a pre-allocated double[3] array, updated with
    out[0] = f(λ), out[1] = f'(λ), out[2] = f″(λ)."""
    return _f("pw85_legacy_f1", lambda_, r12, q1, q2, out, (3,))


def f2(lambda_, r12, q1, q2, out=None):
    """Return f(λ) as a rational fraction. If out is not None, it must be a
    pre-allocated double[1] array (pw85 1.0), updated with f(λ), or a
    double[3] array, updated with f(λ), f'(λ), f″(λ)."""
    return _f("pw85_legacy_f2", lambda_, r12, q1, q2, out, (1, 3))


def _cf(cname, r12, q1, q2, out):
    r12 = _in(r12, "r12", 3)
    q1 = _in(q1, "q1", 6)
    q2 = _in(q2, "q2", 6)
    ret, buf = _outarr(out, "out", 2)
    getattr(_lib.legacy(), cname)(r12.ctypes.data, q1.ctypes.data, q2.ctypes.data,
                                  buf.ctypes.data)
    _copy_back(ret, buf)
    return ret


def contact_function1(r12, q1, q2, out=None):
    """(μ², λ) by safeguarded Newton iterations on f' (f by f1); out as
    pypw85.contact_function."""
    return _cf("pw85_legacy_contact_function1", r12, q1, q2, out)


def contact_function2(r12, q1, q2, out=None):
    """(μ², λ) by bisection on the numerator of f' (rational fractions);
    out as pypw85.contact_function."""
    return _cf("pw85_legacy_contact_function2", r12, q1, q2, out)
