"""A resting contact's sub-micrometre sink undone: two balls found overlapping (by at most a
couple of SINK, roots.py) are moved apart along their line of centres before they start their
new motion, each by a share of the overlap in proportion to its inverse mass."""

from __future__ import annotations

import numpy as np

from termpool.physics.vec import max_one, norm


def undo(pi, pj, ri, rj, mi, mj) -> tuple[np.ndarray, np.ndarray]:
    """Positions of balls i and j (arrays over K pairs) with their overlap undone."""
    d = pj - pi
    dist = norm(d)
    n = d / dist[:, None]
    depth = np.maximum(ri + rj - dist, 0.0)
    share = mj / (mi + mj)
    return pi - (depth * share)[:, None] * n, pj + (depth * (1.0 - share))[:, None] * n


def undo_one(pi: list, pj: list, ri: float, rj: float, mi: float, mj: float) -> tuple:
    """`undo` for one pair in plain floats, bit-identical to it (the centres apart)."""
    d0, d1 = pj[0] - pi[0], pj[1] - pi[1]
    dist = float(np.hypot(d0, d1))
    n0, n1 = d0 / dist, d1 / dist
    depth = max_one(ri + rj - dist, 0.0)
    share = mj / (mi + mj)
    ki, kj = depth * share, depth * (1.0 - share)
    return [pi[0] - ki * n0, pi[1] - ki * n1], [pj[0] + kj * n0, pj[1] + kj * n1]
