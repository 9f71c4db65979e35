"""The computer opponent: candidate shots simulated in one batch and judged by the referee.

`choose_shot` builds candidate strikes (the break: hard shots at the rack's apex; otherwise
ghost-ball pots for every legal target and pocket at a few speeds and spins, combinations, and
soft safeties and one-rail kicks at each legal ball), simulates them all in ONE batched Engine,
judges every table with the rules and scores it; the best few are simulated again aimed a
little to either side, and the best expected score is played (`Plan`). `score_shots` returns
every candidate of the batch with its score. `choose_placement` picks a spot for the cue ball
in hand from cheap geometry (the shots the spot leaves).

Scores: a win far above a legal pot (the shooter continues) above a shot that passes the turn
without a foul above a foul above a loss. A pot is weighted by its chance to go in under the
level's notional aim error (thin cuts and long shots are risky), plus a position term: how
makeable the next shot is from where the cue ball stops. A turn that passes is marked down by
how makeable the table it leaves is for the opponent.

Cut shots throw the object ball off the line of centres (ball-ball friction), so before the
batch each pot's aim is corrected by two cheap rounds on two-ball tables without pockets
(cue ball and target only): the object ball's measured heading corrects the contact angle.

The package: `levels` (what each level is), `balls` (the arguments, checked), `geometry`
(pockets, chances, blocked paths, kick aims), `candidates` (the strikes tried and the batch
that simulates them), `scoring` (the tables judged and valued), `shots` (the choice, and how a
level strikes it), `placement` (ball in hand, and `best_chance`) and `player` (`Computer`, the
computer as a player of a match). It reads the physics, rules and game and never changes them;
no terminal code here.
"""

from termpool.ai.candidates import BREAK_SPEEDS, SIM_SECONDS
from termpool.ai.levels import LEVELS, Level
from termpool.ai.placement import best_chance, choose_placement
from termpool.ai.player import Computer
from termpool.ai.scoring import LEAVE_SIGMA
from termpool.ai.shots import (
    Plan,
    as_struck,
    choose_option,
    choose_shot,
    score_shots,
    with_error,
)

__all__ = [
    "BREAK_SPEEDS",
    "LEAVE_SIGMA",
    "LEVELS",
    "SIM_SECONDS",
    "Computer",
    "Level",
    "Plan",
    "as_struck",
    "best_chance",
    "choose_option",
    "choose_placement",
    "choose_shot",
    "score_shots",
    "with_error",
]
