"""Continuous contact detection: first time two quadratic paths come within a distance.

Between events every ball moves on a quadratic p(t) = p0 + v t + a t^2 / 2, so the squared
distance of two balls (or of a ball and a fixed point) is a quartic in t and the distance of a
ball from a straight cushion is a quadratic. These routines find the first approaching root
inside a window, vectorized over many pairs, exactly (companion-matrix eigenvalues polished by
Newton steps) so that nothing tunnels whatever the step. Callers run them under
np.errstate(all="ignore"): infinities stand for "no contact".
"""

from __future__ import annotations

import math

import numpy as np

from termpool.physics.vec import max_one, min_one

TOUCH = 1e-9  # gaps below this (m) count as touching
SINK = 4.5e-7  # a resting contact pushed together is caught after this much overlap (m):
# with anything deeper than SINK resolved at once, no overlap can pass 2 SINK < 1 micrometre
V_MIN = 1e-6  # closing speeds below this (m/s) are not an immediate contact
A_MIN = 1e-6  # m/s^2: a touching pair that neither closes nor parts but accelerates together
# faster than this is pressed together: a contact now (a resting one, joined.py); slower is
# rounding, and is caught by SINK if it lasts
PIECES = 4  # straight pieces of the window in the cull
try:  # the gufunc np.linalg.eigvals calls, without the checks around it (see `eigvals`)
    from numpy.linalg import _umath_linalg
    _EIGVALS = _umath_linalg.eigvals
except (ImportError, AttributeError):  # pragma: no cover (another numpy): its public form
    _EIGVALS = None
_FRACTIONS = np.arange(PIECES, dtype=float)
_PIECES_ONE = _FRACTIONS.tolist()


def first_contact(
    p0: np.ndarray, v: np.ndarray, a: np.ndarray, dist: np.ndarray, horizon: np.ndarray,
    pressed: bool = True,
) -> np.ndarray:
    """First t in [0, horizon] at which |p0 + v t + a t^2/2| falls to `dist`; inf if none.

    p0, v, a: (K, 2) relative position, velocity, acceleration; dist, horizon: (K,).
    Touching pairs (gap < TOUCH) that close faster than V_MIN meet at t = 0; touching pairs
    that do not close are looked for at a depth of SINK, so that a pair pushed together by
    friction is caught again after a bounded, sub-micrometre overlap instead of chattering.
    With `pressed`, a touching pair accelerating together meets at t = 0 as well.
    """
    return first_contact_rows(np.concatenate([p0.T, v.T, a.T]), dist, horizon, pressed)


def meeting_now(px, py, vx, vy, dist) -> tuple:
    """Relative positions and velocities (K,) and contact distances: (p.v, |p|, V_MIN |p|,
    touching, meeting now), where touching pairs (gap < TOUCH) that close faster than V_MIN,
    or have sunk deeper than SINK (left so by another contact), meet at once. (A touching
    pair pressed together meets at once too: `first_contact_rows` looks at those.)"""
    pv = px * vx + py * vy
    r0 = np.sqrt(px * px + py * py)
    touching = r0 - dist < TOUCH
    vr = V_MIN * r0  # (-(V_MIN r0) is -V_MIN r0, bit for bit)
    return pv, r0, vr, touching, touching & ((pv < -vr) | (r0 < dist - SINK))


def first_contact_rows(rel: np.ndarray, dist: np.ndarray, horizon: np.ndarray,
                       pressed: bool = True) -> np.ndarray:
    """`first_contact` of relative motions given as the rows of rel (6, K): x, y, vx, vy,
    ax, ay (the candidates that pass a cull are one take of it)."""
    px, py, vx, vy, ax, ay = rel
    pv, r0, vr, touching, now = meeting_now(px, py, vx, vy, dist)
    rest = (touching & ~now & (pv <= vr)).nonzero()[0] if pressed else ()
    if len(rest):
        # The distance's second derivative, (v.v + p.a) / r - (p.v)^2 / r^3.
        px_, py_, vx_, vy_, ax_, ay_ = rel.take(rest, axis=1)
        r_ = r0[rest]
        acc = ((vx_ * vx_ + vy_ * vy_ + px_ * ax_ + py_ * ay_) / r_
               - pv[rest] ** 2 / r_ ** 3)
        now[rest] = acc < -A_MIN
    target = np.where(touching, np.minimum(dist, r0) - SINK, dist)
    out = np.where(now, 0.0, np.inf)
    # First cull, cheap: the distance is at least the path's projection on the initial
    # direction, r0 + vn t + an t^2 / 2; a pair whose projection stays beyond the target over
    # the window (touching pairs moving apart, above all) cannot meet.
    vn = pv / r0
    an = (px * ax + py * ay) / r0
    tv = np.where(an > 0, np.minimum(np.maximum(-vn / an, 0.0), horizon), horizon)
    proj = np.minimum(r0 + (vn + 0.5 * an * tv) * tv, r0)
    keep = ((proj <= target) | ~(r0 > 0)) & ~now & (horizon > 0)  # (r0 = 0: keep, no divide)
    idx = keep.nonzero()[0]
    if idx.size == 0:
        return out
    # Second cull, on what is left: the window in PIECES straight pieces, each widened by the
    # most the acceleration can bend the path within it; a pair none of whose pieces comes
    # close cannot meet.
    rel = rel.take(idx, axis=1)
    px, py, vx, vy, ax, ay = rel
    hz, tg = horizon[idx], target[idx]
    vv = vx * vx + vy * vy
    aa = ax * ax + ay * ay
    h = hz / PIECES
    # (PIECES, K), a piece a row: each operation then runs along the candidates, contiguous.
    s0 = _FRACTIONS[:, None] * h  # piece start times
    qx = px + (vx + 0.5 * ax * s0) * s0
    qy = py + (vy + 0.5 * ay * s0) * s0
    wx = vx + ax * s0
    wy = vy + ay * s0
    ww = wx * wx + wy * wy
    ts = np.minimum(np.maximum(-(qx * wx + qy * wy) / ww, 0.0), h)
    ts = np.where(ww > 0, ts, 0.0)
    cx, cy = qx + wx * ts, qy + wy * ts
    reach = tg + 0.5 * np.sqrt(aa) * h * h
    close = (cx * cx + cy * cy <= reach * reach).any(axis=0) & ((vv > 0) | (aa > 0))
    sel = close.nonzero()[0]
    if sel.size == 0:
        return out
    idx = idx[sel]
    out[idx] = solve(*rel.take(sel, axis=1), hz[sel], tg[sel], pv[idx], r0[idx], vv[sel],
                     aa[sel])
    return out


def first_contact_few(cands: list, pressed: bool = True) -> list:
    """`first_contact` for a few candidates in plain floats: each of `cands` is a tuple
    (px, py, vx, vy, ax, ay, dist, horizon). The culls run in plain floats, operation for
    operation as the array version; only the pairs that pass them go to `solve`, in arrays,
    so the result is bit-identical."""
    out = []
    keep = []  # (place in out, px, py, vx, vy, ax, ay, horizon, target, pv, r0, vv, aa)
    for px, py, vx, vy, ax, ay, dist, horizon in cands:
        pv = px * vx + py * vy
        r0 = math.sqrt(px * px + py * py)
        touching = r0 - dist < TOUCH
        now = touching and (pv < -V_MIN * r0 or r0 < dist - SINK)
        if touching and not now and pv <= V_MIN * r0 and pressed:
            # numpy's array power can differ from the C library's in the last bit: cube
            # through numpy, as the array version does.
            acc = (_over(vx * vx + vy * vy + px * ax + py * ay, r0)
                   - _over(pv * pv, float((np.array([r0]) ** 3)[0])))
            now = acc < -A_MIN
        if now:
            out.append(0.0)
            continue
        out.append(math.inf)
        target = (min_one(dist, r0) - SINK) if touching else dist
        if r0 != 0.0:
            vn, an = pv / r0, (px * ax + py * ay) / r0
        else:
            vn, an = _over(pv, r0), _over(px * ax + py * ay, r0)
        if an > 0:  # (np.minimum and np.maximum written out, see vec.min_one)
            tv = -vn / an
            tv = tv if tv > 0.0 or tv != tv else 0.0
            tv = tv if tv < horizon or tv != tv else horizon
        else:
            tv = horizon
        proj = r0 + (vn + 0.5 * an * tv) * tv
        proj = proj if proj < r0 or proj != proj else r0
        if not ((proj <= target or not r0 > 0) and horizon > 0):
            continue
        vv = vx * vx + vy * vy
        aa = ax * ax + ay * ay
        h = horizon / PIECES
        reach = target + 0.5 * math.sqrt(aa) * h * h
        reach2 = reach * reach
        close = False
        for f in _PIECES_ONE:
            s0 = h * f
            qx = px + (vx + 0.5 * ax * s0) * s0
            qy = py + (vy + 0.5 * ay * s0) * s0
            wx = vx + ax * s0
            wy = vy + ay * s0
            ww = wx * wx + wy * wy
            ts = min_one(max_one(-(qx * wx + qy * wy) / ww, 0.0), h) if ww > 0 else 0.0
            cx, cy = qx + wx * ts, qy + wy * ts
            if cx * cx + cy * cy <= reach2:
                close = True
                break
        if close and (vv > 0 or aa > 0):
            keep.append((len(out) - 1, px, py, vx, vy, ax, ay, horizon, target, pv, r0, vv, aa))
    if keep:
        for k, t in zip((c[0] for c in keep), solve_few([c[1:] for c in keep]), strict=True):
            out[k] = t
    return out


def solve_few(pairs: list) -> list:
    """`solve` in plain floats, operation for operation, for pairs given as tuples of its
    arguments; only the quartics' eigenvalues go through numpy, all in one call, so the times
    are bit-identical."""
    coef = []
    for px, py, vx, vy, ax, ay, T, tg, pv, r0, vv, aa in pairs:
        c4 = 0.25 * aa
        c3 = ax * vx + ay * vy
        c2 = vv + ax * px + ay * py
        c1 = 2.0 * pv
        c0 = r0 * r0 - tg * tg
        T2 = T * T
        C4, C3, C2, C1 = c4 * T2 * T2, c3 * T2 * T, c2 * T2, c1 * T
        coef.append((c4, c3, c2, c1, c0, C4, C3, C2, C1, T, tg,
                     C4 > 1e-13 * (abs(C2) + abs(C1) + abs(c0))))
    quartics = [c for c in coef if c[-1]]
    if quartics:
        comp = np.zeros((len(quartics), 4, 4))
        comp[:, 1, 0] = comp[:, 2, 1] = comp[:, 3, 2] = 1.0
        top = []
        for _, _, _, _, c0, C4, C3, C2, C1, _, _, _ in quartics:
            inv = -1.0 / C4
            top.append((C3 * inv, C2 * inv, C1 * inv, c0 * inv))
        comp[:, 0] = top
        roots = iter(eigvals(comp).tolist())
    out = []
    for c4, c3, c2, c1, c0, C4, C3, C2, C1, T, tg, quartic in coef:
        s = math.inf
        if quartic:
            for root in next(roots):
                re = root.real
                slope = ((4 * C4 * re + 3 * C3) * re + 2 * C2) * re + C1
                if (abs(root.imag) <= 1e-6 * (1.0 + abs(re)) and re >= -1e-9 and re <= 1 + 1e-9
                        and slope <= 0 and re < s):
                    s = re
        else:
            A, B, C = C2, C1, c0
            disc = B * B - 4 * A * C
            root = _over(C, -0.5 * (B - math.sqrt(max_one(disc, 0.0))))
            if disc >= 0 and B < 0 and A > 0 and root >= -1e-9 and root <= 1 + 1e-9:
                s = root
        if not s < math.inf:
            out.append(math.inf)
            continue
        t = min_one(max_one(s, 0.0), 1.0) * T
        f = (((c4 * t + c3) * t + c2) * t + c1) * t + c0
        df = ((4 * c4 * t + 3 * c3) * t + 2 * c2) * t + c1
        d2 = (12 * c4 * t + 6 * c3) * t + 2 * c2
        band = 2 * tg * TOUCH
        if abs(f) <= band and df < -2 * tg * V_MIN and (d2 <= 0 or df * df > 8 * d2 * band):
            out.append(min_one(max_one(t - f / df, 0.0), T))
        else:
            out.append(_first_crossing(c4, c3, c2, c1, c0, T, tg))
    return out


def solve(px, py, vx, vy, ax, ay, T, tg, pv, r0, vv, aa) -> np.ndarray:
    """The contact times (inf: none) of the pairs that passed `first_contact`'s culls, from
    their relative motion, window T, target distance tg and the culls' pv = p.v, r0 = |p|,
    vv = |v|^2 and aa = |a|^2: the quartic's roots, checked and polished."""
    c4 = 0.25 * aa
    c3 = ax * vx + ay * vy
    c2 = vv + ax * px + ay * py
    c1 = 2.0 * pv
    c0 = r0 ** 2 - tg * tg
    # Work in s = t / T so that the interesting roots lie in [0, 1] whatever the window.
    T2 = T * T
    C4, C3, C2, C1 = c4 * T2 * T2, c3 * T2 * T, c2 * T2, c1 * T
    quartic = C4 > 1e-13 * (np.abs(C2) + np.abs(C1) + np.abs(c0))
    s = np.full(T.size, np.inf)
    q = quartic.nonzero()[0]
    if q.size:
        comp = np.zeros((q.size, 4, 4))
        top = comp[:, 0]
        inv = -1.0 / C4[q]
        top[:, 0] = C3[q] * inv
        top[:, 1] = C2[q] * inv
        top[:, 2] = C1[q] * inv
        top[:, 3] = c0[q] * inv
        comp[:, 1, 0] = comp[:, 2, 1] = comp[:, 3, 2] = 1.0
        roots = eigvals(comp)
        re = roots.real
        slope = ((4 * C4[q, None] * re + 3 * C3[q, None]) * re + 2 * C2[q, None]) * re + C1[q, None]
        ok = (np.abs(roots.imag) <= 1e-6 * (1.0 + np.abs(re))) & (re >= -1e-9) & (re <= 1 + 1e-9)
        s[q] = np.where(ok & (slope <= 0), re, np.inf).min(axis=1)
    d = (~quartic).nonzero()[0]
    if d.size:
        # Negligible curvature: the quadratic part gives the root, Newton below corrects it.
        A, B, C = C2[d], C1[d], c0[d]
        disc = B * B - 4 * A * C
        root = C / (-0.5 * (B - np.sqrt(np.maximum(disc, 0.0))))
        good = (disc >= 0) & (B < 0) & (A > 0) & (root >= -1e-9) & (root <= 1 + 1e-9)
        s[d] = np.where(good, root, np.inf)
    hit = s < np.inf
    if not hit.any():
        return s
    t = np.minimum(np.maximum(s, 0.0), 1.0) * T
    # Accept only a clear crossing: the pair touches at t (the gap within TOUCH), closes
    # faster than V_MIN, and would go on to overlap by more than TOUCH (the local parabola's
    # minimum, f - f'^2 / 2f'', is below -4 tg TOUCH); one Newton step on the unscaled
    # quartic then polishes it. A tangent path (a double root, where a Newton step divides
    # one rounding-level value by another) or a root the eigenvalues placed badly fails this
    # and is decided by `_first_crossing`, which is exact but slow, and rarely needed.
    f = (((c4 * t + c3) * t + c2) * t + c1) * t + c0
    df = ((4 * c4 * t + 3 * c3) * t + 2 * c2) * t + c1
    d2 = (12 * c4 * t + 6 * c3) * t + 2 * c2
    band = 2 * tg * TOUCH  # f is about 2 tg times the gap
    clear = (np.abs(f) <= band) & (df < -2 * tg * V_MIN) & ((d2 <= 0) | (df * df > 8 * d2 * band))
    t = np.minimum(np.maximum(t - np.where(clear, f / df, 0.0), 0.0), T)
    for k in (hit & ~clear).nonzero()[0].tolist():
        t[k] = _first_crossing(float(c4[k]), float(c3[k]), float(c2[k]), float(c1[k]),
                               float(c0[k]), float(T[k]), float(tg[k]))
    return np.where(hit, t, np.inf)


def eigvals(comp: np.ndarray) -> np.ndarray:
    """np.linalg.eigvals of real (K, n, n) matrices, the same numbers (as complex), without
    the checks and the error-state switch it wraps around LAPACK (some 20 us a call; callers
    run under np.errstate(all="ignore") already). What would make it raise, a matrix that is
    not finite or eigenvalues that do not converge (NaNs out), goes to it, so that it raises
    as before."""
    if _EIGVALS is None or not np.isfinite(comp).all():
        return np.linalg.eigvals(comp)
    w = _EIGVALS(comp, signature="d->D")
    return np.linalg.eigvals(comp) if np.isnan(w).any() else w


def _poly(c: tuple, t: float) -> float:
    """The quartic c = (c4, c3, c2, c1, c0) at t (Horner)."""
    c4, c3, c2, c1, c0 = c
    return (((c4 * t + c3) * t + c2) * t + c1) * t + c0


def _first_crossing(c4: float, c3: float, c2: float, c1: float, c0: float, T: float,
                    tg: float) -> float:
    """First t in [0, T] at which the quartic f (the squared distance minus tg^2, f(0) > 0)
    falls to zero and goes on to a real overlap; inf if it never does.

    The window is cut at the critical points of f into pieces on which f is monotone; the
    first piece that ends deeper than a TOUCH overlap holds the crossing, found by bisection
    kept honest by Newton steps. A path that only grazes (its deepest point within TOUCH of
    touching, an exact tangency above all) is no contact.
    """
    c = (c4, c3, c2, c1, c0)
    # Every root's real part is a breakpoint: one too many costs nothing, one missed (a
    # real root reported with a rounding-level imaginary part) could hide a dip.
    crit = [float(r.real) for r in np.roots([4 * c4, 3 * c3, 2 * c2, c1]) if 0.0 < r.real < T]
    # Polished against f', so that a tangency's minimum is found exactly.
    dc = (0.0, 4 * c4, 3 * c3, 2 * c2, c1)
    for n, r in enumerate(crit):
        for _ in range(3):
            d2 = (12 * c4 * r + 6 * c3) * r + 2 * c2
            if d2 == 0:
                break
            r = min(max(r - _poly(dc, r) / d2, 0.0), T)
        crit[n] = r
    deep = -2 * tg * TOUCH
    lo = 0.0
    for hi in sorted(crit) + [T]:
        if _poly(c, hi) >= deep:
            lo = hi
            continue
        if _poly(c, lo) <= 0.0:
            return lo
        for _ in range(200):  # f(lo) > 0 >= f(hi); f is monotone between them
            f_lo = _poly(c, lo)
            step = lo - f_lo / _poly(dc, lo) if _poly(dc, lo) < 0 else math.nan
            mid = step if lo < step < hi else 0.5 * (lo + hi)
            if not lo < mid < hi:
                break
            if _poly(c, mid) > 0.0:
                lo = mid
            else:
                hi = mid
        return hi
    return math.inf


def first_line_contact(
    s0: np.ndarray, sv: np.ndarray, sa: np.ndarray, dist: np.ndarray, horizon: np.ndarray,
    beside: np.ndarray,
) -> np.ndarray:
    """First t in [0, horizon] at which s0 + sv t + sa t^2/2 falls to `dist`; inf if none.

    s is a ball's signed distance from a cushion line (positive on the playing side).
    Touching and resting contacts are treated as in `first_contact`, but only where the ball
    is `beside` the cushion segment now: a ball off its end (just off a jaw tip, say) may be
    nearer the line than `dist` without touching anything, and meets the segment when it
    comes down to `dist` over it. A ball behind the line is only ignored beside the segment
    (it came through); off its end (in a pocket's mouth) it can still come out and meet it.
    """
    gap = s0 - dist
    touching = (gap < TOUCH) & beside
    front = s0 > 0  # the ball's centre is on the playing side of the line
    now = touching & ((sv < -V_MIN) | (gap < -SINK) | ((sv <= V_MIN) & (sa < -A_MIN))) & front
    C = np.where(touching, np.maximum(gap, 0.0) + SINK, gap)  # distance still to go
    A = 0.5 * sa
    disc = sv * sv - 4 * A * C
    sq = np.sqrt(disc)
    q = -0.5 * (sv + np.where(sv >= 0, sq, -sq))
    best = np.full(s0.shape, np.inf)
    # Roots of A t^2 + sv t + C = 0 where the distance is falling (derivative < 0).
    for r in (q / A, C / q):
        ok = (r >= 0) & (2 * A * r + sv < 0)
        best = np.where(ok & (r < best), r, best)
    best = np.where((A == 0) & (sv < 0) & (C >= 0), -C / sv, best)
    best = np.where((best <= horizon) & (front | ~beside), best, np.inf)
    return np.where(now, 0.0, best)


def _over(x: float, d: float) -> float:
    """x / d as numpy divides (d = 0 gives inf or nan instead of an exception)."""
    if d != 0.0:
        return x / d
    if x != x or x == 0.0:
        return math.nan
    return math.copysign(math.inf, x) * math.copysign(1.0, d)


def first_line_contact_one(s0: float, sv: float, sa: float, dist: float, horizon: float,
                           beside: bool) -> float:
    """`first_line_contact` for one ball and one line in plain floats, operation for
    operation as the array version, so the result is bit-identical."""
    gap = s0 - dist
    touching = gap < TOUCH and beside
    front = s0 > 0
    now = touching and (sv < -V_MIN or gap < -SINK or (sv <= V_MIN and sa < -A_MIN)) and front
    C = ((0.0 if gap < 0.0 else gap) + SINK) if touching else gap
    A = 0.5 * sa
    disc = sv * sv - 4 * A * C
    sq = math.sqrt(disc) if disc >= 0.0 else math.nan
    q = -0.5 * (sv + (sq if sv >= 0 else -sq))
    best = math.inf
    for r in (_over(q, A), _over(C, q)):
        if r >= 0 and 2 * A * r + sv < 0 and r < best:
            best = r
    if A == 0 and sv < 0 and C >= 0:
        best = _over(-C, sv)
    if not (best <= horizon and (front or not beside)):
        best = math.inf
    return 0.0 if now else best
