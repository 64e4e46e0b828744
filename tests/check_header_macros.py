#!/usr/bin/env python3
"""Every macro a public header defines carries the PW85_ prefix.

usage: check_header_macros.py HEADER CC [CC ARGS...]

Preprocesses HEADER with -dM and an empty file the same way and fails for
each macro the header adds whose name does not start with PW85_.
"""
import subprocess
import sys


def macros(cc, source):
    out = subprocess.run(cc + ["-dM", "-E", "-x", "c", "-"], input=source,
                         capture_output=True, text=True, check=True).stdout
    return {line.split()[1].split("(")[0] for line in out.splitlines()
            if line.startswith("#define ")}


def main():
    header, cc = sys.argv[1], sys.argv[2:]
    added = macros(cc, f'#include "{header}"\n') - macros(cc, "")
    bad = sorted(name for name in added if not name.startswith("PW85_"))
    for name in bad:
        print(f"{header} defines the unprefixed macro {name}")
    print(f"{len(added)} macros added by {header}, {len(bad)} unprefixed")
    return 1 if bad or not added else 0


if __name__ == "__main__":
    sys.exit(main())
