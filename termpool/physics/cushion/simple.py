"""The simple cushion: the horizontal normal speed reversed times e, then Coulomb friction at
the nose.

The game's first cushion model, kept to the bit so that records made with it replay exactly.
"""

from __future__ import annotations

import math

import numpy as np

from termpool.physics.cushion.model import CushionPhysics
from termpool.physics.vec import cross, cross_one, length, max_one, min_one, to3

# Restitution and nose friction when a scene gives none: the game's cushion from the start
# (the nominal values pooltool uses too).
E_CUSHION = 0.85
MU_CUSHION = 0.2


def bounce(n: np.ndarray, v: np.ndarray, w: np.ndarray, r: np.ndarray, m: np.ndarray,
           ph: CushionPhysics) -> tuple[np.ndarray, np.ndarray]:
    """Bounce balls off cushions with horizontal normals n (into the table); returns (v, w).

    The nose touches the ball above its centre (sin t = (h - R) / R), so friction at the
    nose acts on both side spin (running or reverse english) and top or back spin.
    The horizontal normal speed is reversed times e; friction is Coulomb, at most stopping
    the contact point's slip.
    """
    e, mu, height, v_inelastic = ph.e_cushion, ph.mu_cushion, ph.cushion_height, ph.v_inelastic
    sin_t = np.clip((height - r) / r, -0.95, 0.95)
    cos_t = np.sqrt(1.0 - sin_t * sin_t)
    approach = -np.einsum("ij,ij->i", v, n)
    ee = np.where(approach > v_inelastic, e, 0.0)
    p_h = (1.0 + ee) * m * np.maximum(approach, 0.0)
    v = v + (p_h / m)[:, None] * n
    n3 = to3(n)
    z = np.array([0.0, 0.0, 1.0])
    arm = r[:, None] * (-cos_t[:, None] * n3 + sin_t[:, None] * z)
    normal = -arm / r[:, None]
    slip = to3(v) + cross(w, arm)
    slip_t = slip - np.einsum("ij,ij->i", slip, normal)[:, None] * normal
    speed = length(slip_t)
    jt = np.minimum(mu * p_h / cos_t, speed * m / 3.5)
    with np.errstate(invalid="ignore", divide="ignore"):  # 0/0 where there is no slip
        dirn = np.where(speed[:, None] > 0, slip_t / speed[:, None], 0.0)
    imp = -jt[:, None] * dirn
    v = v + imp[:, :2] / m[:, None]
    w = w + cross(arm, imp) / (0.4 * m * r * r)[:, None]
    return v, w


def bounce_one(n: list, v: list, w: list, r: float, m: float,
               ph: CushionPhysics) -> tuple[list, list]:
    """`bounce` for one ball in plain floats (lists in, lists out), bit-identical to the
    array version (same operations in the same order; see contact.ball_ball_one)."""
    e, mu, height, v_inelastic = ph.e_cushion, ph.mu_cushion, ph.cushion_height, ph.v_inelastic
    n0, n1 = n
    sin_t = min(max((height - r) / r, -0.95), 0.95)
    cos_t = math.sqrt(1.0 - sin_t * sin_t)
    approach = -(v[0] * n0 + v[1] * n1)
    ee = e if approach > v_inelastic else 0.0
    p_h = (1.0 + ee) * m * max_one(approach, 0.0)
    k = p_h / m
    v = [v[0] + k * n0, v[1] + k * n1]
    c = -cos_t
    arm = [r * (c * n0 + sin_t * 0.0), r * (c * n1 + sin_t * 0.0), r * (c * 0.0 + sin_t * 1.0)]
    normal = [-x / r for x in arm]
    cw = cross_one(w, arm)
    slip = [v[0] + cw[0], v[1] + cw[1], 0.0 + cw[2]]
    sn = (slip[0] * normal[0] + slip[2] * normal[2]) + slip[1] * normal[1]
    st = [slip[x] - sn * normal[x] for x in range(3)]
    speed = math.sqrt((st[0] * st[0] + st[1] * st[1]) + st[2] * st[2])
    a, b = mu * p_h / cos_t, speed * m / 3.5
    jt = min_one(a, b)
    dirn = [x / speed for x in st] if speed > 0 else [0.0, 0.0, 0.0]
    imp = [-jt * x for x in dirn]
    v = [v[0] + imp[0] / m, v[1] + imp[1] / m]
    torque = cross_one(arm, imp)
    inertia = 0.4 * m * r * r
    w = [w[x] + torque[x] / inertia for x in range(3)]
    return v, w
