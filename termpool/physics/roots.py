"""Continuous contact detection: first time two quadratic paths come within a distance.

Between events every ball moves on a quadratic p(t) = p0 + v t + a t^2 / 2, so the squared
distance of two balls (or of a ball and a fixed point) is a quartic in t and the distance of a
ball from a straight cushion is a quadratic. These routines find the first approaching root
inside a window, vectorized over many pairs, exactly (companion-matrix eigenvalues polished by
Newton steps) so that nothing tunnels whatever the step.
"""

from __future__ import annotations

import numpy as np

TOUCH = 1e-9  # gaps below this (m) count as touching
SINK = 4e-7  # a resting contact pushed together is caught after this much overlap (m)
V_MIN = 1e-9  # closing speeds below this (m/s) are not an immediate contact


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def first_contact(
    p0: np.ndarray, v: np.ndarray, a: np.ndarray, dist: np.ndarray, horizon: np.ndarray
) -> np.ndarray:
    """First t in [0, horizon] at which |p0 + v t + a t^2/2| falls to `dist`; inf if none.

    p0, v, a: (K, 2) relative position, velocity, acceleration; dist, horizon: (K,).
    Touching pairs (gap < TOUCH) that close faster than V_MIN meet at t = 0; touching pairs
    that do not close are looked for at a depth of SINK, so that a pair pushed together by
    friction is caught again after a bounded, sub-micrometre overlap instead of chattering.
    """
    K = p0.shape[0]
    out = np.full(K, np.inf)
    if K == 0:
        return out
    r0 = np.sqrt(_dot(p0, p0))
    gap = r0 - dist
    closing = -_dot(p0, v) / np.maximum(r0, 1e-300)
    touching = gap < TOUCH
    out[touching & (closing > V_MIN)] = 0.0
    target = np.where(touching, np.minimum(dist, r0) - SINK, dist)
    # Cull: straight-line closest approach, widened by the most the acceleration can bend it.
    vv = _dot(v, v)
    with np.errstate(divide="ignore", invalid="ignore"):
        ts = np.clip(np.where(vv > 0, -_dot(p0, v) / vv, 0.0), 0.0, horizon)
    closest = p0 + v * ts[:, None]
    amag = np.sqrt(_dot(a, a))
    bend = 0.5 * amag * horizon * horizon
    cand = (np.sqrt(_dot(closest, closest)) - bend <= target) & (out != 0.0) & (horizon > 0)
    cand &= (vv > 0) | (amag > 0)
    idx = np.flatnonzero(cand)
    if idx.size == 0:
        return out
    p, vel, acc, tgt, T = p0[idx], v[idx], a[idx], target[idx], horizon[idx]
    c4 = 0.25 * _dot(acc, acc)
    c3 = _dot(acc, vel)
    c2 = _dot(vel, vel) + _dot(acc, p)
    c1 = 2.0 * _dot(p, vel)
    c0 = _dot(p, p) - tgt * tgt
    # Work in s = t / T so that the interesting roots lie in [0, 1] whatever the window.
    C4, C3, C2, C1 = c4 * T**4, c3 * T**3, c2 * T**2, c1 * T
    scale = np.abs(C2) + np.abs(C1) + np.abs(c0)
    quartic = C4 > 1e-13 * scale
    s = np.full(idx.size, np.inf)
    q = np.flatnonzero(quartic)
    if q.size:
        comp = np.zeros((q.size, 4, 4))
        comp[:, 0, 0] = -C3[q] / C4[q]
        comp[:, 0, 1] = -C2[q] / C4[q]
        comp[:, 0, 2] = -C1[q] / C4[q]
        comp[:, 0, 3] = -c0[q] / C4[q]
        comp[:, 1, 0] = comp[:, 2, 1] = comp[:, 3, 2] = 1.0
        roots = np.linalg.eigvals(comp)
        re = roots.real
        ok = (np.abs(roots.imag) <= 1e-6 * (1.0 + np.abs(re))) & (re >= -1e-9) & (re <= 1 + 1e-9)
        dfd = ((4 * C4[q, None] * re + 3 * C3[q, None]) * re + 2 * C2[q, None]) * re + C1[q, None]
        ok &= dfd <= 0
        s[q] = np.where(ok, re, np.inf).min(axis=1)
    d = np.flatnonzero(~quartic)
    if d.size:
        # Negligible curvature: the quadratic part gives the root, Newton below corrects it.
        A, B, C = C2[d], C1[d], c0[d]
        disc = B * B - 4 * A * C
        with np.errstate(divide="ignore", invalid="ignore"):
            qq = -0.5 * (B - np.sqrt(np.maximum(disc, 0.0)))
            root = np.where(qq != 0, C / qq, np.inf)
        good = (disc >= 0) & (B < 0) & (A > 0)
        s[d] = np.where(good & (root >= -1e-9) & (root <= 1 + 1e-9), root, np.inf)
    hit = np.isfinite(s)
    t = np.clip(s, 0.0, 1.0) * T
    # Newton polish on the unscaled quartic.
    for _ in range(2):
        f = (((c4 * t + c3) * t + c2) * t + c1) * t + c0
        df = ((4 * c4 * t + 3 * c3) * t + 2 * c2) * t + c1
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(df < 0, f / df, 0.0)
        t = np.clip(t - np.where(hit, step, 0.0), 0.0, T)
    out[idx] = np.where(hit, t, np.inf)
    return out


def first_line_contact(
    s0: np.ndarray, sv: np.ndarray, sa: np.ndarray, dist: np.ndarray, horizon: np.ndarray
) -> np.ndarray:
    """First t in [0, horizon] at which s0 + sv t + sa t^2/2 falls to `dist`; inf if none.

    s is a ball's signed distance from a cushion line (positive on the playing side).
    Touching and resting contacts are treated as in `first_contact`.
    """
    out = np.full(s0.shape, np.inf)
    gap = s0 - dist
    touching = gap < TOUCH
    front = s0 > 0  # the ball's centre is on the playing side of the line
    out[touching & (sv < -V_MIN) & front] = 0.0
    C = np.where(touching, np.maximum(gap, 0.0) + SINK, gap)  # distance still to go
    A, B = 0.5 * sa, sv
    disc = B * B - 4 * A * C
    sq = np.sqrt(np.maximum(disc, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        q = -0.5 * (B + np.where(B >= 0, sq, -sq))
        r1 = np.where(A != 0, q / A, np.inf)
        r2 = np.where(q != 0, C / q, np.inf)
    # Roots of A t^2 + B t + C = 0 where the distance is falling (derivative < 0).
    best = np.full(s0.shape, np.inf)
    for r in (r1, r2):
        with np.errstate(invalid="ignore"):
            ok = np.isfinite(r) & (r >= 0) & (2 * A * r + B < 0) & (disc >= 0)
        best = np.where(ok & (r < best), r, best)
    lin = (A == 0) & (B < 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        best = np.where(lin, -C / B, best)
    best = np.where((best <= horizon) & front, best, np.inf)
    return np.where(out == 0.0, 0.0, best)
