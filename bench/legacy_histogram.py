#!/usr/bin/python3
"""Draw docs/legacy_histogram.png from the CSV written by the test legacy-f.

usage: /usr/bin/python3 bench/legacy_histogram.py [CSV] [PNG]

CSV defaults to docs/legacy_histogram.csv (a copy of
<builddir>/tests/legacy_histogram.csv, written by `meson test legacy-f`),
PNG to docs/legacy_histogram.png. Columns: digits, then the percentage of the
/F values evaluated with that many correct digits by pw85_f_neg,
pw85_legacy_f1 and pw85_legacy_f2.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    here = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "docs")
    src = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "legacy_histogram.csv")
    dst = sys.argv[2] if len(sys.argv) > 2 else os.path.join(here, "legacy_histogram.png")
    with open(src) as f:
        rows = list(csv.reader(f))
    header, rows = rows[0], rows[1:]
    digits = [int(r[0]) for r in rows]
    series = [[float(r[j]) for r in rows] for j in range(1, len(header))]
    width = 0.8 / len(series)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for j, (name, values) in enumerate(zip(header[1:], series)):
        ax.bar([d + (j - (len(series) - 1) / 2) * width for d in digits], values,
               width=width, label=name)
    ax.set_xlabel("number of correct digits of f (15 = at least 15, or exact)")
    ax.set_ylabel("share of the /F values [%]")
    ax.set_yscale("log")
    ax.set_ylim(1e-3, 100)
    ax.set_xticks(digits)
    ax.set_title("Accuracy of f on the 108 x 108 x 12 x 11 reference values")
    ax.legend(loc="upper left")
    fig.tight_layout()
    fig.savefig(dst, dpi=100)
    print("wrote", dst)


if __name__ == "__main__":
    main()
