"""Cost of pair_style pw85/soft per neighbour pair against pair_style
gayberne (docs/performance.md, "LAMMPS"): one lmp run alternating the two
styles (tests/bench.in) on the same configuration, cutoff and neighbour
list; the Pair time of LAMMPS's timing breakdown of each run divided by the
steps and the neighbour pairs; medians over the repetitions and the ratio of
the medians. Writes CSV to stdout (one row per run, then the summary as
comment lines).

    python3 integrations/lammps/bench_pair.py LMP PLUGIN [--n N] [--phi PHI]
        [--steps S] [--reps R]"""
import argparse
import os
import re
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "tests"))
import lammps_run as lr  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("lmp")
    ap.add_argument("plugin")
    ap.add_argument("--n", type=int, default=4000)
    ap.add_argument("--phi", type=float, default=0.3)
    ap.add_argument("--steps", type=int, default=50)
    ap.add_argument("--reps", type=int, default=7)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        lr.write_config(f"{tmp}/bench.data", a.n, a.phi, seed=5)
        # cutoff: the sum of the largest semi-axes (pw85/soft's, for both types)
        cut = 2 * max(max(s) for s in lr.SEMI_AXES.values())
        _, out = lr.run_lmp(a.lmp, a.plugin, "bench.in",
                            {"data": f"{tmp}/bench.data", "cut": cut, "steps": a.steps,
                             "reps": a.reps}, tmp)
    pair = [float(m.group(1)) for m in re.finditer(r"^Pair\s*\|\s*([0-9.eE+-]+)", out, re.M)]
    neigh = [float(m.group(1)) for m in re.finditer(r"^Total # of neighbors = ([0-9.eE+]+)", out, re.M)]
    if len(pair) != 2 * a.reps or len(neigh) != 2 * a.reps:
        sys.exit(f"expected {2 * a.reps} runs, found {len(pair)} Pair times, {len(neigh)} counts")
    print("rep,style,pair_seconds,steps,neighbour_pairs,ns_per_pair")
    per = {"pw85/soft": [], "gayberne": []}
    for k, (t, m) in enumerate(zip(pair, neigh)):
        style = "pw85/soft" if k % 2 == 0 else "gayberne"
        ns = t / (a.steps * m) * 1e9
        per[style].append(ns)
        print(f"{k // 2},{style},{t:.6g},{a.steps},{m:.0f},{ns:.2f}")
    mp, mg = statistics.median(per["pw85/soft"]), statistics.median(per["gayberne"])
    print(f"# {a.n} ellipsoids, packing fraction {a.phi}, cutoff {cut}, "
          f"{neigh[0]:.0f} neighbour pairs (skin 0.3)")
    for s, v in per.items():
        print(f"# {s}: median {statistics.median(v):.1f} ns per neighbour pair "
              f"(range {min(v):.1f}-{max(v):.1f}, {len(v)} runs)")
    print(f"# ratio pw85/soft / gayberne: {mp / mg:.2f}")


if __name__ == "__main__":
    main()
