"""The compiled module pw85._ext (python/ext/_ext.cpp), or None.

Search order: the environment variable PW85_EXTENSION (the path of the
module file; the meson tests name the build tree's; "none": no module, the
ctypes calls only), then pw85._ext beside this package (pip install, meson
install when nanobind was found). Imported after _lib has loaded libpw85,
whose soname then satisfies the module's dependency on it: the compiled and
the ctypes calls run the same library.
"""
import importlib
import importlib.util
import os

from . import _lib  # noqa: F401  (libpw85 loaded first)


def _load():
    path = os.environ.get("PW85_EXTENSION")
    if path:
        if path.lower() == "none":
            return None
        spec = importlib.util.spec_from_file_location("pw85._ext", path)
        if spec is None:
            raise ImportError(f"PW85_EXTENSION = {path!r} is not a Python extension module")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module
    try:
        return importlib.import_module("pw85._ext")
    except ModuleNotFoundError:
        return None


ext = _load()
