"""Frictionless balls: the relative normal speed reversed times e, momentum kept, spins
untouched (the textbook impulse; with e = 1 a stun shot leaves the cue ball at 90 degrees)."""

from __future__ import annotations

import math

import numpy as np

from termpool.physics.vec import length, max_one


def impulse(pi, pj, vi, vj, mi, mj, e: float, v_inelastic: float) -> tuple:
    """The normal impulse of contacts (arrays over K): returns (n, jn, inv, vi, vj), n the unit
    normal from i to j, jn the impulse, inv = 1/mi + 1/mj, and the velocities after it."""
    d = pj - pi
    n = d / length(d)[:, None]
    closing = np.einsum("ij,ij->i", vi - vj, n)
    ee = np.where(closing > v_inelastic, e, 0.0)
    inv = 1.0 / mi + 1.0 / mj
    jn = (1.0 + ee) * np.maximum(closing, 0.0) / inv
    vi = vi - (jn / mi)[:, None] * n
    vj = vj + (jn / mj)[:, None] * n
    return n, jn, inv, vi, vj


def impulse_one(pi, pj, vi, vj, mi, mj, e: float, v_inelastic: float) -> tuple:
    """`impulse` for one contact in plain floats, operation for operation (numpy's norm of
    two components adds in the order written here); n is returned as (n0, n1)."""
    d0, d1 = pj[0] - pi[0], pj[1] - pi[1]
    nrm = math.sqrt(d0 * d0 + d1 * d1)
    n0, n1 = d0 / nrm, d1 / nrm
    # numpy's row sum starts from +0.0: a sum of -0.0 terms comes out +0.0 there too.
    closing = (0.0 + (vi[0] - vj[0]) * n0) + (vi[1] - vj[1]) * n1
    ee = e if closing > v_inelastic else 0.0
    inv = 1.0 / mi + 1.0 / mj
    jn = (1.0 + ee) * max_one(closing, 0.0) / inv
    ki, kj = jn / mi, jn / mj
    vi = [vi[0] - ki * n0, vi[1] - ki * n1]
    vj = [vj[0] + kj * n0, vj[1] + kj * n1]
    return (n0, n1), jn, inv, vi, vj


def collide(pi, pj, vi, vj, wi, wj, ri, rj, mi, mj, ph) -> tuple:
    """Collide balls i and j (arrays over K contacts); returns new (vi, vj, wi, wj)."""
    _, _, _, vi, vj = impulse(pi, pj, vi, vj, mi, mj, ph.e_ball, ph.v_inelastic)
    return vi, vj, wi, wj


def collide_one(pi, pj, vi, vj, wi, wj, ri, rj, mi, mj, ph) -> tuple:
    """`collide` for one contact in plain floats, bit-identical to it."""
    _, _, _, vi, vj = impulse_one(pi, pj, vi, vj, mi, mj, ph.e_ball, ph.v_inelastic)
    return vi, vj, list(wi), list(wj)
