"""A shot on screen: power to speed, its frames computed at the strike, and the clock that
shows them a frame at a time (the game's and the watched match's alike).

A shot is simulated whole when it is struck (`simulate`): a step can cost far more than a
frame (the break's impact: ~100 contacts in 1/60 s), and a hitch there would show; the same
cost paid at the strike does not. The frames are then shown by wall-clock time through a
fixed-step accumulator (`Clock`), fast-forwarded by FAST.
"""

from __future__ import annotations

from dataclasses import dataclass

from termpool.physics.results import DT

MAX_STEPS_PER_TICK = 12  # a stalled terminal drops time instead of freezing on catch-up
MAX_SHOT_FRAMES = 180 * 60  # frames computed ahead; a longer shot finishes at once
MIN_SPEED, MAX_SPEED = 0.25, 9.0  # m/s at no and full power
DEFAULT_POWER = 0.5  # the aid's power (and the digits') before a match's first shot
FAST = 4.0  # fast-forward factor


def power_to_speed(level: float) -> float:
    """Cue-ball speed for a power level in [0, 1]: finer control of the soft shots most
    positions need (half power is about 3.3 m/s, full power a 9 m/s break)."""
    level = min(1.0, max(0.0, level))
    return MIN_SPEED + (MAX_SPEED - MIN_SPEED) * level ** 1.5


def speed_to_power(speed: float) -> float:
    """The power level (0 to 1) that strikes at `speed` (the inverse of `power_to_speed`)."""
    f = (float(speed) - MIN_SPEED) / (MAX_SPEED - MIN_SPEED)
    return min(1.0, max(0.0, f)) ** (2 / 3)


def simulate(run) -> list:
    """Every frame of a shot begun (`game.ShotRun`), as (pos, state) of its balls, computed
    when it is struck. The steps are the ones `run.step` takes live, so the match and its
    replay are unchanged; at most MAX_SHOT_FRAMES (the rest is played out when it ends)."""
    frames = []
    while not run.done and len(frames) < MAX_SHOT_FRAMES:
        run.step(DT)
        e = run.engine
        frames.append((e.pos[0].copy(), e.state[0].copy()))
    return frames


@dataclass(frozen=True)
class Clock:
    """Wall-clock time owed to a shot on show: `last` the time of the last tick (None before
    the first, or after a pause), `owed` the seconds not yet shown as frames."""

    last: float | None = None
    owed: float = 0.0

    def started(self) -> bool:
        return self.last is not None

    def at(self, t: float, fast: bool) -> Clock:
        """The clock at tick t: the time since the last tick is owed (×FAST fast-forwarded);
        the first tick only starts it."""
        if self.last is None:
            return Clock(t, self.owed)
        return Clock(t, self.owed + (t - self.last) * (FAST if fast else 1.0))

    def frames(self) -> tuple[int, Clock]:
        """The frames due now (at most MAX_STEPS_PER_TICK: beyond that the time is dropped),
        and the clock once they are shown."""
        n = min(int(self.owed / DT), MAX_STEPS_PER_TICK)
        return n, Clock(self.last, 0.0 if n == MAX_STEPS_PER_TICK else self.owed - n * DT)

    def stopped(self) -> Clock:
        """Time stands still (a box is open): the next tick starts the clock again."""
        return Clock(None, self.owed)
