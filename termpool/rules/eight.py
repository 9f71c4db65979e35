"""8-ball under WPA rules, as a pure function of the state and one shot's summary.

Choices made where the rules leave one to a player, or where they are simplified:

- **Break.** Legal when an object ball is pocketed or at least four distinct object balls touch
  a cushion (rail, jaw or jaw tip). Otherwise it is the foul "illegal_break" and the incoming
  player may accept the table or have it re-racked: the outcome carries
  ``option="rerack_or_accept"`` and the new state is the table accepted in position (a re-rack is
  for the match to do). A scratch (or the cue ball leaving the table) on the break gives the
  incoming player ball in hand behind the head string ("kitchen"); balls pocketed stay down.
- **8 on the break** is re-spotted (``respot=("8",)``) and the breaker continues, unless the
  break was a foul, when the opponent gets ball in hand in the kitchen. WPA also lets the
  breaker (or, after a scratch, the opponent) ask for a re-rack instead: with
  ``state.eight_break == "rerack"`` the 8 on the break always means a fresh rack, broken again
  by the same player from the kitchen (``rerack=True``; the new state is that rack's break).
- **Open table.** The table is open after the break whatever went down. On an open table any
  solid or stripe may be hit first, but hitting the 8 first is a foul. The first legal pocket
  after the break assigns the groups: the shooter gets the group of the ball pocketed; if both
  groups go down on that shot, the first ball to drop decides.
- **Fouls.** "scratch" (cue ball pocketed), "off_table" (a ball left the table), "no_hit",
  "wrong_ball_first" (not a ball of the shooter's group, or not the 8 once the group is
  cleared, or the 8 on an open table) and "no_rail" (after contact no ball touched a cushion
  and nothing was pocketed). After a foul the opponent has ball in hand anywhere; balls pocketed
  on a foul stay down and never assign groups. An object ball that leaves the table stays off.
- **The 8.** It must be called: ``state.called == ("8", pocket)``. Pocketing it (or driving it
  off the table) loses when the shooter's group was not cleared before the shot (an open table
  included), when it goes into another pocket than the called one or was not called, and when
  the shot is a foul. Otherwise the shooter wins.
- Calls of other balls are not enforced (every other shot counts as obvious).
- The shooter continues after legally pocketing a ball of their group (any ball on an open
  table, which then assigns the group).
"""

from __future__ import annotations

from termpool.rules.codes import Foul, Option, Said, Why
from termpool.rules.common import (
    Outcome,
    State,
    after,
    count_fouls,
    group_of,
    legal_targets,
    order_fouls,
    other_group,
    said_potted,
)
from termpool.rules.events import ShotSummary
from termpool.rules.words import BREAK_RAIL_BALLS


def judge(state: State, summary: ShotSummary) -> tuple[Outcome, State]:
    """Judge one 8-ball shot: the outcome and the state for the next shot."""
    if state.mode != "8ball":
        raise ValueError(f"eight.judge: state.mode is {state.mode!r}, not '8ball'")
    if state.is_break or summary.is_break:
        return _break(state, summary)
    return _shot(state, summary)


def _down(state: State, summary: ShotSummary, respot: tuple[str, ...] = ()) -> tuple[str, ...]:
    gone = [*summary.object_pocketed, *(b for b in summary.off_table if b != summary.cue_id)]
    new = [b for b in dict.fromkeys(gone) if b not in respot and b not in state.pocketed]
    return (*state.pocketed, *new)


def _cue_fouls(summary: ShotSummary) -> set[Foul]:
    fouls = set()
    if summary.scratch:
        fouls.add(Foul.SCRATCH)
    if summary.off_table:
        fouls.add(Foul.OFF_TABLE)
    return fouls


def _foul_said(foul: Foul, summary: ShotSummary, targets: list[str], groups,
               shooter: int) -> Said:
    if foul == Foul.SCRATCH:
        return Said(Why.SCRATCH, pocket=summary.pocketed.get(summary.cue_id))
    if foul == Foul.OFF_TABLE:
        return Said(Why.LEFT_TABLE, balls=tuple(summary.off_table))
    if foul == Foul.NO_HIT:
        return Said(Why.NO_HIT)
    if foul == Foul.WRONG_BALL_FIRST:
        hit = summary.first_contact
        if groups is None:
            return Said(Why.HIT_ON_OPEN_TABLE, ball=hit)
        own = groups[shooter]
        if targets == ["8"]:
            return Said(Why.HIT_NOT_EIGHT, ball=hit, group=own)
        return Said(Why.HIT_NOT_GROUP, ball=hit, group=own)
    return Said(Why.NO_RAIL)


# ---------------------------------------------------------------------------------- break


def _break(state: State, s: ShotSummary) -> tuple[Outcome, State]:
    me, you = state.shooter, state.opponent
    rails = len(s.object_rail_balls)
    potted = s.object_pocketed
    legal = bool(potted) or rails >= BREAK_RAIL_BALLS
    fouls = _cue_fouls(s)
    eight = "8" in s.pocketed or "8" in s.off_table
    rerack = eight and state.eight_break == "rerack"
    respot = ("8",) if eight and not rerack else ()
    if not legal:
        fouls.add(Foul.ILLEGAL_BREAK)
    order = order_fouls(fouls)
    said = []
    if not legal:
        said.append(Said(Why.ILLEGAL_BREAK, count=rails))
    said += [_foul_said(f, s, [], None, me) for f in order if f != Foul.ILLEGAL_BREAK]
    if rerack:
        # The variant where the 8 on the break means a fresh rack, broken by the same player.
        if legal:
            said.insert(0, said_potted(Why.LEGAL_BREAK_POTTED, s, potted))
        said.append(Said(Why.EIGHT_RERACKED, player=me))
        out = Outcome(foul=order[0] if order else None, fouls=order, next_shooter=me,
                      ball_in_hand=True, ball_in_hand_area="kitchen", groups=None,
                      winner=None, said=tuple(said), continue_turn=not order, rerack=True)
        return out, State(mode=state.mode, shooter=me, is_break=True,
                          three_foul=state.three_foul, eight_break=state.eight_break)
    if eight:
        said.append(Said(Why.EIGHT_RESPOTTED))
    pocketed_after = _down(state, s, respot)
    if order:
        in_hand = bool(fouls - {Foul.ILLEGAL_BREAK})
        if not legal:
            said.append(Said(Why.MAY_RERACK, player=you))
        if in_hand:
            said.append(Said(Why.IN_HAND_KITCHEN, player=you))
        out = Outcome(
            foul=order[0],
            fouls=order,
            next_shooter=you,
            ball_in_hand=in_hand,
            ball_in_hand_area="kitchen" if in_hand else None,
            groups=None,
            winner=None,
            said=tuple(said),
            respot=respot,
            continue_turn=False,
            option=None if legal else Option.RERACK_OR_ACCEPT,
        )
        new = after(state, shooter=you, groups=None, fouls=count_fouls(state, True),
                    pocketed=pocketed_after)
        return out, new
    if potted:
        said.insert(0, said_potted(Why.LEGAL_BREAK_POTTED, s, potted))
        said.append(Said(Why.OPEN_CONTINUES, player=me))
        nxt = me
    else:
        said.insert(0, Said(Why.LEGAL_BREAK_RAILS, count=rails))
        said.append(Said(Why.OPEN_TURN, player=you))
        nxt = you
    out = Outcome(
        foul=None,
        next_shooter=nxt,
        ball_in_hand=False,
        groups=None,
        winner=None,
        said=tuple(said),
        respot=respot,
        continue_turn=nxt == me,
    )
    new = after(state, shooter=nxt, groups=None, fouls=count_fouls(state, False),
                pocketed=pocketed_after)
    return out, new


# ------------------------------------------------------------------------------ other shots


def _targets(state: State) -> list[str]:
    # Once the group is down the target is the 8, even in a scene that left it off the table.
    return legal_targets(state, state.on_table()) or ([] if state.groups is None else ["8"])


def _shot(state: State, s: ShotSummary) -> tuple[Outcome, State]:
    me, you = state.shooter, state.opponent
    targets = _targets(state)
    fouls = _cue_fouls(s)
    if s.first_contact is None:
        fouls.add(Foul.NO_HIT)
    else:
        if s.first_contact not in targets:
            fouls.add(Foul.WRONG_BALL_FIRST)
        if not s.rail_balls and not s.object_pocketed:
            fouls.add(Foul.NO_RAIL)
    order = order_fouls(fouls)
    groups = state.groups
    said = [_foul_said(f, s, targets, groups, me) for f in order]

    def end(winner: int, why: Said) -> tuple[Outcome, State]:
        out = Outcome(
            foul=order[0] if order else None,
            fouls=order,
            next_shooter=me,
            ball_in_hand=False,
            groups=groups,
            winner=winner,
            said=(*said, why),
        )
        return out, after(state, fouls=count_fouls(state, bool(order)), pocketed=_down(state, s))

    if "8" in s.off_table:
        return end(you, Said(Why.EIGHT_OFF_TABLE, player=me))
    if "8" in s.pocketed:
        pocket = s.pocketed["8"]
        if order:
            return end(you, Said(Why.EIGHT_ON_FOUL, player=me))
        if targets != ["8"]:
            return end(you, Said(Why.EIGHT_EARLY, player=me,
                                 group=None if groups is None else groups[me]))
        if state.called is None or state.called[0] != "8":
            return end(you, Said(Why.EIGHT_UNCALLED, pocket=pocket, player=me))
        if state.called[1] != pocket:
            return end(you, Said(Why.EIGHT_WRONG_POCKET, pocket=pocket, called=state.called[1],
                                 player=me))
        return end(me, Said(Why.EIGHT_CALLED, pocket=pocket, player=me))

    potted = tuple(s.object_pocketed)
    if order:
        if potted:
            said.append(Said(Why.STAY_DOWN, balls=potted))
        said.append(Said(Why.IN_HAND, player=you))
        out = Outcome(
            foul=order[0],
            fouls=order,
            next_shooter=you,
            ball_in_hand=True,
            ball_in_hand_area="anywhere",
            groups=groups,
            winner=None,
            said=tuple(said),
        )
        new = after(state, shooter=you, fouls=count_fouls(state, True), pocketed=_down(state, s))
        return out, new

    if groups is None and potted:
        g = group_of(potted[0])
        groups = {me: g, you: other_group(g)}
        nxt, why = me, said_potted(Why.TAKES_GROUP, s, potted, player=me, group=g)
    elif groups is not None and any(group_of(b) == groups[me] for b in potted):
        nxt, why = me, said_potted(Why.POTTED_CONTINUES, s, potted, player=me)
    elif potted:
        nxt, why = you, said_potted(Why.POTTED_NOT_OWN, s, potted, group=groups[me],
                                    player=you)
    else:
        nxt, why = you, Said(Why.NOTHING_TURN, player=you)
    out = Outcome(
        foul=None,
        next_shooter=nxt,
        ball_in_hand=False,
        groups=groups,
        winner=None,
        said=(why,),
        continue_turn=nxt == me,
    )
    new = after(state, shooter=nxt, groups=groups, fouls=count_fouls(state, False),
                pocketed=_down(state, s))
    return out, new
