#!/usr/bin/env python3
"""Options, exit status and batch mode of the pw85 program (docs/usage.md).

usage: check_pw85_cli.py PROGRAM

mu^2 is compared with an mpmath reference (50 digits, maximum of
f(l) = l (1 - l) r^T ((1 - l) Q1 + l Q2)^{-1} r), the batch rows with the
one-pair call, and the quaternion lines with matrices built here by
rotating the body axes with the Hamilton product q v q*. The messages:
the count of failed lines among the non-blank ones, the number of values
--spheroids and --matrices need, a zero, NaN or infinite quaternion named
as such (scaled quaternions, 1e-300 to 1e300, give the unit one's mu^2).
Garbage lines (seeded) must give a message naming the line, never a crash.
"""
import os
import random
import re
import subprocess
import sys
import tempfile

import mpmath
import numpy as np

PROG = sys.argv[1]
FAILURES = []


def check(cond, what):
    if not cond:
        FAILURES.append(what)
        print("FAIL:", what)


def run(args, stdin=None):
    r = subprocess.run([PROG] + args, input=stdin, capture_output=True)
    return r.returncode, r.stdout.decode(errors="replace"), r.stderr.decode(errors="replace")


def value(out, key):
    m = re.search(r"^" + re.escape(key) + r" = (\S+)$", out, re.M)
    return float(m.group(1)) if m else None


def mu2_reference(r12, q1, q2):
    """max over l of f(l), mpmath 50 digits."""
    mpmath.mp.dps = 50
    def mat(q):
        return mpmath.matrix([[q[0], q[1], q[2]], [q[1], q[3], q[4]], [q[2], q[4], q[5]]])
    r = mpmath.matrix([mpmath.mpf(x) for x in r12])
    a, b = mat([mpmath.mpf(x) for x in q1]), mat([mpmath.mpf(x) for x in q2])
    def f(l):
        return l * (1 - l) * (r.T * mpmath.lu_solve((1 - l) * a + l * b, r))[0]
    # golden section on [0, 1] (f is concave in l), then Newton on f'
    lo, hi = mpmath.mpf(0), mpmath.mpf(1)
    g = (mpmath.sqrt(5) - 1) / 2
    for _ in range(60):
        m1, m2 = hi - g * (hi - lo), lo + g * (hi - lo)
        if f(m1) > f(m2):
            hi = m2
        else:
            lo = m1
    lam = mpmath.findroot(lambda l: mpmath.diff(f, l), (lo + hi) / 2)
    return float(f(lam))


def sym6(m):
    return [m[0][0], m[0][1], m[0][2], m[1][1], m[1][2], m[2][2]]


def hamilton(p, q):
    w1, x1, y1, z1 = p
    w2, x2, y2, z2 = q
    return (w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)


def q_from_quaternion(radii, quat):
    """Q = sum_k radii_k^2 v_k v_k^T, v_k = q e_k q* (independent of the
    rotation-matrix formula of the program)."""
    quat = np.asarray(quat, float) / np.linalg.norm(quat)
    conj = (quat[0], -quat[1], -quat[2], -quat[3])
    q = np.zeros((3, 3))
    for k in range(3):
        e = [0.0, 0.0, 0.0, 0.0]
        e[k + 1] = 1.0
        v = np.array(hamilton(hamilton(quat, e), conj)[1:])
        q += radii[k] ** 2 * np.outer(v, v)
    return sym6(q)


def main():
    # --help, --version, bad options
    rc, out, err = run(["--help"])
    check(rc == 0 and out.startswith("usage: pw85") and err == "", "--help: exit 0, usage on stdout")
    rc, out, err = run(["--version"])
    check(rc == 0 and re.fullmatch(r"pw85 \d+\.\d+\.\d+\n", out) is not None,
          f"--version: exit 0 and 'pw85 X.Y.Z' (got {rc}, {out!r})")
    for bad in (["--bogus"], ["--method"], ["--method", "fastest"], ["--matrices", "1", "2"],
                ["--spheroids"] + ["x"] * 16, ["--batch", "/nonexistent/pairs.txt"],
                ["--matrices"] + ["1"] * 15 + ["extra"]):
        rc, out, err = run(bad)
        check(rc == 2 and err.startswith("pw85: "), f"{bad}: exit 2 and a message (got {rc})")

    # --method: every name, any case, against the mpmath reference
    r12, q1 = [0.7, -0.7, 1.1], [100.0, 0.0, 0.0, 100.0, 0.0, 0.01]
    q2 = [25.0, 0.0, 0.0, 0.25, 0.0, 0.25]
    ref = mu2_reference(r12, q1, q2)
    tol = {"DEFAULT": 1e-14, "BRENT": 1e-10, "NEWTON": 1e-12, "RATIONAL": 1e-12, "ZHENG": 1e-9}
    rc, out, _ = run([])
    check(rc == 0 and "method" not in out, "no argument: exit 0, pw85 1.0 output")
    for name, t in tol.items():
        for spelled in (name, name.lower(), name.capitalize()):
            rc, out, err = run(["--method", spelled])
            mu2 = value(out, "mu^2")
            check(rc == 0 and mu2 is not None and f"method = {name}\n" in out,
                  f"--method {spelled}: exit 0 and 'method = {name}'")
            check(mu2 is not None and abs(mu2 - ref) <= t * ref,
                  f"--method {spelled}: mu2 {mu2} vs reference {ref!r} within {t}")
    # default method: DEFAULT
    rc, out, _ = run(["--matrices"] + [str(x) for x in r12 + q1 + q2])
    check("method = DEFAULT\n" in out and abs(value(out, "mu^2") - ref) <= 1e-14 * ref,
          "--matrices: DEFAULT method by default, accurate to 1e-14")

    # exit status carries the verdict
    unit = ["1", "0", "0", "1", "0", "1"]
    rc, out, _ = run(["--matrices", "1", "0", "0"] + unit + unit)
    check(rc == 1 and "verdict: overlap" in out, f"overlapping pair: exit 1 (got {rc})")
    rc, out, _ = run(["--matrices", "3", "0", "0"] + unit + unit)
    check(rc == 0 and "verdict: no overlap" in out, f"separate pair: exit 0 (got {rc})")
    rc, out, err = run(["--matrices", "3", "0", "0", "-1", "0", "0", "1", "0", "1"] + unit)
    check(rc == 3 and "positive definite" in err, f"non-SPD matrix: exit 3 and a message (got {rc})")
    rc, out, _ = run(["--spheroids", "0", "0", "0", "0.5", "1.5", "0", "0", "1",
                      "1.2", "0", "0", "0.5", "1.5", "1", "0", "0"])
    check(rc == 1, f"--spheroids overlapping: exit 1 (got {rc})")

    # too few numbers: the message says how many the option needs and how
    # many it got (counted up to the next option)
    for args, option, need, got in ((["--spheroids", "0", "0", "0", "1", "2"], "--spheroids", 16, 5),
                                    (["--spheroids", "0", "0", "0", "1", "2", "--method", "brent"],
                                     "--spheroids", 16, 5),
                                    (["--method", "brent", "--spheroids"], "--spheroids", 16, 0),
                                    (["--matrices", "1", "2"], "--matrices", 15, 2),
                                    (["--matrices"] + ["1"] * 14, "--matrices", 15, 14)):
        rc, out, err = run(args)
        check(rc == 2 and err.startswith(f"pw85: {option} needs {need} numbers (")
              and err.splitlines()[0].endswith(f"got {got}") and "unexpected argument" not in err,
              f"{args}: exit 2, '{option} needs {need} numbers ... got {got}' (got {rc}, {err!r})")
    for args in (["--batch", "-", "--spheroids"] + ["1"] * 16, ["--matrices"] + ["1"] * 15 + ["--batch"]):
        rc, out, err = run(args, stdin=b"")
        check(rc == 2 and "only one of --spheroids, --matrices and --batch" in err,
              f"{args[:3]}...: exit 2, one mode only (got {rc}, {err!r})")

    # batch: good and bad lines, comments, both formats
    rng = np.random.default_rng(43)
    lines, expect = [], {}
    for k in range(12):
        radii = rng.uniform(0.2, 3.0, 3), rng.uniform(0.2, 3.0, 3)
        quats = rng.normal(size=4), rng.normal(size=4)
        c1, c2 = rng.uniform(-3, 3, 3), rng.uniform(-3, 3, 3)
        if k % 2:
            nums = list(c1) + list(radii[0]) + list(quats[0]) + list(c2) + list(radii[1]) + list(quats[1])
        else:
            nums = list(c2 - c1) + q_from_quaternion(radii[0], quats[0]) + q_from_quaternion(radii[1], quats[1])
        lines.append(" ".join(repr(float(x)) for x in nums) + ("  # pair %d" % k if k == 3 else ""))
        qa, qb = q_from_quaternion(radii[0], quats[0]), q_from_quaternion(radii[1], quats[1])
        expect[len(lines)] = (list(c2 - c1), qa, qb)
        if k == 4:
            lines += ["", "# a comment", "1 2 3 four"]
        if k == 7:
            lines += ["1 2 3", " ".join(["1"] * 21), "0 0 0 1 1 1 0 0 0 0 1 0 0 1 1 1 1 0 0 0"]
    text = "\n".join(lines) + "\n"
    bad_lines = [i + 1 for i, l in enumerate(lines) if l in ("1 2 3 four", "1 2 3") or l.startswith("1 1 1 1")
                 or l.startswith("0 0 0 1 1 1 0 0 0 0")]
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "pairs.txt")
        with open(path, "w") as f:
            f.write(text)
        rc, out, err = run(["--batch", path])
        rc2, out2, err2 = run(["--batch"], stdin=text.encode())
        rc3, out3, _ = run(["--batch", "-"], stdin=text.encode())
    check(rc == 3 and rc2 == 3 and out == out2 == out3, f"batch with bad lines: exit 3 ({rc}, {rc2}, {rc3})")
    nonblank_lines = sum(1 for l in lines if l.split("#")[0].strip())
    check(f"pw85: {len(bad_lines)} of {nonblank_lines} lines failed\n" in err,
          f"batch: '{len(bad_lines)} of {nonblank_lines} lines failed' (got {err.splitlines()[-1]!r})")
    zero_q = lines.index("0 0 0 1 1 1 0 0 0 0 1 0 0 1 1 1 1 0 0 0") + 1
    check(f"pw85: line {zero_q}: the quaternion of ellipsoid 1 is zero" in err and "NULL pointer" not in err,
          f"batch: the zero quaternion of line {zero_q} named as such")
    rows = out.splitlines()
    check(rows[0] == "line,mu2,lambda,overlap,status", "batch: CSV header")
    for b in bad_lines:
        check(re.search(rf"^pw85: line {b}: ", err, re.M) is not None, f"batch: bad line {b} named on stderr")
    good = {}
    for row in rows[1:]:
        f = row.split(",")
        good[int(f[0])] = f
    for lineno, (r, qa, qb) in expect.items():
        f = good.get(lineno)
        check(f is not None and f[4] == "0", f"batch: line {lineno} computed with status 0")
        if f is None:
            continue
        one_rc, one, _ = run(["--matrices"] + [repr(float(x)) for x in r + qa + qb])
        mu2 = float(f[1])
        one_mu2 = value(one, "mu^2")
        check(abs(mu2 - one_mu2) <= 1e-13 * one_mu2,
              f"batch line {lineno}: mu2 {mu2!r} vs one-pair call {one_mu2!r}")
        check(int(f[3]) == (1 if one_rc == 1 else 0), f"batch line {lineno}: overlap column vs exit status")
    ref_batch = mu2_reference(*expect[1])
    check(abs(float(good[1][1]) - ref_batch) <= 1e-14 * ref_batch, "batch line 1 against mpmath")

    all_good = "\n".join(l for i, l in enumerate(lines) if i + 1 not in bad_lines) + "\n"
    rc, out, err = run(["--batch", "-", "--method", "brent"], stdin=all_good.encode())
    check(rc == 0 and err == "" and len(out.splitlines()) == 1 + len(expect),
          f"batch of good lines with --method brent: exit 0, every pair a row (got {rc}, {err!r})")

    # spheroid along x as a quaternion (rotation of z onto x, angle pi/2 about y)
    s = 2 ** -0.5
    line = f"0 0 0 0.5 0.5 1.5 1 0 0 0  3 0.1 0 0.5 0.5 1.5 {s!r} 0 {s!r} 0\n"
    _, out, _ = run(["--batch"], stdin=line.encode())
    _, one, _ = run(["--spheroids", "0", "0", "0", "0.5", "1.5", "0", "0", "1",
                     "3", "0.1", "0", "0.5", "1.5", "1", "0", "0"])
    mu2 = float(out.splitlines()[1].split(",")[1])
    check(abs(mu2 - value(one, "mu^2")) <= 1e-14 * mu2, "quaternion (w, x, y, z) convention against --spheroids")

    # the count of failed lines: a one-line file (a non-SPD matrix), lines
    # among blank and comment lines
    bad_spd = "3 0 0 -1 0 0 1 0 1 1 0 0 1 0 1\n"
    rc, out, err = run(["--batch"], stdin=bad_spd.encode())
    check(rc == 3 and err.endswith("pw85: 1 of 1 lines failed\n") and "positive definite" in err,
          f"one non-SPD line: exit 3, '1 of 1 lines failed' (got {rc}, {err!r})")
    good_line = "3 0 0 1 0 0 1 0 1 1 0 0 1 0 1\n"
    text = "# pairs\n\n" + good_line + bad_spd + "\n" + good_line + "   # only a comment\n"
    rc, out, err = run(["--batch"], stdin=text.encode())
    check(rc == 3 and err.endswith("pw85: 1 of 3 lines failed\n") and len(out.splitlines()) == 4,
          f"1 bad of 3 pair lines among blank and comment lines: '1 of 3 lines failed' (got {err!r})")

    # quaternions: zero, NaN or infinite named in the message, scaled ones
    # (down to 1e-300, up to 1e300) the same pair as the unit one
    pair = "0 0 0 0.5 0.5 1.5 {} {} {} {}  1.2 0.3 0 0.5 0.5 1.5 1 0 0 0\n"
    for quat, what in (((0, 0, 0, 0), "is zero"), (("nan", 0, 1, 0), "is not a number"),
                       ((1, "inf", 0, 0), "has an infinite component")):
        rc, out, err = run(["--batch"], stdin=pair.format(*quat).encode())
        check(rc == 3 and f"pw85: line 1: the quaternion of ellipsoid 1 {what}" in err
              and "NULL pointer" not in err and out.splitlines()[1].endswith(",-1"),
              f"quaternion {quat}: exit 3, message '{what}', status -1 (got {rc}, {err!r})")
    unit_row = run(["--batch"], stdin=pair.format(s, 0, s, 0).encode())[1].splitlines()[1]
    for scale in (1e-300, 1e-160, 3.0, 1e160, 1e300):
        rc, out, err = run(["--batch"], stdin=pair.format(scale, 0, scale, 0).encode())
        row = out.splitlines()[1].split(",")
        check(rc == 0 and abs(float(row[1]) - float(unit_row.split(",")[1])) <= 1e-15 * float(row[1]),
              f"quaternion scaled by {scale}: the unit quaternion's mu^2 (got {rc}, {row}, {err!r})")

    # garbage never crashes: every non-blank line is a row or a message
    rnd = random.Random(20261125)
    tokens = ["nan", "inf", "-inf", "1e999", "1e-320", "0x1p3", "-0", "#", ",", "1,2", "--", "\t", "\x00",
              "\xff\xfe", "1.5.5", "e", "+", "9" * 400]
    garbage = []
    for k in range(600):
        kind = k % 4
        if kind == 0:
            garbage.append(bytes(rnd.getrandbits(8) for _ in range(rnd.randint(0, 300))).replace(b"\n", b" "))
        elif kind == 1:
            garbage.append(" ".join(rnd.choice(tokens) for _ in range(rnd.randint(1, 25))).encode(errors="replace"))
        else:
            n = rnd.choice([15, 20, 14, 16, 21])
            nums = [rnd.choice([rnd.uniform(-5, 5), rnd.choice([0.0, 1e300, -1e-300, 1e-160])]) for _ in range(n)]
            garbage.append(" ".join(repr(x) for x in nums).encode())
    data = b"\n".join(garbage) + b"\n" + b"7" * 100000 + b"\n"
    r = subprocess.run([PROG, "--batch"], input=data, capture_output=True)
    check(r.returncode in (0, 3), f"garbage: exit 0 or 3, no crash (got {r.returncode})")
    out_rows = r.stdout.decode().splitlines()[1:]
    named = set(int(m) for m in re.findall(rb"^pw85: line (\d+): ", r.stderr, re.M))
    row_lines = set(int(x.split(",")[0]) for x in out_rows)
    ok_rows = set(int(x.split(",")[0]) for x in out_rows if x.endswith(",0"))
    raw = data.split(b"\n")[:-1]
    nonblank = set(i + 1 for i, l in enumerate(raw)
                   if b"\x00" in l or l.split(b"#")[0].replace(b",", b" ").strip())
    check(nonblank == (row_lines | named), "garbage: every non-blank line gives a row or a message")
    check(not (ok_rows & named) and (row_lines - ok_rows) <= named,
          "garbage: lines with a non-zero status are named on stderr, OK lines are not")
    print(f"garbage: {len(raw)} lines, {len(ok_rows)} computed with status 0, {len(named)} named on stderr")

    if FAILURES:
        print(f"{len(FAILURES)} failures")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
