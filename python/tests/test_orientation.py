"""pw85.ellipsoid_quat, pw85.ellipsoid_rotation, pw85.ellipsoid_axes: the
conventions of the simulation codes checked against an independent
construction (Hamilton products q p q*), float32 quaternions as read from a
GSD file, eigenvalues against mpmath at 50 digits, errors."""
import numpy as np
import pytest

import pw85

U = 2.0 ** -53


def hamilton(a, b):
    """Hamilton product of quaternions (..., 4) = (w, x, y, z)."""
    aw, ax, ay, az = np.moveaxis(a, -1, 0)
    bw, bx, by, bz = np.moveaxis(b, -1, 0)
    return np.stack([aw * bw - ax * bx - ay * by - az * bz,
                     aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw], axis=-1)


def rotate(q, p):
    """q p q* / |q|^2 for vectors p (..., 3): body frame to lab frame."""
    pq = np.concatenate([np.zeros(p.shape[:-1] + (1,)), p], axis=-1)
    conj = q * np.array([1, -1, -1, -1])
    return hamilton(hamilton(q, pq), conj)[..., 1:] / np.sum(q * q, axis=-1)[..., None]


def full(q):
    m = np.empty(q.shape[:-1] + (3, 3))
    for (i, j), k in zip([(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)], range(6)):
        m[..., i, j] = m[..., j, i] = q[..., k]
    return m


def random_quats(rng, n):
    q = rng.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1)[:, None]


def test_hoomd_and_lammps_conventions():
    # (cos 45°, 0, 0, sin 45°) turns the body x axis into the lab y axis.
    c = np.sqrt(0.5)
    q = pw85.ellipsoid_quat([3., 1., 1.], [c, 0., 0., c])
    assert np.allclose(q, [1, 0, 0, 9, 0, 1], rtol=0, atol=8 * 9 * U)
    # LAMMPS atom_style ellipsoid: shape = diameters, radii = shape / 2.
    shape = np.array([6., 2., 2.])
    assert np.array_equal(pw85.ellipsoid_quat(shape / 2, [c, 0., 0., c]), q)
    # OVITO stores (x, y, z, w): reorder.
    ovito = np.array([0., 0., c, c])
    assert np.array_equal(pw85.ellipsoid_quat([3., 1., 1.], ovito[[3, 0, 1, 2]]), q)


def test_surface_points_and_rotation_columns():
    rng = np.random.default_rng(3)
    n = 400
    quat = random_quats(rng, n)
    radii = rng.uniform(0.5, 2, (n, 3))
    q = pw85.ellipsoid_quat(radii, quat)
    # R by Hamilton products: column k = image of e_k.
    rot = np.stack([rotate(quat, np.broadcast_to(e, (n, 3))) for e in np.eye(3)], axis=-1)
    q_rot = pw85.ellipsoid_rotation(radii, rot)
    assert np.array_equal(q_rot, pw85.ellipsoid(radii, np.swapaxes(rot, -1, -2)))
    u = rng.normal(size=(n, 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    for p in [radii * u] + [radii * e for e in np.eye(3)]:
        x = rotate(quat, p)
        for qq in (q, q_rot):
            v = np.einsum("ni,ni->n", x, np.linalg.solve(full(qq), x[..., None])[..., 0])
            assert np.max(np.abs(v - 1)) <= 1e-13


def test_gsd_float32_quaternions():
    # 512 random unit quaternions stored as float32 (as HOOMD-blue writes
    # them to a GSD file): all accepted, and Q is that of the float32
    # components normalised in float64.
    rng = np.random.default_rng(512)
    q32 = random_quats(rng, 512).astype(np.float32)
    n2 = np.sum(q32.astype(np.float64) ** 2, axis=1)
    assert np.max(np.abs(n2 - 1)) > 1e-10  # not unit in float64
    radii = np.array([1.5, 0.5, 0.5])
    q = pw85.ellipsoid_quat(radii, q32)
    assert q.shape == (512, 6)
    qn = q32.astype(np.float64) / np.sqrt(n2)[:, None]
    rot = np.stack([rotate(qn, np.broadcast_to(e, (512, 3))) for e in np.eye(3)], axis=-1)
    ref = pw85.ellipsoid_rotation(radii, rot)
    assert np.max(np.abs(q - ref)) <= 32 * U * 2.25


def test_broadcasting():
    rng = np.random.default_rng(4)
    quat = random_quats(rng, 10).reshape(2, 5, 4)
    assert pw85.ellipsoid_quat([1., 2., 3.], quat).shape == (2, 5, 6)
    assert pw85.ellipsoid_quat(np.ones((5, 3)), quat).shape == (2, 5, 6)
    q = pw85.ellipsoid_quat([1., 2., 3.], quat[0, 0])
    assert q.shape == (6,)
    radii, rot, qt = pw85.ellipsoid_axes(pw85.ellipsoid_quat([1., 2., 3.], quat))
    assert radii.shape == (2, 5, 3) and rot.shape == (2, 5, 3, 3) and qt.shape == (2, 5, 4)
    assert pw85.ellipsoid_rotation([1., 2., 3.], np.eye(3)).tolist() == [1, 0, 0, 4, 0, 9]


def test_axes_round_trip():
    rng = np.random.default_rng(5)
    n = 1000
    quat = random_quats(rng, n)
    r0 = rng.uniform(0.1, 10, (n, 3))
    q = pw85.ellipsoid_quat(r0, quat)
    radii, rot, qt = pw85.ellipsoid_axes(q)
    assert np.allclose(radii, np.sort(r0, axis=1), rtol=1e-12, atol=0)
    assert np.all(qt[:, 0] >= 0)
    assert np.allclose(np.linalg.det(rot), 1, rtol=0, atol=16 * U)
    m = np.max(np.abs(q), axis=1)[:, None]
    for back in (pw85.ellipsoid_quat(radii, qt), pw85.ellipsoid_rotation(radii, rot)):
        assert np.all(np.abs(back - q) <= 16 * U * m)


def test_axes_against_mpmath():
    mp = pytest.importorskip("mpmath")
    mp.mp.dps = 50
    rng = np.random.default_rng(6)
    for _ in range(40):
        axes = np.linalg.qr(rng.normal(size=(3, 3)))[0]
        q = pw85.ellipsoid(np.exp(rng.uniform(-3, 3, 3)), axes)
        radii, rot, _ = pw85.ellipsoid_axes(q)
        ev, _ = mp.eigsy(mp.matrix(full(q).tolist()))
        ev = sorted(float(e) for e in ev)
        norm = max(ev)
        assert max(abs(r * r - e) for r, e in zip(radii, ev)) <= 10 * U * norm


def test_sphere_and_spheroid():
    radii, rot, qt = pw85.ellipsoid_axes([2.25, 0, 0, 2.25, 0, 2.25])
    assert radii.tolist() == [1.5, 1.5, 1.5]
    assert rot.tolist() == np.eye(3).tolist() and qt.tolist() == [1, 0, 0, 0]
    n = np.array([1., 2., 2.]) / 3
    radii, rot, _ = pw85.ellipsoid_axes(pw85.spheroid(2., 0.5, n))
    assert np.allclose(radii, [0.5, 2, 2], rtol=1e-15, atol=0)
    assert abs(abs(rot[:, 0] @ n) - 1) <= 1e-14


def test_errors():
    with pytest.raises(pw85.Error, match="not within 1e-5 of 1") as info:
        pw85.ellipsoid_quat([1., 2., 3.], [[1., 0., 0., 0.], [0., 0., 0., 0.]])
    assert info.value.status == pw85.Status.ERR_NOT_ORTHONORMAL and info.value.index == 1
    with pytest.raises(pw85.Error, match="not within 1e-5 of 1"):
        pw85.ellipsoid_quat([1., 2., 3.], [1.0001, 0., 0., 0.])
    assert pw85.ellipsoid_quat([1., 2., 3.], [1.000004, 0., 0., 0.]).shape == (6,)
    with pytest.raises(pw85.Error, match="quat holds a non-finite"):
        pw85.ellipsoid_quat([1., 2., 3.], [np.nan, 0., 0., 1.])
    with pytest.raises(pw85.Error, match="radius is <= 0"):
        pw85.ellipsoid_quat([1., -2., 3.], [1., 0., 0., 0.])
    with pytest.raises(ValueError, match="quat"):
        pw85.ellipsoid_quat([1., 2., 3.], [1., 0., 0.])
    with pytest.raises(pw85.Error, match="rot is not orthonormal"):
        pw85.ellipsoid_rotation([1., 2., 3.], 2 * np.eye(3))
    with pytest.raises(ValueError, match="rot"):
        pw85.ellipsoid_rotation([1., 2., 3.], np.eye(3)[:2])
    with pytest.raises(pw85.Error, match="q not positive definite") as info:
        pw85.ellipsoid_axes([[1, 0, 0, 1, 0, 1], [1, 2, 0, 1, 0, 1]])
    assert info.value.status == pw85.Status.ERR_NOT_SPD and info.value.index == 1
    with pytest.raises(pw85.Error, match="non-finite"):
        pw85.ellipsoid_axes([1, 0, 0, np.inf, 0, 1])


def test_scalar_last_order():
    # scalar_first=False takes (x, y, z, w) (SciPy's as_quat(), OVITO):
    # the same bits as the reordered quaternion, and the surface points of
    # the body frame, rotated by Hamilton products, lie on the surface.
    rng = np.random.default_rng(7)
    n = 200
    quat = random_quats(rng, n)
    radii = rng.uniform(0.5, 2, (n, 3))
    last = np.ascontiguousarray(quat[:, [1, 2, 3, 0]])
    q = pw85.ellipsoid_quat(radii, last, scalar_first=False)
    assert np.array_equal(q, pw85.ellipsoid_quat(radii, quat))
    for e in np.eye(3):
        x = rotate(quat, radii * e)
        v = np.einsum("ni,ni->n", x, np.linalg.solve(full(q), x[..., None])[..., 0])
        assert np.max(np.abs(v - 1)) <= 1e-13
    # The scalar-last array read as scalar-first is another rotation.
    assert np.max(np.abs(pw85.ellipsoid_quat(radii, last) - q)) > 0.1
    with pytest.raises(TypeError, match="scalar_first"):
        pw85.ellipsoid_quat(radii, quat, scalar_first=1)
    with pytest.raises(TypeError, match="scalar_first"):
        pw85.ellipsoid_quat(radii, quat, scalar_first="xyzw")


class Rotations:
    """Stands for scipy.spatial.transform.Rotation: only as_matrix()."""

    def __init__(self, quat):
        self.quat = quat

    def as_matrix(self):
        return np.stack([rotate(self.quat, np.broadcast_to(e, self.quat.shape[:-1] + (3,)))
                         for e in np.eye(3)], axis=-1)


def test_rotation_object_duck_typed():
    # An object with as_matrix() (columns: the images of the body axes,
    # built here by Hamilton products) is taken as rotation matrices.
    rng = np.random.default_rng(8)
    quat = random_quats(rng, 100)
    radii = rng.uniform(0.5, 2, (100, 3))
    rot = Rotations(quat).as_matrix()
    q = pw85.ellipsoid_quat(radii, Rotations(quat))
    assert np.array_equal(q, pw85.ellipsoid_rotation(radii, rot))
    ref = np.einsum("nij,nj,nkj->nik", rot, radii ** 2, rot)
    assert np.max(np.abs(full(q) - ref)) <= 16 * U * 4
    one = pw85.ellipsoid_quat(radii[0], Rotations(quat[0]))
    assert np.array_equal(one, q[0])
    scaled = Rotations(quat[0])
    scaled.as_matrix = lambda: 2 * np.eye(3)
    with pytest.raises(pw85.Error, match="not orthonormal"):
        pw85.ellipsoid_quat(radii[0], scaled)


def test_scipy_rotation():
    transform = pytest.importorskip(
        "scipy.spatial.transform",
        reason="SciPy not installed (Debian: python3-scipy): the duck-typed test covers as_matrix()")
    r = transform.Rotation.random(300, random_state=9)
    rng = np.random.default_rng(9)
    radii = rng.uniform(0.5, 2, (300, 3))
    q = pw85.ellipsoid_quat(radii, r)
    assert np.array_equal(q, pw85.ellipsoid_rotation(radii, r.as_matrix()))
    # as_quat() is scalar-last: scalar_first=False gives the same Q within
    # rounding; the default order would not.
    q_last = pw85.ellipsoid_quat(radii, r.as_quat(), scalar_first=False)
    assert np.max(np.abs(q_last - q)) <= 32 * U * 4
    assert np.max(np.abs(pw85.ellipsoid_quat(radii, r.as_quat()) - q)) > 0.1
    # Body axis k of the particle is column k of the matrix: r.apply(e_k).
    for k, e in enumerate(np.eye(3)):
        x = r.apply(radii[:, k:k + 1] * e)
        v = np.einsum("ni,ni->n", x, np.linalg.solve(full(q), x[..., None])[..., 0])
        assert np.max(np.abs(v - 1)) <= 1e-13
