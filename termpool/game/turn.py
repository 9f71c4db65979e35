"""One turn: the shot a player makes (`Shot`), the shot in progress (`ShotRun`), and the
rules state as JSON and as a scene's `game` block."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from termpool.rules.common import Outcome, State, groups_to_json

from . import record

if TYPE_CHECKING:
    from .match import Match


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


def state_to_json(s: State) -> dict:
    return {"mode": s.mode, "shooter": s.shooter, "groups": groups_to_json(s.groups),
            "fouls": list(s.fouls), "pocketed": list(s.pocketed), "is_break": s.is_break,
            "push_out": s.push_out, "called": None if s.called is None else list(s.called),
            "three_foul": s.three_foul}


def state_from_json(d: Any, path: str = "state") -> State:
    if not isinstance(d, dict):
        raise ValueError(f"{path}: must be an object")
    try:
        groups = d.get("groups")
        called = d.get("called")
        return State(
            mode=d["mode"], shooter=d["shooter"],
            groups=None if groups is None else {int(p): g for p, g in groups.items()},
            fouls=tuple(int(n) for n in d["fouls"]), pocketed=tuple(d["pocketed"]),
            is_break=bool(d["is_break"]), push_out=d["push_out"],
            called=None if called is None else (str(called[0]), str(called[1])),
            three_foul=bool(d["three_foul"]))
    except KeyError as e:
        raise ValueError(f"{path}: missing key '{e.args[0]}'") from None
    except (TypeError, ValueError, AttributeError, IndexError) as e:
        raise ValueError(f"{path}: {e}") from None


def game_block(s: State) -> dict:
    """The scene `game` block for the referee of the shot about to be played from `s`."""
    g: dict[str, Any] = {"mode": s.mode, "shooter": s.shooter, "break": s.is_break,
                         "fouls": {"0": s.fouls[0], "1": s.fouls[1]}}
    if s.groups is not None:
        g["groups"] = groups_to_json(s.groups)
    if s.called is not None:
        g["called"] = {"ball": s.called[0], "pocket": s.called[1]}
    if s.mode == "9ball":
        g["push_out"] = s.push_out == "declared"
        g["three_foul"] = s.three_foul
    return g


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
    rows `rows` of the match's arrays). The UI calls `step(dt)` once per frame and reads
    `engine.pos[0]`; `finish()` runs to rest, judges and applies the shot to the match."""

    def __init__(self, match: Match, shot: Shot, state: State, scene_dict: dict) -> None:
        self.match, self.shot, self.state = match, shot, state
        self.scene_dict = scene_dict
        self.scene = record.shot_scene(scene_dict, shot.to_json())
        self.engine = record.start_engine(self.scene)
        self.ids: list[str] = list(self.scene.ids)
        self.rows = np.array([match.ids.index(b) for b in self.ids])
        self.dt = match.dt
        self.outcome: Outcome | None = None
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
        """Run to rest if needed, judge, apply the outcome to the match and record the shot.
        Calling it again returns the same outcome."""
        if self.outcome is None:
            record.run_to_rest(self.engine, self.dt)
            self.outcome = self.match._apply(self)
        return self.outcome
