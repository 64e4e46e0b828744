"""The minimum image of the scene calls (src/core/batch/box.hpp) against an
exact reference in rational arithmetic (fractions.Fraction).

usage: check_box.py BOX_IMAGE_PROGRAM [CASES]

Reference: HOOMD's triclinic wrap (z, then y, then x, each count the nearest
integer to the exact quotient, ties away from zero) on the exact values of
the doubles d and of the box, whose tilt offsets xy*Ly, xz*Lz, yz*Lz are
rounded to double once; each component of the exact result rounded to the
nearest double (float(Fraction) rounds correctly, ties to even).

Accepted answers: that image, bit for bit (a zero of either sign); where a
quotient lies within a relative 2^-48 of a half-integer, the image of the
other nearest count there; a refusal (status -1) only where the box.hpp
contract allows one: a count that is needed (along z with xz or yz not zero,
along y with xy not zero) beyond 2^50, or an intermediate value beyond
2^1020. A needed count beyond 2^50 + 2 must be refused. Exit 1 on any other
answer.
"""
import math
import random
import struct
import subprocess
import sys
from fractions import Fraction

MAX_COUNT = 2**50
NEAR_TIE = Fraction(1, 2**48)


def bits(x):
    return "%016x" % struct.unpack("<Q", struct.pack("<d", x))[0]


def from_bits(s):
    return struct.unpack("<d", struct.pack("<Q", int(s, 16)))[0]


def round_away(q):
    return math.floor(q + Fraction(1, 2)) if q >= 0 else -math.floor(-q + Fraction(1, 2))


def near_tie(q):
    f = abs(q) - math.floor(abs(q))
    return abs(f - Fraction(1, 2)) <= NEAR_TIE * max(1, abs(q))


def images(box, d):
    """Every accepted exact image (list of (x, y, z, counts, largest)), the
    first one the exact wrap's."""
    lx, ly, lz, xy, xz, yz = box
    txy, txz, tyz = Fraction(xy * ly), Fraction(xz * lz), Fraction(yz * lz)
    out = []

    def step(q):
        n = round_away(q)
        if near_tie(q):
            return [n, math.floor(q) if n != math.floor(q) else math.ceil(q)]
        return [n]

    z0, y0, x0 = (Fraction(v) for v in (d[2], d[1], d[0]))
    for nz in step(z0 / Fraction(lz)):
        z1, y1, x1 = z0 - nz * Fraction(lz), y0 - nz * tyz, x0 - nz * txz
        for ny in step(y1 / Fraction(ly)):
            y2, x2 = y1 - ny * Fraction(ly), x1 - ny * txy
            for nx in step(x2 / Fraction(lx)):
                x3 = x2 - nx * Fraction(lx)
                largest = max(abs(v) for v in (z0, y0, x0, y1, x1, x2, nz * tyz, nz * txz,
                                                 ny * txy))
                out.append((x3, y1 - ny * Fraction(ly), z1, (nz, ny, nx), largest))
    return out


def to_double(q):
    try:
        return float(q)
    except OverflowError:
        return math.inf


def check(box, d, answer):
    """None if the answer is accepted, else a message."""
    lx, ly, lz, xy, xz, yz = box
    imgs = images(box, d)
    nz, ny, _ = imgs[0][3]
    need_z = xz * lz != 0 or yz * lz != 0
    need_y = xy * ly != 0
    over = (need_z and abs(nz) > MAX_COUNT) or (need_y and abs(ny) > MAX_COUNT)
    must_refuse = (need_z and abs(nz) > MAX_COUNT + 2) or (need_y and abs(ny) > MAX_COUNT + 2)
    huge = imgs[0][4] > 2**1020
    status, vals = answer
    if status != 0:
        if status == -1 and (over or huge):
            return None
        return "refused (status %d) within the limits, exact image %s" % (
            status, [to_double(v) for v in imgs[0][:3]])
    if must_refuse:
        return "answered beyond the count limit (counts %s)" % (imgs[0][3],)
    for img in imgs:
        want = [to_double(v) for v in img[:3]]
        if all(a == w for a, w in zip(vals, want)):
            return None
    return "image %s, exact %s (counts %s)" % (vals, [to_double(v) for v in imgs[0][:3]],
                                              imgs[0][3])


def cases(rng, count):
    s53 = 2.0**53
    # The examples of the red-team report: tilt 2^60, 2^52, 2^20 with the
    # sphere pair's centres; a 2^53 offset in a box of 3; tilts +-100 with
    # centres ~1e6 box lengths apart.
    for t in (2.0**60, 2.0**52, 2.0**20):
        yield (1.0, 1.0, 1.0, t, 0.0, 0.0), (float.fromhex("0x1.3333333333333p-2"),
                                             float.fromhex("0x1.ccccccccccccdp-1"), 0.0)
    yield (3.0, 3.0, 3.0, 0.0, 0.0, 0.0), (s53, 0.0, 0.0)
    for _ in range(200):
        box = (rng.uniform(1, 3), rng.uniform(1, 3), rng.uniform(1, 3),
               rng.choice((100.0, -100.0)), rng.choice((100.0, -100.0)),
               rng.choice((100.0, -100.0)))
        yield box, tuple(rng.uniform(-1e6, 1e6) * box[i] for i in range(3))
    boxes = [
        (10.0, 10.0, 10.0, 0.0, 0.0, 0.0),
        (10.3, 9.7, 12.1, 0.0, 0.0, 0.0),
        (0.1, 0.7, 0.3, 0.0, 0.0, 0.0),
        (10.0, 9.0, 11.0, 0.5, -0.25, 0.125),
        (10.3, 9.7, 12.1, 0.3, -0.2, 0.45),
        (1.0, 1.0, 1.0, 0.1, 0.1, 0.1),
        (7.0, 3.0, 5.0, -3.7, 2.2, 9.1),
    ]
    for _ in range(count):
        kind = rng.randrange(9)
        box = rng.choice(boxes)
        lx, ly, lz = box[:3]
        if kind == 0:  # centres in the box
            c1 = [rng.uniform(0, b) for b in box[:3]]
            c2 = [rng.uniform(0, b) for b in box[:3]]
            d = tuple(c2[i] - c1[i] for i in range(3))
        elif kind == 1:  # a few box lengths
            d = tuple(rng.uniform(-4, 4) * b for b in box[:3])
        elif kind == 2:  # near a half-integer quotient (ties and their neighbours)
            d = tuple(math.nextafter((rng.randrange(-3, 4) + 0.5) * b, rng.choice(
                (math.inf, -math.inf))) if rng.random() < 0.5 else (rng.randrange(-3, 4) + 0.5) * b
                for b in box[:3])
        elif kind == 3:  # large: up to 2^60 box lengths
            d = tuple(rng.uniform(-1, 1) * 2.0 ** rng.uniform(0, 60) * b for b in box[:3])
        elif kind == 4:  # any magnitude
            d = tuple(rng.choice((-1, 1)) * 2.0 ** rng.uniform(-1074, 1023) for _ in range(3))
        elif kind == 5:  # tiny and extreme boxes
            scale = 2.0 ** rng.randrange(-1070, 1000)
            box = tuple(b * scale for b in box[:3]) + box[3:]
            d = tuple(rng.uniform(-3, 3) * b for b in box[:3])
        elif kind == 6:  # large tilts
            t = 2.0 ** rng.uniform(0, 70)
            box = box[:3] + (rng.uniform(-t, t), rng.uniform(-t, t), rng.uniform(-t, t))
            d = tuple(rng.uniform(-3, 3) * b * (1 + t) for b in box[:3])
        elif kind == 7:  # a coordinate much smaller than the others
            d = (rng.uniform(-2, 2) * lx, 2.0 ** rng.uniform(-100, -40), rng.uniform(-2, 2) * lz)
        else:  # exact multiples of the lengths and their neighbours
            d = tuple(math.nextafter(rng.randrange(-5, 6) * b, rng.choice((math.inf, -math.inf)))
                      for b in box[:3])
        if all(math.isfinite(v) for v in d):
            yield box, d


def main():
    program = sys.argv[1]
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 20000
    rng = random.Random(55)
    todo = list(cases(rng, count))
    text = "".join(" ".join(bits(v) for v in box + d) + "\n" for box, d in todo)
    run = subprocess.run([program], input=text, capture_output=True, text=True, check=True)
    lines = run.stdout.splitlines()
    assert len(lines) == len(todo), "the program answered %d of %d" % (len(lines), len(todo))
    bad = refused = slow = 0
    for (box, d), line in zip(todo, lines):
        if line == "invalid-box":
            msg = "invalid box"
        else:
            f = line.split()
            answer = (int(f[0]), [from_bits(v) for v in f[1:]])
            refused += answer[0] != 0
            msg = check(box, d, answer)
        if msg is not None:
            bad += 1
            if bad <= 20:
                print("FAIL box %s d %s: %s" % (box, d, msg))
    # The three examples of the report, exactly.
    first = [l.split() for l in lines[:4]]
    want = [(float.fromhex("0x1.3333333333333p-2"),
             float.fromhex("0x1.ccccccccccccdp-1") - 1.0, 0.0)] * 3 + [(-1.0, 0.0, 0.0)]
    for f, w in zip(first, want):
        got = tuple(from_bits(v) for v in f[1:])
        if f[0] != "0" or got != w:
            bad += 1
            print("FAIL report example: got %s %s, want %s" % (f[0], got, w))
    print("%d images checked, %d refused within the contract, %d wrong" % (len(todo), refused,
                                                                          bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
