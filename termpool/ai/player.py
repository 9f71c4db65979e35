"""The computer as a player of a match (`termpool.game.players.Computer`)."""

from __future__ import annotations

from dataclasses import dataclass

from termpool.rules.codes import Choice

from . import placement, shots
from .levels import LEVELS
from .shots import Plan


@dataclass(frozen=True)
class Computer:
    """The computer as a player of a match (`game.players.Computer`): it answers options,
    places the cue ball in hand and plays its shots as its level does, seeded by the match's
    seed and the shot's number (the same match gives the same decisions)."""

    level: str = "normal"
    name: str = "Computer"
    candidates: int = 256  # the batch's budget (`choose_shot`'s max_candidates)

    def __post_init__(self) -> None:
        if self.level not in LEVELS:
            raise ValueError(f"level: must be one of {', '.join(LEVELS)}, not {self.level!r}")

    @staticmethod
    def seed(match) -> int:
        """The seed of the next decision in `match`."""
        return match.seed * 1000 + len(match.history)

    @staticmethod
    def _balls(match) -> tuple:
        return (match.table, match.physics, match.ids, match.pos, match.radius, match.mass,
                match.on_table, match.state)

    def answer(self, match) -> Choice:
        return shots.choose_option(match.option)

    def place(self, match) -> tuple[float, float]:
        """Where it puts the cue ball in hand (`choose_placement`); should that ever be
        refused, where a scratched cue ball waits."""
        x, y = placement.choose_placement(*self._balls(match), match.ball_in_hand,
                                          level=self.level, seed=self.seed(match))
        return match.waiting_spot() if match.placement_error(x, y) else (x, y)

    def shot(self, match) -> Plan:
        """The shot it plays: `choose_shot`'s plan as it strikes it (`as_struck`)."""
        seed = self.seed(match)
        plan = shots.choose_shot(*self._balls(match), level=self.level, seed=seed,
                                 max_candidates=self.candidates)
        return shots.as_struck(plan, self.level, seed)
