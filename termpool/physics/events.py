"""What the engine reports: typed events, the one seam between the physics and the rules.

Each table's log is a list of `Event`s in time order. `Event.to_json` gives the form records,
`termpool sim` and the engine's `events` view hold: ``{"t", "type", ["feature" | "pocket"],
"i", "balls"}``, with ``i`` the ball indices and ``balls`` their states at the event.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from termpool.physics.state import (
    ROLLING,
    SLIDING,
    SPINNING,
    STATE_NAMES,
    STATIONARY,
)


class EventKind(Enum):
    """What happened; the value is the event's JSON `type`."""

    BALL_BALL = "ball_ball"  # balls: the pair, then other balls its cluster's solve moved
    CUSHION = "cushion"  # a rail, a jaw or a jaw tip
    POCKET = "pocket"
    SLIDE_TO_ROLL = "slide_to_roll"
    SLIDE_TO_SPIN = "slide_to_spin"
    SLIDE_TO_STOP = "slide_to_stop"
    ROLL_TO_SPIN = "roll_to_spin"
    ROLL_TO_STOP = "roll_to_stop"
    SPIN_TO_STOP = "spin_to_stop"
    TRANSITION = "transition"  # any other change of motion state (a still ball pushed on)


# The motion state changes a ball's own motion makes, by (state before, state after).
ENDS = {
    (SLIDING, ROLLING): EventKind.SLIDE_TO_ROLL,
    (SLIDING, SPINNING): EventKind.SLIDE_TO_SPIN,
    (SLIDING, STATIONARY): EventKind.SLIDE_TO_STOP,
    (ROLLING, SPINNING): EventKind.ROLL_TO_SPIN,
    (ROLLING, STATIONARY): EventKind.ROLL_TO_STOP,
    (SPINNING, STATIONARY): EventKind.SPIN_TO_STOP,
}


@dataclass(slots=True)
class BallState:
    """One ball's position, velocity, spin and motion state (a `state` code) at an instant."""

    x: float
    y: float
    vx: float
    vy: float
    w: tuple[float, float, float]
    state: int

    def to_json(self) -> dict:
        return {"x": self.x, "y": self.y, "vx": self.vx, "vy": self.vy, "w": list(self.w),
                "state": STATE_NAMES[self.state]}


@dataclass(slots=True)
class Event:
    """One event of one table: its kind, time, the balls it concerns (indices) with their
    states just after it (none in a light log, whose JSON "balls" is then empty), and for a
    cushion the feature met (`cushion`: its index among the table's rails and jaws, then jaw
    tips; `feature`: "rail", "jaw" or "tip"), for a pocket the pocket's name."""

    kind: EventKind
    t: float
    table: int
    balls: tuple[int, ...]
    states: tuple[BallState, ...]
    cushion: int | None = None
    feature: str | None = None
    pocket: str | None = None

    def to_json(self) -> dict:
        out: dict = {"t": self.t, "type": self.kind.value}
        if self.kind is EventKind.CUSHION:
            out["feature"] = self.feature
        elif self.kind is EventKind.POCKET:
            out["pocket"] = self.pocket
        out["i"] = list(self.balls)
        out["balls"] = [s.to_json() for s in self.states]
        return out
