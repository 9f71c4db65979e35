"""Frame-stepping baselines for `termpool bench accuracy` (the game never uses them).

Both schemes move every ball by explicit Euler, ``p += v dt``, and look for contacts only at
the end of each frame: a pair that overlaps there and is closing collides, a ball past a
cushion bounces, a ball whose centre is over a pocket drops. Anything that happens and
un-happens inside one frame is missed (a fast ball tunnels through another), and every
contact is handled up to a frame late, at an overlapping position. They take the same
`Table` and `Physics` as the `Engine` and expose the same driving surface (`step(dt)`,
`time`, `steps`, `at_rest()`, `pos`, `state`, `pocket`, `events`) so the benchmark can run
all schemes with one loop.

- `NaiveSim` is the seed game's scheme, the baseline: no spin at all. Friction is subtracted
  from the speed each frame (``|v| -= mu_roll g dt``, clamped at zero), so a struck ball rolls
  off at its full speed instead of sliding down to 5/7 of it. Ball-ball contacts are
  frictionless equal-mass impulses with `e_ball`; the cushions are straight walls one radius
  inside the cushion noses that mirror a ball with `e_cushion`; pockets are circles at the
  mouths (a corner's at the corner, a side's at the middle of its rail) of radius half the
  mouth. With ``substeps=k`` every frame is run as k frames of dt / k (the "substep" scheme).
- `EulerSim` is the engine's own model stepped the naive way: sliding, rolling and spinning
  friction (a slip that would reverse within a frame is completed to rolling), the engine's
  contact laws (the ball-ball model, the scene's cushion model with spin), the table's real rails,
  jaws, jaw tips and pocket holes. Its error is the stepping error alone.

Events are dicts like the engine's: ``{"t", "type", "i"}`` plus ``"feature"`` for cushions
and ``"pocket"`` for pockets, stamped with the time of the frame end that found them.
"""

from __future__ import annotations

import math

import numpy as np

from termpool.physics import cushion
from termpool.physics.ball_ball import MODELS as BALL_BALL
from termpool.physics.params import BALL_MASS, BALL_RADIUS, Physics
from termpool.physics.state import POCKETED, ROLLING, SPINNING, STATIONARY
from termpool.physics.table import POCKET_NAMES, Table
from termpool.physics.vec import norm as _norm
from termpool.physics.vec import perp as _perp

TINY = 1e-300  # keeps 0 / 0 out of speed updates
EPS_SLIP = 1e-9  # m/s: a slip below this is rounding error of a rolling ball


class _FrameSim:
    """What both schemes share: state arrays, the frame loop, pocketing and the event log."""

    def __init__(self, table: Table, physics: Physics, pos, vel=None, w=None,
                 radius=BALL_RADIUS, mass=BALL_MASS, substeps: int = 1,
                 record: bool = True) -> None:
        p = np.array(pos, dtype=float)
        if p.ndim != 2 or p.shape[1] != 2:
            raise ValueError(f"pos: shape {p.shape} is not (N, 2)")
        if substeps < 1:
            raise ValueError("substeps: must be at least 1")
        n = len(p)
        self.N = n
        self.table, self.physics, self.substeps, self.record = table, physics, substeps, record
        self.p = p
        self.v = np.broadcast_to(np.asarray(0.0 if vel is None else vel, float), (n, 2)).copy()
        self.w = np.broadcast_to(np.asarray(0.0 if w is None else w, float), (n, 3)).copy()
        self.r = np.broadcast_to(np.asarray(radius, float), (n,)).copy()
        self.m = np.broadcast_to(np.asarray(mass, float), (n,)).copy()
        self.on = np.ones(n, dtype=bool)  # still on the table
        self.pocket = np.full(n, -1, dtype=np.int16)
        self.time = 0.0
        self.steps = 0
        self.events: list[dict] = []
        self.pocket_c, self.pocket_r = self._pockets()  # each scheme has its own
        self._pocket_r2 = self.pocket_r**2
        self._pair_i, self._pair_j = np.triu_indices(n, 1)
        self._pair_r2 = (self.r[self._pair_i] + self.r[self._pair_j]) ** 2

    # ------------------------------------------------------------------ the public surface
    @property
    def pos(self) -> np.ndarray:
        return self.p.copy()

    @property
    def vel(self) -> np.ndarray:
        return self.v.copy()

    @property
    def state(self) -> np.ndarray:
        moving = _norm(self.v) > 0
        spinning = self.w[:, 2] != 0
        st = np.where(moving, ROLLING, np.where(spinning, SPINNING, STATIONARY))
        return np.where(self.on, st, POCKETED).astype(np.int8)

    def at_rest(self) -> bool:
        # Pocketed balls have v = w = 0.
        return not (self.v.any() or self.w.any())

    def step(self, dt: float) -> None:
        """Advance by one frame of dt seconds (`substeps` frames of dt / substeps inside)."""
        if not (dt > 0 and math.isfinite(dt)):
            raise ValueError("dt: must be a positive finite number of seconds")
        h = dt / self.substeps
        for k in range(1, self.substeps + 1):
            if self.at_rest():
                break
            self._frame(h, self.time + k * h)  # each scheme has its own
        self.time += dt
        self.steps += 1

    # ------------------------------------------------------------------ shared frame-end tests
    def _drop_in_pockets(self, t: float) -> None:
        if not self.pocket_r.size:
            return
        d = self.p[:, None] - self.pocket_c[None]
        d2 = (d * d).sum(axis=-1)
        inside = d2 < self._pocket_r2
        if not inside.any():
            return
        inside &= self.on[:, None]
        for i in np.flatnonzero(inside.any(axis=1)).tolist():
            k = int(np.argmin(np.where(inside[i], d2[i], np.inf)))
            self.on[i] = False
            self.pocket[i] = k
            # Pocketed balls sit at their pocket's hole centre, as in the engine.
            self.p[i] = self.table.hole_c[k]
            self.v[i] = 0.0
            self.w[i] = 0.0
            self._log(t, "pocket", [i], pocket=self.table.hole_names[k])

    def _overlapping_pairs(self) -> list[tuple[int, int]]:
        if self.N < 2:
            return []
        d = self.p[self._pair_j] - self.p[self._pair_i]
        close = (d * d).sum(axis=1) < self._pair_r2
        if not close.any():
            return []
        close &= self.on[self._pair_i] & self.on[self._pair_j]
        k = np.flatnonzero(close)
        return list(zip(self._pair_i[k].tolist(), self._pair_j[k].tolist(), strict=True))

    def _separate(self, i: int, j: int, n: np.ndarray, depth: float) -> None:
        """Push an overlapping pair apart along n (from i to j), sharing it by inverse mass."""
        share = self.m[j] / (self.m[i] + self.m[j])
        self.p[i] -= (depth * share) * n
        self.p[j] += (depth * (1.0 - share)) * n

    def _log(self, t: float, kind: str, ids: list[int], **extra) -> None:
        if self.record:
            self.events.append({"t": t, "type": kind, "i": ids, **extra})


class NaiveSim(_FrameSim):
    """The seed game's scheme: explicit Euler, friction subtracted per frame, no spin,
    contacts tested at frame ends. See the module docstring."""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self.w[:] = 0.0  # the seed game has no spin
        self._wall_lo = np.repeat(self.r[:, None], 2, axis=1)
        self._wall_hi = np.array([self.table.length, self.table.width]) - self._wall_lo

    def _pockets(self) -> tuple[np.ndarray, np.ndarray]:
        tab = self.table
        if tab.pockets == "none":
            return np.empty((0, 2)), np.empty(0)
        L, W = tab.length, tab.width
        mouths = {
            "head_right": ((0.0, 0.0), tab.corner_mouth),
            "head_left": ((0.0, W), tab.corner_mouth),
            "side_right": ((L / 2, 0.0), tab.side_mouth),
            "side_left": ((L / 2, W), tab.side_mouth),
            "foot_right": ((L, 0.0), tab.corner_mouth),
            "foot_left": ((L, W), tab.corner_mouth),
        }
        centres = np.array([mouths[name][0] for name in POCKET_NAMES])
        radii = np.array([mouths[name][1] / 2 for name in POCKET_NAMES])
        return centres, radii

    def _frame(self, h: float, t: float) -> None:
        ph = self.physics
        p, v = self.p, self.v
        p += v * h
        speed = _norm(v)
        # |v| -= mu_roll g h, clamped at zero (a still ball's 0 / TINY keeps it still).
        v *= (1.0 - np.minimum(ph.mu_roll * ph.g * h, speed) / np.maximum(speed, TINY))[:, None]
        self._drop_in_pockets(t)
        self._walls(t)
        for i, j in self._overlapping_pairs():
            d = p[j] - p[i]
            dist = math.hypot(d[0], d[1])
            n = d / dist
            closing = float((v[i] - v[j]) @ n)
            if closing > 0:
                jn = 0.5 * (1.0 + ph.e_ball) * closing  # equal masses
                v[i] -= jn * n
                v[j] += jn * n
                self._log(t, "ball_ball", [i, j])
            self._separate(i, j, n, self.r[i] + self.r[j] - dist)

    def _walls(self, t: float) -> None:
        """Mirror balls that ended the frame beyond a wall, one radius inside the noses."""
        p, v = self.p, self.v
        below, above = p < self._wall_lo, p > self._wall_hi
        if not (below.any() or above.any()):
            return
        below &= self.on[:, None]
        above &= self.on[:, None]
        p[:] = np.where(below, 2.0 * self._wall_lo - p, np.where(above, 2.0 * self._wall_hi - p, p))
        towards = (below & (v < 0)) | (above & (v > 0))
        v[towards] *= -self.physics.e_cushion
        for i in np.flatnonzero(towards.any(axis=1)).tolist():
            self._log(t, "cushion", [i], feature="rail")


class EulerSim(_FrameSim):
    """The engine's model (spin, sliding, real pockets and jaws) stepped by explicit Euler
    with contacts tested at frame ends. See the module docstring."""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        tab, ph = self.table, self.physics
        sin_t = np.clip((ph.cushion_height - self.r) / self.r, -0.95, 0.95)
        self.rc = self.r * np.sqrt(1.0 - sin_t * sin_t)  # centre-to-nose distance at contact
        self.spin_rate = 2.5 * ph.mu_spin * ph.g / self.r
        self._inner_lo = np.repeat(self.rc[:, None], 2, axis=1)
        self._inner_hi = np.array([tab.length, tab.width]) - self._inner_lo
        d = tab.seg_b - tab.seg_a
        self.seg_len = _norm(d)
        self.seg_dir = d / self.seg_len[:, None]
        self.seg_rail = np.array([k == "rail" for k in tab.seg_kind], dtype=bool)

    def _pockets(self) -> tuple[np.ndarray, np.ndarray]:
        return self.table.hole_c.reshape(-1, 2), self.table.hole_r

    def _frame(self, h: float, t: float) -> None:
        ph = self.physics
        g = ph.g
        p, v, w, R = self.p, self.v, self.w, self.r
        p += v * h
        ds = ph.mu_slide * g * h  # the speed sliding friction takes in one frame
        u = v + R[:, None] * _perp(w[:, :2])  # contact-point slip
        us = _norm(u)
        rolling = us <= EPS_SLIP
        if not rolling.all():
            # A slip that friction would stop within the frame is completed to rolling
            # (v -= u / 3.5, as in the engine); the others slide on for the whole frame.
            done = ~rolling & (us <= 3.5 * ds)
            k = np.where(rolling | done, 0.0, ds)[:, None]
            uhat = u / np.maximum(us, TINY)[:, None]
            v -= k * uhat + np.where(done, 1.0 / 3.5, 0.0)[:, None] * u
            w[:, :2] += (2.5 / R)[:, None] * k * _perp(uhat)
            rolling |= done
        speed = _norm(v)
        slower = 1.0 - np.minimum(ph.mu_roll * g * h, speed) / np.maximum(speed, TINY)
        v *= np.where(rolling, slower, 1.0)[:, None]
        w[:, :2] = np.where(rolling[:, None], _perp(v) / R[:, None], w[:, :2])
        wz = w[:, 2]
        w[:, 2] = np.copysign(np.maximum(np.abs(wz) - self.spin_rate * h, 0.0), wz)
        self._drop_in_pockets(t)
        self._cushions(t)
        for i, j in self._overlapping_pairs():
            d = p[j] - p[i]
            dist = math.hypot(d[0], d[1])
            n = d / dist
            if float((v[i] - v[j]) @ n) > 0:
                ii, jj = np.array([i]), np.array([j])
                vi, vj, wi, wj = BALL_BALL[ph.ball_ball].collide(
                    p[ii], p[jj], v[ii], v[jj], w[ii], w[jj], R[ii], R[jj], self.m[ii],
                    self.m[jj], ph)
                v[i], v[j], w[i], w[j] = vi[0], vj[0], wi[0], wj[0]
                self._log(t, "ball_ball", [i, j])
            self._separate(i, j, n, R[i] + R[j] - dist)

    def _cushions(self, t: float) -> None:
        """Bounce balls that ended the frame within reach of a rail, jaw or jaw tip."""
        tab, ph = self.table, self.physics
        # Rails, jaws and tips all lie on or behind the cushion-nose lines: a ball at least rc
        # inside all four touches none of them.
        inner = (self.p >= self._inner_lo) & (self.p <= self._inner_hi)
        idx = np.flatnonzero(self.on & ~inner.all(axis=1))
        if idx.size == 0 or not len(tab.seg_a):
            return
        p, rc = self.p[idx], self.rc[idx]
        rel = p[:, None] - tab.seg_a[None]  # (M, S, 2)
        along = (rel * self.seg_dir[None]).sum(axis=-1)
        s = (rel * tab.seg_n[None]).sum(axis=-1)  # signed distance in front of the nose
        within = (along >= 0) & (along <= self.seg_len[None])
        # A rail is a wall: anything behind it has come through. A jaw is thin: only a
        # ball within reach of its face touches it.
        deep = np.where(self.seg_rail[None], s < rc[:, None], np.abs(s) < rc[:, None])
        face = within & deep
        gap_face = np.where(face, s - rc[:, None], np.inf)
        if len(tab.points):
            dp = p[:, None] - tab.points[None]
            dd = _norm(dp)
            gap_tip = dd - rc[:, None]
        else:
            gap_tip = np.empty((len(idx), 0))
        allgap = np.concatenate([gap_face, np.where(gap_tip < 0, gap_tip, np.inf)], axis=1)
        for m in np.flatnonzero(np.isfinite(allgap).any(axis=1)).tolist():
            k = int(np.argmin(allgap[m]))
            i = int(idx[m])
            if k < len(tab.seg_a):
                n = tab.seg_n[k]
                feature = tab.seg_kind[k]
            else:
                d = dp[m, k - len(tab.seg_a)]
                n = d / _norm(d)
                feature = "tip"
            self.p[i] -= allgap[m, k] * n  # back to touching
            if float(self.v[i] @ n) >= 0:
                continue
            v, w = cushion.MODELS[ph.cushion].bounce(n[None], self.v[i][None], self.w[i][None],
                                                     self.r[i:i + 1], self.m[i:i + 1], ph)
            self.v[i], self.w[i] = v[0], w[0]
            self._log(t, "cushion", [i], feature=feature)
