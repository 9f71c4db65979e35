"""The engine: a batch of tables advanced by fixed steps, exact inside each step.

State lives in arrays with a leading table axis (B) and a ball axis (N). Between events every
ball moves on a closed-form quadratic from its own reference time t0, so a ball nobody touches
is never updated: its position at any time is evaluated from (t0, p0, v0, acc) when needed.
For every ball the engine keeps the time of its next motion transition and of its next cushion
or pocket contact, and for every pair the time of their next contact; an event renews only the
predictions of the balls it touched. A step runs the events inside it in time order, one per
table per pass and all tables at once; a step without events costs one comparison, and tables
at rest cost nothing.
"""

from __future__ import annotations

import math

import numpy as np

from termpool.physics import cushion, motion, pocket, transition
from termpool.physics.ball_ball import MODELS as BALL_BALL
from termpool.physics.ball_ball import sink as ball_sink
from termpool.physics.balls import FEW, Balls
from termpool.physics.cushion import sink
from termpool.physics.events import ENDS, BallState, Event, EventKind
from termpool.physics.features import Features
from termpool.physics.motion import Col
from termpool.physics.params import BALL_MASS, BALL_RADIUS, Physics
from termpool.physics.roots import (
    V_MIN,
)
from termpool.physics.schedule import Due, Schedule
from termpool.physics.slow import SlowContacts
from termpool.physics.state import (  # noqa: F401  (state codes are part of the engine's API)
    CLUSTER_GAP,
    EPS_U,
    EPS_V,
    EPS_W,
    POCKETED,
    ROLLING,
    SLIDING,
    SPINNING,
    STATE_NAMES,
    STATIONARY,
)
from termpool.physics.table import Table
from termpool.physics.vec import norm as _norm

HORIZON = 2.0  # s; contact predictions look this far ahead, then are renewed
# The work limit (docs/limits.md): an engine that has done WORK_LIMIT units of work raises
# WorkLimit at its next step or event pass, so that no input makes a run endless. The units
# are counted, not timed, so a run meets the limit at the same point on every machine; each
# is roughly 3 us of computing here: a step, 1/PASS_WORK of an event pass, one ball's
# contact predictions against one ball, or 1/CLUSTER_WORK of k^3 for a cluster of k balls
# solved together (a dense solve).
WORK_LIMIT = 20_000_000
PASS_WORK = 64
CLUSTER_WORK = 32
# Work bound: after BUDGET events of one table within a WINDOW of simulated time, its further
# contacts in that window are solved as clusters, inelastically (a light ball squeezed
# between a heavy one and a rail would otherwise bounce without end). Windows are fixed in
# simulated time, so the bound does not depend on the step.
BUDGET = 200
WINDOW = 1 / 60

_ONE = np.zeros(1, dtype=np.int64)  # index of the only event of a one-table pass
_NONE = np.zeros(0, dtype=np.int64)


class WorkLimit(RuntimeError):
    """A run that met the work limit; the message is one line naming it."""


def _batch(x, shape: tuple, name: str) -> np.ndarray:
    arr = np.asarray(x, dtype=float)
    try:
        return np.broadcast_to(arr, shape).copy()
    except ValueError:
        raise ValueError(f"{name}: shape {arr.shape} does not fit {shape}") from None


class Engine(SlowContacts):
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
        max_work: float | None = None,
    ) -> None:
        pos = np.asarray(pos, dtype=float)
        if pos.ndim not in (2, 3) or pos.shape[-1] != 2:
            raise ValueError(f"pos: shape {pos.shape} is not (N, 2) or (B, N, 2)")
        self.batched = pos.ndim == 3
        if not self.batched:
            pos = pos[None]
        B, N = pos.shape[:2]
        self.B, self.N = B, N
        self.table, self.physics, self.record, self.horizon = table, physics, record, horizon
        lead = (B, N) if self.batched else (N,)
        vel = _batch(np.zeros(2) if vel is None else vel, lead + (2,), "vel").reshape(B, N, 2)
        w = _batch(np.zeros(3) if w is None else w, lead + (3,), "w").reshape(B, N, 3)
        radius = _batch(radius, lead, "radius").reshape(B, N)
        mass = _batch(mass, lead, "mass").reshape(B, N)
        for name, arr in (("radius", radius), ("mass", mass)):
            if not (arr > 0).all() or not np.isfinite(arr).all():
                raise ValueError(f"{name}: must be positive and finite")
        times = Schedule.new_times(B, N)
        self.balls = Balls(physics, radius, mass, times[:, :N])
        b = self.balls  # the balls' arrays the engine's users read
        self.radius, self.mass, self.rc, self.state, self.pocket, self.t_trans = (
            b.radius, b.mass, b.rc, b.state, b.pocket, b.t_trans)
        self.tb = np.zeros(B)  # each table's own clock inside a step
        self._win = np.full(B, -1, dtype=np.int64)  # work bound: window and events in it
        self._count = np.zeros(B, dtype=np.int64)
        # Groups of balls held by resting contacts (joined.py): a label per ball (-1: none)
        # and, per table, how many balls are grouped, so that tables without any pay nothing.
        self.group = np.full((B, N), -1, dtype=np.int64)
        self._ngroup = np.zeros(B, dtype=np.int64)
        self.time = 0.0
        self.steps = 0
        self.passes = 0  # event passes run
        self.work = 0  # units of work done, and the limit (see WORK_LIMIT)
        self.max_work = WORK_LIMIT if max_work is None else max_work
        self.log: list[list[Event]] = [[] for _ in range(B)]  # each table's events, typed
        self._json: list[list[dict]] = [[] for _ in range(B)]  # and as JSON (`events`)
        self._unsynced = False
        self.features = Features(table)
        self.schedule = sc = Schedule(times, self.balls, self.features, self.tb, horizon)
        # The predictions the engine's users read.
        self.t_cush, self.f_cush, self.t_next = sc.t_cush, sc.f_cush, sc.t_next
        b, i = np.divmod(np.arange(B * N), N)
        with np.errstate(all="ignore"):
            self.balls.set(b, i, self.tb[b], pos[b, i], vel[b, i], w[b, i])
            self._predict(b, i)
            self.schedule.refresh(np.arange(B))

    # ----------------------------------------------------------------- predictions
    def _predict(self, b: np.ndarray, i: np.ndarray) -> None:
        """Renew the contact predictions of balls (b, i), counting the work."""
        self.work += b.size * self.N
        self.schedule.predict(b, i)

    # ----------------------------------------------------------------- events
    def _run_until(self, t_end: float) -> None:
        """Run every table's events up to t_end in time order; clocks end at t_end."""
        self._spend(1)
        if (self.t_next <= t_end).any():
            with np.errstate(all="ignore"):  # infinities stand for "never"
                self._run_events(t_end)
        if math.isfinite(t_end):
            self.tb[:] = t_end

    def _run_events(self, t_end: float) -> None:
        while True:
            tabs = np.nonzero((self.t_next <= t_end) & (self.t_next < math.inf))[0]
            if tabs.size == 0:
                break
            self._spend(PASS_WORK)
            self.passes += 1
            self.tb[tabs] = self.t_next[tabs]
            self._handle(tabs, self.schedule.c_next[tabs])
            self.schedule.refresh(tabs)

    def _spend(self, units: int) -> None:
        """Count work before a step or a pass; raise WorkLimit past the limit (between
        passes, so the engine's state stays whole)."""
        self.work += units
        if self.work > self.max_work:
            raise WorkLimit(f"engine: the run met its work limit of {self.max_work:,.0f} units "
                            f"at {float(self.tb.max()):.6g} s of simulated time (docs/limits.md)")

    def _handle(self, tabs: np.ndarray, code: np.ndarray) -> None:
        kind, i, j = self.schedule.decode(code)
        old_state = self.state[tabs, i] if self.record else None
        t = self.tb[tabs]
        win = np.floor(t / WINDOW).astype(np.int64)
        count = np.where(win != self._win[tabs], 1, self._count[tabs] + 1)
        self._win[tabs] = win
        self._count[tabs] = count
        busy = count > BUDGET
        any_busy = busy.any()
        if tabs.size == 1:  # one table (the usual case): pick its kind without array scans
            which = _ONE
            tr = cu = pr = _NONE
            k0 = int(kind[0])
            if k0 == Due.TRANSITION:
                tr = which
            elif k0 == Due.CUSHION:
                cu = which
            elif k0 == Due.PAIR:
                pr = which
        else:
            tr = np.flatnonzero(kind == Due.TRANSITION)
            cu = np.flatnonzero(kind == Due.CUSHION)
            pr = np.flatnonzero(kind == Due.PAIR)
        labels: dict = {}
        # (event, seed balls, every contact inelastic, the event's own slow contact)
        clusters: list[tuple[int, list[int], bool, bool]] = []
        quiet: set[int] = set()  # resting contacts that began: no impulse, no event
        # Balls held in a group by resting contacts (joined.py): any event of one of them
        # renews the whole group's motion, since its contact forces change with it.
        grouped = self._grouped(tabs, i, j, kind)
        if tr.size:
            if grouped is not None:
                for n in tr[grouped[tr]].tolist():
                    clusters.append((n, self._group_of(int(tabs[n]), int(i[n])), False, False))
                tr = tr[~grouped[tr]]
            if tr.size:
                self._transition(tabs[tr], i[tr])
        if cu.size:
            # A slow bounce (or any bounce over the work bound) is solved with its cluster:
            # the ball settles on the cushion, and stays pressed to it while friction drives
            # it there.
            approach = self._approach(tabs[cu], i[cu])
            slow = approach < self.physics.v_inelastic
            # Slowly, touching a ball (pressed into the rail by it) or grouped: with the
            # cluster; over the work bound: with the cluster, inelastically.
            crowd = np.zeros(cu.size, dtype=bool)
            if slow.any():
                crowd[slow] = self._crowded(tabs[cu[slow]], i[cu[slow]])
            if any_busy:
                crowd |= busy[cu] & (self.f_cush[tabs[cu], i[cu]] < self.features.first_hole)
            if crowd.any():
                # A cluster's solve leaves out a contact sunk deeper than CLUSTER_GAP, and
                # the ball would meet it again at once, for ever: it bounces (and is lifted).
                k = np.flatnonzero(crowd)
                crowd[k] = ~self._sunk(tabs[cu[k]], i[cu[k]])
            if self.record:
                f = self.f_cush[tabs[cu], i[cu]]
                labels = dict(zip(cu.tolist(), zip(f.tolist(), self.features.names(f), strict=True),
                                  strict=True))
            for n in cu[crowd].tolist():
                clusters.append((n, [int(i[n])], bool(busy[n]), True))
            alone = ~crowd
            if alone.any():
                self._cushion(tabs[cu[alone]], i[cu[alone]])
                # A slow ball left pressed to the cushion by its friction stays on it, held
                # by the cushion's force (a group); one that met it with no speed at all was
                # no impact.
                calm = alone & slow
                if calm.any():
                    pressed = np.zeros(cu.size, dtype=bool)
                    pressed[calm] = self._pressed_on(tabs[cu[calm]], i[cu[calm]])
                    for n in cu[pressed].tolist():
                        clusters.append((n, [int(i[n])], False, True))
                    quiet.update(cu[calm & ~pressed & (approach <= V_MIN)].tolist())
        more_b, more_i = [tabs], [i]
        if pr.size:
            more_b.append(tabs[pr])
            more_i.append(j[pr])
            self._pairs(tabs[pr], i[pr], j[pr], pr, busy[pr] if any_busy else None, clusters,
                        quiet)
        if grouped is not None:
            # A fast contact or bounce of a grouped ball breaks its group: the others move
            # freely again, and those still pressed together are joined again as their
            # predictions find them (a cheap step where a break's impacts cross a group).
            for n in np.flatnonzero(grouped & (kind >= Due.CUSHION)).tolist():
                b = int(tabs[n])
                own = {int(x) for x in (i[n], j[n]) if x >= 0}
                members = {k for x in own for k in self._group_of(b, x)}
                rest = sorted(members - own)
                self.group[b, sorted(members)] = -1
                self._ngroup[b] = int((self.group[b] >= 0).sum())
                if rest:
                    k = np.array(rest)
                    bb, tt = np.full(k.size, b), np.full(k.size, self.tb[b])
                    self.balls.set(bb, k, tt, *self.balls.eval(bb, k, tt))
                    more_b.append(bb)
                    more_i.append(k)
        extra: dict[int, list[int]] = {}  # event -> other balls its cluster solve moved
        also: dict[int, list[tuple[int, int, int]]] = {}  # event -> other balls' transitions
        for n, seeds, every, own in clusters:
            b = int(tabs[n])
            before = self.state[b].copy()
            members, moved = self._cluster(b, seeds, every)
            self.work += len(members) ** 3 // CLUSTER_WORK
            if own and not moved:
                quiet.add(n)
            more_b.append(np.full(len(members), b))
            more_i.append(np.array(members, dtype=np.int64))
            ends = []
            if self.record:
                # A group renewed when one of its balls stops may stop the others with it:
                # each such end is an event of its own.
                self_ = int(i[n]) if kind[n] == Due.TRANSITION else -1  # a transition's own ball
                ends = [(k, int(before[k]), int(self.state[b, k])) for k in members if k != self_]
                ends = [e for e in ends if e[1:] in ENDS]
                also.setdefault(n, []).extend(ends)
            if kind[n] != Due.TRANSITION:  # a transition renews a group: others move by rounding
                skip = {int(i[n]), int(j[n])} | {k for k, _, _ in ends} | set(extra.get(n, ()))
                extra.setdefault(n, []).extend(k for k in moved if k not in skip)
        self._predict(np.concatenate(more_b), np.concatenate(more_i))
        for n in quiet:
            if kind[n] == Due.PAIR:
                self.schedule.unstick(int(tabs[n]), int(i[n]), int(j[n]))
        if self.record:
            self._log(tabs, kind, i, j, old_state, labels, extra, also, quiet)

    def _grouped(self, tabs, i, j, kind):
        """Events (by position in the pass) that involve a grouped ball, or None if no table
        of the pass has a group (the usual case, decided without array work)."""
        if (not self._ngroup[int(tabs[0])]) if tabs.size == 1 else not self._ngroup[tabs].any():
            return None
        out = (self.group[tabs, i] >= 0) & (kind != Due.CHECK)
        pair = kind == Due.PAIR
        out[pair] |= self.group[tabs[pair], j[pair]] >= 0
        return out

    def _group_of(self, b: int, i: int) -> list[int]:
        """The balls of ball i's group (itself alone if it has none)."""
        g = int(self.group[b, i])
        if g < 0:
            return [i]
        return np.flatnonzero(self.group[b] == g).tolist()

    def _pairs(self, b, i, j, pr, busy, clusters, quiet) -> None:
        """Ball-ball contacts (b, i, j), events pr of the pass (busy: over the work bound, or
        None for none): fast ones collide; slow ones of a pair that touches nothing else
        settle here (events that change nothing go to `quiet`), the rest go to `clusters`."""
        n = b.size
        if n == 1 and busy is None and self._pair_one(int(b[0]), int(i[0]), int(j[0])):
            return
        # Both balls' states, once, for the closing speed and for whichever response.
        tb = self.tb[b]
        p, v, w = self.balls.eval(np.concatenate([b, b]), np.concatenate([i, j]),
                             np.concatenate([tb, tb]))
        states = (p[:n], v[:n], w[:n], p[n:], v[n:], w[n:])
        d = states[3] - states[0]
        closing = ((states[1] - states[4]) * d).sum(axis=1) / _norm(d)
        slow = closing < self.physics.v_inelastic
        if busy is not None:
            slow |= busy
        if not slow.any():
            self._collide(b, i, j, *states)
            return
        fast = ~slow
        if fast.any():
            self._collide(b[fast], i[fast], j[fast], *(x[fast] for x in states))
        calm = slow if busy is None else slow & ~busy
        sl = np.flatnonzero(calm)
        if sl.size:
            # A pair alone, neither ball grouped: settled here, unless it stays pressed
            # together, which the cluster's solve makes a group.
            bs, is_, js = b[sl], i[sl], j[sl]
            alone = self._alone(bs, is_, js) & (self.group[bs, is_] < 0) & (self.group[bs, js] < 0)
            if alone.any():
                a = sl[alone]
                changed = self._settle(b[a], i[a], j[a], *(x[a] for x in states))
                pressed = self._pressed(b[a], i[a], j[a])
                quiet.update(int(pr[k]) for k in a[~changed & ~pressed].tolist())
                alone[alone] = ~pressed
            sl = sl[~alone]
        late = sl.tolist() + (np.flatnonzero(busy).tolist() if busy is not None else [])
        for k in late:
            every = busy is not None and bool(busy[k])
            clusters.append((int(pr[k]), [int(i[k]), int(j[k])], every, True))

    def _transition(self, b, i) -> None:
        """Balls (b, i) whose motion state ends now start their next one."""
        if b.size <= FEW:
            self._transition_few(b, i)
            return
        t = self.tb[b]
        p, v, w = self.balls.eval(b, i, t)
        v, w = transition.end(self.state[b, i], v, w, self.radius[b, i])
        self.balls.set(b, i, t, p, v, w)

    def _transition_few(self, b, i) -> None:
        """_transition in plain floats, ball by ball (bit-identical)."""
        ph = self.physics
        out = []
        for t, row, st, R in zip(self.tb[b].tolist(), self.balls.motion[b, i].tolist(),
                                 self.state[b, i].tolist(), self.radius[b, i].tolist(),
                                 strict=True):
            p, v, w = motion.at(row, t)
            v, w = transition.end_one(st, v, w, R)
            out.append(motion.start(ph, t, p, v, w, R, row[Col.RATE], st == POCKETED))
        self.balls.write_few(b, i, out)

    def _cushion(self, b, i) -> None:
        """Balls (b, i) meet the rail, jaw, jaw tip or pocket hole they were headed for."""
        tab, ph, feat = self.table, self.physics, self.features
        if b.size == 1:
            self._cushion_one(int(b[0]), int(i[0]))
            return
        t = self.tb[b]
        f = self.f_cush[b, i]
        p, v, w = self.balls.eval(b, i, t)
        hole = f >= feat.first_hole
        rc = self.rc[b, i]
        ref, n = feat.points(f), feat.normals(f, p)  # of the rails, jaws and tips met
        bounce = np.nonzero(~hole)[0]
        if bounce.size:
            bb, ib = b[bounce], i[bounce]
            nb = n[bounce]
            vb, wb = cushion.MODELS[ph.cushion].bounce(nb, v[bounce], w[bounce],
                                                       self.radius[bb, ib], self.mass[bb, ib], ph)
            pb = sink.lift(p[bounce], ref[bounce], nb, rc[bounce])
            self.balls.set(bb, ib, t[bounce], pb, vb, wb)
        hl = np.nonzero(hole)[0]
        if hl.size:
            bh, ih = b[hl], i[hl]
            k = f[hl] - feat.first_hole
            self.state[bh, ih] = POCKETED
            self.pocket[bh, ih] = k
            self.balls.set(bh, ih, t[hl], *pocket.drop(tab.hole_c[k]))

    def _cushion_one(self, b: int, i: int) -> None:
        """_cushion for one ball in plain floats, bit-identical to it."""
        tab, ph = self.table, self.physics
        t = float(self.tb[b])
        f = int(self.f_cush[b, i])
        row = self.balls.motion[b, i].tolist()
        r = row[Col.RADIUS]
        hole = f - self.features.first_hole
        if hole >= 0:
            self.state[b, i] = POCKETED
            self.pocket[b, i] = hole
            p, v, w = pocket.drop_one(tab.hole_c[hole].tolist())
        else:
            p, v, w = motion.at(row, t)
            ref, n = self.features.contact_one(f, p)
            v, w = cushion.MODELS[ph.cushion].bounce_one(n, v, w, r, row[Col.MASS], ph)
            p = sink.lift_one(p, ref, n, float(self.rc[b, i]))
        self.balls.write_few(np.array([b]), np.array([i]), [
            motion.start(ph, t, p, v, w, r, row[Col.RATE], bool(self.state[b, i] == POCKETED))])

    def _sunk(self, b, i) -> np.ndarray:
        """True for balls (b, i) sunk deeper than CLUSTER_GAP into the rail, jaw or jaw tip
        they are about to meet."""
        p, _, _ = self.balls.eval(b, i, self.tb[b], spin=False)
        f = self.f_cush[b, i]
        n = self.features.normals(f, p)
        depth = self.rc[b, i] - ((p - self.features.points(f)) * n).sum(axis=1)
        return depth > CLUSTER_GAP

    def _pair_one(self, b: int, i: int, j: int) -> bool:
        """One fast ball-ball contact in plain floats (the usual pass), bit-identical to the
        array path; False, doing nothing, if the contact is slow."""
        t = float(self.tb[b])
        rows = self.balls.motion[b, [i, j]].tolist()
        pi, vi, wi = motion.at(rows[0], t)
        pj, vj, wj = motion.at(rows[1], t)
        d0, d1 = pj[0] - pi[0], pj[1] - pi[1]
        dist = float(np.hypot(d0, d1))
        if not dist > 0:  # centres together: leave it to the array path's nan handling
            return False
        closing = ((vi[0] - vj[0]) * d0 + (vi[1] - vj[1]) * d1) / dist
        ph = self.physics
        if closing < ph.v_inelastic:
            return False
        ri, rj = rows[0][Col.RADIUS], rows[1][Col.RADIUS]
        mi, mj = rows[0][Col.MASS], rows[1][Col.MASS]
        vi, vj, wi, wj = BALL_BALL[ph.ball_ball].collide_one(pi, pj, vi, vj, wi, wj, ri, rj,
                                                             mi, mj, ph)
        pi, pj = ball_sink.undo_one(pi, pj, ri, rj, mi, mj)  # as _part
        pocketed = self.state[b, [i, j]] == POCKETED
        self.balls.write_few(np.array([b, b]), np.array([i, j]), [
            motion.start(ph, t, pi, vi, wi, ri, rows[0][Col.RATE], bool(pocketed[0])),
            motion.start(ph, t, pj, vj, wj, rj, rows[1][Col.RATE], bool(pocketed[1]))])
        return True

    def _collide(self, b, i, j, pi, vi, wi, pj, vj, wj) -> None:
        """Fast contacts (b, i, j), balls i and j now at (pi, vi, wi) and (pj, vj, wj)."""
        ph = self.physics
        t = self.tb[b]
        ri, rj = self.radius[b, i], self.radius[b, j]
        mi, mj = self.mass[b, i], self.mass[b, j]
        vi, vj, wi, wj = BALL_BALL[ph.ball_ball].collide(pi, pj, vi, vj, wi, wj, ri, rj, mi, mj,
                                                         ph)
        self._part(b, i, j, t, pi, pj, vi, vj, wi, wj)

    def _part(self, b, i, j, t, pi, pj, vi, vj, wi, wj) -> None:
        """Start both balls of contacts (b, i, j) on their new motion, first undoing a resting
        contact's sub-micrometre sink."""
        pi, pj = ball_sink.undo(pi, pj, self.radius[b, i], self.radius[b, j], self.mass[b, i],
                           self.mass[b, j])
        self.balls.set(np.concatenate([b, b]), np.concatenate([i, j]), np.concatenate([t, t]),
                  np.concatenate([pi, pj]), np.concatenate([vi, vj]), np.concatenate([wi, wj]))

    def ball_state(self, b: int, i: int) -> BallState:
        """Ball i of table b as it is at the table's clock (for events and output)."""
        return self.balls.ball_state(b, i, self.tb[b])

    def _log(self, tabs, kind, i, j, old_state, labels, extra, also, quiet) -> None:
        """Record events; a contact solved with its cluster also names the other balls of the
        cluster it set moving (after the contact's own one or two), and transitions of other
        balls of a group renewed by the event follow it as events of their own. A resting
        contact that begins (`quiet`: balls start pressing together, no impulse) is not a
        collision and is not recorded."""
        for n, b in enumerate(tabs.tolist()):
            k = int(kind[n])
            if k == Due.CHECK or n in quiet:
                self._log_also(b, also.get(n, ()))
                continue
            ib = int(i[n])
            where: dict = {}
            if k == Due.TRANSITION:
                pair = (int(old_state[n]), int(self.state[b, ib]))
                if pair[0] == pair[1]:  # a group's motion renewed, nothing ended
                    self._log_also(b, also.get(n, ()))
                    continue
                what = ENDS.get(pair, EventKind.TRANSITION)
                balls = [ib]
            elif k == Due.CUSHION:
                f, name = labels[n]
                if self.state[b, ib] == POCKETED:
                    what, where["pocket"] = EventKind.POCKET, name
                else:
                    what, where["cushion"], where["feature"] = EventKind.CUSHION, f, name
                balls = [ib]
            else:
                what = EventKind.BALL_BALL
                balls = [ib, int(j[n])]
            balls += extra.get(n, [])
            self._append(Event(what, float(self.tb[b]), b, tuple(balls),
                               tuple(self.ball_state(b, x) for x in balls), **where))
            self._log_also(b, also.get(n, ()))

    def _log_also(self, b: int, changes) -> None:
        for x, old, new in changes:
            self._append(Event(ENDS[(old, new)], float(self.tb[b]), b, (x,),
                               (self.ball_state(b, x),)))

    def _append(self, ev: Event) -> None:
        self.log[ev.table].append(ev)
        self._unsynced = True

    @property
    def events(self) -> list[list[dict]]:
        """Each table's events in the JSON form (`Event.to_json`) of records and output."""
        if self._unsynced:
            for log, out in zip(self.log, self._json, strict=True):
                out.extend(ev.to_json() for ev in log[len(out):])
            self._unsynced = False
        return self._json

    # ----------------------------------------------------------------- public view and driving
    def _now(self):
        return self.balls.now(self.tb)

    @property
    def pos(self) -> np.ndarray:
        """(B, N, 2) positions now (pocketed balls sit at their pocket's centre)."""
        return self._now()[0]

    @property
    def vel(self) -> np.ndarray:
        return self._now()[1]

    @property
    def w(self) -> np.ndarray:
        return self._now()[2]

    def at_rest(self) -> np.ndarray:
        """(B,) True where every ball is stationary or pocketed."""
        return np.isinf(self.t_next)

    def step(self, dt: float) -> None:
        """Advance every table by dt seconds, exactly: every event inside the step is run at
        its own time, however many there are."""
        if not (dt > 0 and math.isfinite(dt)):
            raise ValueError("dt: must be a positive finite number of seconds")
        self._run_until(self.time + dt)
        self.time += dt
        self.steps += 1

    def _sample(self) -> tuple[float, np.ndarray, np.ndarray]:
        return (self.time, self.pos, self.state.copy())

    def run(self, dt: float, duration: float | None = None, sample_hz: float | None = None,
            max_steps: int | None = None) -> list:
        """Fixed steps of dt until every table is at rest, or until the clock reaches
        `duration` (simulated seconds since the start, not since this call).

        With sample_hz, positions are also taken at multiples of 1/sample_hz.
        """
        if not (dt > 0 and math.isfinite(dt)):
            raise ValueError("dt: must be a positive finite number of seconds")
        samples = []
        k = 0
        if sample_hz:
            samples.append(self._sample())
            k = 1
        start, n = self.time, 0
        while not self.at_rest().all():
            # Step ends are start + n dt (no drift from summing steps); a sliver left by
            # rounding is not another step.
            if duration is not None and self.time >= duration - 1e-9 * dt:
                break
            if max_steps is not None and self.steps >= max_steps:
                break
            n += 1
            t_end = start + n * dt
            if duration is not None and t_end > duration - 1e-9 * dt:
                t_end = duration
            while sample_hz and k / sample_hz <= t_end:
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
        self.time = t_stop if math.isfinite(t_stop) else max(self.time, float(self.tb.max()))
        return samples
