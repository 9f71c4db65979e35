"""The engine's record of what happened: each table's events, typed (`Event`) and as JSON.

Two modes. The full log gives each event the states of its balls just after it (records,
replays and `termpool sim` print them). The light log (`LIGHT`) keeps the rest of each event
(kind, time, table, balls, cushion or pocket) and no states: all the referee reads, for a
fraction of the cost, as the computer opponent's batches use it.
"""

from __future__ import annotations

import numpy as np

from termpool.physics import motion
from termpool.physics.balls import FEW, Balls
from termpool.physics.events import ENDS, BallState, Event, EventKind
from termpool.physics.features import Features
from termpool.physics.flat import flat
from termpool.physics.motion import Col
from termpool.physics.schedule import Due
from termpool.physics.state import POCKETED

LIGHT = "light"  # the engine's `record` for a log without the balls' states


def check_mode(record) -> None:
    """Raise ValueError naming `record` unless it is True (the full log), False (none) or LIGHT."""
    if not (record == LIGHT if isinstance(record, str) else record in (True, False)):
        raise ValueError(f"record: must be True, False or {LIGHT!r}, not {record!r}")


class EventLog:
    """Every table's events in time order: `tables` (typed) and `json()` (`Event.to_json`).
    `tb` is the tables' clocks, at which the balls' states are taken; without `states`
    (the light log) events carry none."""

    def __init__(self, balls: Balls, features: Features, tb: np.ndarray,
                 states: bool = True) -> None:
        self.balls, self.features, self.tb, self.states = balls, features, tb, states
        self.tables: list[list[Event]] = [[] for _ in range(balls.B)]
        self._json: list[list[dict]] = [[] for _ in range(balls.B)]
        self._unsynced = False  # events were added since json() was last brought up to date
        self._tb = flat(tb)  # the clocks as plain floats (flat.py)

    def met(self, events: np.ndarray, f: np.ndarray) -> dict[int, tuple[int, str]]:
        """Cushion events (by place in a pass) -> the feature each met, (index, name): taken
        before the features' predictions are renewed."""
        return dict(zip(events.tolist(), zip(f.tolist(), self.features.names(f), strict=True),
                        strict=True))

    def record(self, tabs, due, i, j, old_state, cushions, extra, also, quiet) -> None:
        """Record the events of a pass: tables `tabs`, what was due, balls i and j, the
        balls' states before; `cushions` maps a cushion event to its feature (index, name).
        A contact solved with its cluster also names the other balls of the cluster it set
        moving (`extra`, after the contact's own one or two), and transitions of other balls
        of a group renewed by the event (`also`: ball, state before, state after) follow it
        as events of their own. A resting contact that begins (`quiet`: balls start pressing
        together, no impulse) is not a collision and is not recorded.

        The events are built first and the balls' states taken after, all of the pass's
        balls in one evaluation."""
        if isinstance(tabs, list):  # one table's event, as lists (Engine._handle_one)
            tabs_l, due_l, i_l, j_l, old = tabs, due, i, j, old_state
            N, st, tb = self.balls.N, self.balls.flat_state, self._tb
            now = [st[b * N + x] for b, x in zip(tabs_l, i_l, strict=True)]
            times = [tb[b] for b in tabs_l]
        else:
            tabs_l, due_l, i_l = tabs.tolist(), due.tolist(), i.tolist()
            j_l = j.tolist() if j is not None else None
            now = self.balls.state[tabs, i].tolist()
            old = old_state.tolist() if old_state is not None else None
            times = self.tb[tabs].tolist()
        # (kind, table, time, balls, cushion, feature, pocket), in the order of the pass;
        # the light log makes its events at once (it takes no states after them).
        out: list = []
        add = out.append
        light = not self.states
        tables = self.tables
        CHECK, TRANSITION, CUSHION = Due.CHECK, Due.TRANSITION, Due.CUSHION
        for n, b in enumerate(tabs_l):
            k = due_l[n]
            t = times[n]
            if k != CHECK and n not in quiet:
                ib = i_l[n]
                cushion = feature = pocket = None
                if k == TRANSITION:
                    was, new = old[n], now[n]
                    what = None if was == new else ENDS.get((was, new), EventKind.TRANSITION)
                    balls = (ib,)  # (nothing ended when a group's motion was only renewed)
                elif k == CUSHION:
                    f, name = cushions[n]
                    if now[n] == POCKETED:
                        what, pocket = EventKind.POCKET, name
                    else:
                        what, cushion, feature = EventKind.CUSHION, f, name
                    balls = (ib,)
                else:
                    what = EventKind.BALL_BALL
                    balls = (ib, j_l[n])
                if what is not None:
                    if extra and n in extra:
                        balls += tuple(extra[n])
                    if light:
                        tables[b].append(Event(what, t, b, balls, (), cushion, feature, pocket))
                    else:
                        add((what, b, t, balls, cushion, feature, pocket))
            if also and n in also:
                for x, was, new in also[n]:
                    if light:
                        tables[b].append(Event(ENDS[(was, new)], t, b, (x,), ()))
                    else:
                        add((ENDS[(was, new)], b, t, (x,), None, None, None))
        if light:
            self._unsynced = True
            return
        if not out:
            return
        states = iter(self._states([(b, x) for _, b, _, balls, *_ in out for x in balls]))
        for what, b, t, balls, cushion, feature, pocket in out:
            got = tuple(next(states) for _ in balls)
            tables[b].append(Event(what, t, b, balls, got, cushion, feature, pocket))
        self._unsynced = True

    def _states(self, which: list[tuple[int, int]]) -> list[BallState]:
        """The states of balls (table, ball) at their tables' clocks: up to FEW in plain
        floats (`motion.at`), more in one array evaluation (`motion.at_many`), which agree
        bit for bit."""
        bl, tb = self.balls, self.tb
        if len(which) <= FEW:
            out = []
            N, C, mm, st = bl.N, Col.N, bl.flat_motion, bl.flat_state
            for b, x in which:
                k = b * N + x
                p, v, w = motion.at(mm[k * C:(k + 1) * C].tolist(), self._tb[b])
                out.append(BallState(p[0], p[1], v[0], v[1], (w[0], w[1], w[2]), st[k]))
            return out
        b, x = np.array(which).T
        p, v, w = bl.eval(b, x, tb[b])
        return [BallState(px, py, vx, vy, (wx, wy, wz), s) for (px, py), (vx, vy), (wx, wy, wz), s
                in zip(p.tolist(), v.tolist(), w.tolist(), bl.state[b, x].tolist(), strict=True)]

    def json(self) -> list[list[dict]]:
        """Each table's events in the JSON form of records and output."""
        if self._unsynced:
            for log, out in zip(self.tables, self._json, strict=True):
                out.extend(ev.to_json() for ev in log[len(out):])
            self._unsynced = False
        return self._json
