#!/usr/bin/env python3
"""Compare the dynamic symbols a shared library exports with a committed list.

usage: check_symbols.py NM LIBRARY LIST PREFIX

Fails when a symbol is exported that the list does not have (an accidental
ABI addition or a leaked internal symbol), when a listed symbol is missing
(an ABI break), or when an exported symbol lacks PREFIX.
"""
import subprocess
import sys


def main():
    nm, library, listing, prefix = sys.argv[1:5]
    out = subprocess.run([nm, "-D", "--defined-only", library],
                         check=True, capture_output=True, text=True).stdout
    exported = set()
    for line in out.splitlines():
        fields = line.split()
        if len(fields) >= 3 and fields[1] in "TDBRVWiu":
            exported.add(fields[2].split("@")[0])
    with open(listing) as f:
        expected = {l.strip() for l in f if l.strip() and not l.startswith("#")}
    ok = True
    for name in sorted(exported - expected):
        print(f"exported but not in {listing}: {name}")
        ok = False
    for name in sorted(expected - exported):
        print(f"listed but not exported: {name}")
        ok = False
    for name in sorted(exported):
        if not name.startswith(prefix):
            print(f"exported symbol without the prefix {prefix!r}: {name}")
            ok = False
    print(f"{len(exported)} symbols exported, {len(expected)} listed:",
          "OK" if ok else "MISMATCH")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
