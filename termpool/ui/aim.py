"""Aiming geometry: where the cue ball first meets something along a straight line.

The aid is a straight cast of the cue ball's centre: against every other ball on the table
(contact when the centres are r_cue + r_i apart), against the cushion noses (lines offset by a
gap, the cue ball's radius unless told), against the jaw tips (circles of that gap) and against
the pocket holes (the ball drops when its centre reaches a hole's radius, as in the engine).
All of it is one vectorized pass; nothing here knows about the terminal.

The cast ignores cloth friction and spin: it is where a ball struck without spin would go,
which is what a player's aiming line shows. For a ball hit, the object ball leaves along the
line of centres at contact and a stunned cue ball along the tangent line (square to it).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from termpool.physics.params import BALL_RADIUS
from termpool.physics.table import Table

# A touching ball counts as hit only when the aim closes on it by more than this (m per m of
# travel): aiming exactly along the tangent of a touching ball passes it by.
CLOSING_EPS = 1e-12


class Aim(NamedTuple):
    ghost: tuple[float, float]  # cue-ball centre where it first meets something (m)
    hit: str  # "ball" | "cushion" | "pocket" | "none"
    ball: int | None  # index of the ball hit
    object_dir: tuple[float, float] | None  # unit direction the object ball leaves along
    cue_dir: tuple[float, float] | None  # the stunned cue ball's tangent line after contact
    cut: float | None  # cut angle in degrees (0 = full ball)


def aim_direction(angle_deg: float) -> tuple[float, float]:
    """Unit vector at angle_deg counter-clockwise from +x; exact at multiples of 90 degrees,
    so that a straight shot along an axis stays exactly on it."""
    q, r = divmod(float(angle_deg), 90.0)
    if r == 0.0:
        return ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(q) % 4]
    a = math.radians(angle_deg)
    return (math.cos(a), math.sin(a))


def _circle_hits(c: np.ndarray, d: np.ndarray, centres: np.ndarray,
                 dist: np.ndarray) -> np.ndarray:
    """Distance along the unit ray c + t d at which it comes within `dist` of each centre;
    inf where it never does. A ray starting inside (or touching) a circle meets it at 0 if it
    heads inwards, never if it heads out."""
    w = centres - c
    b = w @ d  # closing rate: how far along the ray the centre lies
    cc = np.einsum("ij,ij->i", w, w) - dist * dist
    disc = b * b - cc
    hit = (b > CLOSING_EPS) & (disc >= 0.0)
    # cc / (b + sqrt) is b - sqrt(disc) without the cancellation of a far, thin hit.
    root = np.sqrt(np.where(hit, disc, 0.0))
    t = np.where(hit, cc / np.where(hit, b + root, 1.0), np.inf)
    return np.maximum(t, 0.0)


def _line_hits(c: np.ndarray, d: np.ndarray, table: Table, gap: float) -> np.ndarray:
    """Distance along the ray at which the centre comes `gap` from each cushion segment's
    line, heading into it, with the contact beside the segment (its ends are the jaw tips,
    cast as circles); inf where it does not."""
    a, b, n = table.seg_a, table.seg_b, table.seg_n
    s0 = np.einsum("ij,ij->i", c - a, n)  # the centre's height above each nose line
    dn = n @ d
    toward = (dn < 0.0) & (s0 >= 0.0)  # on the table side, moving at the nose
    t = np.where(toward, (gap - s0) / np.where(toward, dn, -1.0), np.inf)
    t = np.maximum(t, 0.0)
    seg = b - a
    seg_len = np.hypot(seg[:, 0], seg[:, 1])
    u = seg / seg_len[:, None]
    tt = np.where(np.isfinite(t), t, 0.0)
    along = np.einsum("ij,ij->i", c + tt[:, None] * d - a, u)
    return np.where(np.isfinite(t) & (along >= 0.0) & (along <= seg_len), t, np.inf)


def aim_trace(table: Table, pos, radius, on_table, cue: int, angle_deg: float, *,
              rail_gap: float | None = None) -> Aim:
    """Cast the cue ball's centre from pos[cue] along angle_deg (ccw from +x); the first thing
    it meets wins (a ball on a tie).

    pos (N, 2) or (1, N, 2) m; radius a number, (N,) or None (the standard ball); on_table
    None (all) or a boolean mask
    (N,) of balls still on the table (pocketed balls are ignored). rail_gap is the centre's
    distance from a cushion nose (and a jaw tip) at contact: the cue ball's radius by default;
    pass the engine's `rc` for the cue ball to match its cushion contacts exactly.
    With no hit (a ball outside the cushions), ghost is a point well beyond the table.
    """
    if not math.isfinite(angle_deg):
        raise ValueError("aim.angle: must be finite")
    p = np.asarray(pos, dtype=float).reshape(-1, 2)
    n = p.shape[0]
    if not isinstance(cue, (int, np.integer)) or not 0 <= cue < n:
        raise ValueError(f"aim.cue: no ball {cue} among {n}")
    rad = np.broadcast_to(np.asarray(BALL_RADIUS if radius is None else radius, float), (n,))
    if on_table is None:
        alive = np.ones(n, dtype=bool)
    else:
        alive = np.asarray(on_table).reshape(-1)
        # Engine state codes would pass as numbers and silently mean the wrong thing.
        if alive.dtype != bool:
            raise ValueError("aim.on_table: must be booleans (e.g. state != POCKETED), "
                             f"not {alive.dtype}")
    if alive.shape[0] != n:
        raise ValueError(f"aim.on_table: {alive.shape[0]} flags for {n} balls")
    c = p[cue]
    if not np.isfinite(c).all():
        raise ValueError(f"aim.pos: cue ball {cue} has no finite position")
    d = np.array(aim_direction(angle_deg))
    r_cue = float(rad[cue])
    gap = r_cue if rail_gap is None else float(rail_gap)

    others = alive & np.isfinite(p).all(axis=1)
    others[cue] = False
    idx = np.flatnonzero(others)
    npt = len(table.points)
    centres = np.concatenate([p[idx], table.points.reshape(-1, 2), table.hole_c.reshape(-1, 2)])
    dist = np.concatenate([rad[idx] + r_cue, np.full(npt, gap), table.hole_r])
    with np.errstate(all="ignore"):
        t_circ = _circle_hits(c, d, centres, dist)
        t_line = _line_hits(c, d, table, gap)
    nb = idx.size
    # Order: balls, cushion lines, jaw tips, holes; argmin takes the first of equal times.
    t_all = np.concatenate([t_circ[:nb], t_line, t_circ[nb:]])
    k = int(np.argmin(t_all)) if t_all.size else 0
    if t_all.size == 0 or not np.isfinite(t_all[k]):
        far = c + d * 2.0 * (table.length + table.width)
        return Aim((float(far[0]), float(far[1])), "none", None, None, None, None)
    t = float(t_all[k])
    g = c + t * d
    ghost = (float(g[0]), float(g[1]))
    if k >= nb + len(t_line) + npt:
        return Aim(ghost, "pocket", None, None, None, None)
    if k >= nb:
        return Aim(ghost, "cushion", None, None, None, None)
    i = int(idx[k])
    line = p[i] - g
    obj = line / math.hypot(line[0], line[1])
    cosc = min(1.0, max(-1.0, float(obj @ d)))
    tangent = d - cosc * obj
    tl = math.hypot(tangent[0], tangent[1])
    # A full-ball hit leaves the stunned cue ball no tangent to follow: it stops.
    cue_dir = None if tl < 1e-12 else (float(tangent[0] / tl), float(tangent[1] / tl))
    return Aim(ghost, "ball", i, (float(obj[0]), float(obj[1])), cue_dir,
               math.degrees(math.acos(cosc)))
