"""Shared pieces of the rules: the game state before a shot and the outcome of a shot.

Players are 0 and 1. Ball ids are strings: "cue" and "1".."15" (1-7 solids, 8, 9-15 stripes).
Everything here is plain data: the judges are pure functions ``judge(state, summary) ->
(Outcome, new_state)`` that never touch the state they are given.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

from termpool.rules.codes import GROUPS, SOLIDS, STRIPES, Foul, Option, Said, Why, group_of
from termpool.rules.words import reason as in_words

EIGHT_BALLS = (*SOLIDS, "8", *STRIPES)
NINE_BALLS = tuple(str(n) for n in range(1, 10))
MODES = ("8ball", "9ball", "practice")
MODE_BALLS = {"8ball": EIGHT_BALLS, "9ball": NINE_BALLS, "practice": EIGHT_BALLS}
PUSH_OUT = ("none", "available", "declared")
EIGHT_BREAKS = ("respot", "rerack")  # what the 8 pocketed on an 8-ball break means
AREAS = ("anywhere", "kitchen")

FOULS = tuple(Foul)  # in the order `Outcome.fouls` lists them


def other_group(group: str) -> str:
    return "stripes" if group == "solids" else "solids"


@dataclass(frozen=True)
class State:
    """A game between two shots: what the referee needs to judge the next one.

    `groups` is None while the table is open, else ``{0: "solids", 1: "stripes"}`` (or the other
    way round). `fouls` counts each player's consecutive fouls. `pocketed` lists the object balls
    already down in this rack (balls of the mode's set that are not on the table). `push_out`
    (9-ball) is "available" on the shot after the break, "declared" when the shooter has
    announced a push-out for this shot, else "none". `called` is (ball, pocket) when the shooter
    has named a pocket (8-ball: needed to pot the 8). `three_foul` turns on 9-ball's three
    consecutive fouls rule. `eight_break` is what the 8 pocketed on an 8-ball break means:
    "respot" (it is re-spotted) or "rerack" (the balls are racked again).
    """

    mode: str = "8ball"
    shooter: int = 0
    groups: dict[int, str] | None = None
    fouls: tuple[int, int] = (0, 0)
    pocketed: tuple[str, ...] = ()
    is_break: bool = False
    push_out: str = "none"
    called: tuple[str, str] | None = None
    three_foul: bool = False
    eight_break: str = "respot"

    def __post_init__(self) -> None:
        if self.mode not in MODES:
            raise ValueError(f"mode: must be one of {', '.join(MODES)}, not {self.mode!r}")
        if self.shooter not in (0, 1):
            raise ValueError(f"shooter: must be 0 or 1, not {self.shooter!r}")
        if self.push_out not in PUSH_OUT:
            raise ValueError(f"push_out: must be one of {', '.join(PUSH_OUT)}")
        if self.eight_break not in EIGHT_BREAKS:
            raise ValueError(f"eight_break: must be one of {', '.join(EIGHT_BREAKS)}, "
                             f"not {self.eight_break!r}")
        if self.eight_break != "respot" and self.mode != "8ball":
            raise ValueError("eight_break: only for mode '8ball'")
        if self.groups is not None:
            if sorted(self.groups) != [0, 1] or sorted(self.groups.values()) != sorted(GROUPS):
                raise ValueError("groups: must give one player solids and the other stripes")

    @property
    def opponent(self) -> int:
        return 1 - self.shooter

    def on_table(self) -> list[str]:
        """Object balls of this mode still on the table before the shot."""
        down = set(self.pocketed)
        return [b for b in MODE_BALLS[self.mode] if b not in down]


@dataclass(frozen=True)
class Outcome:
    """What a shot means.

    `foul` is None or the first of `fouls`, every `Foul` the shot committed. After a foul
    the incoming player has ball in hand in `ball_in_hand_area` ("anywhere", or "kitchen":
    behind the head string); when there is no ball in hand the area is None. `groups` are the
    groups after the shot (None while the table is open). `winner` is None while the game goes
    on, else the player who won. `said` is the verdict as codes (`rules.codes.Said`), which
    `rules.words` puts in words; `reason` is it in the record's words. `respot` lists balls to
    put back on the table (the 8 pocketed on the break, the 9 pocketed on a foul).
    `continue_turn` is True when the shooter shoots again. `option` is a choice the incoming
    player has (`Option`). `rerack`: the balls are racked afresh and `next_shooter` breaks
    (8-ball, the 8 on the break with the re-rack variant). Once `winner` is set the game is
    over and `next_shooter` is simply the shooter; the match decides who breaks next.
    """

    foul: Foul | None
    next_shooter: int
    ball_in_hand: bool
    groups: dict[int, str] | None
    winner: int | None
    said: tuple[Said, ...]
    respot: tuple[str, ...] = ()
    continue_turn: bool = False
    ball_in_hand_area: str | None = None
    fouls: tuple[Foul, ...] = ()
    option: Option | None = None
    rerack: bool = False

    @property
    def reason(self) -> str:
        """The verdict in the record's words ("... player 0 continues")."""
        return in_words(self.said)

    def to_json(self) -> dict:
        """A JSON-able dict (player keys of `groups` become "0" and "1"; codes their
        strings). `rerack` is written only when set (outcomes from before it had none)."""
        out = {
            "foul": None if self.foul is None else self.foul.value,
            "next_shooter": self.next_shooter,
            "ball_in_hand": self.ball_in_hand,
            "groups": groups_to_json(self.groups),
            "winner": self.winner,
            "reason": self.reason,
            "ball_in_hand_area": self.ball_in_hand_area,
            "continue_turn": self.continue_turn,
            "respot": list(self.respot),
            "fouls": [f.value for f in self.fouls],
            "option": None if self.option is None else self.option.value,
        }
        if self.rerack:
            out["rerack"] = True
        return out


def legal_targets(state: State, present: Sequence[str]) -> list[str]:
    """The balls the shooter may hit first, among the ids `present` on the table (the cue ball
    and ids of no group are skipped): 9-ball the lowest; practice any; 8-ball on an open table
    any solid or stripe, else the shooter's group, and the 8 once the group is down."""
    here = set(present)
    objects = [b for b in present if b != "cue"]
    if state.mode == "9ball":
        nine = [b for b in objects if b.isdigit()]
        return [min(nine, key=int)] if nine else []
    if state.mode == "practice":
        return objects
    if state.groups is None:
        return [b for b in objects if group_of(b) is not None]
    own = [b for b in GROUPS[state.groups[state.shooter]] if b in here]
    return own or (["8"] if "8" in here else [])


def groups_to_json(groups: dict[int, str] | None) -> dict[str, str] | None:
    return None if groups is None else {str(p): g for p, g in sorted(groups.items())}


def order_fouls(fouls: set[Foul]) -> tuple[Foul, ...]:
    return tuple(f for f in FOULS if f in fouls)


def count_fouls(state: State, fouled: bool) -> tuple[int, int]:
    """Consecutive fouls after the shot: the shooter's count grows on a foul, else resets."""
    f = list(state.fouls)
    f[state.shooter] = f[state.shooter] + 1 if fouled else 0
    return (f[0], f[1])


def said_potted(why: Why, summary, balls: Sequence[str], **args) -> Said:
    """A clause of balls pocketed (`balls`, in order), with where each went down (the shot's
    summary's pockets; None for a ball that left the table)."""
    return Said(why, balls=tuple(balls), pockets=tuple(summary.pocketed.get(b) for b in balls),
                **args)


def after(state: State, **changes) -> State:
    """The state for the next shot: no break, no call, no declared push-out unless given."""
    base = {"is_break": False, "called": None, "push_out": "none"}
    base.update(changes)
    return replace(state, **base)


__all__ = [
    "AREAS",
    "EIGHT_BALLS",
    "EIGHT_BREAKS",
    "FOULS",
    "GROUPS",
    "MODES",
    "NINE_BALLS",
    "Outcome",
    "SOLIDS",
    "STRIPES",
    "State",
    "after",
    "count_fouls",
    "group_of",
    "groups_to_json",
    "legal_targets",
    "order_fouls",
    "other_group",
]
