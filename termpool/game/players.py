"""Who plays: a person, whose moves come from the keys of a UI, or the computer, which makes
its own (implemented in `termpool.ai`, and handed to the match by whoever sets it up).

Every player has a `name` and a `level`: the computer's level, None for a person (the record
keeps both). A computer player also answers the three questions of a turn: `answer` (the
choice for a pending option), `place` (where to put the cue ball in hand) and `shot` (the
shot to play, as it strikes it: a `Strike`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

from termpool.rules.codes import Choice

# The computer's levels by name, weakest first (what each one is: `termpool.ai.LEVELS`).
LEVELS = ("easy", "normal", "hard", "pro")


@runtime_checkable
class Player(Protocol):
    name: str
    level: str | None


class Strike(Protocol):
    """A shot as a computer strikes it: `Shot`'s speed, angle, side, top and called."""

    speed: float
    angle: float
    side: float
    top: float
    called: tuple[str, str] | None


@runtime_checkable
class Computer(Player, Protocol):
    """A player that decides for itself (`termpool.ai.Computer`)."""

    # `match` is the `Match` being played (not imported here: the match imports this module).
    def answer(self, match: Any) -> Choice: ...

    def place(self, match: Any) -> tuple[float, float]: ...

    def shot(self, match: Any) -> Strike: ...


@dataclass(frozen=True)
class Person:
    """A person: the UI's keys make every move."""

    name: str
    level: None = None


def is_computer(player: Player) -> bool:
    return player.level is not None


def check_players(players) -> tuple[Player, Player]:
    """Two players: names (people) or `Player`s; ValueError naming the field."""
    if not isinstance(players, (tuple, list)) or len(players) != 2:
        raise ValueError("players: must be two non-empty names")
    out = tuple(Person(p) if isinstance(p, str) else p for p in players)
    if not all(isinstance(p, Player) and isinstance(p.name, str) and p.name.strip()
               for p in out):
        raise ValueError("players: must be two non-empty names")
    if not all(p.level is None or p.level in LEVELS for p in out):
        raise ValueError(f"levels: must be two of None (a person), {', '.join(LEVELS)}")
    return out[0], out[1]
