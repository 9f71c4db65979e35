"""The rail frame the cushion models work in, in array and plain-float forms.

For a cushion with horizontal normal n (into the table): x runs along the rail, t = (-n1, n0);
y points into the cushion, -n; z is up (x, y, z right-handed). The nose touches the ball at
R (0, cos t, sin t) from its centre, above the equator by sin t = (h - R) / R, clipped as
`params.nose_reach` clips it. The two forms do the same operations in the same order, so
they agree to the bit.
"""

from __future__ import annotations

import math

import numpy as np

from termpool.physics.vec import columns


def nose(r, height: float) -> tuple[np.ndarray, np.ndarray]:
    """(sin t, cos t) of the nose contact for balls of radii r (an array)."""
    sin_t = np.clip((height - r) / r, -0.95, 0.95)
    return sin_t, np.sqrt(1.0 - sin_t * sin_t)


def nose_one(r: float, height: float) -> tuple[float, float]:
    sin_t = min(max((height - r) / r, -0.95), 0.95)
    return sin_t, math.sqrt(1.0 - sin_t * sin_t)


def to_rail(n, v, w) -> tuple[np.ndarray, ...]:
    """(vx, vy, wx, wy, wz) in the rail frame; vy > 0 approaches the cushion."""
    n0, n1 = n[:, 0], n[:, 1]
    vx = v[:, 1] * n0 - v[:, 0] * n1
    vy = -(v[:, 0] * n0 + v[:, 1] * n1)
    wx = w[:, 1] * n0 - w[:, 0] * n1
    wy = -(w[:, 0] * n0 + w[:, 1] * n1)
    return vx, vy, wx, wy, w[:, 2]


def from_rail(n, vx, vy, wx, wy, wz) -> tuple[np.ndarray, np.ndarray]:
    """The table frame's v (K, 2) and w (K, 3) from rail-frame components."""
    n0, n1 = n[:, 0], n[:, 1]
    v = columns(-(vx * n1) - vy * n0, vx * n0 - vy * n1)
    w = columns(-(wx * n1) - wy * n0, wx * n0 - wy * n1, wz)
    return v, w


def to_rail_one(n: list, v: list, w: list) -> tuple[float, ...]:
    n0, n1 = n
    return (v[1] * n0 - v[0] * n1, -(v[0] * n0 + v[1] * n1),
            w[1] * n0 - w[0] * n1, -(w[0] * n0 + w[1] * n1), w[2])


def from_rail_one(n: list, vx, vy, wx, wy, wz) -> tuple[list, list]:
    n0, n1 = n
    return ([-(vx * n1) - vy * n0, vx * n0 - vy * n1],
            [-(wx * n1) - wy * n0, wx * n0 - wy * n1, wz])
