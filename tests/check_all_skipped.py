#!/usr/bin/python3
"""Runs a GLib test program with --tap and checks that it exits with status 0
and that every test it ran was skipped (none passed, none failed).

Usage: check_all_skipped.py [--reference-only] PROGRAM [ARGS...]

Used with PW85_REF_DATA pointing at a file that does not exist: every test
reading the reference data must skip cleanly (g_test_skip), not crash or
fail. A crash (signal, sanitizer report with non-zero exit), a missing TAP
plan, a "not ok" line or an "ok" line without "# SKIP" makes this fail.

With --reference-only, only the tests whose path contains "/reference/" must
skip (there must be at least one); the others must pass (an "ok" line
without "# SKIP").
"""

import re
import subprocess
import sys


def main():
    args = sys.argv[1:]
    reference_only = bool(args) and args[0] == "--reference-only"
    if reference_only:
        args = args[1:]
    if not args:
        print(__doc__)
        return 2
    cmd = args + ["--tap"]
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True, timeout=300)
    out = proc.stdout
    sys.stdout.write(out)
    problems = []
    if proc.returncode != 0:
        problems.append("exit status %d" % proc.returncode)
    plan = re.search(r"^1\.\.(\d+)", out, re.M)
    results = re.findall(r"^(ok|not ok) \d+.*$", out, re.M)
    lines = [m.group(0) for m in re.finditer(r"^(ok|not ok) \d+.*$", out, re.M)]
    if plan is None:
        problems.append("no TAP plan")
    elif int(plan.group(1)) != len(results) or not results:
        problems.append("plan 1..%s but %d results" % (plan.group(1), len(results)))
    skipped = 0
    for line in lines:
        must_skip = not reference_only or "/reference/" in line
        if line.startswith("not ok"):
            problems.append("failed: " + line)
        elif must_skip and "# SKIP" not in line:
            problems.append("not skipped: " + line)
        elif not must_skip and "# SKIP" in line:
            problems.append("skipped without reading the reference data: " + line)
        else:
            skipped += must_skip
    if skipped == 0:
        problems.append("no test skipped")
    if problems:
        print("FAIL: " + "; ".join(problems))
        return 1
    print("PASS: %d of %d tests skipped" % (skipped, len(lines)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
