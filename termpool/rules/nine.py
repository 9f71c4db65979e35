"""9-ball (WPA rules) as a pure function of the state and one shot's summary.

- **Legal shot.** The cue ball first hits the lowest-numbered ball on the table; afterwards a
  ball is pocketed or some ball (the cue ball included) touches a cushion. Any object ball
  pocketed on a legal shot counts and the shooter continues; the 9 pocketed on a legal shot
  wins, on the break too.
- **Break.** The cue ball must hit the lowest ball (the 1) first, and a ball must be pocketed or
  at least four distinct object balls must touch a cushion; otherwise it is a foul
  ("wrong_ball_first", "no_hit" or "illegal_break").
- **Fouls** ("scratch", "off_table", "no_hit", "wrong_ball_first", "no_rail", "illegal_break")
  give the opponent ball in hand anywhere (the break included). Balls pocketed on a foul stay
  down, except the 9, which is re-spotted (``respot=("9",)``); so is a 9 that left the table.
- **Push-out.** After a break that met the break requirements (even with a scratch), the next
  shot may be declared a push-out (``state.push_out == "available"``; the shooter declares it by
  setting "declared"). On a push-out the cue ball need not hit the lowest ball or any ball and
  nothing need reach a cushion; a scratch or a ball off the table is still a foul. Balls pocketed
  on a push-out stay down (the 9 is re-spotted) and the opponent chooses to shoot or to pass the
  shot back: ``option="shoot_or_pass"``, and the new state has the opponent to shoot (passing
  back is for the match to do).
- **Three fouls** (optional, ``state.three_foul``): a third consecutive foul by the same player
  loses the game. The warning the WPA requires before the third foul is left to the match.
"""

from __future__ import annotations

from termpool.rules.codes import Foul, Option, Said, Why
from termpool.rules.common import Outcome, State, after, count_fouls, order_fouls, said_potted
from termpool.rules.events import ShotSummary
from termpool.rules.words import BREAK_RAIL_BALLS, FOUL_LIMIT


def judge(state: State, s: ShotSummary) -> tuple[Outcome, State]:
    """Judge one 9-ball shot: the outcome and the state for the next shot."""
    if state.mode != "9ball":
        raise ValueError(f"nine.judge: state.mode is {state.mode!r}, not '9ball'")
    is_break = state.is_break or s.is_break
    push = state.push_out == "declared"
    if push and is_break:
        raise ValueError("nine.judge: a break shot cannot be a push-out")
    me, you = state.shooter, state.opponent
    on = state.on_table()
    lowest = min(on, key=int) if on else None
    potted = tuple(s.object_pocketed)
    rails = len(s.object_rail_balls)

    fouls: set[Foul] = set()
    said: list[Said] = []
    if s.scratch:
        fouls.add(Foul.SCRATCH)
        said.append(Said(Why.SCRATCH, pocket=s.pocketed.get(s.cue_id)))
    if s.off_table:
        fouls.add(Foul.OFF_TABLE)
        said.append(Said(Why.LEFT_TABLE, balls=tuple(s.off_table)))
    if not push:
        if s.first_contact is None:
            fouls.add(Foul.NO_HIT)
            said.append(Said(Why.NO_HIT))
        elif s.first_contact != lowest:
            fouls.add(Foul.WRONG_BALL_FIRST)
            said.append(Said(Why.HIT_NOT_LOWEST, ball=s.first_contact, lowest=lowest))
        if is_break:
            if not potted and rails < BREAK_RAIL_BALLS:
                fouls.add(Foul.ILLEGAL_BREAK)
                said.append(Said(Why.ILLEGAL_BREAK, count=rails))
        elif s.first_contact is not None and not s.rail_balls and not potted:
            fouls.add(Foul.NO_RAIL)
            said.append(Said(Why.NO_RAIL))
    order = order_fouls(fouls)
    nine = "9" in s.pocketed or "9" in s.off_table
    gone = [*potted, *(b for b in s.off_table if b != s.cue_id)]
    # Pushing out becomes possible after a break that met its requirements (1 first, and a
    # pocket or four balls to a cushion), for whoever shoots next.
    break_ok = is_break and not ({Foul.NO_HIT, Foul.WRONG_BALL_FIRST, Foul.ILLEGAL_BREAK}
                                 & fouls)
    push_next = "available" if break_ok else "none"

    def new_state(shooter: int, respot: tuple[str, ...]) -> State:
        down = [b for b in dict.fromkeys(gone) if b not in respot and b not in state.pocketed]
        return after(state, shooter=shooter, groups=None, push_out=push_next,
                     fouls=count_fouls(state, bool(order)), pocketed=(*state.pocketed, *down))

    if order:
        respot = ("9",) if nine else ()
        if potted:
            said.append(Said(Why.POTTED_ON_FOUL, balls=potted))
        if nine:
            said.append(Said(Why.NINE_RESPOTTED))
        nxt = new_state(you, respot)
        if state.three_foul and nxt.fouls[me] >= FOUL_LIMIT:
            said.append(Said(Why.FOUL_LIMIT, player=me))
            out = Outcome(foul=order[0], fouls=order, next_shooter=me, ball_in_hand=False,
                          groups=None, winner=you, said=tuple(said), respot=respot)
            return out, after(nxt, shooter=me)
        said.append(Said(Why.IN_HAND, player=you))
        out = Outcome(foul=order[0], fouls=order, next_shooter=you, ball_in_hand=True,
                      ball_in_hand_area="anywhere", groups=None, winner=None,
                      said=tuple(said), respot=respot)
        return out, nxt

    if push:
        respot = ("9",) if nine else ()
        said = [Said(Why.PUSH_OUT, balls=potted)]
        if potted and nine:
            said.append(Said(Why.NINE_RESPOTTED))
        said.append(Said(Why.CHOOSES, player=you))
        out = Outcome(foul=None, next_shooter=you, ball_in_hand=False, groups=None,
                      winner=None, said=tuple(said), respot=respot,
                      option=Option.SHOOT_OR_PASS)
        return out, new_state(you, respot)

    if nine:
        why = Why.NINE_ON_BREAK if is_break else Why.NINE_LEGAL
        out = Outcome(foul=None, next_shooter=me, ball_in_hand=False, groups=None, winner=me,
                      said=(Said(why, pocket=s.pocketed["9"], player=me),))
        return out, new_state(me, ())

    if potted:
        nxt, why = me, said_potted(Why.POTTED_CONTINUES, s, potted, player=me)
    else:
        nxt, why = you, Said(Why.NOTHING_TURN, player=you)
    said = [Said(Why.LEGAL_BREAK), why] if is_break else [why]
    out = Outcome(foul=None, next_shooter=nxt, ball_in_hand=False, groups=None, winner=None,
                  said=tuple(said), continue_turn=nxt == me)
    return out, new_state(nxt, ())
