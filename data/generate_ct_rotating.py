#!/usr/bin/python3
"""Generate tests/ct_rotating_reference.h: rotating trajectories of the first
contact time (docs/contact_time.md) with references computed in mpmath from
the exact double inputs, never by libpw85.

Usage::

    /usr/bin/python3 data/generate_ct_rotating.py [-n 206] [--seed 54]
        [--workers 2] [-o tests/ct_rotating_reference.h]
        [--inputs-from FILE]  (the references again, for the inputs of FILE)

Requirements (Debian): python3-numpy python3-mpmath (python3-gmpy2 speeds
mpmath up).

tests/ct_rotating_reference.h holds the inputs drawn with -n 206 --seed 54
and their references computed by --inputs-from (about 10 minutes on 2
cores); drawing again gives the same inputs except a few class-3 grazes,
whose acceptance depends on the reference.

Exact motion: every input is a double, converted exactly to an mpf at
mp.dps = 40; r12(t) = r12 + t v12; Q_i(t) = R_i Q_i R_i^T with
R_i = I + sin(th) K + (1 - cos(th)) K^2, th = t |w_i|, K = [w_i / |w_i|]x
(Rodrigues) at 45 digits. mu^2(t) = max over lambda of
f(lambda) = lambda (1 - lambda) r^T Q(lambda)^{-1} r by a safeguarded Newton
iteration on f'(lambda) = (1 - lambda)^2 s^T Q1 s - lambda^2 s^T Q2 s
(f'' = -2 (Q1 s)^T Q(lambda)^{-1} (Q2 s)), s = Q(lambda)^{-1} r, to 1e-36.
dmu^2/dt = lambda (1 - lambda) (2 s.v - 2 (1 - lambda) s.(w1 x Q1 s)
- 2 lambda s.(w2 x Q2 s)) (envelope theorem).

Reference of a trajectory on [0, t_max = 1]: a grid of 2048 intervals plus
256 per turn of the faster body, mu^2 and dmu^2/dt evaluated in float64
(numpy) to locate
features, every float64 sign change of mu^2 - 1 checked in mpmath; every minimum of
the grid over 7 points below 1.01, and every grid interval where
dmu^2/dt changes sign from - to + (a minimum however narrow) and 64
float64 samples of it reach below 1.01, is refined in mpmath (zero of dmu^2/dt,
safeguarded secant), every crossing of 1 and of L = 1 - 2.3e-13 by a
safeguarded secant in mpmath to 1e-30. Recorded: mu^2(0) - 1, the smallest
mu^2 - 1 and where, t_c (first crossing of mu^2 = 1), t_d (the last
crossing of 1 at or before t_a), t_a (first time with mu^2 < L); INFINITY
when none.

Kinds, per class (semi-axes log-uniform in [lo, hi], random orientations;
class 0 [0.5, 2], 1 [0.1, 10], 2 [0.01, 100], 3 [0.001, 1000]):
  graze:  a stationary minimum of mu^2 at 1 + delta, delta = +-1e-13,
          +-1e-10, +-1e-6, at t_m in [0.3, 0.7], each body turning 0.5-3
          times over t_max: at t_m a random direction scaled to
          mu^2 = 1 + delta, v = (its component along s set so that
          dmu^2/dt(t_m) = 0) + a random perpendicular part; r0 = r(t_m) -
          t_m v rounded, then the last bits of r0 adjusted until the exact
          minimum of the double inputs lies within |delta| / 4 of 1 + delta;
          speed 2-6 (a_max,1 + a_max,2) per unit time;
          kept when that minimum is the lowest of the trajectory.
  random: centres 1.1-3 bounding radii apart, approaching with an offset,
          each body turning up to once.
  spin:   the same, 2-5 turns.
plus the class-2 trajectory of a reported false contact, verbatim.
"""

import argparse
import math
import multiprocessing
import sys

import numpy as np
import mpmath
from mpmath import mp, mpf

mp.dps = 40
L_LATE = mpf(1) - mpf("2.3e-13")
CLASSES = [(0.5, 2.0), (0.1, 10.0), (0.01, 100.0), (0.001, 1000.0)]
DELTAS = [1e-13, -1e-13, 1e-10, -1e-10, 1e-6, -1e-6]
KINDS = {"graze": 0, "random": 1, "spin": 2, "issue": 3}

ISSUE = dict(
    r0=["0x1.a52ae15d3f21ap-2", "-0x1.146c1ec906af7p-3", "-0x1.ad94f4bfa5d90p+1"],
    v=["0x1.20e3505b0fc08p+1", "-0x1.479a25923e4dbp-4", "0x1.ac7a9ba5411b2p+2"],
    q1=["0x1.2cd6e36801624p+9", "0x1.43013d042d508p+7", "-0x1.0239a87ba3cb2p+1",
        "0x1.5dcc5754abc98p+5", "-0x1.52a051fa52568p-1", "0x1.7ff8e187b810cp-5"],
    w1=["-0x1.687509e92395ep+2", "-0x1.516fc405e9345p+3", "-0x1.72a83d0feca63p+2"],
    q2=["0x1.32d0354a41177p-1", "0x1.f001d7207c2aep-4", "0x1.7ab514c520e89p-1",
        "0x1.89d3659215274p-5", "0x1.72827dd8014fap-3", "0x1.05a4ceb0578fdp+0"],
    w2=["-0x1.272afbf593ab0p+1", "-0x1.db839dbd2e761p+1", "0x1.bbeef49a7f923p+1"],
)


# ---- exact motion in mpmath ---------------------------------------------------

def sym(q):
    return [[q[0], q[1], q[2]], [q[1], q[3], q[4]], [q[2], q[4], q[5]]]


def rot_mp(w, t):
    """R(t) = exp(t [w]x) by Rodrigues' formula at mp.dps digits."""
    wn = mp.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
    eye = [[mpf(int(i == j)) for j in range(3)] for i in range(3)]
    if wn == 0 or t == 0:
        return eye
    k = [x / wn for x in w]
    th = t * wn
    s, c1 = mp.sin(th), 2 * mp.sin(th / 2) ** 2
    K = [[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]]
    K2 = [[sum(K[i][l] * K[l][j] for l in range(3)) for j in range(3)] for i in range(3)]
    return [[eye[i][j] + s * K[i][j] + c1 * K2[i][j] for j in range(3)] for i in range(3)]


def rotq_mp(q, w, t):
    R, Q = rot_mp(w, t), sym(q)
    M = [[sum(R[i][l] * Q[l][j] for l in range(3)) for j in range(3)] for i in range(3)]
    return [[sum(M[i][l] * R[j][l] for l in range(3)) for j in range(3)] for i in range(3)]


def solve3(A, b):
    """A^{-1} b, A symmetric positive definite (L D L^T)."""
    d0 = A[0][0]
    l10, l20 = A[1][0] / d0, A[2][0] / d0
    d1 = A[1][1] - l10 * l10 * d0
    l21 = (A[2][1] - l20 * l10 * d0) / d1
    d2 = A[2][2] - l20 * l20 * d0 - l21 * l21 * d1
    y0 = b[0]
    y1 = b[1] - l10 * y0
    y2 = b[2] - l20 * y0 - l21 * y1
    x2 = y2 / d2
    x1 = y1 / d1 - l21 * x2
    x0 = y0 / d0 - l10 * x1 - l20 * x2
    return [x0, x1, x2]


def mv(A, x):
    return [A[i][0] * x[0] + A[i][1] * x[1] + A[i][2] * x[2] for i in range(3)]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def mu2_static(r, A, B, lam0=0.5):
    """(mu^2, lambda, s) for centre offset r and forms A, B (mpmath)."""
    lo, hi = mpf(0), mpf(1)
    lam = mpf(lam0)
    if not (0 < lam < 1):
        lam = mpf(0.5)
    for _ in range(200):
        Q = [[(1 - lam) * A[i][j] + lam * B[i][j] for j in range(3)] for i in range(3)]
        s = solve3(Q, r)
        As, Bs = mv(A, s), mv(B, s)
        g = (1 - lam) ** 2 * dot(s, As) - lam ** 2 * dot(s, Bs)
        if g > 0:
            lo = lam
        else:
            hi = lam
        gp = -2 * dot(As, solve3(Q, Bs))  # f''
        step = -g / gp if gp < 0 else None
        new = lam + step if step is not None else None
        if new is None or not (lo < new < hi):
            new = (lo + hi) / 2
        if abs(new - lam) < mpf(10) ** (-36) or hi - lo < mpf(10) ** (-36):
            lam = new
            break
        lam = new
    Q = [[(1 - lam) * A[i][j] + lam * B[i][j] for j in range(3)] for i in range(3)]
    s = solve3(Q, r)
    return lam * (1 - lam) * dot(r, s), lam, s


class Traj:
    def __init__(self, r0, v, q1, w1, q2, w2, t_max=1.0):
        self.d = dict(r0=list(r0), v=list(v), q1=list(q1), w1=list(w1), q2=list(q2),
                      w2=list(w2), t_max=float(t_max))
        self.m = {k: ([mpf(x) for x in val] if isinstance(val, list) else mpf(val))
                  for k, val in self.d.items()}
        self.lam = 0.5

    def mu2(self, t, want_rate=False):
        m = self.m
        t = mpf(t)
        r = [m["r0"][i] + t * m["v"][i] for i in range(3)]
        A, B = rotq_mp(m["q1"], m["w1"], t), rotq_mp(m["q2"], m["w2"], t)
        val, lam, s = mu2_static(r, A, B, self.lam)
        self.lam = lam
        if not want_rate:
            return val
        As, Bs = mv(A, s), mv(B, s)
        rate = lam * (1 - lam) * (2 * dot(s, m["v"]) - 2 * (1 - lam) * dot(s, cross(m["w1"], As))
                                  - 2 * lam * dot(s, cross(m["w2"], Bs)))
        return val, rate, lam, s, A, B, r

    # float64 grid (numpy), for locating features only
    def grid64(self, n, ts=None):
        d = self.d
        if ts is None:
            ts = np.linspace(0.0, d["t_max"], n + 1)
        n = len(ts) - 1
        r = np.array(d["r0"])[None, :] + ts[:, None] * np.array(d["v"])[None, :]

        def rot(q, w):
            Q = np.array(sym(q), dtype=float)
            w = np.array(w, dtype=float)
            wn = np.linalg.norm(w)
            if wn == 0:
                return np.broadcast_to(Q, (n + 1, 3, 3)).copy()
            k = w / wn
            K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
            th = ts * wn
            R = (np.eye(3)[None] + np.sin(th)[:, None, None] * K[None]
                 + (1 - np.cos(th))[:, None, None] * (K @ K)[None])
            return R @ Q[None] @ np.transpose(R, (0, 2, 1))

        A, B = rot(d["q1"], d["w1"]), rot(d["q2"], d["w2"])
        lo, hi = np.zeros(n + 1), np.ones(n + 1)
        for _ in range(60):
            lam = 0.5 * (lo + hi)
            Q = (1 - lam)[:, None, None] * A + lam[:, None, None] * B
            s = np.linalg.solve(Q, r[:, :, None])[:, :, 0]
            g = ((1 - lam) ** 2 * np.einsum("ni,nij,nj->n", s, A, s)
                 - lam ** 2 * np.einsum("ni,nij,nj->n", s, B, s))
            lo = np.where(g > 0, lam, lo)
            hi = np.where(g > 0, hi, lam)
        lam = 0.5 * (lo + hi)
        Q = (1 - lam)[:, None, None] * A + lam[:, None, None] * B
        s = np.linalg.solve(Q, r[:, :, None])[:, :, 0]
        As, Bs = np.einsum("nij,nj->ni", A, s), np.einsum("nij,nj->ni", B, s)
        w1, w2 = np.array(d["w1"], dtype=float), np.array(d["w2"], dtype=float)
        rate = lam * (1 - lam) * (2 * s @ np.array(d["v"], dtype=float)
                                  - 2 * (1 - lam) * np.einsum("ni,ni->n", s, np.cross(w1[None], As))
                                  - 2 * lam * np.einsum("ni,ni->n", s, np.cross(w2[None], Bs)))
        self.rate64 = rate
        return ts, lam * (1 - lam) * np.einsum("ni,ni->n", r, s)


def secant_root(fun, a, b, fa, fb, tol=mpf(10) ** -30):
    """Root of fun in [a, b], fa = fun(a), fb = fun(b) of opposite signs
    (Illinois regula falsi with bisection safeguard)."""
    a, b = mpf(a), mpf(b)
    side = 0
    for it in range(200):
        if b - a <= tol * max(1, abs(b)):
            break
        c = b - fb * (b - a) / (fb - fa)
        if not (a < c < b) or it % 4 == 3:
            c = (a + b) / 2
        fc = fun(c)
        if fc == 0:
            return c
        if (fc > 0) == (fa > 0):
            a, fa = c, fc
            if side == -1:
                fb /= 2
            side = -1
        else:
            b, fb = c, fc
            if side == 1:
                fa /= 2
            side = 1
    return b if abs(fb) < abs(fa) else a


def reference(tr):
    """Features of mu^2 on [0, t_max] (see the module docstring)."""
    d = tr.d
    wmax = max(math.sqrt(sum(x * x for x in d["w1"])), math.sqrt(sum(x * x for x in d["w2"])))
    n = 2048 + int(256 * wmax * d["t_max"] / (2 * math.pi))
    ts, g = tr.grid64(n)
    rate = tr.rate64
    vals = [None] * (n + 1)

    def val(j):  # mpmath value at grid point j, mu^2 - 1
        if vals[j] is None:
            vals[j] = tr.mu2(mpf(ts[j])) - 1
        return vals[j]

    # signs: float64, checked in mpmath next to every float64 sign change
    # (dips the float64 values miss are found by the local minima below)
    sgn = [g[j] > 1 for j in range(n + 1)]
    sgn[0] = val(0) > 0
    for j in range(1, n + 1):
        if (g[j - 1] > 1) != (g[j] > 1):
            sgn[j - 1] = val(j - 1) > 0
            sgn[j] = val(j) > 0
    mu0 = val(0)
    fm1 = lambda t: tr.mu2(t) - 1
    fla = lambda t: tr.mu2(t) - L_LATE
    crossings1, crossingsL = [], []
    best, tbest = mu0, mpf(0)
    if not sgn[0]:
        return None
    # crossings between grid points
    for j in range(1, n + 1):
        if sgn[j - 1] and not sgn[j] and vals[j] is not None and vals[j - 1] is not None:
            crossings1.append(secant_root(fm1, ts[j - 1], ts[j], val(j - 1), val(j)))
    # local minima of the grid
    done = set()
    for j in range(n + 1):
        lo, hi = max(j - 3, 0), min(j + 3, n)
        low = g[j] <= g[lo:hi + 1].min() and g[j] < 1.01
        turn = j > 0 and rate[j - 1] < 0 <= rate[j]  # a minimum in (t_{j-1}, t_j], however narrow
        if turn and not low:  # kept when 64 float64 samples of the interval reach below 1.01
            sub = tr.grid64(0, np.linspace(ts[j - 1], ts[j], 65))[1]
            turn = sub.min() < 1.01
        if not (low or turn):
            continue
        # the interval of a sign change of dmu^2/dt from - to + nearest to j
        ks = [k for k in range(max(j - 3, 1), min(j + 3, n) + 1) if rate[k - 1] < 0 <= rate[k]]
        if ks:
            k = min(ks, key=lambda k: abs(k - j))
            a, b = k - 1, k
        else:
            a, b = max(j - 2, 0), min(j + 2, n)
        if (a, b) in done:
            continue
        done.add((a, b))
        fa = tr.mu2(mpf(ts[a]), True)[1]
        fb = tr.mu2(mpf(ts[b]), True)[1]
        if fa < 0 and fb > 0:
            tm = secant_root(lambda t: tr.mu2(t, True)[1], ts[a], ts[b], fa, fb, mpf(10) ** -25)
        else:  # monotone on [a, b] in mpmath: the lower end
            tm = mpf(ts[a]) if fa >= 0 else mpf(ts[b])
        vm = tr.mu2(tm) - 1
        if vm < best:
            best, tbest = vm, tm
        if vm <= 0 and val(a) > 0:
            crossings1.append(secant_root(fm1, ts[a], tm, val(a), vm))
        if vm + 1 < L_LATE:
            crossingsL.append(secant_root(fla, ts[a], tm, val(a) + 1 - L_LATE, vm + 1 - L_LATE))
    for j in range(1, n + 1):
        if vals[j] is not None and vals[j] + 1 < L_LATE and vals[j - 1] is not None and \
                vals[j - 1] + 1 >= L_LATE:
            crossingsL.append(secant_root(fla, ts[j - 1], ts[j], vals[j - 1] + 1 - L_LATE,
                                          vals[j] + 1 - L_LATE))
        if vals[j] is not None and vals[j] < best:
            best, tbest = vals[j], mpf(ts[j])
    inf = math.inf
    t_c = min(crossings1) if crossings1 else inf
    t_a = min(crossingsL) if crossingsL else inf
    before = [c for c in crossings1 if c <= t_a]
    t_d = max(before) if before else inf
    return dict(mu0=float(mu0), min=float(best), t_min=float(tbest), t_c=float(t_c),
                t_d=float(t_d), t_a=float(t_a), grid=n)


# ---- trajectories -------------------------------------------------------------

def ellipsoid(rng, lo, hi):
    a = lo * np.exp(rng.uniform(size=3) * math.log(hi / lo))
    p = rng.normal(size=4)
    w, x, y, z = [mpf(c) for c in p / np.linalg.norm(p)]
    R = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    q = []
    for i in range(3):
        for j in range(i, 3):
            q.append(float(sum(R[i][k] * R[j][k] * mpf(a[k]) ** 2 for k in range(3))))
    return q, float(max(a))


def unit(rng):
    u = rng.normal(size=3)
    return u / np.linalg.norm(u)


def make_graze(rng, lo, hi, delta):
    q1, a1 = ellipsoid(rng, lo, hi)
    q2, a2 = ellipsoid(rng, lo, hi)
    w1 = [float(x) for x in 2 * math.pi * rng.uniform(0.5, 3.0) * unit(rng)]
    w2 = [float(x) for x in 2 * math.pi * rng.uniform(0.5, 3.0) * unit(rng)]
    tm = mpf(float(rng.uniform(0.3, 0.7)))
    mq1, mq2 = [mpf(x) for x in q1], [mpf(x) for x in q2]
    mw1, mw2 = [mpf(x) for x in w1], [mpf(x) for x in w2]
    A, B = rotq_mp(mq1, mw1, tm), rotq_mp(mq2, mw2, tm)
    dvec = [mpf(x) for x in unit(rng)]
    m2, lam, s = mu2_static(dvec, A, B)
    sc = mp.sqrt((1 + mpf(delta)) / m2)
    rm = [x * sc for x in dvec]
    m2, lam, s = mu2_static(rm, A, B, lam)
    As, Bs = mv(A, s), mv(B, s)
    alpha = (1 - lam) * dot(s, cross(mw1, As)) + lam * dot(s, cross(mw2, Bs))
    ss = dot(s, s)
    e = [mpf(x) for x in unit(rng)]
    es = dot(e, s) / ss
    perp = [e[i] - es * s[i] for i in range(3)]
    pn = mp.sqrt(dot(perp, perp))
    speed = (a1 + a2) * rng.uniform(2.0, 6.0)
    v = [float(speed * perp[i] / pn + alpha * s[i] / ss) for i in range(3)]
    r0 = [float(rm[i] - tm * v[i]) for i in range(3)]
    tr = Traj(r0, v, q1, w1, q2, w2)
    # the exact minimum near t_m of the double inputs, then the last bits of
    # r0 adjusted (linear prediction through d mu^2 / d r0 = 2 lambda (1 -
    # lambda) s)
    target = mpf(delta)
    for attempt in range(4):
        h = mpf(0.02)
        fa = tr.mu2(tm - h, True)[1]
        fb = tr.mu2(tm + h, True)[1]
        if not (fa < 0 < fb):
            return None
        t0 = secant_root(lambda t: tr.mu2(t, True)[1], tm - h, tm + h, fa, fb, mpf(10) ** -25)
        val, rate, lam, s, A, B, r = tr.mu2(t0, True)
        err = (val - 1) - target
        if abs(err) <= abs(target) / 4:
            return tr
        grad = [2 * lam * (1 - lam) * s[i] for i in range(3)]
        quanta = [float(grad[i]) * math.ulp(r0[i]) if r0[i] != 0 else 0.0 for i in range(3)]
        # a few ulps per component: brute force over a small lattice
        K = 20
        ks = np.arange(-K, K + 1)
        kk = np.stack(np.meshgrid(ks, ks, ks, indexing="ij"), -1).reshape(-1, 3)
        pred = kk @ np.array(quanta)
        gn = float(np.linalg.norm([float(x) for x in grad]))
        # a plain Newton step first when the error is many quanta
        if abs(float(err)) > np.abs(pred).max():
            step = [-float(err) * float(grad[i]) / gn ** 2 for i in range(3)]
            r0 = [r0[i] + step[i] for i in range(3)]
        else:
            best = kk[np.argmin(np.abs(pred + float(err)))]
            r0 = [r0[i] + int(best[i]) * math.ulp(r0[i]) for i in range(3)]
        tr = Traj(r0, v, q1, w1, q2, w2)
    return None


def make_random(rng, lo, hi, spin):
    q1, a1 = ellipsoid(rng, lo, hi)
    q2, a2 = ellipsoid(rng, lo, hi)
    d = unit(rng)
    dist = (a1 + a2) * rng.uniform(1.1, 3.0)
    e = unit(rng)
    off = (a1 + a2) * rng.uniform()
    speed = dist * rng.uniform(1.0, 3.0)
    r0 = [float(dist * d[i]) for i in range(3)]
    v = [float(-speed * d[i] + 2 * off * e[i]) for i in range(3)]
    t1 = rng.uniform(2, 5) if spin else rng.uniform(0, 1)
    t2 = rng.uniform(2, 5) if spin else rng.uniform(0, 1)
    w1 = [float(x) for x in 2 * math.pi * t1 * unit(rng)]
    w2 = [float(x) for x in 2 * math.pi * t2 * unit(rng)]
    return Traj(r0, v, q1, w1, q2, w2)


def job(args):
    cls, kind, k, seed = args
    rng = np.random.default_rng([seed, cls, KINDS[kind], k])
    lo, hi = CLASSES[cls]
    for attempt in range(40):
        if kind == "graze":
            delta = DELTAS[k % len(DELTAS)]
            tr = make_graze(rng, lo, hi, delta)
        elif kind == "issue":
            tr = Traj(*[[float.fromhex(x) for x in ISSUE[key]]
                        for key in ("r0", "v", "q1", "w1", "q2", "w2")])
            delta = 0
        else:
            tr = make_random(rng, lo, hi, kind == "spin")
            delta = 0
        if tr is None:
            continue
        if kind == "graze" and tr.grid64(600)[1].min() < 1 - 1e-2:
            continue  # another dip, deeper than the constructed minimum
        ref = reference(tr)
        if ref is None or ref["mu0"] < 1e-3:
            continue
        if kind == "graze":
            # the constructed minimum must be the lowest of the trajectory
            if abs(ref["min"] - delta) > abs(delta) / 4:
                continue
        return cls, kind, k, tr.d, ref, delta
    return None


def hexs(x):
    if x == math.inf:
        return "INFINITY"
    return float(x).hex()


def parse_header(path):
    """The inputs of an existing output file: (cls, kind, delta, Traj)."""
    out = []
    for line in open(path):
        if not line.startswith("  {"):
            continue
        v = [x.strip() for x in line.replace("{", "").replace("}", "").strip().strip(",").split(",")]
        f = [math.inf if x == "INFINITY" else float.fromhex(x) for x in v[2:]]
        out.append((int(v[0]), int(v[1]), f[0], f[1:4], f[4:7], f[7:13], f[13:16], f[16:22],
                    f[22:25]))
    return out


def rejob(args):
    cls, kind, delta, r0, v, q1, w1, q2, w2 = args
    tr = Traj(r0, v, q1, w1, q2, w2)
    name = [k for k, i in KINDS.items() if i == kind][0]
    return cls, name, 0, tr.d, reference(tr), delta


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-n", type=int, default=210, help="trajectories per class")
    ap.add_argument("--seed", type=int, default=54)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("-o", default="tests/ct_rotating_reference.h")
    ap.add_argument("--name", default="ct_rot")
    ap.add_argument("--inputs-from", help="recompute the references of the inputs of this file")
    a = ap.parse_args()
    if a.inputs_from:
        out = []
        with multiprocessing.Pool(a.workers) as pool:
            for i, res in enumerate(pool.imap(rejob, parse_header(a.inputs_from), chunksize=1)):
                out.append(res)
                if i % 20 == 0:
                    print(f"{i}", file=sys.stderr, flush=True)
        write(a, out)
        return
    jobs = []
    for cls in range(4):
        ng = (a.n * 5) // 7
        nr = (a.n - ng) // 2
        jobs += [(cls, "graze", k, a.seed) for k in range(ng)]
        jobs += [(cls, "random", k, a.seed) for k in range(nr)]
        jobs += [(cls, "spin", k, a.seed) for k in range(a.n - ng - nr)]
    jobs.append((2, "issue", 0, a.seed))
    out = []
    with multiprocessing.Pool(a.workers) as pool:
        for i, res in enumerate(pool.imap(job, jobs, chunksize=1)):
            if res is not None:
                out.append(res)
            if i % 20 == 0:
                print(f"{i}/{len(jobs)}", file=sys.stderr, flush=True)
    write(a, out)


def write(a, out):
    lines = [
        "/* Generated by data/generate_ct_rotating.py (" + " ".join(sys.argv[1:]) + "): rotating",
        " * trajectories of pw85_contact_time and their references in mpmath (40",
        " * digits, exact rotation of the double inputs); see that script. Do not edit. */",
        "/* cls, kind (0 graze, 1 random, 2 spin, 3 issue), delta of a graze, r0, v, q1, w1,",
        " * q2, w2, t_max, mu^2(0) - 1, min mu^2 - 1, t_min, t_c, t_d, t_a */",
        f"static const ct_rot_case {a.name}_cases[] = {{",
    ]
    for cls, kind, k, d, ref, delta in out:
        vals = [hexs(delta)] + ["{" + ", ".join(hexs(x) for x in d[key]) + "}"
                                for key in ("r0", "v", "q1", "w1", "q2", "w2")] + [hexs(d["t_max"])]
        vals += [hexs(ref[key]) for key in ("mu0", "min", "t_min", "t_c", "t_d", "t_a")]
        lines.append(f"  {{{cls}, {KINDS[kind]}, " + ", ".join(vals) + "},")
    lines.append("};")
    lines.append(f"static const int {a.name}_count = {len(out)};")
    with open(a.o, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"{len(out)} trajectories written to {a.o}", file=sys.stderr)


if __name__ == "__main__":
    main()
