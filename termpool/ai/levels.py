"""The computer's levels: what each one tries, how it weighs a shot and how it strikes.

The names are `termpool.game.players.LEVELS`; docs/ai.md has the figures they give.
"""

from __future__ import annotations

from typing import NamedTuple


class Level(NamedTuple):
    """Everything that makes a level, in one place (docs/ai.md has the figures they give)."""

    # What it tries.
    share: float  # fraction of max_candidates used
    speeds: tuple[float, ...]  # pot speeds: multiples of the slowest that reaches the pocket
    spins: tuple[tuple[float, float], ...]  # (side, top) tip offsets of pots
    combos: int  # candidates kept for combinations (two speeds each)
    verify: int  # best candidates simulated again under its errors before choosing
    spots: int  # ball in hand: distances behind the ghost ball tried per cut angle
    break_spots: tuple[float, ...]  # where it may break from: across the head string, as
    # shares of the width (0.5: the head spot); with several, it tries its break from each
    # How it weighs a shot.
    position: float  # weight of its next shot's chance from where the cue ball stops after a
    # pot (0: it plans no position, only the pot)
    leave: float  # weight of the opponent's best chance when the turn passes, a miss
    # included (0: it never plays safe while a pot is possible)
    scratch: float  # chance each cushion a pot's cue ball meets sends it into a pocket in its
    # play (the sim's exact stroke escaped them): its stroke's errors move the path after each
    # How it strikes: the sd of each error, drawn from a normal distribution per shot.
    aim_sd: float  # degrees of aim (also the error it weighs a pot's risk with)
    speed_sd: float  # relative speed
    tip_sd: float  # tip position, in ball radii, across and along
    spot_sd: float  # m, where it puts the cue ball in hand


STUN, FOLLOW, DRAW = (0.0, 0.0), (0.0, 0.3), (0.0, -0.3)
LEVELS = {
    # A beginner: the pot in front of it, hit firmly; no position, no safeties.
    "easy": Level(0.25, (1.3, 2.4), (STUN, FOLLOW), 0, 4, 1, (0.5,),
                  0.0, 0.0, 0.03, 0.9, 0.10, 0.10, 0.03),
    # A club player: a sound choice of pot, some thought of what a miss leaves.
    "normal": Level(0.8, (1.0, 1.8, 3.0), (STUN, FOLLOW, DRAW), 8, 8, 2, (0.5,),
                    0.0, 30.0, 0.03, 0.3, 0.06, 0.06, 0.01),
    # A strong amateur: plays position for the next ball, safe when the pot is poor, and
    # breaks from where its break works best on the rack.
    "hard": Level(1.2, (1.0, 1.4, 1.9, 2.6, 3.4),
                  (STUN, (0.0, 0.35), (0.0, -0.35), (0.25, 0.1), (-0.25, 0.1), (0.25, -0.3),
                   (-0.25, -0.3)), 16, 10, 3, (0.5, 0.16, 0.275, 0.35, 0.65, 0.725, 0.84),
                  100.0, 200.0, 0.03, 0.23, 0.03, 0.03, 0.0),
    # A professional: a steadier stroke, more of the batch; with a third of hard's aim
    # error, its cue ball strays from the path it planned a third as far.
    "pro": Level(1.5, (1.0, 1.4, 1.9, 2.6, 3.4),
                 (STUN, (0.0, 0.35), (0.0, -0.4), (0.3, 0.1), (-0.3, 0.1), (0.25, -0.3),
                  (-0.25, -0.3)), 24, 12, 3, (0.5, 0.16, 0.275, 0.35, 0.65, 0.725, 0.84),
                 150.0, 300.0, 0.01, 0.07, 0.02, 0.015, 0.0),
}
