"""pw85: the contact function of two ellipsoids, vectorised over NumPy arrays.

Python API of libpw85 (docs/python.md). A vector is an array (..., 3), a
symmetric matrix its upper triangle row by row (..., 6); the leading (batch)
axes of the arguments of a call broadcast. Every call accepts one pair
(returning NumPy scalars or a record) or arrays of pairs; the per-pair calls
run the C batch calls (pw85_*_pairs, pw85_scene_*) with nthreads OpenMP
threads (0: the OpenMP default), without the GIL.

Errors: TypeError or ValueError naming the argument for a wrong type, shape
or value; pw85.Error (a ValueError) with .status, .status_name and .index
for the first pair the C library reports as failed, unless check=False,
which returns the per-pair statuses too (failing entries NaN, or False for
overlap verdicts).
"""
from ._lib import (Error, Method, Status, status_name, strerror,
                   RESULT_DTYPE, CONTACT_DTYPE, DERIVATIVES_DTYPE, library_path, lib as _clib)
from ._api import (spheroid, ellipsoid, ellipsoid_quat, ellipsoid_rotation, ellipsoid_axes,
                   contact_function, overlap, contact, contact_derivatives, contact_time,
                   scene_overlap, scene_contact_function, scene_contact,
                   scene_contact_derivatives,
                   dca, dca_ex, dca_2d, contact_function_2d)
from ._scene import Scene

__version__ = _clib.pw85_version().decode()

__all__ = ["Error", "Method", "Status", "status_name", "strerror", "spheroid", "ellipsoid",
           "ellipsoid_quat", "ellipsoid_rotation", "ellipsoid_axes",
           "contact_function", "overlap", "contact", "contact_derivatives", "contact_time",
           "scene_overlap", "scene_contact_function", "scene_contact",
           "scene_contact_derivatives", "dca", "dca_ex", "dca_2d", "contact_function_2d",
           "CONTACT_DTYPE", "DERIVATIVES_DTYPE", "RESULT_DTYPE", "Scene", "__version__"]
