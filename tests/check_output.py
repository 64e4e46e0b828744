#!/usr/bin/env python3
"""Run a program and check that its standard output holds given lines.

usage: check_output.py PROGRAM [--expect LINE]... [-- ARGS...]

Fails when PROGRAM exits with a non-zero status or when one of the expected
lines is not, exactly, a line of its standard output.
"""
import subprocess
import sys


def main():
    args = sys.argv[1:]
    program, args = args[0], args[1:]
    expected, program_args = [], []
    while args:
        if args[0] == "--expect":
            expected.append(args[1])
            args = args[2:]
        elif args[0] == "--":
            program_args = args[1:]
            break
        else:
            sys.exit(f"check_output.py: unexpected argument {args[0]!r}")
    run = subprocess.run([program] + program_args, capture_output=True, text=True)
    sys.stdout.write(run.stdout)
    sys.stderr.write(run.stderr)
    ok = run.returncode == 0
    if not ok:
        print(f"FAIL: {program} exited with status {run.returncode}")
    lines = run.stdout.splitlines()
    for line in expected:
        if line not in lines:
            print(f"FAIL: expected the line {line!r}")
            ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
