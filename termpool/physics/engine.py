"""The engine: a batch of tables advanced by fixed steps, exact inside each step.

State lives in arrays with a leading table axis (B) and a ball axis (N). Between events every
ball moves on a closed-form quadratic. For every ball the engine keeps the time of its next
motion transition, of its next cushion or pocket contact and, for every pair, of their next
contact, and recomputes only the predictions of the balls an event touched. A step runs the
events that fall inside it in time order (one per table per pass, all tables at once) and then
moves every ball to the step's end; a step without events costs a few array operations, and
tables at rest cost nothing.
"""

from __future__ import annotations

import math

import numpy as np

from termpool.physics import contact
from termpool.physics.params import BALL_MASS, BALL_RADIUS, Physics
from termpool.physics.roots import first_contact, first_line_contact
from termpool.physics.table import Table

STATIONARY, SPINNING, SLIDING, ROLLING, POCKETED = range(5)
STATE_NAMES = ("stationary", "spinning", "sliding", "rolling", "pocketed")
HORIZON = 0.5  # s; pair and cushion predictions look this far ahead, then are renewed
EPS_U = 1e-9  # m/s of contact-point slip below which a ball counts as rolling
EPS_V = 1e-9  # m/s below which a ball counts as not translating
EPS_W = 1e-9  # rad/s of side spin below which a ball counts as still
MAX_PASSES = 200_000  # guard against a run that would never finish a step

_TRANSITION_NAMES = {
    (SLIDING, ROLLING): "slide_to_roll",
    (SLIDING, SPINNING): "slide_to_spin",
    (SLIDING, STATIONARY): "slide_to_stop",
    (ROLLING, SPINNING): "roll_to_spin",
    (ROLLING, STATIONARY): "roll_to_stop",
    (SPINNING, STATIONARY): "spin_to_stop",
}


def _norm(v: np.ndarray) -> np.ndarray:
    return np.sqrt(v[..., 0] * v[..., 0] + v[..., 1] * v[..., 1])


def _batch(x, shape: tuple, name: str) -> np.ndarray:
    arr = np.asarray(x, dtype=float)
    try:
        return np.broadcast_to(arr, shape).copy()
    except ValueError:
        raise ValueError(f"{name}: shape {arr.shape} does not fit {shape}") from None


class Engine:
    """Advance B independent tables of N balls each (arrays may omit the table axis)."""

    def __init__(
        self,
        table: Table,
        physics: Physics,
        pos,
        vel=None,
        w=None,
        radius=BALL_RADIUS,
        mass=BALL_MASS,
        record: bool = True,
        horizon: float = HORIZON,
    ) -> None:
        pos = np.asarray(pos, dtype=float)
        self.batched = pos.ndim == 3
        if not self.batched:
            pos = pos[None]
        B, N = pos.shape[:2]
        self.B, self.N = B, N
        self.table, self.physics, self.record, self.horizon = table, physics, record, horizon
        self.pos = pos.copy()
        lead = (B, N) if self.batched else (N,)
        self.vel = _batch(np.zeros(2) if vel is None else vel, lead + (2,), "vel").reshape(B, N, 2)
        self.w = _batch(np.zeros(3) if w is None else w, lead + (3,), "w").reshape(B, N, 3)
        self.radius = _batch(radius, lead, "radius").reshape(B, N)
        self.mass = _batch(mass, lead, "mass").reshape(B, N)
        sin_t = np.clip((physics.cushion_height - self.radius) / self.radius, -0.95, 0.95)
        self.rc = self.radius * np.sqrt(1.0 - sin_t * sin_t)  # centre-to-nose distance at contact
        g = physics.g
        self.spin_rate = 5.0 * physics.mu_spin * g / (2.0 * self.radius)
        self.state = np.zeros((B, N), dtype=np.int8)
        self.pocket = np.full((B, N), -1, dtype=np.int16)
        self.acc = np.zeros((B, N, 2))
        self.alpha = np.zeros((B, N, 2))  # rate of change of (wx, wy)
        self.t_trans = np.full((B, N), np.inf)
        self.t_check = np.full((B, N), np.inf)
        self.t_cush = np.full((B, N), np.inf)
        self.f_cush = np.zeros((B, N), dtype=np.int64)
        self.t_pair = np.full((B, N, N), np.inf)
        self.tb = np.zeros(B)  # each table's own clock inside a step
        self.time = 0.0
        self.steps = 0
        self.passes = 0  # event passes run, a measure of work
        self.events: list[list[dict]] = [[] for _ in range(B)]
        nseg, npt = len(table.seg_a), len(table.points)
        self._nseg, self._npt = nseg, npt
        seg_d = table.seg_b - table.seg_a
        self._seg_len = _norm(seg_d)
        self._seg_dir = seg_d / self._seg_len[:, None]
        self._arange = np.arange(B)
        b, i = np.divmod(np.arange(B * N), N)
        self._set_motion(b, i)
        self._predict(b, i)

    # ----------------------------------------------------------------- motion between events
    def _set_motion(self, b: np.ndarray, i: np.ndarray) -> None:
        """Classify balls (b, i) from their v and w; set accelerations and transition times."""
        ph = self.physics
        g = ph.g
        v = self.vel[b, i]
        w = self.w[b, i]
        R = self.radius[b, i]
        t = self.tb[b]
        u = np.stack([v[:, 0] - R * w[:, 1], v[:, 1] + R * w[:, 0]], axis=1)
        us, vs, wz = _norm(u), _norm(v), np.abs(w[:, 2])
        pocketed = self.state[b, i] == POCKETED
        sliding = (us > EPS_U) & ~pocketed
        rolling = ~sliding & (vs > EPS_V) & ~pocketed
        spinning = ~sliding & ~rolling & (wz > EPS_W) & ~pocketed
        still = ~(sliding | rolling)
        v = np.where(still[:, None], 0.0, v)
        w[:, :2] = np.where(rolling[:, None], np.stack([-v[:, 1], v[:, 0]], 1) / R[:, None],
                            np.where(still[:, None], 0.0, w[:, :2]))
        w[:, 2] = np.where(spinning | sliding | rolling, w[:, 2], 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            uhat = np.where(sliding[:, None], u / us[:, None], 0.0)
            vhat = np.where(rolling[:, None], v / vs[:, None], 0.0)
            acc = -ph.mu_slide * g * uhat - ph.mu_roll * g * vhat
            k = 2.5 * ph.mu_slide * g / R
            alpha = np.where(
                sliding[:, None],
                k[:, None] * np.stack([-uhat[:, 1], uhat[:, 0]], 1),
                np.stack([-acc[:, 1], acc[:, 0]], 1) / R[:, None],
            )
            dt_slide = 2.0 * us / (7.0 * ph.mu_slide * g)
            dt_roll = vs / (ph.mu_roll * g)
            dt_spin = wz / self.spin_rate[b, i]
        dt = np.where(sliding, dt_slide, np.where(rolling, dt_roll, np.where(spinning, dt_spin, np.inf)))
        state = np.where(sliding, SLIDING, np.where(rolling, ROLLING, np.where(spinning, SPINNING, STATIONARY)))
        self.state[b, i] = np.where(pocketed, POCKETED, state)
        self.vel[b, i] = v
        self.w[b, i] = w
        self.acc[b, i] = acc
        self.alpha[b, i] = alpha
        self.t_trans[b, i] = np.where(pocketed, np.inf, t + np.where(np.isnan(dt), np.inf, dt))

    def _advance(self, dtb: np.ndarray) -> None:
        """Move every ball of every table along its current quadratic by dtb[b] seconds."""
        d = dtb[:, None]
        d3 = d[:, :, None]
        self.pos += self.vel * d3 + 0.5 * self.acc * (d3 * d3)
        self.vel += self.acc * d3
        self.w[..., :2] += self.alpha * d3
        wz = self.w[..., 2]
        self.w[..., 2] = np.sign(wz) * np.maximum(np.abs(wz) - self.spin_rate * d, 0.0)

    # ----------------------------------------------------------------- predictions
    def _window_end(self, b, i) -> np.ndarray:
        return np.minimum(self.t_trans[b, i], self.t_check[b, i])

    def _predict(self, b: np.ndarray, i: np.ndarray) -> None:
        """Renew the contact predictions of balls (b, i), whose tables' clocks are current."""
        st = self.state[b, i]
        moving = (st == SLIDING) | (st == ROLLING)
        t = self.tb[b]
        self.t_check[b, i] = np.where(moving, t + self.horizon, np.inf)
        self.t_cush[b, i] = np.inf
        end = self._window_end(b, i)
        mv = np.flatnonzero(moving)
        if mv.size:
            tc, fc = self._predict_cushions(b[mv], i[mv], end[mv] - t[mv])
            self.t_cush[b[mv], i[mv]] = t[mv] + tc
            self.f_cush[b[mv], i[mv]] = fc
        self._predict_pairs(b, i, t, end, st)

    def _predict_cushions(self, b, i, horizon):
        tab = self.table
        p, v, a = self.pos[b, i], self.vel[b, i], self.acc[b, i]
        rc = self.rc[b, i]
        parts = []
        if self._nseg:
            n = tab.seg_n
            s0 = np.einsum("mkj,kj->mk", p[:, None, :] - tab.seg_a[None], n)
            sv = v @ n.T
            sa = a @ n.T
            M, S = s0.shape
            hz = np.broadcast_to(horizon[:, None], (M, S))
            tl = first_line_contact(s0.ravel(), sv.ravel(), sa.ravel(),
                                    np.broadcast_to(rc[:, None], (M, S)).ravel(), hz.ravel())
            tl = tl.reshape(M, S)
            # The contact must fall on the segment itself; its ends are the jaw-tip points.
            fin = np.isfinite(tl)
            if fin.any():
                tt = np.where(fin, tl, 0.0)[..., None]
                pt = p[:, None, :] + v[:, None, :] * tt + 0.5 * a[:, None, :] * tt * tt
                along = np.einsum("mkj,kj->mk", pt - tab.seg_a[None], self._seg_dir)
                tl = np.where(fin & (along >= 0) & (along <= self._seg_len[None]), tl, np.inf)
            parts.append(tl)
        circ_c = []
        if self._npt:
            circ_c.append(tab.points)
        if len(tab.hole_c):
            circ_c.append(tab.hole_c)
        if circ_c:
            cc = np.concatenate(circ_c)
            M, C = p.shape[0], cc.shape[0]
            dist = np.concatenate([np.broadcast_to(rc[:, None], (M, self._npt)),
                                   np.broadcast_to(tab.hole_r[None], (M, len(tab.hole_c)))], axis=1)
            p0 = (p[:, None, :] - cc[None]).reshape(-1, 2)
            vv = np.broadcast_to(v[:, None, :], (M, C, 2)).reshape(-1, 2)
            aa = np.broadcast_to(a[:, None, :], (M, C, 2)).reshape(-1, 2)
            hz = np.broadcast_to(horizon[:, None], (M, C)).ravel()
            parts.append(first_contact(p0, vv, aa, dist.ravel(), hz).reshape(M, C))
        allt = np.concatenate(parts, axis=1)
        f = allt.argmin(axis=1)
        return allt[np.arange(len(f)), f], f

    def _predict_pairs(self, b, i, t, end, st) -> None:
        N = self.N
        M = len(b)
        k = np.arange(N)
        stk = self.state[b]  # (M, N)
        moving_i = (st == SLIDING) | (st == ROLLING)
        moving_k = (stk == SLIDING) | (stk == ROLLING)
        valid = (stk != POCKETED) & (k[None] != i[:, None]) & (moving_i[:, None] | moving_k)
        valid &= (st != POCKETED)[:, None]
        self.t_pair[b, i, :] = np.inf
        self.t_pair[b, :, i] = np.inf
        mi, kk = np.nonzero(valid)
        if mi.size == 0:
            return
        bb, ii = b[mi], i[mi]
        p0 = self.pos[bb, kk] - self.pos[bb, ii]
        v = self.vel[bb, kk] - self.vel[bb, ii]
        a = self.acc[bb, kk] - self.acc[bb, ii]
        dist = self.radius[bb, kk] + self.radius[bb, ii]
        horizon = np.minimum(end[mi], self._window_end(bb, kk)) - t[mi]
        tc = t[mi] + first_contact(p0, v, a, dist, horizon)
        self.t_pair[bb, ii, kk] = tc
        self.t_pair[bb, kk, ii] = tc

    # ----------------------------------------------------------------- events
    def _run_until(self, t_end: float) -> None:
        """Run every table's events up to t_end in time order, then move all to t_end."""
        B, N = self.B, self.N
        for _ in range(MAX_PASSES):
            allt = np.concatenate(
                [self.t_trans, self.t_check, self.t_cush, self.t_pair.reshape(B, N * N)], axis=1)
            code = allt.argmin(axis=1)
            tn = allt[self._arange, code]
            act = (tn <= t_end) & (tn < math.inf)
            if not act.any():
                break
            self.passes += 1
            tabs = np.flatnonzero(act)
            self._advance(np.where(act, np.maximum(tn - self.tb, 0.0), 0.0))
            self.tb[tabs] = tn[tabs]
            self._handle(tabs, code[tabs])
        else:
            raise RuntimeError("engine: too many events in one step (a contact that never resolves)")
        if math.isfinite(t_end):
            self._advance(np.maximum(t_end - self.tb, 0.0))
            self.tb[:] = t_end

    def _handle(self, tabs: np.ndarray, code: np.ndarray) -> None:
        N = self.N
        kind = np.minimum(code // N, 3)
        i = np.where(kind < 3, code % N, (code - 3 * N) // N)
        j = np.where(kind < 3, -1, (code - 3 * N) % N)
        old_state = self.state[tabs, i].copy()
        labels: list = [None] * len(tabs)

        tr = np.flatnonzero(kind == 0)
        if tr.size:
            self._transition(tabs[tr], i[tr])
        cu = np.flatnonzero(kind == 2)
        if cu.size:
            feats = self._cushion(tabs[cu], i[cu])
            if self.record:
                for n, f in zip(cu, feats, strict=True):
                    labels[n] = f
        pr = np.flatnonzero(kind == 3)
        if pr.size:
            self._collide(tabs[pr], i[pr], j[pr])
        # Renew predictions for every ball an event touched.
        bb = np.concatenate([tabs, tabs[pr]])
        ii = np.concatenate([i, j[pr]])
        self._predict(bb, ii)
        if self.record:
            self._log(tabs, kind, i, j, old_state, labels)

    def _transition(self, b, i) -> None:
        st = self.state[b, i]
        R = self.radius[b, i]
        v = self.vel[b, i]
        w = self.w[b, i]
        sl = st == SLIDING
        # End of sliding: slip is exactly zero; end of rolling: no translation; end of spin.
        w[:, :2] = np.where(sl[:, None], np.stack([-v[:, 1], v[:, 0]], 1) / R[:, None], w[:, :2])
        rl = st == ROLLING
        v = np.where(rl[:, None], 0.0, v)
        w[:, :2] = np.where(rl[:, None], 0.0, w[:, :2])
        w[:, 2] = np.where(st == SPINNING, 0.0, w[:, 2])
        self.vel[b, i] = v
        self.w[b, i] = w
        self._set_motion(b, i)

    def _cushion(self, b, i) -> list:
        tab, ph = self.table, self.physics
        f = self.f_cush[b, i]
        nseg, npt = self._nseg, self._npt
        p = self.pos[b, i]
        rc = self.rc[b, i]
        hole = f >= nseg + npt
        seg = f < nseg
        pt = ~hole & ~seg
        n = np.zeros_like(p)
        if seg.any():
            n[seg] = tab.seg_n[f[seg]]
        if pt.any():
            d = p[pt] - tab.points[f[pt] - nseg]
            n[pt] = d / _norm(d)[:, None]
        bounce = np.flatnonzero(~hole)
        if bounce.size:
            bb, ib = b[bounce], i[bounce]
            v, w = contact.cushion(n[bounce], self.vel[bb, ib], self.w[bb, ib], self.radius[bb, ib],
                                   self.mass[bb, ib], ph.e_cushion, ph.mu_cushion,
                                   ph.cushion_height, ph.v_inelastic)
            self.vel[bb, ib] = v
            self.w[bb, ib] = w
            # Undo any sub-micrometre sink so that the ball rests exactly at contact distance.
            fb = f[bounce]
            isseg = seg[bounce]
            ref = np.where(isseg[:, None], tab.seg_a[np.where(isseg, fb, 0)],
                           tab.points[np.clip(fb - nseg, 0, max(npt - 1, 0))] if npt else 0.0)
            depth = rc[bounce] - np.einsum("ij,ij->i", p[bounce] - ref, n[bounce])
            self.pos[bb, ib] = p[bounce] + np.maximum(depth, 0.0)[:, None] * n[bounce]
            self._set_motion(bb, ib)
        hl = np.flatnonzero(hole)
        if hl.size:
            bh, ih = b[hl], i[hl]
            k = f[hl] - nseg - npt
            self.state[bh, ih] = POCKETED
            self.pocket[bh, ih] = k
            self.pos[bh, ih] = tab.hole_c[k]
            self.vel[bh, ih] = 0.0
            self.w[bh, ih] = 0.0
            self.acc[bh, ih] = 0.0
            self.alpha[bh, ih] = 0.0
            self.t_trans[bh, ih] = np.inf
        kinds = []
        if self.record:
            for fi in f:
                if fi < nseg:
                    kinds.append(tab.seg_kind[fi])
                elif fi < nseg + npt:
                    kinds.append("tip")
                else:
                    kinds.append(tab.hole_names[fi - nseg - npt])
        return kinds

    def _collide(self, b, i, j) -> None:
        ph = self.physics
        pi, pj = self.pos[b, i], self.pos[b, j]
        ri, rj = self.radius[b, i], self.radius[b, j]
        mi, mj = self.mass[b, i], self.mass[b, j]
        vi, vj, wi, wj = contact.ball_ball(
            pi, pj, self.vel[b, i], self.vel[b, j], self.w[b, i], self.w[b, j], ri, rj, mi, mj,
            ph.e_ball, ph.v_inelastic, ph.ball_ball == "frictional")
        self.vel[b, i], self.vel[b, j] = vi, vj
        self.w[b, i], self.w[b, j] = wi, wj
        # Separate a resting contact that sank by up to SINK back to touching, by inverse mass.
        d = pj - pi
        dist = _norm(d)
        depth = np.maximum(ri + rj - dist, 0.0)
        n = d / dist[:, None]
        share_i = (1.0 / mi) / (1.0 / mi + 1.0 / mj)
        self.pos[b, i] = pi - (depth * share_i)[:, None] * n
        self.pos[b, j] = pj + (depth * (1.0 - share_i))[:, None] * n
        self._set_motion(np.concatenate([b, b]), np.concatenate([i, j]))

    def _ball_dict(self, b: int, i: int) -> dict:
        w = self.w[b, i]
        return {
            "x": float(self.pos[b, i, 0]), "y": float(self.pos[b, i, 1]),
            "vx": float(self.vel[b, i, 0]), "vy": float(self.vel[b, i, 1]),
            "w": [float(w[0]), float(w[1]), float(w[2])],
            "state": STATE_NAMES[self.state[b, i]],
        }

    def _log(self, tabs, kind, i, j, old_state, labels) -> None:
        for n, b in enumerate(tabs.tolist()):
            k = int(kind[n])
            if k == 1:
                continue
            ib = int(i[n])
            ev: dict = {"t": float(self.tb[b])}
            if k == 0:
                ev["type"] = _TRANSITION_NAMES.get((int(old_state[n]), int(self.state[b, ib])),
                                                   "transition")
                ev["i"] = [ib]
            elif k == 2:
                if self.state[b, ib] == POCKETED:
                    ev["type"] = "pocket"
                    ev["pocket"] = labels[n]
                else:
                    ev["type"] = "cushion"
                    ev["feature"] = labels[n]
                ev["i"] = [ib]
            else:
                ev["type"] = "ball_ball"
                ev["i"] = [ib, int(j[n])]
            ev["balls"] = [self._ball_dict(b, x) for x in ev["i"]]
            self.events[b].append(ev)

    # ----------------------------------------------------------------- public driving
    def at_rest(self) -> np.ndarray:
        """(B,) True where every ball is stationary or pocketed."""
        st = self.state
        return ((st == STATIONARY) | (st == POCKETED)).all(axis=1)

    def step(self, dt: float) -> None:
        """Advance every table by dt seconds (exact inside the step)."""
        if not (dt > 0 and math.isfinite(dt)):
            raise ValueError("dt: must be a positive finite number of seconds")
        t_end = self.time + dt
        if not self.at_rest().all():
            self._run_until(t_end)
        else:
            self.tb[:] = t_end
        self.time = t_end
        self.steps += 1

    def _sample(self) -> tuple[float, np.ndarray, np.ndarray]:
        return (self.time, self.pos.copy(), self.state.copy())

    def run(self, dt: float, duration: float | None = None, sample_hz: float | None = None,
            max_steps: int | None = None) -> list:
        """Fixed steps of dt until every table is at rest (or `duration` seconds have passed).

        With sample_hz, positions are also taken at multiples of 1/sample_hz (each step is
        split at those instants; the engine is exact inside a step, so this changes nothing).
        """
        samples = []
        k = 0
        if sample_hz:
            samples.append(self._sample())
            k = 1
        while not self.at_rest().all():
            if duration is not None and self.time >= duration:
                break
            if max_steps is not None and self.steps >= max_steps:
                break
            h = dt if duration is None else min(dt, duration - self.time)
            t_end = self.time + h
            if sample_hz:
                while k / sample_hz < t_end and not self.at_rest().all():
                    ts = k / sample_hz
                    self._run_until(ts)
                    self.time = ts
                    samples.append(self._sample())
                    k += 1
            self._run_until(t_end)
            self.time = t_end
            self.steps += 1
        return samples

    def run_events(self, duration: float | None = None, sample_hz: float | None = None) -> list:
        """Reference driver: jump from event to event with exact event times, no steps."""
        samples = []
        t_stop = math.inf if duration is None else duration
        if sample_hz:
            samples.append(self._sample())
            k = 1
            while not self.at_rest().all() and k / sample_hz <= t_stop:
                self._run_until(k / sample_hz)
                self.time = k / sample_hz
                samples.append(self._sample())
                k += 1
        self._run_until(t_stop)
        if math.isfinite(t_stop):
            self.time = t_stop
        else:
            self.time = float(self.tb.max())
        return samples
