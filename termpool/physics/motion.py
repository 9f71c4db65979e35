"""A ball's motion on the cloth between events: starting it (its state, accelerations and the
time of its next transition) and evaluating it, in array and plain-float forms.

Within a state a ball moves on a quadratic from its clock t0 (physics-notes: sliding,
rolling, spinning), packed in one row (`Col`). An event usually starts the motion of one or
two balls, and on arrays that small the cost is the number of numpy calls (about a
microsecond each), not the arithmetic: `start` and `at` do for one ball what `start_many`
and `at_many` do for many, operation for operation in the same order, so the results are
bit-identical (IEEE +, -, *, / and sqrt round the same in Python and numpy; hypot goes
through numpy, since the C library's and Python's own can differ in the last bit).
`tests/test_models.py` and `tests/test_motion.py` hold the two forms to that.
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
from termpool.physics.vec import columns, max_one, perp

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


def slip(v: np.ndarray, w: np.ndarray, R: np.ndarray) -> tuple:
    """The contact point's slip u = v + R (z x w) of balls with velocities v (K, 2), spins
    w (K, 3) and radii R (K,), as (ux, uy, |u|). (Worked a component at a time: numpy
    takes an operation on (K, 2) rows with a (K, 1) column two elements at a time.)"""
    ux = v[:, 0] + R * (w[:, 1] * -1.0)
    uy = v[:, 1] + R * w[:, 0]
    return ux, uy, _hypot(ux, uy)


def snap(ph: Physics, p, v, w, R, rate, only=None, move: bool = True) -> tuple:
    """Complete tiny slides at once: returns (p, v, w, t_s), t_s = 0 where nothing changed.

    A slip u with |u| <= EPS_U ends after t_s = |u| / (3.5 mu_s g) with v -= u / 3.5 and
    the ball rolling. With `move`, the returned p is where the slide ends,
    p + v t_s - mu_s g t_s^2 u/2|u|, and side spin has decayed (at `rate`) for t_s: a ball
    started rolling from there at t + t_s follows the exact path from then on, and before
    then (extrapolated back) strays from the slide by under 20 nm at 1 mm/s. Without it
    only the velocities change (the solves of slow contacts, whose clocks stay put). w is
    changed in place. No snap on frictionless cloth, where a slide never ends.
    """
    return _snap(ph, p, v, w, R, rate, slip(v, w, R), only, move)[:4]


def _snap(ph: Physics, p, v, w, R, rate, u: tuple, only, move: bool) -> tuple:
    """`snap` given the balls' `slip` u; returns (p, v, w, t_s, whether any slide ended)."""
    ux, uy, us = u
    small = (us <= EPS_U) & (us > 0) & (ph.mu_slide > 0)
    if only is not None:
        small &= only
    ts = np.where(small, us / (3.5 * ph.mu_slide * ph.g), 0.0)
    if not small.any():
        return p, v, w, ts, False
    u = columns(ux, uy)
    s = small[:, None]
    if move:
        uhat = u / np.where(us > 0, us, 1.0)[:, None]
        p = np.where(s, p + (v - 0.5 * ph.mu_slide * ph.g * ts[:, None] * uhat) * ts[:, None],
                     p)
        wz = w[:, 2]
        w[:, 2] = np.copysign(np.maximum(np.abs(wz) - rate * ts, 0.0), wz)
    v = np.where(s, v - u / 3.5, v)
    w[:, :2] = np.where(s, perp(v) / R[:, None], w[:, :2])
    return p, v, w, ts, True


def start_many(ph: Physics, t, p, v, w, R, rate, pocketed) -> tuple:
    """New motions of K balls from times t at (p, v, w), radii R, side-spin decay rates `rate`,
    `pocketed` (K,) bools: returns (state, t_trans, rows), rows (K, Col.RATE) the packed
    motions. w is changed in place. (Worked a component at a time, as `start` is.)"""
    g, mu_s, mu_r = ph.g, ph.mu_slide, ph.mu_roll
    u = slip(v, w, R)
    p, v, w, ts, snapped = _snap(ph, p, v, w, R, rate, u, None, True)
    t = t + ts
    ux, uy, us = slip(v, w, R) if snapped else u
    vx, vy = v[:, 0], v[:, 1]
    vs, wza = _hypot(vx, vy), np.abs(w[:, 2])
    live = ~pocketed
    sliding = (us > (EPS_U if mu_s > 0 else 0.0)) & live
    rolling = ~sliding & (vs > EPS_V) & live
    spinning = ~sliding & ~rolling & (wza > EPS_W) & live
    still = ~(sliding | rolling)
    vx, vy = np.where(still, 0.0, vx), np.where(still, 0.0, vy)
    # Rolling is kept exact (slip zero); still balls keep only their side spin.
    w[:, 0] = wx = np.where(rolling, (vy * -1.0) / R, np.where(still, 0.0, w[:, 0]))
    w[:, 1] = wy = np.where(rolling, vx / R, np.where(still, 0.0, w[:, 1]))
    w[:, 2] = wz = np.where(spinning | ~still, w[:, 2], 0.0)
    uhx, uhy = np.where(sliding, ux / us, 0.0), np.where(sliding, uy / us, 0.0)
    vhx, vhy = np.where(rolling, vx / vs, 0.0), np.where(rolling, vy / vs, 0.0)
    ax = -mu_s * g * uhx - mu_r * g * vhx
    ay = -mu_s * g * uhy - mu_r * g * vhy
    k = 2.5 * mu_s * g / R
    alx = np.where(sliding, k * (uhy * -1.0), (ay * -1.0) / R)
    aly = np.where(sliding, k * uhx, ax / R)
    dt = np.where(sliding, us / (3.5 * mu_s * g),
                  np.where(rolling, vs / (mu_r * g),
                           np.where(spinning, wza / rate, np.inf)))
    dt = np.where(np.isnan(dt) | pocketed, np.inf, dt)
    state = np.where(sliding, SLIDING, np.where(rolling, ROLLING,
                                                  np.where(spinning, SPINNING, STATIONARY)))
    state = np.where(pocketed, POCKETED, state)
    rows = np.array([t, p[:, 0], p[:, 1], vx, vy, ax, ay, wx, wy, wz, alx, aly]).T
    return state, t + dt, rows


def start(ph: Physics, t: float, p: list, v: list, w: list, R: float, rate: float,
          pocketed: bool) -> tuple[int, float, list]:
    """`start_many` for one ball in plain floats: returns (state, t_trans, row), row the
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


def _moved(p0, v0, acc, d) -> tuple:
    """Position and velocity a time d after (p0, v0) at constant acceleration."""
    return p0 + (v0 + 0.5 * acc * d) * d, v0 + acc * d


def at_planes(rows: np.ndarray, t) -> np.ndarray:
    """`at_many` without spin as six planes: (6, ...) x, y, vx, vy, ax, ay at times t of
    balls whose packed motions are `rows` (..., Col.N); each plane contiguous. The columns
    read (t0, position, velocity, acceleration) are copied into planes once, and `_moved`'s
    arithmetic done there in place, operation for operation (the same bits)."""
    planes = rows[..., :Col.AY + 1].transpose((-1,) + tuple(range(rows.ndim - 1))).copy()
    d = t - planes[Col.T0]
    a = planes[Col.ACC]
    step = 0.5 * a  # p0 + (v0 + 0.5 a d) d
    step *= d
    step += planes[Col.V]
    step *= d
    planes[Col.P] += step
    planes[Col.V] += a * d  # v0 + a d
    return planes[Col.PX:]


def at_many(rows: np.ndarray, t, spin: bool = True) -> tuple:
    """Position, velocity and (if `spin`, else None) spin at times t of balls whose packed
    motions are `rows` (..., Col.N), a copy: its spin columns are changed in place."""
    d = (t - rows[..., Col.T0])[..., None]
    p, v = _moved(rows[..., Col.P], rows[..., Col.V], rows[..., Col.ACC], d)
    if not spin:
        return p, v, None
    w = rows[..., Col.W]
    w[..., :2] += rows[..., Col.ALPHA] * d
    wz = w[..., 2]
    # Before t0 (a ball whose tiny slide was completed ahead, see snap) spin is held.
    decay = rows[..., Col.RATE] * np.maximum(d[..., 0], 0.0)
    w[..., 2] = np.copysign(np.maximum(np.abs(wz) - decay, 0.0), wz)
    return p, v, w


def at(row: list, t: float) -> tuple[list, list, list]:
    """`at_many` for one ball in plain floats: its position, velocity and spin at time t."""
    t0, px, py, vx, vy, ax, ay, wx, wy, wz, alx, aly, rate = row[:Col.RADIUS]  # Col's order
    d = t - t0
    p = [px + (vx + 0.5 * ax * d) * d, py + (vy + 0.5 * ay * d) * d]
    v = [vx + ax * d, vy + ay * d]
    # Before t0 (a ball whose tiny slide was completed ahead) spin is held.
    decay = rate * max_one(d, 0.0)
    w = [wx + alx * d, wy + aly * d, math.copysign(max_one(abs(wz) - decay, 0.0), wz)]
    return p, v, w


def swept(p: np.ndarray, v: np.ndarray, a: np.ndarray, T: np.ndarray) -> tuple:
    """(lo, hi): the box, coordinate by coordinate, that the quadratic p + v s + a s^2 / 2
    sweeps over s in [0, T] (T >= 0): its ends and, where it turns inside the window, its
    vertex. Exact up to rounding (a few ulps of the coordinates). (Worked in place: the
    operations of p + (v + 0.5 a T) T and the rest, in their order.)"""
    ha = 0.5 * a
    e = ha * T
    e += v
    e *= T
    e += p
    s = np.minimum(np.maximum(-v / a, 0.0), T)  # the vertex; nan where v = a = 0 (no vertex)
    m = ha * s
    m += v
    m *= s
    m += p
    return np.fmin(np.minimum(p, e), m), np.fmax(np.maximum(p, e), m)
