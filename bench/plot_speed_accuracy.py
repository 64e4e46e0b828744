#!/usr/bin/python3
"""Speed-accuracy chart of the contact-function methods.

    /usr/bin/python3 bench/plot_speed_accuracy.py [docs/bench_contact.csv]

Reads the CSV written by bench/bench_contact.cpp and draws, for each class of
semi-axes (columns) and for the median and the maximum relative error of mu2
(rows), the time per call against the error, one marker per method; the
Pareto front (methods that no other method beats in both time and error) is
drawn as a dashed staircase. Writes docs/speed_accuracy.png and .svg. Errors of exactly 0 are drawn at 1e-17.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DOCS = os.path.join(HERE, os.pardir, "docs")
FLOOR = 1e-17
MARKERS = ["o", "s", "^", "D", "v", "P", "X", "*", "h", "<", ">", "p"]


def read(path):
    rows, header = [], []
    with open(path) as fh:
        lines = []
        for line in fh:
            if line.startswith("#"):
                header.append(line[1:].strip())
            else:
                lines.append(line)
    for row in csv.DictReader(lines):
        rows.append(row)
    return rows, header


def pareto(points):
    """Non-dominated points (min x, min y), sorted by x."""
    front, best = [], float("inf")
    for x, y, name in sorted(points):
        if y < best:
            front.append((x, y, name))
            best = y
    return front


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(DOCS, "bench_contact.csv")
    rows, header = read(path)
    methods = []
    for r in rows:
        if r["method"] not in methods:
            methods.append(r["method"])
    classes = sorted({int(r["class"]) for r in rows})
    fig, axes = plt.subplots(2, len(classes), figsize=(4.2 * len(classes), 8), squeeze=False)
    for j, c in enumerate(classes):
        sub = [r for r in rows if int(r["class"]) == c]
        lo, hi = sub[0]["axis_min"], sub[0]["axis_max"]
        for i, (col, label) in enumerate([("median_rel_err", "median"), ("max_rel_err", "max")]):
            ax = axes[i][j]
            pts = []
            for r in sub:
                x = float(r["median_ns"])
                y = max(float(r[col]), FLOOR)
                k = methods.index(r["method"])
                ax.errorbar(x, y, xerr=[[x - float(r["min_ns"])], [float(r["max_ns"]) - x]],
                            marker=MARKERS[k % len(MARKERS)], ms=8, ls="none", capsize=2,
                            label=r["method"], color="C%d" % k)
                pts.append((x, y, r["method"]))
            front = pareto(pts)
            xs = [p[0] for p in front]
            ys = [p[1] for p in front]
            ax.step(xs + [xs[-1] * 3], ys + [ys[-1]], where="post", ls="--", color="0.4",
                    lw=1, label="Pareto front")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_ylim(FLOOR / 3, 10)
            ax.axhline(1e-14, color="r", lw=0.6, ls=":")
            ax.grid(True, which="both", lw=0.3)
            ax.set_title("class %d: semi-axes in [%s, %s]" % (c, lo, hi), fontsize=9)
            ax.set_xlabel("time per call (ns, median over passes)")
            ax.set_ylabel("%s relative error of mu^2" % label)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=len(labels), fontsize=9)
    cpu = next((h for h in header if h.startswith("cpu:")), "")
    fig.suptitle("libpw85 contact function: speed vs accuracy (%s; red dotted: 1e-14)" % cpu,
                 fontsize=10)
    fig.tight_layout(rect=(0, 0.05, 1, 0.96))
    for ext in ("png", "svg"):
        out = os.path.join(DOCS, "speed_accuracy." + ext)
        # No date in the SVG metadata: the figure depends only on the CSV.
        fig.savefig(out, dpi=110, metadata={"Date": None} if ext == "svg" else None)
        print("wrote", out)


if __name__ == "__main__":
    main()
