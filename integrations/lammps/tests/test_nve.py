"""NVE with fix nve/asphere: relative energy drift |E(end) - E(0)| / |E(0)|
<= 1e-5 over 10^4 steps of dt, and the fluctuation of E about its linear
trend (RMS of the residual of a least-squares line through E, sampled every
10 steps, relative to |E(0)|) divided by 4 +- 20 % when dt is halved over
the same time (velocity Verlet: an energy error of order dt^2). The trend is
removed because fix nve/asphere's quaternion update (Richardson iteration)
is not symplectic: its drift shrinks faster than dt^2 and would mix into a
plain RMS of E - E(0) (integrations/lammps/README.md, "Tests"). 512 ellipsoids (spheroids
and general ellipsoids), packing fraction 0.2, kT = 0.5, epsilon = 1
(pw85_md's test, here in LAMMPS)."""
import sys
import tempfile

import numpy as np

import lammps_run as lr

N, PHI, SEED, DT, STEPS = 512, 0.2, 7, 0.002, 10000


def energy_stats(run):
    """Relative drift, fluctuation about the linear trend, slope over the run."""
    e = run["v_etotal"]
    t = np.arange(len(e))
    line = np.polyfit(t, e, 1)
    residual = e - np.polyval(line, t)
    e0 = abs(e[0])
    return abs(e[-1] - e[0]) / e0, np.sqrt(np.mean(residual ** 2)) / e0, line[0] * len(e) / e0


def main():
    lmp, plugin, _ = lr.args()
    with tempfile.TemporaryDirectory() as tmp:
        lr.write_config(f"{tmp}/nve.data", N, PHI, SEED)
        common = {"data": f"{tmp}/nve.data"}
        _, out1 = lr.run_lmp(lmp, plugin, "nve.in", dict(common, dt=DT, steps=STEPS, every=10), tmp)
        _, out2 = lr.run_lmp(lmp, plugin, "nve.in",
                             dict(common, dt=DT / 2, steps=2 * STEPS, every=20), tmp)
    r1, r2 = lr.thermo(out1)[0], lr.thermo(out2)[0]
    drift, fluct, slope = energy_stats(r1)
    drift2, fluct2, slope2 = energy_stats(r2)
    ratio = fluct / fluct2
    pe, e0 = r1["PotEng"], abs(r1["v_etotal"][0])
    print(f"dt {DT}: drift {drift:.3e}, trend {slope:.3e}, fluctuation {fluct:.3e}")
    print(f"dt {DT / 2}: drift {drift2:.3e}, trend {slope2:.3e}, fluctuation {fluct2:.3e}")
    print(f"fluctuation ratio {ratio:.3f}; potential energy {pe.min():.4g} to {pe.max():.4g},"
          f" E = {e0:.6g}")
    ok = lr.report("interacting", pe.max() - pe.min() > 0.01 * e0,
                   "the potential energy varies by more than 1 % of E")
    ok &= lr.report("drift", drift <= 1e-5, f"{drift:.3e} <= 1e-5")
    ok &= lr.report("dt^2", 3.2 <= ratio <= 4.8, f"fluctuation ratio {ratio:.3f} in [3.2, 4.8]")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
