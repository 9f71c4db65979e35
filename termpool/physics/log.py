"""The engine's record of what happened: each table's events, typed (`Event`) and as JSON."""

from __future__ import annotations

import numpy as np

from termpool.physics.balls import Balls
from termpool.physics.events import ENDS, BallState, Event, EventKind
from termpool.physics.features import Features
from termpool.physics.schedule import Due
from termpool.physics.state import POCKETED


class EventLog:
    """Every table's events in time order: `tables` (typed) and `json()` (`Event.to_json`).
    `tb` is the tables' clocks, at which the balls' states are taken."""

    def __init__(self, balls: Balls, features: Features, tb: np.ndarray) -> None:
        self.balls, self.features, self.tb = balls, features, tb
        self.tables: list[list[Event]] = [[] for _ in range(balls.B)]
        self._json: list[list[dict]] = [[] for _ in range(balls.B)]
        self._unsynced = False  # events were added since json() was last brought up to date

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
        together, no impulse) is not a collision and is not recorded."""
        state = self.balls.state
        for n, b in enumerate(tabs.tolist()):
            k = int(due[n])
            if k == Due.CHECK or n in quiet:
                self._also(b, also.get(n, ()))
                continue
            ib = int(i[n])
            where: dict = {}
            if k == Due.TRANSITION:
                pair = (int(old_state[n]), int(state[b, ib]))
                if pair[0] == pair[1]:  # a group's motion renewed, nothing ended
                    self._also(b, also.get(n, ()))
                    continue
                what = ENDS.get(pair, EventKind.TRANSITION)
                balls = [ib]
            elif k == Due.CUSHION:
                f, name = cushions[n]
                if state[b, ib] == POCKETED:
                    what, where["pocket"] = EventKind.POCKET, name
                else:
                    what, where["cushion"], where["feature"] = EventKind.CUSHION, f, name
                balls = [ib]
            else:
                what = EventKind.BALL_BALL
                balls = [ib, int(j[n])]
            balls += extra.get(n, [])
            self._append(Event(what, float(self.tb[b]), b, tuple(balls),
                               tuple(self._state(b, x) for x in balls), **where))
            self._also(b, also.get(n, ()))

    def _also(self, b: int, changes) -> None:
        for x, old, new in changes:
            self._append(Event(ENDS[(old, new)], float(self.tb[b]), b, (x,), (self._state(b, x),)))

    def _state(self, b: int, x: int) -> BallState:
        return self.balls.ball_state(b, x, self.tb[b])

    def _append(self, ev: Event) -> None:
        self.tables[ev.table].append(ev)
        self._unsynced = True

    def json(self) -> list[list[dict]]:
        """Each table's events in the JSON form of records and output."""
        if self._unsynced:
            for log, out in zip(self.tables, self._json, strict=True):
                out.extend(ev.to_json() for ev in log[len(out):])
            self._unsynced = False
        return self._json
