"""A ball's motion state ends (physics-notes, motion on the cloth): sliding ends with the slip
exactly zero, so the ball rolls on; rolling ends with no translation, so the ball only spins
or rests; spinning ends with the side spin gone. The ball then starts its next motion from
what is left (motion.start)."""

from __future__ import annotations

import numpy as np

from termpool.physics.state import ROLLING, SLIDING, SPINNING
from termpool.physics.vec import perp


def end(st, v, w, R) -> tuple[np.ndarray, np.ndarray]:
    """Velocities and spins of K balls in states st (K,) at the end of that state; w is
    changed in place."""
    w[:, :2] = np.where((st == SLIDING)[:, None], perp(v) / R[:, None], w[:, :2])
    rl = (st == ROLLING)[:, None]
    v = np.where(rl, 0.0, v)
    w[:, :2] = np.where(rl, 0.0, w[:, :2])
    w[:, 2] = np.where(st == SPINNING, 0.0, w[:, 2])
    return v, w


def end_one(st: int, v: list, w: list, R: float) -> tuple[list, list]:
    """`end` for one ball in plain floats, bit-identical to it."""
    w = list(w)
    if st == SLIDING:
        w[0], w[1] = (v[1] * -1.0) / R, (v[0] * 1.0) / R
    elif st == ROLLING:
        v = [0.0, 0.0]
        w[0] = w[1] = 0.0
    elif st == SPINNING:
        w[2] = 0.0
    return list(v), w
