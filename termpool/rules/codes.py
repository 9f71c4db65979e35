"""The referee's vocabulary as codes: 8-ball's groups of balls, fouls, options and their
choices, and the reasons a verdict gives; and the computer's plans. Outcomes carry these
codes and their arguments; `termpool.rules.words` is the one place that turns them into
words (for people, for the record, for `termpool replay`).

The codes' values are the strings the JSON forms hold (a `StrEnum` compares equal to them).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

# 8-ball's two groups of balls (the 8 and the cue ball are in neither).
SOLIDS = tuple(str(n) for n in range(1, 8))
STRIPES = tuple(str(n) for n in range(9, 16))
GROUPS = {"solids": SOLIDS, "stripes": STRIPES}


def group_of(ball: str) -> str | None:
    """The group of a ball: "solids", "stripes" or None (the 8, the cue ball, others)."""
    for name, balls in GROUPS.items():
        if ball in balls:
            return name
    return None


class Foul(StrEnum):
    """A foul, in the order `Outcome.fouls` lists them when a shot commits several."""

    SCRATCH = "scratch"  # the cue ball pocketed
    OFF_TABLE = "off_table"  # a ball left the table
    ILLEGAL_BREAK = "illegal_break"  # a break that pocketed nothing and reached too few rails
    NO_HIT = "no_hit"
    WRONG_BALL_FIRST = "wrong_ball_first"
    NO_RAIL = "no_rail"  # after contact no ball reached a cushion and nothing was pocketed


class Choice(StrEnum):
    """An answer to an option."""

    RERACK = "rerack"
    ACCEPT = "accept"
    SHOOT = "shoot"
    PASS = "pass"


class Option(StrEnum):
    """A choice the incoming player has after a shot."""

    RERACK_OR_ACCEPT = "rerack_or_accept"  # after an illegal 8-ball break
    SHOOT_OR_PASS = "shoot_or_pass"  # after a 9-ball push-out

    @property
    def choices(self) -> tuple[Choice, Choice]:
        """The two answers, in the order they are offered."""
        return CHOICES[self]


CHOICES = {Option.RERACK_OR_ACCEPT: (Choice.RERACK, Choice.ACCEPT),
           Option.SHOOT_OR_PASS: (Choice.SHOOT, Choice.PASS)}


class Why(StrEnum):
    """One clause of a verdict. The arguments each takes are listed in `Said`."""

    # fouls
    SCRATCH = "scratch"  # pocket (None: the pocket is unknown)
    LEFT_TABLE = "left_table"  # balls
    ILLEGAL_BREAK = "illegal_break"  # count: object balls that reached a cushion
    NO_HIT = "no_hit"
    HIT_ON_OPEN_TABLE = "hit_on_open_table"  # ball: the 8, hit first on an open table
    HIT_NOT_EIGHT = "hit_not_eight"  # ball, group: the group is cleared, the 8 is next
    HIT_NOT_GROUP = "hit_not_group"  # ball, group: not a ball of the shooter's group
    HIT_NOT_LOWEST = "hit_not_lowest"  # ball, lowest (9-ball)
    NO_RAIL = "no_rail"
    # the break
    LEGAL_BREAK = "legal_break"
    LEGAL_BREAK_POTTED = "legal_break_potted"  # balls
    LEGAL_BREAK_RAILS = "legal_break_rails"  # count
    EIGHT_RESPOTTED = "eight_respotted"  # the 8 went down on the break
    EIGHT_RERACKED = "eight_reracked"  # player: the 8 went down on the break, a new rack
    MAY_RERACK = "may_rerack"  # player: may accept the table or have it re-racked
    OPEN_CONTINUES = "open_continues"  # player
    OPEN_TURN = "open_turn"  # player
    # the turn
    IN_HAND = "in_hand"  # player: ball in hand anywhere
    IN_HAND_KITCHEN = "in_hand_kitchen"  # player: ball in hand behind the head string
    STAY_DOWN = "stay_down"  # balls pocketed on a foul (8-ball)
    POTTED_ON_FOUL = "potted_on_foul"  # balls (9-ball)
    NINE_RESPOTTED = "nine_respotted"
    TAKES_GROUP = "takes_group"  # balls, player, group
    POTTED_CONTINUES = "potted_continues"  # balls, player
    POTTED_NOT_OWN = "potted_not_own"  # balls, group (the shooter's), player (the next)
    NOTHING_TURN = "nothing_turn"  # player (the next)
    PUSH_OUT = "push_out"  # balls: pocketed on the push-out, not counted
    CHOOSES = "chooses"  # player: chooses to shoot or to pass the shot back
    # the end of a frame
    EIGHT_OFF_TABLE = "eight_off_table"  # player (who loses)
    EIGHT_ON_FOUL = "eight_on_foul"  # player (who loses)
    EIGHT_EARLY = "eight_early"  # player (who loses), group (None: the table was open)
    EIGHT_UNCALLED = "eight_uncalled"  # pocket, player (who loses)
    EIGHT_WRONG_POCKET = "eight_wrong_pocket"  # pocket, called, player (who loses)
    EIGHT_CALLED = "eight_called"  # pocket, player (who wins)
    NINE_ON_BREAK = "nine_on_break"  # pocket, player (who wins)
    NINE_LEGAL = "nine_legal"  # pocket, player (who wins)
    FOUL_LIMIT = "foul_limit"  # player (who loses): the third foul in a row
    # practice
    PRACTICE_POTTED = "practice_potted"  # balls
    NOTHING_POCKETED = "nothing_pocketed"
    SCRATCH_IN_HAND = "scratch_in_hand"  # pocket (None: unknown)
    CUE_LEFT_IN_HAND = "cue_left_in_hand"


@dataclass(frozen=True)
class Said:
    """One clause of a verdict: its code and the arguments it names (ball ids, pockets,
    players 0 and 1, a group, a count). A clause of balls pocketed gives their pockets too."""

    why: Why
    player: int | None = None
    balls: tuple[str, ...] = ()
    pockets: tuple[str | None, ...] = ()  # where each of `balls` went down (None: off the table)
    ball: str | None = None
    lowest: str | None = None
    pocket: str | None = None
    called: str | None = None
    group: str | None = None
    count: int | None = None


class Aim(StrEnum):
    """What the computer's plan for a shot is (`PlanNote`)."""

    VERDICT = "verdict"  # the shot wins, loses or fouls: the referee's verdict says it
    POT = "pot"  # `ball` into `pocket`
    COMBO = "combo"  # `ball` into `sunk`, `sunk` into `pocket`
    FLUKE = "fluke"  # `balls` drop by the break or by a kiss or combination (`by_break`)
    TRY = "try"  # a pot tried that passes the turn: `ball` (into `sunk`) into `pocket`
    BREAK = "break"
    SAFETY = "safety"  # on `ball`
    KICK = "kick"  # on `ball`
    NOTHING = "nothing"  # no object ball on the table


@dataclass(frozen=True)
class PlanNote:
    """The computer's plan for a shot as data, for `rules.words.plan_note` to say: a pot, a
    combination, a try, a safety or kick on a ball, or (when its batch saw the shot win, lose
    or foul) the referee's verdict on it. Pockets by the table's names."""

    aim: Aim
    ball: str | None = None  # the ball the cue ball is sent at
    sunk: str | None = None  # a combination's: the ball it sends on to the pocket
    pocket: str | None = None
    balls: tuple[str, ...] = ()  # a fluke's balls
    by_break: bool = False  # a fluke's: by the break (else a kiss or a combination)
    said: tuple[Said, ...] = ()  # a verdict's clauses
    foul: bool = False  # a verdict's: a foul


__all__ = ["CHOICES", "GROUPS", "SOLIDS", "STRIPES", "Aim", "Choice", "Foul", "Option",
           "PlanNote", "Said", "Why", "group_of"]
