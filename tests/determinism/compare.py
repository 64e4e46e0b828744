#!/usr/bin/env python3
"""Runs two builds of pw85-determinism over the same corpus and compares
their output line by line (streamed, nothing stored).

usage: compare.py PROGRAM_A PROGRAM_B [PAIRS [SEED]]

Prints the number of differing lines per function and status and the first
few differing lines; exit status 1 when any line differs (or the programs
print different numbers of lines or fail)."""
import collections
import subprocess
import sys


def main():
    prog_a, prog_b = sys.argv[1:3]
    extra = sys.argv[3:]
    pa = subprocess.Popen([prog_a] + extra, stdout=subprocess.PIPE, text=True, bufsize=1 << 20)
    pb = subprocess.Popen([prog_b] + extra, stdout=subprocess.PIPE, text=True, bufsize=1 << 20)
    lines = differ = 0
    per_fn = collections.Counter()
    shown = []
    for la, lb in zip(pa.stdout, pb.stdout):
        lines += 1
        if la != lb:
            differ += 1
            f = la.split()
            per_fn[f"{f[1]} (status {f[2]})"] += 1
            if len(shown) < 5:
                shown.append((la.rstrip(), lb.rstrip()))
    rest_a, rest_b = pa.stdout.read(), pb.stdout.read()
    ok = pa.wait() == 0 and pb.wait() == 0 and not rest_a and not rest_b
    if not ok:
        print("the programs failed or printed different numbers of lines")
    for fn, n in sorted(per_fn.items()):
        print(f"{n:8d}  {fn}")
    for la, lb in shown:
        print(f"A: {la}\nB: {lb}")
    print(f"{lines} lines compared, {differ} differ")
    return 0 if ok and differ == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
