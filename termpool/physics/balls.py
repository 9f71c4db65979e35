"""The balls of a batch of tables: their sizes and masses, motion states, pockets, and each
ball's motion since its own clock, with starting and evaluating motions.

A ball nobody touches is never updated: its motion is a quadratic from its clock t0, packed in
one row of `motion` (columns `motion.Col`), so that evaluating balls takes one gather (the
cost of a pass is the number of numpy calls, not the data). Up to FEW balls at once take the
plain-float forms, which agree with the array forms bit for bit.
"""

from __future__ import annotations

from array import array

import numpy as np

from termpool.physics import motion
from termpool.physics.events import BallState
from termpool.physics.flat import flat
from termpool.physics.motion import Col
from termpool.physics.params import Physics, nose_reach
from termpool.physics.state import POCKETED

FEW = 4  # up to this many balls, events work in plain floats (most events move one or two)


def _batch(x, shape: tuple, name: str) -> np.ndarray:
    arr = np.asarray(x, dtype=float)
    try:
        return np.broadcast_to(arr, shape).copy()
    except ValueError:
        raise ValueError(f"{name}: shape {arr.shape} does not fit {shape}") from None


def ball_arrays(pos, vel, w, radius, mass) -> tuple:
    """The engine's ball arguments as (batched, pos (B, N, 2), vel (B, N, 2), w (B, N, 3),
    radius (B, N), mass (B, N)), checked: pos (N, 2) or (B, N, 2), batched when it has the
    table axis; the others broadcast to it (vel and w None: at rest); radius and mass
    positive and finite. Raises ValueError naming the argument."""
    pos = np.asarray(pos, dtype=float)
    if pos.ndim not in (2, 3) or pos.shape[-1] != 2:
        raise ValueError(f"pos: shape {pos.shape} is not (N, 2) or (B, N, 2)")
    batched = pos.ndim == 3
    if not batched:
        pos = pos[None]
    B, N = pos.shape[:2]
    lead = (B, N) if batched else (N,)
    vel = _batch(np.zeros(2) if vel is None else vel, lead + (2,), "vel").reshape(B, N, 2)
    w = _batch(np.zeros(3) if w is None else w, lead + (3,), "w").reshape(B, N, 3)
    radius = _batch(radius, lead, "radius").reshape(B, N)
    mass = _batch(mass, lead, "mass").reshape(B, N)
    for name, arr in (("radius", radius), ("mass", mass)):
        if not (arr > 0).all() or not np.isfinite(arr).all():
            raise ValueError(f"{name}: must be positive and finite")
    return batched, pos, vel, w, radius, mass


class Balls:
    """B tables of N balls. `t_trans` (B, N) receives each ball's time of its next motion
    transition (the engine keeps it among its predictions)."""

    def __init__(self, physics: Physics, radius: np.ndarray, mass: np.ndarray,
                 t_trans: np.ndarray) -> None:
        self.physics = physics
        self.B, self.N = radius.shape
        self.radius, self.mass = radius, mass
        self.rc = nose_reach(radius, physics.cushion_height)  # centre to nose at contact
        self.spin_rate = 2.5 * physics.mu_spin * physics.g / radius
        self.motion = np.zeros((self.B, self.N, Col.N))
        self._rows = self.motion.reshape(-1, Col.N)  # a ball's row at b N + i (a view)
        # Views of the motion's columns.
        self.t0 = self.motion[..., Col.T0]
        self.p0 = self.motion[..., Col.P]
        self.v0 = self.motion[..., Col.V]
        self.acc = self.motion[..., Col.ACC]
        self.w0 = self.motion[..., Col.W]
        self.alpha = self.motion[..., Col.ALPHA]
        self.motion[..., Col.RATE] = self.spin_rate
        self.motion[..., Col.RADIUS] = radius
        self.motion[..., Col.MASS] = mass
        self.state = np.zeros((self.B, self.N), dtype=np.int8)
        self.pocket = np.full((self.B, self.N), -1, dtype=np.int16)  # pocket index, or -1
        self.t_trans = t_trans
        # Flat views for the plain-float paths (flat.py); the transition times live in the
        # schedule's rows of times, which `flat_times` views (width apart).
        self.flat_motion, self.flat_state = flat(self.motion), flat(self.state)
        self.flat_rc = flat(self.rc)
        self.flat_times: memoryview | None = None
        self.width = 0

    def eval(self, b, i, t, spin: bool = True):
        """Position, velocity and (if `spin`) spin of balls (b, i) at times t."""
        # One take of whole rows by a flat index: a two-index lookup costs several times more.
        return motion.at_many(self._rows.take(np.asarray(b) * self.N + i, axis=0), t, spin)

    def planes(self, tabs: np.ndarray, t: np.ndarray) -> np.ndarray:
        """Every ball of tables `tabs` at times t (one a table, (T, 1)) as six planes
        (motion.at_planes): (6, T N) x, y, vx, vy, ax, ay, ball i of tabs[u] at u N + i;
        the same bits as `eval`."""
        return motion.at_planes(self.motion.take(tabs, axis=0), t).reshape(6, -1)

    def set(self, b, i, t, p, v, w) -> None:
        """Start new motion for balls (b, i) at times t from (p, v, w): classify the state,
        set accelerations and the time of the next transition."""
        if b.size <= FEW:
            self.set_few(b, i, t, p, v, w)
        else:
            self.set_many(b, i, t, p, v, w)

    def set_few(self, b, i, t, p, v, w) -> None:
        """`set` one ball at a time in plain floats (motion.start): bit-identical, and faster
        than numpy calls on arrays of one or two balls."""
        ph = self.physics
        self.write_few(b, i, [motion.start(ph, *args) for args in zip(
            t.tolist(), p.tolist(), v.tolist(), w.tolist(), self.radius[b, i].tolist(),
            self.spin_rate[b, i].tolist(), (self.state[b, i] == POCKETED).tolist(),
            strict=True)])

    def set_many(self, b, i, t, p, v, w) -> None:
        """`set` on arrays (motion.start_many)."""
        state, self.t_trans[b, i], self.motion[b, i, :Col.RATE] = motion.start_many(
            self.physics, t, p, v, w, self.radius[b, i], self.spin_rate[b, i],
            self.state[b, i] == POCKETED)
        self.state[b, i] = state

    def write_few(self, b, i, out: list) -> None:
        """Store motion.start's results for balls (b, i) (arrays or lists), through the flat
        views when the schedule's rows of times are known to them."""
        if self.flat_times is None:
            state, t_trans, rows = zip(*out, strict=True)
            self.state[b, i] = state
            self.t_trans[b, i] = t_trans
            self.motion[b, i, :Col.RATE] = rows
            return
        N, W, C = self.N, self.width, Col.N
        st, tt, mm = self.flat_state, self.flat_times, self.flat_motion
        bl = b.tolist() if isinstance(b, np.ndarray) else b
        il = i.tolist() if isinstance(i, np.ndarray) else i
        for bm, im, (state, t_trans, row) in zip(bl, il, out, strict=True):
            st[bm * N + im] = state
            tt[bm * W + im] = t_trans
            k = (bm * N + im) * C
            mm[k:k + Col.RATE] = array("d", row)

    def ball_state(self, b: int, i: int, t: float) -> BallState:
        """Ball i of table b as it is at time t."""
        p, v, w = motion.at(self.motion[b, i].tolist(), float(t))  # `eval` in plain floats
        return BallState(p[0], p[1], v[0], v[1], (w[0], w[1], w[2]), int(self.state[b, i]))

    def now(self, tb: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(B, N, 2) positions, (B, N, 2) velocities and (B, N, 3) spins at each table's clock
        tb (pocketed balls sit at their pocket's centre)."""
        B, N = self.B, self.N
        b, i = np.divmod(np.arange(B * N), N)
        p, v, w = self.eval(b, i, tb[b])
        return p.reshape(B, N, 2), v.reshape(B, N, 2), w.reshape(B, N, 3)
