"""A resting contact's sub-micrometre sink into a cushion undone: a ball found a little deeper
than its reach rc (by at most a couple of roots.SINK) is lifted back along the feature's normal
before it starts its new motion."""

from __future__ import annotations

import numpy as np

from termpool.physics.vec import max_one


def lift(p, ref, n, rc) -> np.ndarray:
    """Positions of K balls at p, each meeting the feature through point ref with unit normal
    n (into the table) at reach rc, with any sink undone."""
    depth = rc - np.einsum("ij,ij->i", p - ref, n)
    return p + np.maximum(depth, 0.0)[:, None] * n


def lift_one(p: list, ref: list, n: list, rc: float) -> list:
    """`lift` for one ball in plain floats, bit-identical to it (a row sum starts from +0.0)."""
    depth = rc - ((0.0 + (p[0] - ref[0]) * n[0]) + (p[1] - ref[1]) * n[1])
    up = max_one(depth, 0.0)
    return [p[0] + up * n[0], p[1] + up * n[1]]
