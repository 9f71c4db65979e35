"""Practice: free play for one player, with no fouls that end anything.

Every shot is judged by the same function: pocketed object balls stay down, a scratch (or the
cue ball leaving the table) gives ball in hand anywhere, and the same player always shoots
again. The outcome never names a foul and never has a winner.

Re-racking and taking a shot back are match-level actions (they need the table before the
shot, not only its events) and belong to ``termpool.game``: a re-rack starts a fresh state with
``pocketed=()``, and a take-back restores the scene and the state recorded before the shot.
"""

from __future__ import annotations

from termpool.rules.common import Outcome, State, after


def judge(state: State, s) -> tuple[Outcome, State]:
    """Judge one practice shot: the outcome and the state for the next shot."""
    if state.mode != "practice":
        raise ValueError(f"practice.judge: state.mode is {state.mode!r}, not 'practice'")
    me = state.shooter
    gone = [*s.object_pocketed, *(b for b in s.off_table if b != s.cue_id)]
    down = [b for b in dict.fromkeys(gone) if b not in state.pocketed]
    words = [f"{', '.join('the ' + b for b in down)} pocketed"] if down else ["nothing pocketed"]
    in_hand = s.scratch or s.cue_off_table
    if s.scratch:
        words.append(f"{s.scratch_words}: ball in hand")
    elif s.cue_off_table:
        words.append("the cue ball left the table: ball in hand")
    out = Outcome(
        foul=None,
        next_shooter=me,
        ball_in_hand=in_hand,
        ball_in_hand_area="anywhere" if in_hand else None,
        groups=None,
        winner=None,
        reason="; ".join(words),
        continue_turn=True,
    )
    return out, after(state, pocketed=(*state.pocketed, *down), fouls=(0, 0))
