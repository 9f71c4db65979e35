"""The engine: a batch of tables advanced by fixed steps, exact inside each step.

State lives in arrays with a leading table axis (B) and a ball axis (N). Between events every
ball moves on a closed-form quadratic from its own reference time t0 (balls.py), so a ball
nobody touches is never updated. For every ball the schedule keeps the time of its next
motion transition and of its next cushion or pocket contact, and for every pair the time of
their next contact (schedule.py); an event renews only the predictions of the balls it
touched. A step runs the events inside it in time order, one per table per pass and all
tables at once; a step without events costs one comparison, and tables at rest cost nothing.
The engine is the scheduler: the event loop, the work limit and the dispatch of each pass to
the responses (respond.py: fast events; slow.py: slow contacts and clusters; joined.py:
groups), whose models live one per unit (physics/models.py lists them).
"""

from __future__ import annotations

import math

import numpy as np

from termpool.physics.balls import Balls, ball_arrays
from termpool.physics.events import BallState
from termpool.physics.features import Features
from termpool.physics.flat import flat
from termpool.physics.joined import Groups
from termpool.physics.log import LIGHT, EventLog, check_mode
from termpool.physics.params import BALL_MASS, BALL_RADIUS, Physics
from termpool.physics.respond import Responses
from termpool.physics.schedule import Due, Schedule
from termpool.physics.slow import Cluster, SlowContacts
from termpool.physics.state import POCKETED, SPINNING, STATE_NAMES, STATIONARY  # noqa: F401
from termpool.physics.table import Table

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
_TRUE, _FALSE = np.ones(1, dtype=bool), np.zeros(1, dtype=bool)  # one table over the bound, or not
for _a in (_ONE, _NONE, _TRUE, _FALSE):
    _a.flags.writeable = False


class WorkLimit(RuntimeError):
    """A run that met the work limit; the message is one line naming it."""


def _split(due: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The events of a pass of n tables that are transitions, cushion contacts and pairs."""
    if n == 1:  # one table (the usual case): pick its kind without array scans
        k = int(due[0])
        return (_ONE if k == Due.TRANSITION else _NONE, _ONE if k == Due.CUSHION else _NONE,
                _ONE if k == Due.PAIR else _NONE)
    return ((due == Due.TRANSITION).nonzero()[0], (due == Due.CUSHION).nonzero()[0],
            (due == Due.PAIR).nonzero()[0])


class Engine:
    """Advance B independent tables of N balls each (arrays may omit the table axis).

    `record`: True keeps the full event log (each event with its balls' states), LIGHT
    (`"light"`) the log without the states (what the referee reads), False none."""

    def __init__(
        self,
        table: Table,
        physics: Physics,
        pos,
        vel=None,
        w=None,
        radius=BALL_RADIUS,
        mass=BALL_MASS,
        record: bool | str = True,
        horizon: float = HORIZON,
        max_work: float | None = None,
    ) -> None:
        self.batched, pos, vel, w, radius, mass = ball_arrays(pos, vel, w, radius, mass)
        check_mode(record)
        B, N = radius.shape
        self.B, self.N = B, N
        self.table, self.physics, self.record = table, physics, record
        self.tb = np.zeros(B)  # each table's own clock inside a step
        self.time = 0.0
        self.steps = 0
        self.passes = 0  # event passes run
        self.work = 0  # units of work done, and the limit (see WORK_LIMIT)
        self.max_work = WORK_LIMIT if max_work is None else max_work
        self._win = np.full(B, -1, dtype=np.int64)  # work bound: window and events in it
        self._count = np.zeros(B, dtype=np.int64)
        self._win_one, self._count_one = -1, 0  # the same for one table, as ints
        self._stopped: np.ndarray | None = None  # tables `stop` took out of the run
        # The collaborators: the balls and their motions, the table's features, the
        # predictions, the responses to fast events, groups, slow contacts, the event log.
        times = Schedule.new_times(B, N)
        self.balls = Balls(physics, radius, mass, times[:, :N])
        self.features = Features(table)
        self.schedule = Schedule(times, self.balls, self.features, self.tb, horizon)
        self.respond = Responses(physics, self.balls, self.features, self.schedule, self.tb)
        self.groups = Groups(physics, self.balls, self.tb)
        self.slow = SlowContacts(physics, self.balls, self.features, self.schedule, self.groups,
                                 self.respond, self.tb)
        self.recorder = EventLog(self.balls, self.features, self.tb, states=record != LIGHT)
        self.log = self.recorder.tables  # each table's events, typed
        # The arrays the engine's users read, as the collaborators hold them.
        bl, sc = self.balls, self.schedule
        self.radius, self.mass, self.rc, self.state, self.pocket, self.t_trans = (
            bl.radius, bl.mass, bl.rc, bl.state, bl.pocket, bl.t_trans)
        self.t_cush, self.f_cush, self.t_next = sc.t_cush, sc.f_cush, sc.t_next
        # One table's clock and next event time as plain floats, through flat views.
        self._tb_one, self._next_one = flat(self.tb), flat(self.t_next)
        b, i = np.divmod(np.arange(B * N), N)
        with np.errstate(all="ignore"):
            self.balls.set(b, i, self.tb[b], pos[b, i], vel[b, i], w[b, i])
            self._predict(b, i)
            self.schedule.refresh(np.arange(B))
        self.schedule.defer = B > 1  # (from the first event on: see Schedule._later)

    # ----------------------------------------------------------------- the event loop
    def _run_until(self, t_end: float) -> None:
        """Run every table's events up to t_end in time order; clocks end at t_end."""
        self._spend(1)
        one = self.B == 1
        due = self._next_one[0] <= t_end if one else (self.t_next <= t_end).any()
        if due:
            with np.errstate(all="ignore"):  # infinities stand for "never"
                self._run_events(t_end)
        if math.isfinite(t_end):
            if one and self._stopped is None:
                self._tb_one[0] = t_end
            elif self._stopped is None:
                self.tb[:] = t_end
            else:
                self.tb[~self._stopped] = t_end

    def _run_events(self, t_end: float) -> None:
        one = self.B == 1  # one table (the usual case): no array scans
        while True:
            if one:
                t = self._next_one[0]
                if not (t <= t_end and t < math.inf):
                    break
                tabs = _ONE
            else:
                tabs = ((self.t_next <= t_end) & (self.t_next < math.inf)).nonzero()[0]
                if tabs.size == 0:
                    break
            self._spend(PASS_WORK)
            self.passes += 1
            if one:
                self._tb_one[0] = t
                self._handle_one(self.schedule.code_one)
                self.schedule.refresh_one(0)
            else:
                self.tb[tabs] = self.t_next[tabs]
                self._handle(tabs, self.schedule.c_next[tabs])
                self.schedule.refresh(tabs)
                if self.schedule.pending:
                    self.schedule.complete()

    def _spend(self, units: int) -> None:
        """Count work before a step or a pass; raise WorkLimit past the limit (between
        passes, so the engine's state stays whole)."""
        self.work += units
        if self.work > self.max_work:
            if self.schedule.pending:  # every prediction made, as after any pass
                with np.errstate(all="ignore"):
                    self.schedule.complete(force=True)
            raise WorkLimit(f"engine: the run met its work limit of {self.max_work:,.0f} units "
                            f"at {float(self.tb.max()):.6g} s of simulated time (docs/limits.md)")

    def _predict(self, b: np.ndarray, i: np.ndarray) -> None:
        """Renew the contact predictions of balls (b, i), counting the work."""
        self.work += b.size * self.N
        self.schedule.predict(b, i)

    def _busy(self, tabs: np.ndarray) -> np.ndarray:
        """Count an event of each of tables `tabs` in its window: True where over BUDGET."""
        if self.B == 1:  # one table: in plain numbers (floor of the same quotient)
            win = math.floor(self._tb_one[0] / WINDOW)
            self._count_one = 1 if win != self._win_one else self._count_one + 1
            self._win_one = win
            return _TRUE if self._count_one > BUDGET else _FALSE
        win = np.floor(self.tb[tabs] / WINDOW).astype(np.int64)
        count = np.where(win != self._win[tabs], 1, self._count[tabs] + 1)
        self._win[tabs] = win
        self._count[tabs] = count
        return count > BUDGET

    def _handle(self, tabs: np.ndarray, code: np.ndarray) -> None:
        """Run the next event of each of tables `tabs` (event codes `code`), at its clock."""
        due, i, j = self.schedule.decode(code)
        old_state = self.state[tabs, i] if self.record else None
        busy = self._busy(tabs)
        any_busy = bool(busy.any())
        tr, cu, pr = _split(due, tabs.size)
        clusters: list[Cluster] = []
        quiet: set[int] = set()  # events that changed nothing: resting contacts that began
        # Balls held in a group by resting contacts (joined.py): any event of one of them
        # renews the whole group's motion, since its contact forces change with it.
        involved = self.groups.involved(tabs, i, j, due)
        if tr.size:
            if involved is not None:
                for n in tr[involved[tr]].tolist():
                    members = self.groups.members(int(tabs[n]), int(i[n]))
                    clusters.append(Cluster(n, members, False, False))
                tr = tr[~involved[tr]]
            if tr.size:
                self.respond.transition(tabs[tr], i[tr])
        cushions: dict = {}  # cushion event -> its feature (index, name), for the log
        if cu.size:
            if self.record:
                cushions = self.recorder.met(cu, self.f_cush[tabs[cu], i[cu]])
            more, still = self.slow.cushions(tabs, i, cu, busy, any_busy)
            clusters += more
            quiet |= still
        more_b, more_i = [tabs], [i]
        if pr.size:
            more_b.append(tabs[pr])
            more_i.append(j[pr])
            more, still = self.slow.pairs(tabs[pr], i[pr], j[pr], pr,
                                          busy[pr] if any_busy else None)
            clusters += more
            quiet |= still
        if involved is not None:
            bb, ii = self.groups.break_up(tabs, i, j, due, involved)
            more_b += bb
            more_i += ii
        solved = self.slow.solve(tabs, i, j, due, clusters, self.record)
        self.work += sum(k ** 3 // CLUSTER_WORK for k in solved.sizes)
        quiet |= solved.quiet
        self._predict(np.concatenate(more_b + solved.tables), np.concatenate(more_i + solved.balls))
        for n in quiet:
            if due[n] == Due.PAIR:
                self.schedule.unstick(int(tabs[n]), int(i[n]), int(j[n]))
        if self.record:
            self.recorder.record(tabs, due, i, j, old_state, cushions, solved.extra, solved.also,
                                 quiet)

    def _handle_one(self, code: int) -> None:
        """`_handle` for one table (B == 1), step for step, with its event's kind and balls
        as ints and its one-element arrays made once (`Schedule.one_array`)."""
        sc = self.schedule
        k, i0, j0 = sc.decode_one(code)
        tabs, due, i, j = _ONE, sc.one_array(k), sc.one_array(i0), sc.one_array(j0)
        old_state = [self.balls.flat_state[i0]] if self.record else None
        busy = self._busy(tabs)
        any_busy = busy is _TRUE
        clusters: list[Cluster] = []
        quiet: set[int] = set()
        involved = (self.groups.involved(tabs, i, j, due) if self.groups.flat_count[0]
                    else None)
        if k == Due.TRANSITION:
            if involved is not None and involved[0]:
                clusters.append(Cluster(0, self.groups.members(0, i0), False, False))
            else:
                self.respond.transition(tabs, i)
        cushions: dict = {}
        if k == Due.CUSHION:
            if self.record:
                f = sc.flat_f_cush[i0]
                cushions = {0: (f, self.features.names([f])[0])}
            more, still = self.slow.cushions(tabs, i, _ONE, busy, any_busy)
            clusters += more
            quiet |= still
        bl, il = [0], [i0]
        if k == Due.PAIR:
            bl.append(0)
            il.append(j0)
            more, still = self.slow.pairs(tabs, i, j, _ONE, busy if any_busy else None)
            clusters += more
            quiet |= still
        more_b: list = []
        more_i: list = []
        if involved is not None:
            more_b, more_i = self.groups.break_up(tabs, i, j, due, involved)
        solved = self.slow.solve(tabs, i, j, due, clusters, self.record)
        self.work += sum(n ** 3 // CLUSTER_WORK for n in solved.sizes)
        quiet |= solved.quiet
        if more_b or solved.tables:
            self._predict(np.concatenate([np.array(bl)] + more_b + solved.tables),
                          np.concatenate([np.array(il)] + more_i + solved.balls))
        else:  # (the usual event: one or two balls, FEW at most)
            self.work += len(bl) * self.N
            sc.predict_few(bl, il)
        if quiet and k == Due.PAIR:
            sc.unstick(0, i0, j0)
        if self.record:
            self.recorder.record([0], [k], [i0], [j0], old_state, cushions, solved.extra,
                                 solved.also, quiet)

    # ----------------------------------------------------------------- public view and driving
    def ball_state(self, b: int, i: int) -> BallState:
        """Ball i of table b as it is at the table's clock (for events and output)."""
        return self.balls.ball_state(b, i, self.tb[b])

    @property
    def events(self) -> list[list[dict]]:
        """Each table's events in the JSON form (`Event.to_json`) of records and output."""
        return self.recorder.json()

    @property
    def pos(self) -> np.ndarray:
        """(B, N, 2) positions now (pocketed balls sit at their pocket's centre)."""
        return self.balls.now(self.tb)[0]

    @property
    def vel(self) -> np.ndarray:
        return self.balls.now(self.tb)[1]

    @property
    def w(self) -> np.ndarray:
        return self.balls.now(self.tb)[2]

    def stop(self, tables) -> None:
        """Run no more events of `tables` (indices): their clocks stay where they are, so
        positions read later are as of now. For a batch whose user has seen what it needed
        of some tables; the other tables run on exactly as they would have."""
        tables = np.asarray(tables, dtype=np.int64)
        if self._stopped is None:
            self._stopped = np.zeros(self.B, bool)
        self._stopped[tables] = True
        self.t_next[tables] = math.inf

    def at_rest(self) -> np.ndarray:
        """(B,) True where every ball is stationary or pocketed (or the table was stopped)."""
        return np.isinf(self.t_next)

    def _all_at_rest(self) -> bool:
        """`at_rest().all()`, for one table without array calls."""
        return math.isinf(self._next_one[0]) if self.B == 1 else bool(self.at_rest().all())

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
        while not self._all_at_rest():
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
