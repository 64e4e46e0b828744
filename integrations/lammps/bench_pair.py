"""Cost of pair_style pw85/soft per neighbour pair against pair_style
gayberne (docs/performance.md, "LAMMPS"): one lmp run alternating the two
styles (tests/bench.in) on the same configuration (lammps_run.write_config),
cutoff and neighbour list; the Pair time of LAMMPS's timing breakdown of
each run (wall, and CPU = wall x the section's %CPU of `timer full`, which
discounts the time other processes took) divided by the steps and the
neighbour pairs; medians over the repetitions and the ratio of the medians.
--callgrind: one repetition under valgrind --tool=callgrind instead, the
instructions of PairPW85Soft::compute and PairGayBerne::compute (inclusive)
per neighbour pair and step, independent of the load (valgrind emulates no
AVX-512: libpw85 takes its AVX2 path there). Prints CSV (one row per run),
then the summary as comment lines.

    python3 integrations/lammps/bench_pair.py LMP PLUGIN [--n N] [--phi PHI]
        [--steps S] [--reps R] [--callgrind]"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "tests"))
import lammps_run as lr  # noqa: E402

FUNCTIONS = {"pw85/soft": "PairPW85Soft::compute", "gayberne": "PairGayBerne::compute"}


def callgrind(a, tmp, cut):
    lmp = [a.lmp, "-in", os.path.join(lr.HERE, "bench.in"), "-log", "none", "-nocite",
           "-var", "plugin", a.plugin, "-var", "data", f"{tmp}/bench.data", "-var", "cut",
           str(cut), "-var", "steps", str(a.steps), "-var", "reps", "1"]
    p = subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={tmp}/cg.out"] + lmp,
                       cwd=tmp, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       env=dict(os.environ, **lr.MPI_ENV))
    if p.returncode:
        sys.exit(p.stdout[-3000:])
    # the neighbour count of the timed runs (the first is that of run 0's full list)
    neigh = float(re.findall(r"^Total # of neighbors = ([0-9.eE+]+)", p.stdout, re.M)[1])
    ann = subprocess.run(["callgrind_annotate", "--inclusive=yes", f"{tmp}/cg.out"],
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                         check=True).stdout
    print("style,instructions,calls,neighbour_pairs,instructions_per_pair")
    per = {}
    for style, fn in FUNCTIONS.items():
        m = re.search(r"^\s*([\d,]+) .*" + re.escape(fn) + r"\(int, int\)", ann, re.M)
        ir = int(m.group(1).replace(",", ""))
        # the setup of each run calls compute once more than the steps, and
        # pw85/soft once more in run 0
        calls = a.steps + (2 if style == "pw85/soft" else 1)
        per[style] = ir / (calls * neigh)
        print(f"{style},{ir},{calls},{neigh:.0f},{per[style]:.0f}")
    overlapping = lr.thermo(p.stdout)[0]["c_overlap[1]"][0]
    print(f"# {a.n} ellipsoids, packing fraction {a.phi}, cutoff {cut}, {neigh:.0f} neighbour"
          f" pairs (skin 0.3), {overlapping:.0f} of them overlapping")
    print(f"# ratio pw85/soft / gayberne (instructions): {per['pw85/soft'] / per['gayberne']:.2f}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("lmp")
    ap.add_argument("plugin")
    ap.add_argument("--n", type=int, default=4000)
    ap.add_argument("--phi", type=float, default=0.3)
    ap.add_argument("--steps", type=int, default=50)
    ap.add_argument("--reps", type=int, default=7)
    ap.add_argument("--callgrind", action="store_true")
    a = ap.parse_args()
    # cutoff: the sum of the largest semi-axes (pw85/soft's, for both types)
    cut = 2 * max(max(s) for s in lr.SEMI_AXES.values())
    with tempfile.TemporaryDirectory() as tmp:
        lr.write_config(f"{tmp}/bench.data", a.n, a.phi, seed=5)
        if a.callgrind:
            callgrind(a, tmp, cut)
            return
        _, out = lr.run_lmp(a.lmp, a.plugin, "bench.in",
                            {"data": f"{tmp}/bench.data", "cut": cut, "steps": a.steps,
                             "reps": a.reps}, tmp)
    pair = [(float(m.group(1)), float(m.group(2))) for m in
            re.finditer(r"^Pair\s*\|[^|]*\|\s*([0-9.eE+-]+)\s*\|[^|]*\|[^|]*\|\s*([0-9.]+)\s*\|", out, re.M)]
    neigh = [float(m.group(1)) for m in re.finditer(r"^Total # of neighbors = ([0-9.eE+]+)", out, re.M)]
    overlapping = lr.thermo(out)[0]["c_overlap[1]"][0]
    pair, neigh = pair[1:], neigh[1:]  # the untimed run 0
    if len(pair) != 2 * a.reps or len(neigh) != 2 * a.reps:
        sys.exit(f"expected {2 * a.reps} runs, found {len(pair)} Pair times, {len(neigh)} counts")
    print("rep,style,pair_wall_s,pair_cpu_percent,steps,neighbour_pairs,wall_ns_per_pair,cpu_ns_per_pair")
    per = {s: {"wall": [], "cpu": []} for s in FUNCTIONS}
    for k, ((wall, cpu), m) in enumerate(zip(pair, neigh)):
        style = "pw85/soft" if k % 2 == 0 else "gayberne"
        ns = wall / (a.steps * m) * 1e9
        per[style]["wall"].append(ns)
        per[style]["cpu"].append(ns * cpu / 100)
        print(f"{k // 2},{style},{wall:.6g},{cpu:.1f},{a.steps},{m:.0f},{ns:.1f},{ns * cpu / 100:.1f}")
    print(f"# {a.n} ellipsoids, packing fraction {a.phi}, cutoff {cut}, {neigh[0]:.0f} neighbour"
          f" pairs (skin 0.3), {overlapping:.0f} of them overlapping")
    for clock in ("cpu", "wall"):
        for s, v in per.items():
            v = v[clock]
            print(f"# {s}: {clock} median {statistics.median(v):.1f} ns per neighbour pair "
                  f"(range {min(v):.1f}-{max(v):.1f}, {len(v)} runs)")
        ratio = statistics.median(per["pw85/soft"][clock]) / statistics.median(per["gayberne"][clock])
        print(f"# ratio pw85/soft / gayberne ({clock}): {ratio:.2f}")


if __name__ == "__main__":
    main()
