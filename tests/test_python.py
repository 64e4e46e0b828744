#!/usr/bin/env python3
"""libpw85 from Python through ctypes and NumPy.

usage: test_python.py HEADER   (pw85.h; the library path is in $LIBPW85)

Loads the built library with dlopen and checks, printing TAP:
 - pw85_version() equals PW85_VERSION of the header;
 - mu^2 and lambda of the pw85 1.0 tutorial spheroids against the values
   published by pw85 1.0 (3.362706040638343, 0.1668589553405904), to 1e-12
   relative;
 - r12 = 0 gives mu^2 = 0;
 - NaN in r12 gives PW85_ERR_INVALID_ARGUMENT and a NaN-filled output.
 - pw85_contact_function_method through a ctypes Structure
   mirroring pw85_result: the tutorial pair by PW85_METHOD_DEFAULT, and an
   unknown method id.
Exits with 77 (skipped) when NumPy is missing, or when the build system sets
PW85_PYTHON_TEST_SKIP (a sanitizer build whose runtime it cannot preload).
"""
import ctypes
import os
import re
import sys

if os.environ.get("PW85_PYTHON_TEST_SKIP"):
    print("1..0 # SKIP " + os.environ["PW85_PYTHON_TEST_SKIP"])
    sys.exit(77)

try:
    import numpy as np
except ImportError:
    print("1..0 # SKIP NumPy is not installed for " + sys.executable)
    sys.exit(77)

MU2_REF = 3.362706040638343
LAMBDA_REF = 0.1668589553405904
RTOL = 1e-12


class Pw85Result(ctypes.Structure):
    """Mirror of struct pw85_result of pw85.h."""
    _fields_ = [("mu2", ctypes.c_double), ("lambda_", ctypes.c_double),
                ("mu2_error", ctypes.c_double), ("iterations", ctypes.c_int),
                ("method", ctypes.c_int)]


def header_macros(path):
    """The #define NAME VALUE lines of the header, as a dict of strings."""
    macros = {}
    with open(path) as f:
        for line in f:
            m = re.match(r"#define\s+(PW85_\w+)\s+(.+?)\s*$", line)
            if m:
                macros[m.group(1)] = m.group(2)
    return macros


def load(path):
    lib = ctypes.CDLL(path)
    vec = np.ctypeslib.ndpointer(dtype=np.float64, ndim=1, shape=(3,),
                                 flags="C_CONTIGUOUS")
    sym = np.ctypeslib.ndpointer(dtype=np.float64, ndim=1, shape=(6,),
                                 flags="C_CONTIGUOUS")
    out2 = np.ctypeslib.ndpointer(dtype=np.float64, ndim=1, shape=(2,),
                                  flags="C_CONTIGUOUS,WRITEABLE")
    lib.pw85_version.argtypes = []
    lib.pw85_version.restype = ctypes.c_char_p
    lib.pw85_strerror.argtypes = [ctypes.c_int]
    lib.pw85_strerror.restype = ctypes.c_char_p
    lib.pw85_spheroid.argtypes = [ctypes.c_double, ctypes.c_double, vec, sym]
    lib.pw85_spheroid.restype = None
    lib.pw85_contact_function.argtypes = [vec, sym, sym, out2]
    lib.pw85_contact_function.restype = ctypes.c_int
    lib.pw85_contact_function_method.argtypes = [vec, sym, sym, ctypes.c_int,
                                                 ctypes.POINTER(Pw85Result)]
    lib.pw85_contact_function_method.restype = ctypes.c_int
    return lib


class Tap:
    def __init__(self):
        self.count = 0
        self.failed = 0

    def check(self, ok, description):
        self.count += 1
        if not ok:
            self.failed += 1
        print(("ok" if ok else "not ok") + f" {self.count} - {description}")


def main():
    macros = header_macros(sys.argv[1])
    ok_code = int(macros["PW85_OK"])
    invalid = int(macros["PW85_ERR_INVALID_ARGUMENT"].strip("()"))
    lib = load(os.environ["LIBPW85"])
    tap = Tap()
    print("TAP version 13")
    print("1..9")

    version = lib.pw85_version().decode()
    tap.check(version == macros["PW85_VERSION"].strip('"'),
              f"pw85_version() = {version!r} equals PW85_VERSION of pw85.h")

    x1 = np.array([-0.5, 0.4, -0.7])
    x2 = np.array([0.2, -0.3, 0.4])
    q1 = np.empty(6)
    q2 = np.empty(6)
    lib.pw85_spheroid(10.0, 0.1, np.array([0.0, 0.0, 1.0]), q1)
    lib.pw85_spheroid(0.5, 5.0, np.array([1.0, 0.0, 0.0]), q2)
    out = np.empty(2)
    status = lib.pw85_contact_function(x2 - x1, q1, q2, out)
    tap.check(status == ok_code, f"tutorial: status {status}")
    tap.check(abs(out[0] - MU2_REF) <= RTOL * MU2_REF,
              f"tutorial: mu^2 = {out[0]!r} (published {MU2_REF!r})")
    tap.check(abs(out[1] - LAMBDA_REF) <= RTOL * LAMBDA_REF,
              f"tutorial: lambda = {out[1]!r} (published {LAMBDA_REF!r})")

    status = lib.pw85_contact_function(np.zeros(3), q1, q2, out)
    tap.check(status == ok_code and out[0] == 0.0,
              f"r12 = 0: status {status}, mu^2 = {out[0]!r}")

    out[:] = 0.0
    status = lib.pw85_contact_function(np.array([0.7, np.nan, 1.1]), q1, q2, out)
    tap.check(status == invalid and np.isnan(out).all(),
              f"NaN in r12: status {status} "
              f"({lib.pw85_strerror(status).decode()}), out = {out}")

    tap.check(lib.pw85_strerror(invalid) != lib.pw85_strerror(ok_code),
              "pw85_strerror distinguishes PW85_OK and an error")

    # Method-selecting contact function.
    res = Pw85Result()
    default = int(macros["PW85_METHOD_DEFAULT"])
    status = lib.pw85_contact_function_method(x2 - x1, q1, q2, default, ctypes.byref(res))
    tap.check(status == ok_code and res.method == default
              and abs(res.mu2 - MU2_REF) <= RTOL * MU2_REF
              and abs(res.lambda_ - LAMBDA_REF) <= 1e-8
              and 0.0 <= res.mu2_error <= 1e-14 * res.mu2,
              f"pw85_contact_function_method DEFAULT: status {status}, mu^2 = {res.mu2!r}, "
              f"lambda = {res.lambda_!r}, mu2_error = {res.mu2_error!r}")
    unknown = int(macros["PW85_ERR_UNKNOWN_METHOD"].strip("()"))
    status = lib.pw85_contact_function_method(x2 - x1, q1, q2, 99, ctypes.byref(res))
    tap.check(status == unknown and np.isnan(res.mu2),
              f"pw85_contact_function_method, method 99: status {status}, mu^2 = {res.mu2!r}")
    return 1 if tap.failed else 0


if __name__ == "__main__":
    sys.exit(main())
