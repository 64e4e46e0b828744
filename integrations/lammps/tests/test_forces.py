"""Forces, torques, energy and virial of pair_style pw85/soft on a fixed
configuration against a brute-force sum over all pairs (minimum image) of
pw85.scene_contact_derivatives (the library's pw85_contact_derivatives),
with newton_pair on and off, on one and two MPI ranks: relative agreement
1e-12 (forces and torques relative to the sum of the magnitudes of the pair
terms of that atom; energy, per-atom energy (compute pe/atom) and virial
relative to the sum of the magnitudes of the pair terms). Per-type epsilon 1, 2 and 0.5 for the mixed pairs."""
import sys
import tempfile

import numpy as np

import lammps_run as lr
import pw85

N, PHI, SEED, TOL = 500, 0.35, 3, 1e-12
EPS = {(1, 1): 1.0, (2, 2): 2.0, (1, 2): 0.5, (2, 1): 0.5}


def reference(dump, bounds):
    n = len(dump["id"])
    L = bounds[:, 1] - bounds[:, 0]
    centres = np.stack([dump["x"], dump["y"], dump["z"]], axis=1)
    quat = np.stack([dump[k] for k in ("quatw", "quati", "quatj", "quatk")], axis=1)
    radii = np.stack([dump["shapex"], dump["shapey"], dump["shapez"]], axis=1) / 2
    q = pw85.ellipsoid_quat(radii, quat)
    i, j = np.triu_indices(n, 1)
    d = centres[j] - centres[i]
    d -= L * np.round(d / L)
    # pairs that can interact: centre distance below the sum of the largest semi-axes
    near = np.einsum("ij,ij->i", d, d) < (radii[i].max(axis=1) + radii[j].max(axis=1)) ** 2
    pairs = np.stack([i[near], j[near]], axis=1)
    der = pw85.scene_contact_derivatives(centres, q, pairs, box=[*L, 0, 0, 0])
    r12 = d[near]
    inside = der["mu2"] < 1
    pairs, der, r12 = pairs[inside], der[inside], r12[inside]
    types = dump["type"].astype(int)
    eps = np.array([EPS[(types[a], types[b])] for a, b in pairs])
    g = 1 - der["mu2"]
    dudmu2 = -3 * eps * g * g
    fi = dudmu2[:, None] * der["d_r12"]
    ti = -dudmu2[:, None] * der["d_theta1"]
    tj = -dudmu2[:, None] * der["d_theta2"]
    force, torque = np.zeros((n, 3)), np.zeros((n, 3))
    fscale, tscale = np.zeros(n), np.zeros(n)
    np.add.at(force, pairs[:, 0], fi)
    np.add.at(force, pairs[:, 1], -fi)
    np.add.at(torque, pairs[:, 0], ti)
    np.add.at(torque, pairs[:, 1], tj)
    fn = np.linalg.norm(fi, axis=1)
    np.add.at(fscale, pairs[:, 0], fn)
    np.add.at(fscale, pairs[:, 1], fn)
    np.add.at(tscale, pairs[:, 0], np.linalg.norm(ti, axis=1))
    np.add.at(tscale, pairs[:, 1], np.linalg.norm(tj, axis=1))
    u = eps * g ** 3
    u_atom = np.zeros(n)  # each atom of a pair takes half of U
    np.add.at(u_atom, pairs[:, 0], u / 2)
    np.add.at(u_atom, pairs[:, 1], u / 2)
    # virial W_ab = sum over pairs of (c_i - c_j)_a F_i,b; pressure W / V
    comps = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]
    w = np.array([np.sum(-r12[:, a] * fi[:, b]) for a, b in comps]) / np.prod(L)
    wscale = np.array([np.sum(np.abs(r12[:, a] * fi[:, b])) for a, b in comps]) / np.prod(L)
    return dict(force=force, torque=torque, fscale=fscale, tscale=tscale, u=u.sum(), u_atom=u_atom,
                uscale=np.abs(u).sum(), virial=w, wscale=wscale, pairs=len(pairs),
                deep=int(np.sum(der["mu2"] < 0.25)))


def compare(name, dump, thermo, ref):
    f = np.stack([dump["fx"], dump["fy"], dump["fz"]], axis=1)
    t = np.stack([dump["tqx"], dump["tqy"], dump["tqz"]], axis=1)
    ef = np.max(np.linalg.norm(f - ref["force"], axis=1) / np.maximum(ref["fscale"], 1e-300))
    et = np.max(np.linalg.norm(t - ref["torque"], axis=1) / np.maximum(ref["tscale"], 1e-300))
    eu = max(abs(thermo["PotEng"][-1] - ref["u"]) / ref["uscale"],
             np.max(np.abs(dump["c_pe"] - ref["u_atom"])) / ref["uscale"])
    w = np.array([thermo[f"c_virial[{k}]"][-1] for k in range(1, 7)])
    ew = np.max(np.abs(w - ref["virial"]) / ref["wscale"])
    return lr.report(name, max(ef, et, eu, ew) <= TOL,
                     f"relative errors: forces {ef:.2e}, torques {et:.2e}, energy {eu:.2e},"
                     f" virial {ew:.2e} (<= {TOL:g})")


def main():
    lmp, plugin, _ = lr.args()
    ok = True
    with tempfile.TemporaryDirectory() as tmp:
        lr.write_config(f"{tmp}/forces.data", N, PHI, SEED)
        ref = None
        for ranks, newton in ((1, "on"), (1, "off"), (2, "on"), (2, "off")):
            dump = f"{tmp}/forces-{ranks}-{newton}.dump"
            _, out = lr.run_lmp(lmp, plugin, "forces.in",
                                {"data": f"{tmp}/forces.data", "dump": dump, "newton": newton},
                                tmp, ranks=ranks)
            frame, bounds = lr.read_dump(dump)
            if ref is None:
                ref = reference(frame, bounds)
                print(f"{N} ellipsoids, {ref['pairs']} interacting pairs ({ref['deep']} with"
                      f" mu^2 < 0.25), U = {ref['u']:.12g}")
                ok &= lr.report("interacting", ref["pairs"] >= N // 2 and ref["deep"] > 0,
                                "at least N / 2 interacting pairs, some deeply overlapping")
            ok &= compare(f"ranks {ranks}, newton {newton}", frame, lr.thermo(out)[-1], ref)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
