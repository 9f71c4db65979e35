"""Balls with friction between them (Alciatore): after the normal impulse (frictionless.py), a
tangential impulse against the slip of the contact points, up to mu times the normal one and
never more than stops the slip, so no contact adds energy. mu falls with the sliding speed
(Alciatore's fit, 0.00995 + 0.108 exp(-1.088 v)): cut-induced throw of 1-5 degrees, more
for slow shots, and spin passed from ball to ball."""

from __future__ import annotations

import math

import numpy as np

from termpool.physics import libm
from termpool.physics.ball_ball.frictionless import impulse, impulse_one
from termpool.physics.vec import cross, cross_one, length, min_one, to3


def collide(pi, pj, vi, vj, wi, wj, ri, rj, mi, mj, ph) -> tuple:
    """Collide balls i and j (arrays over K contacts); returns new (vi, vj, wi, wj)."""
    n, jn, inv, vi, vj = impulse(pi, pj, vi, vj, mi, mj, ph.e_ball, ph.v_inelastic)
    n3 = to3(n)
    arm_i = ri[:, None] * n3
    arm_j = -rj[:, None] * n3
    slip = (to3(vi) + cross(wi, arm_i)) - (to3(vj) + cross(wj, arm_j))
    slip_t = slip - np.einsum("ij,ij->i", slip, n3)[:, None] * n3
    speed = length(slip_t)
    mu = 0.00995 + 0.108 * libm.exp(-1.088 * speed)
    k = 3.5 * inv  # 1/mi + 1/mj + R^2/I terms of two solid spheres
    jt = np.minimum(mu * jn, speed / k)
    dirn = np.where(speed[:, None] > 0, slip_t / speed[:, None], 0.0)
    imp = -jt[:, None] * dirn  # on ball i
    ii = 0.4 * mi * ri * ri
    ij = 0.4 * mj * rj * rj
    vi = vi + imp[:, :2] / mi[:, None]
    vj = vj - imp[:, :2] / mj[:, None]
    wi = wi + cross(arm_i, imp) / ii[:, None]
    wj = wj + cross(arm_j, -imp) / ij[:, None]
    return vi, vj, wi, wj


def collide_one(pi, pj, vi, vj, wi, wj, ri, rj, mi, mj, ph) -> tuple:
    """`collide` for one contact in plain floats, operation for operation as the array version
    does it, so the results are bit-identical (numpy's row sums and norms of 2 and 3
    components add in the order written here; exp is the C library's in both: libm.py)."""
    (n0, n1), jn, inv, vi, vj = impulse_one(pi, pj, vi, vj, mi, mj, ph.e_ball, ph.v_inelastic)
    arm_i = [ri * n0, ri * n1, ri * 0.0]
    arm_j = [-rj * n0, -rj * n1, -rj * 0.0]
    ci, cj = cross_one(wi, arm_i), cross_one(wj, arm_j)
    slip = [(vi[0] + ci[0]) - (vj[0] + cj[0]), (vi[1] + ci[1]) - (vj[1] + cj[1]),
            (0.0 + ci[2]) - (0.0 + cj[2])]
    sn = (slip[0] * n0 + slip[2] * 0.0) + slip[1] * n1
    st = [slip[0] - sn * n0, slip[1] - sn * n1, slip[2] - sn * 0.0]
    speed = math.sqrt((st[0] * st[0] + st[1] * st[1]) + st[2] * st[2])
    mu = 0.00995 + 0.108 * math.exp(-1.088 * speed)
    k = 3.5 * inv
    a, b = mu * jn, speed / k
    jt = min_one(a, b)
    dirn = [x / speed for x in st] if speed > 0 else [0.0, 0.0, 0.0]
    imp = [-jt * x for x in dirn]
    ii = 0.4 * mi * ri * ri
    ij = 0.4 * mj * rj * rj
    vi = [vi[0] + imp[0] / mi, vi[1] + imp[1] / mi]
    vj = [vj[0] - imp[0] / mj, vj[1] - imp[1] / mj]
    ti = cross_one(arm_i, imp)
    tj = cross_one(arm_j, [-x for x in imp])
    wi = [wi[k] + ti[k] / ii for k in range(3)]
    wj = [wj[k] + tj[k] / ij for k in range(3)]
    return vi, vj, wi, wj
