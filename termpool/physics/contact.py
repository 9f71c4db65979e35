"""Impulse responses at ball-ball contacts (vectorized over contacts).

Impulses act at the contact point of rigid spheres. Vertical components of linear velocity
that an impulse would give are absorbed by the slate (no jumping), which can only remove
energy. Friction never exceeds the impulse that stops the slip, so no contact adds energy.
"""

from __future__ import annotations

import math

import numpy as np

from termpool.physics.vec import cross, cross_one, to3


def ball_ball(
    pi, pj, vi, vj, wi, wj, ri, rj, mi, mj, e, v_inelastic, frictional
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Collide balls i and j (arrays over K contacts); returns new (vi, vj, wi, wj)."""
    d = pj - pi
    n = d / np.linalg.norm(d, axis=1)[:, None]
    closing = np.einsum("ij,ij->i", vi - vj, n)
    ee = np.where(closing > v_inelastic, e, 0.0)
    inv = 1.0 / mi + 1.0 / mj
    jn = (1.0 + ee) * np.maximum(closing, 0.0) / inv
    vi = vi - (jn / mi)[:, None] * n
    vj = vj + (jn / mj)[:, None] * n
    if not frictional:
        return vi, vj, wi, wj
    n3 = to3(n)
    arm_i = ri[:, None] * n3
    arm_j = -rj[:, None] * n3
    slip = (to3(vi) + cross(wi, arm_i)) - (to3(vj) + cross(wj, arm_j))
    slip_t = slip - np.einsum("ij,ij->i", slip, n3)[:, None] * n3
    speed = np.linalg.norm(slip_t, axis=1)
    # Alciatore's fit: ball-ball friction falls with the sliding speed at the contact.
    mu = 0.00995 + 0.108 * np.exp(-1.088 * speed)
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


def ball_ball_one(pi, pj, vi, vj, wi, wj, ri, rj, mi, mj, e, v_inelastic, frictional):
    """`ball_ball` for one contact in plain floats (lists in, lists out), operation for
    operation as the array version does it, so the results are bit-identical (numpy's row
    sums and norms of 2 and 3 components add in the order written here; exp goes through
    numpy, whose last bit can differ from the C library's)."""
    d0, d1 = pj[0] - pi[0], pj[1] - pi[1]
    nrm = math.sqrt(d0 * d0 + d1 * d1)
    n0, n1 = d0 / nrm, d1 / nrm
    closing = (vi[0] - vj[0]) * n0 + (vi[1] - vj[1]) * n1
    ee = e if closing > v_inelastic else 0.0
    inv = 1.0 / mi + 1.0 / mj
    jn = (1.0 + ee) * (closing if not closing < 0.0 else 0.0) / inv
    ki, kj = jn / mi, jn / mj
    vi = [vi[0] - ki * n0, vi[1] - ki * n1]
    vj = [vj[0] + kj * n0, vj[1] + kj * n1]
    if not frictional:
        return vi, vj, list(wi), list(wj)
    arm_i = [ri * n0, ri * n1, ri * 0.0]
    arm_j = [-rj * n0, -rj * n1, -rj * 0.0]
    ci, cj = cross_one(wi, arm_i), cross_one(wj, arm_j)
    slip = [(vi[0] + ci[0]) - (vj[0] + cj[0]), (vi[1] + ci[1]) - (vj[1] + cj[1]),
            (0.0 + ci[2]) - (0.0 + cj[2])]
    sn = (slip[0] * n0 + slip[2] * 0.0) + slip[1] * n1
    st = [slip[0] - sn * n0, slip[1] - sn * n1, slip[2] - sn * 0.0]
    speed = math.sqrt((st[0] * st[0] + st[1] * st[1]) + st[2] * st[2])
    # Alciatore's fit: ball-ball friction falls with the sliding speed at the contact.
    mu = 0.00995 + 0.108 * float(np.exp(-1.088 * speed))
    k = 3.5 * inv
    a, b = mu * jn, speed / k
    jt = a if (a <= b or a != a) else b  # np.minimum, nan included
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
