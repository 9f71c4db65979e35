"""Shot geometry for the computer opponent (termpool.ai): pockets as targets, ghost-ball pots
and their chance under an aim error, blocked paths, one-rail kick aims, rough pot speeds.

Cheap and vectorized: it prunes and ranks candidates and values a table for whoever shoots
next; what a shot really does is left to the engine.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from termpool.physics import libm
from termpool.physics.params import Physics
from termpool.physics.table import Table

MAX_CUT = 80.0  # degrees; thinner cuts are not tried as pots
CORNER_LIMIT, SIDE_LIMIT = 60.0, 45.0  # degrees off a pocket's axis that still drop


class Pockets(NamedTuple):
    """The pockets as targets, in the table's hole_names order."""

    names: tuple[str, ...]
    aim: np.ndarray  # (P, 2) where an object ball is sent: a ball radius past the mouth
    out: np.ndarray  # (P, 2) unit vector from the mouth into the pocket
    half: np.ndarray  # (P,) half the mouth
    cos_limit: np.ndarray  # (P,) steepest approach that still drops


def pocket_geometry(table: Table, radius: float) -> Pockets:
    """Where to send a ball of `radius` into each pocket, and from which directions it drops."""
    n = len(table.hole_names)
    if n == 0:
        z = np.zeros((0, 2))
        return Pockets((), z, z, np.zeros(0), np.zeros(0))
    tips = table.points.reshape(n, 2, 2)  # two jaw tips per pocket, in hole_names order
    mid = tips.mean(axis=1)
    out = table.hole_c - mid
    out /= np.linalg.norm(out, axis=1)[:, None]
    half = np.linalg.norm(tips[:, 0] - tips[:, 1], axis=1) / 2
    side = np.array([name.startswith("side") for name in table.hole_names])
    limit = np.radians(np.where(side, SIDE_LIMIT, CORNER_LIMIT))
    return Pockets(tuple(table.hole_names), mid + radius * out, out, half, libm.cos(limit))


def blocked(a: np.ndarray, b: np.ndarray, obst: np.ndarray, rad_move, rad_obst: np.ndarray,
            skip: np.ndarray) -> np.ndarray:
    """True where a ball of radius rad_move going from a to b would touch an obstacle.

    a, b: (S, 2) segments; obst: (S, K, 2); rad_move: a number or (S,); rad_obst: (K,);
    skip: (S, K) obstacles to ignore.
    """
    d = b - a
    length2 = np.maximum((d * d).sum(-1), 1e-12)
    rel = obst - a[:, None]  # (S, K, 2)
    s = np.clip((rel * d[:, None]).sum(-1) / length2[:, None], 0.0, 1.0)
    gap = rel - s[..., None] * d[:, None]
    reach = np.asarray(rad_move, dtype=float)
    reach = (reach[:, None] if reach.ndim else reach) + rad_obst[None]
    close = (gap * gap).sum(-1) < reach ** 2 - 1e-9
    return (close & ~skip).any(-1)


def pot_chances(cue: np.ndarray, balls: np.ndarray, alive: np.ndarray, target: np.ndarray,
                radius: np.ndarray, cue_idx: int, pockets: Pockets, table: Table,
                sigma: float) -> tuple[np.ndarray, np.ndarray]:
    """Chance (B, N, P) that a straight pot of ball i into pocket p goes in from `cue`.

    cue: (B, 2); balls: (B, N, 2); alive, target: (B, N) bool. The chance is that of an aim
    error (sd `sigma` degrees) staying within the pot's tolerance: the mouth seen from the
    object ball, shrunk by the distances and the cut. Blocked paths and thin cuts give 0.
    Also returns the contact normals u (B, N, P, 2).
    """
    B, N = balls.shape[:2]
    P = len(pockets.names)
    if P == 0:
        return np.zeros((B, N, 0)), np.zeros((B, N, 0, 2))
    rc = radius[cue_idx]
    u = pockets.aim[None, None] - balls[:, :, None]  # (B, N, P, 2)
    d2 = np.linalg.norm(u, axis=-1)
    u = u / np.maximum(d2, 1e-9)[..., None]
    ghost = balls[:, :, None] - (rc + radius)[None, :, None, None] * u
    c = ghost - cue[:, None, None]
    d1 = np.linalg.norm(c, axis=-1)
    c = c / np.maximum(d1, 1e-9)[..., None]
    cos_cut = (c * u).sum(-1)
    approach = (u * pockets.out[None, None]).sum(-1)
    ok = target[:, :, None] & alive[:, :, None] & (cos_cut > math.cos(math.radians(MAX_CUT)))
    ok &= approach > pockets.cos_limit[None, None]
    ok &= d1 > 1e-3  # a cue ball frozen to the ghost spot has no line to aim along
    gx, gy = ghost[..., 0], ghost[..., 1]
    ok &= (gx >= rc) & (gx <= table.length - rc) & (gy >= rc) & (gy <= table.width - rc)
    tol = np.maximum(pockets.half[None, None] * approach - 0.6 * rc, 0.004)
    chance = pot_chance(tol, d1, d2, cos_cut, (rc + radius)[None, :, None], sigma)
    # Blockers: every live ball but the target (and the cue ball on the cue's own path).
    # Only the pots still open are checked: most (ball, pocket) pairs are closed already.
    ok = ok.reshape(B, N * P)
    bi, mi = np.nonzero(ok)
    if bi.size:
        ni, pi = np.divmod(mi, P)
        idx = np.arange(N)
        obst = balls[bi]  # (S, N, 2)
        skip_t = (ni[:, None] == idx[None]) | ~alive[bi]
        skip_c = skip_t | (idx == cue_idx)[None]
        g = ghost.reshape(B, N * P, 2)[bi, mi]
        path1 = blocked(cue[bi], g, obst, rc, radius, skip_c)
        path2 = blocked(balls[bi, ni], pockets.aim[pi], obst, radius[ni], radius, skip_t)
        shut = path1 | path2  # the cue ball blocks the object ball's path too
        ok[bi[shut], mi[shut]] = False
    ok = ok.reshape(B, N, P)
    return np.where(ok, chance, 0.0), u


def pot_chance(tol, d1, d2, cos_cut, reach, sigma: float):  # numbers or arrays
    """Chance that a cue aim error (sd `sigma` degrees) keeps the object ball within `tol` of
    its line at distance d2. The cue ball travels d1 to the ghost ball; `reach` is the sum of
    the two radii. An aim error e turns the contact normal by about e d1 / (reach cos cut),
    so the tolerance on the object ball's heading, tol / d2, maps back through that factor."""
    cue_tol = (tol / np.maximum(d2, 1e-3)) * reach * np.maximum(cos_cut, 1e-3) / np.maximum(
        d1, 1e-3)
    return erf(cue_tol / (math.radians(sigma) * math.sqrt(2.0)))


def erf(x: np.ndarray) -> np.ndarray:
    # Abramowitz-Stegun 7.1.26 (error under 1.5e-7), for x >= 0: numpy has no erf.
    t = 1.0 / (1.0 + 0.3275911 * x)
    poly = t * (0.254829592 + t * (-0.284496736 + t * (1.421413741 + t * (
        -1.453152027 + t * 1.061405429))))
    return 1.0 - poly * libm.exp(-x * x)


def leave_value(chance: np.ndarray) -> np.ndarray:
    """How good a table is for whoever shoots next, 0..1: the best pot plus a little for
    each other makeable one (more choices are worth more)."""
    flat = chance.reshape(chance.shape[0], -1)
    best = flat.max(axis=1, initial=0.0)
    count = np.minimum((flat > 0.3).sum(axis=1), 4)
    return np.minimum(best + 0.05 * count, 1.0) / 1.2


def deg(v) -> float:
    """Direction of a 2-vector in degrees, as cue.strike takes it."""
    return math.degrees(math.atan2(float(v[1]), float(v[0])))


def pot_speed(d1: float, d2: float, cos_cut: float, physics: Physics) -> float:
    """About the slowest cue speed that rolls the object ball into the pocket.

    A ball rolls a distance d from speed sqrt(2 mu_r g d); a struck or hit ball leaves sliding
    and rolls at 5/7 of its speed; the cue ball passes cos(cut) of its speed on (times
    (1 + e) / 2)."""
    a = physics.mu_roll * physics.g
    v_obj = math.sqrt(2 * a * (d2 + 0.3)) * 1.4
    v_hit = v_obj / max(cos_cut, 0.2) / ((1 + physics.e_ball) / 2)
    return math.sqrt(v_hit * v_hit + 2 * a * d1) * 1.4


def _rails(table: Table, rc: float) -> list[tuple[int, float]]:
    """The four lines a ball's centre meets the rails on, as (axis, coordinate)."""
    return [(1, rc), (1, table.width - rc), (0, rc), (0, table.length - rc)]


def _image(p: np.ndarray, axis: int, line: float, bounce: float) -> np.ndarray:
    """Where p seems to be seen through a rail: a rebound keeps the speed along the rail and
    `bounce` of the speed across it, so a ball heading for p after the rail travels as if
    straight to p's image, 1/bounce times as deep behind the line (a mirror at bounce = 1)."""
    q = np.array(p, dtype=float)
    q[axis] = line - (q[axis] - line) / bounce
    return q


def kick_aims(pc: np.ndarray, pt: np.ndarray, table: Table, rc: float, bounce: float,
              rails: int = 1) -> list[float]:
    """Aim angles (degrees) of kicks from pc to pt: one-rail kicks, one per rail, or with
    rails=2 two-rail kicks, one per ordered pair of different rails. The ball's centre meets
    a rail on the line rc from its nose."""
    lines = _rails(table, rc)
    aims = []
    if rails == 1:
        for axis, line in lines:
            if abs(float(pc[axis]) - line) + abs(float(pt[axis]) - line) > 1e-9:
                aims.append(deg(_image(pt, axis, line, bounce) - pc))
        return aims
    for first in lines:
        for second in lines:
            if second != first:  # unfold the path: the last rail's image, then the first's
                img = _image(_image(pt, *second, bounce), *first, bounce)
                aims.append(deg(img - pc))
    return aims


def contact_offset(table: Table, physics: Physics, radius: float) -> float:
    """How far a ball's centre stops from a cushion nose (the nose is above the centre)."""
    sin_t = min(max((physics.cushion_height - radius) / radius, -0.95), 0.95)
    return radius * math.sqrt(1 - sin_t * sin_t)
