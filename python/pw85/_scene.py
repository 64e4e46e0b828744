"""pw85.Scene: N ellipsoids in an optional periodic box, over the C
configuration object (pw85_configuration_*, docs/scene.md)."""
import ctypes

import numpy as np

from ._lib import lib, Error, Status, status_name, strerror, P, D, I, LL, _sig
from ._api import _arr, _box, _nthreads, _not_spd, ellipsoid_quat

_sig(lib.pw85_configuration_create, [LL, P, P, P, ctypes.POINTER(P), ctypes.POINTER(LL)])
_sig(lib.pw85_configuration_destroy, [P], None)
_sig(lib.pw85_configuration_update, [P, LL, P, P, P, ctypes.POINTER(LL)])
_sig(lib.pw85_configuration_size, [P], LL)
_sig(lib.pw85_configuration_pairs, [P, D, I, LL, P, P, P, ctypes.POINTER(LL), P])
_sig(lib.pw85_configuration_test_move, [P, LL, P, P, ctypes.POINTER(LL)])
_sig(lib.pw85_configuration_move, [P, LL, P, P])
_sig(lib.pw85_configuration_neighbours, [P, LL, D, LL, P, ctypes.POINTER(LL)])

_destroy = lib.pw85_configuration_destroy


def _copied_box(box):
    bx = _box(box)
    return None if bx is None else bx.copy()


def _particles(centres, q):
    c = _arr(centres, "centres", 3, ndim=2)
    n = c.shape[0]
    qq = _arr(q, "q", 6)
    if qq.ndim == 1:
        qq = np.broadcast_to(qq, (n, 6))
    elif qq.shape != (n, 6):
        raise ValueError(f"q: expected shape ({n}, 6) or (6,) for the {n} centres, got {qq.shape}")
    return np.array(c, dtype=np.float64, order="C"), np.array(qq, dtype=np.float64, order="C")


def _reason(status, k, c, q, box):
    """Why particle k (centre c, matrix q) was refused."""
    if k is None or k < 0:
        return None
    if status == Status.ERR_INVALID_ARGUMENT:
        if not np.all(np.isfinite(c)):
            return f"centres[{k}] holds a non-finite value {c.tolist()}"
        if not np.all(np.isfinite(q)):
            return f"q[{k}] holds a non-finite value {q.tolist()}"
        if box is not None:
            return (f"the bounding sphere of particle {k} is too large for the box "
                    f"(radii of two spheres summing to more than min(Lx, Ly, Lz)/2)")
    if status == Status.ERR_NOT_SPD and _not_spd(q):
        return f"q[{k}] not positive definite"
    if status == Status.ERR_RANGE:
        return f"centres[{k}] = {c.tolist()} too far out of the box"
    return None


def _raise(func, ret, k=None, c=None, q=None, box=None):
    msg = f"pw85.Scene.{func}: {status_name(ret)} ({strerror(ret)})"
    if k is not None and k >= 0:
        msg += f": particle {k}"
        reason = _reason(ret, k, c, q, box)
        if reason:
            msg += f": {reason}"
    raise Error(msg, ret, k if k is not None and k >= 0 else None)


class Scene:
    """N ellipsoids (centres (N, 3), matrices q (N, 6), or one (6,) for all)
    in an optional periodic box {Lx, Ly, Lz, xy, xz, yz} (HOOMD/GSD
    convention) or None, held by the C configuration object: its pairs
    (overlapping_pairs, pairs), trial moves (test_move) and moves (move).
    Every verdict is pw85.scene_overlap's on that pair (i < j). The arrays
    .centres and .q (read-only copies) follow the moves; .box is the box or
    None. The C calls
    run without the GIL. Errors: pw85.Error naming the particle (.index)."""

    def __init__(self, centres, q, box=None):
        self._handle = None
        c, qq = _particles(centres, q)
        bx = _copied_box(box)
        h = P()
        bad = LL(-1)
        ret = lib.pw85_configuration_create(c.shape[0], c.ctypes.data, qq.ctypes.data,
                                            None if bx is None else bx.ctypes.data,
                                            ctypes.byref(h), ctypes.byref(bad))
        if ret != Status.OK:
            k = bad.value
            _raise("__init__", ret, k, c[k] if k >= 0 else None, qq[k] if k >= 0 else None, bx)
        self._handle = h
        self._set(c, qq, bx)

    @classmethod
    def from_axes(cls, centres, radii, quaternions, box=None):
        """From semi-axes radii (N, 3) or (3,) and unit quaternions (N, 4)
        (w, x, y, z; normalised here, so float32 values do), by
        pw85.ellipsoid_quat."""
        quat = _arr(quaternions, "quaternions", 4, ndim=2)
        norm = np.sqrt(np.sum(quat * quat, axis=1))
        if not np.all(norm > 0):
            k = int(np.flatnonzero(~(norm > 0))[0])
            raise ValueError(f"quaternions[{k}]: zero or not finite {quat[k].tolist()}")
        r = _arr(radii, "radii", 3)
        q = ellipsoid_quat(np.broadcast_to(r, (quat.shape[0], 3)), quat / norm[:, None])
        return cls(centres, q, box)

    @classmethod
    def from_gsd(cls, frame):
        """From a gsd.hoomd frame (Frame or Snapshot): particles.position,
        particles.orientation (w, x, y, z, float32 normalised in double),
        particles.typeid and types, particles.type_shapes (ellipsoids:
        {'type': 'Ellipsoid', 'a', 'b', 'c'}) and configuration.box."""
        p = frame.particles
        n = int(p.N)
        pos = np.asarray(p.position, dtype=np.float64).reshape(n, 3)
        if p.orientation is None:
            orient = np.tile([1.0, 0.0, 0.0, 0.0], (n, 1))
        else:
            orient = np.asarray(p.orientation, dtype=np.float64).reshape(n, 4)
        typeid = np.zeros(n, np.int64) if p.typeid is None else np.asarray(p.typeid, np.int64)
        shapes = p.type_shapes or []
        types = p.types or ["A"]
        radii_of_type = np.empty((len(types), 3))
        for t, name in enumerate(types):
            shape = shapes[t] if t < len(shapes) else None
            if not shape or str(shape.get("type", "")).lower() != "ellipsoid":
                raise ValueError(f"frame: type {t} ({name!r}) has no ellipsoid type_shape "
                                 f"(got {shape!r})")
            radii_of_type[t] = [float(shape["a"]), float(shape["b"]), float(shape["c"])]
        if n and (typeid.min() < 0 or typeid.max() >= len(types)):
            raise ValueError("frame: particles.typeid outside the types")
        box = np.asarray(frame.configuration.box, dtype=np.float64)
        return cls.from_axes(pos, radii_of_type[typeid], orient, box)

    def __len__(self):
        return int(self.centres.shape[0])

    def close(self):
        """Frees the C object (also done when the Scene is collected)."""
        if self._handle is not None:
            _destroy(self._handle)
            self._handle = None

    def __del__(self):
        if getattr(self, "_handle", None) is not None:
            _destroy(self._handle)
            self._handle = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __reduce__(self):
        return (Scene, (self.centres, self.q, self.box))

    def _h(self):
        if self._handle is None:
            raise ValueError("pw85.Scene: closed")
        return self._handle

    def update(self, centres, q, box=None):
        """Replaces every particle and the box (no reallocation in C when N
        does not grow); on error the scene is unchanged."""
        c, qq = _particles(centres, q)
        bx = _copied_box(box)
        bad = LL(-1)
        ret = lib.pw85_configuration_update(self._h(), c.shape[0], c.ctypes.data,
                                            qq.ctypes.data,
                                            None if bx is None else bx.ctypes.data,
                                            ctypes.byref(bad))
        if ret != Status.OK:
            k = bad.value
            _raise("update", ret, k, c[k] if k >= 0 else None, qq[k] if k >= 0 else None, bx)
        self._set(c, qq, bx)

    def _set(self, c, qq, bx):
        for a in (c, qq) + ((bx,) if bx is not None else ()):
            a.setflags(write=False)
        self.centres, self.q, self.box = c, qq, bx

    def _pairs(self, s, want_mu2, nthreads):
        if isinstance(s, bool) or not isinstance(s, (int, float, np.integer, np.floating)):
            raise TypeError(f"s: expected a real number >= 1, got {type(s).__name__}")
        s = float(s)
        if not (s >= 1.0 and np.isfinite(s)):
            raise ValueError(f"s: expected a finite number >= 1, got {s}")
        nt = _nthreads(nthreads)
        h = self._h()

        def call(cap, count):
            i = np.empty(cap, np.int64)
            j = np.empty(cap, np.int64)
            mu2 = np.empty(cap, np.float64) if want_mu2 else None
            ret = lib.pw85_configuration_pairs(h, s, nt, cap, i.ctypes.data, j.ctypes.data,
                                               None if mu2 is None else mu2.ctypes.data,
                                               ctypes.byref(count), None)
            return ret, (i, j, mu2)

        (i, j, mu2), m = self._sized("pairs", 4 * len(self) + 16, call,
                                     f": the box cannot hold the pairs at s = {s} (s times the two "
                                     "largest bounding radii exceeds min(Lx, Ly, Lz)/2)")
        return i[:m].copy(), j[:m].copy(), (mu2[:m].copy() if want_mu2 else None)

    def _sized(self, name, cap, call, box_note):
        """call(cap, count) -> (status, arrays), repeated with the count the
        library asks for while the capacity is short; (arrays, count)."""
        count = LL(0)
        while True:
            ret, out = call(cap, count)
            if ret == Status.ERR_CAPACITY:
                cap = count.value
                continue
            if ret != Status.OK:
                msg = f"pw85.Scene.{name}: {status_name(ret)} ({strerror(ret)})"
                if ret == Status.ERR_INVALID_ARGUMENT and self.box is not None:
                    msg += box_note
                raise Error(msg, ret, None)
            return out, count.value

    def overlapping_pairs(self, nthreads=0):
        """(i, j): every overlapping pair i < j (exact verdicts), sorted by
        i then j, int64 arrays."""
        i, j, _ = self._pairs(1.0, False, nthreads)
        return i, j

    def pairs(self, s=1.2, nthreads=0):
        """(i, j, mu2): every pair i < j whose ellipsoids scaled by s overlap
        (mu^2 < s^2; exact for the matrices s*s*q), sorted; mu2 by DEFAULT.
        The pairs as an (m, 2) array for pw85.scene_contact_function and
        the others: np.stack([i, j], axis=1)."""
        return self._pairs(s, True, nthreads)

    def _index(self, i):
        n = len(self)
        if isinstance(i, bool) or not isinstance(i, (int, np.integer)):
            raise TypeError(f"i: expected an integer index, got {type(i).__name__}")
        i = int(i)
        if not 0 <= i < n:
            raise IndexError(f"i = {i} outside [0, {n})")
        return i

    def _trial(self, func, i, centre, q):
        i = self._index(i)
        c = np.array(_arr(centre, "centre", 3, ndim=1), dtype=np.float64)
        qq = np.array(_arr(q, "q", 6, ndim=1), dtype=np.float64)
        return i, c, qq

    def test_move(self, i, centre, q):
        """The smallest j != i whose ellipsoid particle i would overlap at
        (centre, q), or -1; the scene does not change."""
        i, c, qq = self._trial("test_move", i, centre, q)
        j = LL(-1)
        ret = lib.pw85_configuration_test_move(self._h(), i, c.ctypes.data, qq.ctypes.data,
                                               ctypes.byref(j))
        if ret != Status.OK:
            _raise("test_move", ret, i, c, qq, self.box)
        return int(j.value)

    def neighbours(self, i, distance):
        """Every j != i whose centre lies closer than distance to particle
        i's (the pair's minimum image in a box), ascending, an int64 array;
        no narrow phase. In a box, distance <= min(Lx, Ly, Lz)/2."""
        i = self._index(i)
        if isinstance(distance, bool) or not isinstance(distance, (int, float, np.integer, np.floating)):
            raise TypeError(f"distance: expected a real number, got {type(distance).__name__}")
        distance = float(distance)
        if not (distance >= 0.0 and np.isfinite(distance)):
            raise ValueError(f"distance: expected a finite number >= 0, got {distance}")
        h = self._h()

        def call(cap, count):
            j = np.empty(cap, np.int64)
            return lib.pw85_configuration_neighbours(h, i, distance, cap, j.ctypes.data,
                                                     ctypes.byref(count)), j

        j, m = self._sized("neighbours", 64, call,
                           f": distance {distance} exceeds min(Lx, Ly, Lz)/2 of the box")
        return j[:m].copy()

    def move(self, i, centre, q):
        """Moves particle i to (centre, q) (no overlap test); on error the
        scene is unchanged."""
        i, c, qq = self._trial("move", i, centre, q)
        ret = lib.pw85_configuration_move(self._h(), i, c.ctypes.data, qq.ctypes.data)
        if ret != Status.OK:
            _raise("move", ret, i, c, qq, self.box)
        for a, v in ((self.centres, c), (self.q, qq)):
            a.setflags(write=True)
            a[i] = v
            a.setflags(write=False)


Scene.__module__ = "pw85"
