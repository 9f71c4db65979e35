"""One turn: the shot a player makes (`Shot`) and the shot in progress (`ShotRun`)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from termpool.rules.common import Outcome, State

from . import record


@dataclass(frozen=True)
class Shot:
    """What the player does: `cue.strike`'s speed (m/s), angle (degrees), side and top (tip
    offsets in ball radii); `called` = (ball, pocket) when a call is needed (8-ball: the 8);
    `push_out` declares a 9-ball push-out on the shot after the break."""

    speed: float
    angle: float
    side: float = 0.0
    top: float = 0.0
    called: tuple[str, str] | None = None
    push_out: bool = False

    def to_json(self) -> dict:
        return {"speed": float(self.speed), "angle": float(self.angle),
                "side": float(self.side), "top": float(self.top),
                "called": None if self.called is None else list(self.called),
                "push_out": bool(self.push_out)}


def advance(engine, dt: float, owed: float) -> float:
    """Play `owed` seconds of a shot in whole engine steps of the fixed `dt` until the table is
    at rest; returns the time still owed (a remainder waits for the next call). The one way a
    shot is shown frame by frame, live and when a replay is watched."""
    while owed >= dt * (1 - 1e-9) and not engine.at_rest()[0]:
        engine.step(dt)
        owed -= dt
    return owed


class ShotRun:
    """One shot in progress: `engine` holds only the balls on the table (`ids`, which are
    rows `rows` of the match's `match_ids`). The UI calls `step(dt)` once per frame and reads
    `engine.pos[0]`; `finish()` runs to rest and hands the shot to `settle` (the match's),
    which judges, records and applies it."""

    def __init__(self, shot: Shot, state: State, scene_dict: dict, match_ids: Sequence[str],
                 dt: float, settle: Callable[[ShotRun], Outcome]) -> None:
        self.shot, self.state, self.scene_dict = shot, state, scene_dict
        self.scene = record.shot_scene(scene_dict, shot.to_json())
        self.engine = record.start_engine(self.scene)
        self.ids: list[str] = list(self.scene.ids)
        self.rows = np.array([list(match_ids).index(b) for b in self.ids])
        self.dt = dt
        self.outcome: Outcome | None = None
        self._settle = settle
        self._owed = 0.0

    @property
    def done(self) -> bool:
        """True when every ball on the table is at rest."""
        return bool(self.engine.at_rest()[0])

    def step(self, dt: float) -> None:
        """Advance by dt seconds of play, in whole engine steps of the fixed `self.dt` (the
        steps a replay takes; a remainder waits for the next call)."""
        if self.done or self.outcome is not None:
            return
        self._owed = advance(self.engine, self.dt, self._owed + dt)

    def finish(self) -> Outcome:
        """Run to rest if needed, then judge, record and apply the shot (`settle`). Calling
        it again returns the same outcome."""
        if self.outcome is None:
            record.run_to_rest(self.engine, self.dt)
            self.outcome = self._settle(self)
        return self.outcome
