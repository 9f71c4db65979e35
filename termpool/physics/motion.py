"""Starting one ball's motion in plain Python floats: the engine's path for one or two balls.

An event usually starts the motion of one or two balls, and on arrays that small the cost is
the number of numpy calls (about a microsecond each), not the arithmetic. `start` does for
one ball what `Engine._set` does for many, operation for operation in the same order, so the
results are bit-identical (IEEE +, -, *, / and sqrt round the same in Python and numpy;
hypot goes through numpy, since the C library's and Python's own can differ in the last bit).
`tests/test_motion.py` holds the two paths to that.
"""

from __future__ import annotations

import math

import numpy as np

from termpool.physics.params import Physics
from termpool.physics.state import (
    EPS_U,
    EPS_V,
    EPS_W,
    POCKETED,
    ROLLING,
    SLIDING,
    SPINNING,
    STATIONARY,
)
from termpool.physics.vec import max_one

_hypot = np.hypot
INF = math.inf


class Col:
    """The columns of a ball's packed motion, a row of the engine's motion array: its clock
    t0; its position, velocity and acceleration at t0; its spin at t0 and the rate of change
    of (wx, wy); then the ball's constants: side-spin decay rate, radius and mass. A new
    motion (`start`) writes the columns before RATE."""

    T0, PX, PY, VX, VY, AX, AY, WX, WY, WZ, ALX, ALY, RATE, RADIUS, MASS = range(15)
    N = 15
    P, V, ACC, W, ALPHA = slice(1, 3), slice(3, 5), slice(5, 7), slice(7, 10), slice(10, 12)


def _over(x: float, d: float) -> float:
    """x / d as numpy divides (d = 0 gives inf or nan instead of an exception)."""
    if d != 0.0:
        return x / d
    if x != x or x == 0.0:
        return math.nan
    return math.copysign(INF, x) * math.copysign(1.0, d)


def start(ph: Physics, t: float, p: list, v: list, w: list, R: float, rate: float,
          pocketed: bool) -> tuple[int, float, list]:
    """One ball's new motion from time t at (p, v, w): returns (state, t_trans, row), row the
    ball's packed motion up to Col.RATE (t0, p0, v0, acc, w0, alpha)."""
    g, mu_s, mu_r = ph.g, ph.mu_slide, ph.mu_roll
    px, py = p
    vx, vy = v
    wx, wy, wz = w
    ux = vx + R * (wy * -1.0)  # contact-point slip, v + R (z x w)
    uy = vy + R * (wx * 1.0)
    us = float(_hypot(ux, uy))
    # A tiny slide is completed at once: the ball starts rolling where and when it ends.
    if us <= EPS_U and us > 0 and mu_s > 0:
        ts = _over(us, 3.5 * mu_s * g)
        uhx, uhy = ux / us, uy / us
        k = 0.5 * mu_s * g * ts
        px = px + (vx - k * uhx) * ts
        py = py + (vy - k * uhy) * ts
        wz = math.copysign(max_one(abs(wz) - rate * ts, 0.0), wz)
        vx = vx - ux / 3.5
        vy = vy - uy / 3.5
        wx = (vy * -1.0) / R
        wy = (vx * 1.0) / R
        t = t + ts
        ux = vx + R * (wy * -1.0)
        uy = vy + R * (wx * 1.0)
        us = float(_hypot(ux, uy))
    vs = float(_hypot(vx, vy))
    wza = abs(wz)
    live = not pocketed
    sliding = us > (EPS_U if mu_s > 0 else 0.0) and live
    rolling = not sliding and vs > EPS_V and live
    spinning = not sliding and not rolling and wza > EPS_W and live
    still = not (sliding or rolling)
    if still:
        vx = vy = 0.0
    if rolling:  # rolling is kept exact (slip zero); still balls keep only their side spin
        wx = (vy * -1.0) / R
        wy = (vx * 1.0) / R
    elif still:
        wx = wy = 0.0
    if not (spinning or not still):
        wz = 0.0
    uhx = uhy = vhx = vhy = 0.0
    if sliding:
        uhx, uhy = _over(ux, us), _over(uy, us)
    if rolling:
        vhx, vhy = _over(vx, vs), _over(vy, vs)
    ax = -mu_s * g * uhx - mu_r * g * vhx
    ay = -mu_s * g * uhy - mu_r * g * vhy
    if sliding:
        k = _over(2.5 * mu_s * g, R)
        alx, aly = k * (uhy * -1.0), k * (uhx * 1.0)
        dt = _over(us, 3.5 * mu_s * g)
    else:
        alx, aly = _over(ay * -1.0, R), _over(ax * 1.0, R)
        dt = (_over(vs, mu_r * g) if rolling else _over(wza, rate) if spinning else INF)
    if dt != dt or pocketed:
        dt = INF
    state = (POCKETED if pocketed else SLIDING if sliding else ROLLING if rolling
             else SPINNING if spinning else STATIONARY)
    return state, t + dt, [t, px, py, vx, vy, ax, ay, wx, wy, wz, alx, aly]


def at(row: list, t: float) -> tuple[list, list, list]:
    """Position, velocity and spin at time t of a ball whose packed motion is `row` (a row of
    the engine's motion array): Engine._eval for one ball."""
    t0, px, py, vx, vy, ax, ay, wx, wy, wz, alx, aly, rate = row[:Col.RADIUS]  # Col's order
    d = t - t0
    p = [px + (vx + 0.5 * ax * d) * d, py + (vy + 0.5 * ay * d) * d]
    v = [vx + ax * d, vy + ay * d]
    # Before t0 (a ball whose tiny slide was completed ahead) spin is held.
    decay = rate * max_one(d, 0.0)
    w = [wx + alx * d, wy + aly * d, math.copysign(max_one(abs(wz) - decay, 0.0), wz)]
    return p, v, w
