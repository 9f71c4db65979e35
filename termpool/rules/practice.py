"""Practice: free play for one player, with no fouls that end anything.

Every shot is judged by the same function: pocketed object balls stay down, a scratch (or the
cue ball leaving the table) gives ball in hand anywhere, and the same player always shoots
again. The outcome never names a foul and never has a winner.

Re-racking and taking a shot back are match-level actions (they need the table before the
shot, not only its events) and belong to ``termpool.game``: a re-rack starts a fresh state with
``pocketed=()``, and a take-back restores the scene and the state recorded before the shot.
"""

from __future__ import annotations

from termpool.rules.codes import Said, Why
from termpool.rules.common import Outcome, State, after, said_potted


def judge(state: State, s) -> tuple[Outcome, State]:
    """Judge one practice shot: the outcome and the state for the next shot."""
    if state.mode != "practice":
        raise ValueError(f"practice.judge: state.mode is {state.mode!r}, not 'practice'")
    me = state.shooter
    gone = [*s.object_pocketed, *(b for b in s.off_table if b != s.cue_id)]
    down = [b for b in dict.fromkeys(gone) if b not in state.pocketed]
    said = [said_potted(Why.PRACTICE_POTTED, s, down) if down else Said(Why.NOTHING_POCKETED)]
    in_hand = s.scratch or s.cue_off_table
    if s.scratch:
        said.append(Said(Why.SCRATCH_IN_HAND, pocket=s.pocketed.get(s.cue_id)))
    elif s.cue_off_table:
        said.append(Said(Why.CUE_LEFT_IN_HAND))
    out = Outcome(
        foul=None,
        next_shooter=me,
        ball_in_hand=in_hand,
        ball_in_hand_area="anywhere" if in_hand else None,
        groups=None,
        winner=None,
        said=tuple(said),
        continue_turn=True,
    )
    return out, after(state, pocketed=(*state.pocketed, *down), fouls=(0, 0))
