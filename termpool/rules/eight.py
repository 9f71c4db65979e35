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
  breaker (or, after a scratch, the opponent) ask for a re-rack instead; the re-spot is the
  option this referee always takes.
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

from termpool.rules.common import (
    Outcome,
    State,
    after,
    count_fouls,
    group_of,
    legal_targets,
    order_fouls,
    other_group,
)
from termpool.rules.events import ShotSummary
from termpool.rules.words import BREAK_RAIL_BALLS, KITCHEN, NO_HIT, NO_RAIL


def judge(state: State, summary: ShotSummary) -> tuple[Outcome, State]:
    """Judge one 8-ball shot: the outcome and the state for the next shot."""
    if state.mode != "8ball":
        raise ValueError(f"eight.judge: state.mode is {state.mode!r}, not '8ball'")
    if state.is_break or summary.is_break:
        return _break(state, summary)
    return _shot(state, summary)


def _ball(b: str) -> str:
    return "the cue ball" if b == "cue" else f"the {b}"


def _names(balls: list[str]) -> str:
    names = [_ball(b) for b in balls]
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def _down(state: State, summary: ShotSummary, respot: tuple[str, ...] = ()) -> tuple[str, ...]:
    gone = [*summary.object_pocketed, *(b for b in summary.off_table if b != summary.cue_id)]
    new = [b for b in dict.fromkeys(gone) if b not in respot and b not in state.pocketed]
    return (*state.pocketed, *new)


def _cue_fouls(summary: ShotSummary) -> set[str]:
    fouls = set()
    if summary.scratch:
        fouls.add("scratch")
    if summary.off_table:
        fouls.add("off_table")
    return fouls


def _foul_words(foul: str, summary: ShotSummary, targets: list[str], groups, shooter) -> str:
    if foul == "scratch":
        return f"scratch: {summary.scratch_words}"
    if foul == "off_table":
        return f"{_names(list(summary.off_table))} left the table"
    if foul == "no_hit":
        return NO_HIT
    if foul == "wrong_ball_first":
        hit = summary.first_contact
        if groups is None:
            return f"the cue ball hit {_ball(hit)} first, which is not allowed on an open table"
        own = groups[shooter]
        if targets == ["8"]:
            return f"the cue ball hit {_ball(hit)} first; with the {own} cleared it must be the 8"
        return f"the cue ball hit {_ball(hit)} first, not one of the {own}"
    if foul == "no_rail":
        return NO_RAIL
    return foul


# ---------------------------------------------------------------------------------- break


def _break(state: State, s: ShotSummary) -> tuple[Outcome, State]:
    me, you = state.shooter, state.opponent
    rails = len(s.object_rail_balls)
    potted = s.object_pocketed
    legal = bool(potted) or rails >= BREAK_RAIL_BALLS
    fouls = _cue_fouls(s)
    eight = "8" in s.pocketed or "8" in s.off_table
    respot = ("8",) if eight else ()
    if not legal:
        fouls.add("illegal_break")
    order = order_fouls(fouls)
    words = []
    if not legal:
        words.append(
            f"illegal break: nothing pocketed and {rails} object "
            f"{'ball' if rails == 1 else 'balls'} reached a cushion ({BREAK_RAIL_BALLS} needed)"
        )
    words += [_foul_words(f, s, [], None, me) for f in order if f != "illegal_break"]
    if eight:
        words.append("the 8 went down on the break and is re-spotted")
    pocketed_after = _down(state, s, respot)
    if order:
        in_hand = bool(fouls - {"illegal_break"})
        text = "; ".join(words)
        if not legal:
            text += f"; player {you} may accept the table or have it re-racked"
        if in_hand:
            text += f"; player {you} has ball in hand {KITCHEN}"
        out = Outcome(
            foul=order[0],
            fouls=order,
            next_shooter=you,
            ball_in_hand=in_hand,
            ball_in_hand_area="kitchen" if in_hand else None,
            groups=None,
            winner=None,
            reason=text,
            respot=respot,
            continue_turn=False,
            option=None if legal else "rerack_or_accept",
        )
        new = after(state, shooter=you, groups=None, fouls=count_fouls(state, True),
                    pocketed=pocketed_after)
        return out, new
    if potted:
        words.insert(0, f"legal break: {_names(potted)} pocketed")
        words.append(f"the table is open and player {me} continues")
        nxt = me
    else:
        words.insert(0, f"legal break: {rails} object balls reached a cushion, nothing pocketed")
        words.append(f"the table is open and it is player {you}'s turn")
        nxt = you
    out = Outcome(
        foul=None,
        next_shooter=nxt,
        ball_in_hand=False,
        groups=None,
        winner=None,
        reason="; ".join(words),
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
        fouls.add("no_hit")
    else:
        if s.first_contact not in targets:
            fouls.add("wrong_ball_first")
        if not s.rail_balls and not s.object_pocketed:
            fouls.add("no_rail")
    order = order_fouls(fouls)
    groups = state.groups
    words = [_foul_words(f, s, targets, groups, me) for f in order]

    def end(winner: int, why: str) -> tuple[Outcome, State]:
        reason = "; ".join([*words, why]) if words else why
        out = Outcome(
            foul=order[0] if order else None,
            fouls=order,
            next_shooter=me,
            ball_in_hand=False,
            groups=groups,
            winner=winner,
            reason=reason,
        )
        return out, after(state, fouls=count_fouls(state, bool(order)), pocketed=_down(state, s))

    if "8" in s.off_table:
        return end(you, f"with the 8 off the table player {me} loses")
    if "8" in s.pocketed:
        pocket = s.pocketed["8"]
        if order:
            return end(you, f"the 8 went down on a foul: player {me} loses")
        if targets != ["8"]:
            still = "the table is open" if groups is None else f"the {groups[me]} were not cleared"
            return end(you, f"the 8 went down early ({still}): player {me} loses")
        if state.called is None or state.called[0] != "8":
            return end(you, f"the 8 went into the {pocket} pocket without a call: "
                            f"player {me} loses")
        if state.called[1] != pocket:
            return end(you, f"the 8 went into the {pocket} pocket, not the called "
                            f"{state.called[1]}: player {me} loses")
        return end(me, f"the 8 went into the called {pocket} pocket: player {me} wins")

    potted = s.object_pocketed
    if order:
        reason = "; ".join(words)
        if potted:
            reason += f"; {_names(potted)} stay{'s' if len(potted) == 1 else ''} down"
        reason += f"; player {you} has ball in hand"
        out = Outcome(
            foul=order[0],
            fouls=order,
            next_shooter=you,
            ball_in_hand=True,
            ball_in_hand_area="anywhere",
            groups=groups,
            winner=None,
            reason=reason,
        )
        new = after(state, shooter=you, fouls=count_fouls(state, True), pocketed=_down(state, s))
        return out, new

    if groups is None and potted:
        g = group_of(potted[0])
        groups = {me: g, you: other_group(g)}
        nxt, why = me, f"{_names(potted)} pocketed: player {me} takes the {g} and continues"
    elif groups is not None and any(group_of(b) == groups[me] for b in potted):
        nxt, why = me, f"{_names(potted)} pocketed: player {me} continues"
    elif potted:
        nxt, why = you, f"{_names(potted)} pocketed, none of the {groups[me]}: player {you}'s turn"
    else:
        nxt, why = you, f"nothing pocketed: player {you}'s turn"
    out = Outcome(
        foul=None,
        next_shooter=nxt,
        ball_in_hand=False,
        groups=groups,
        winner=None,
        reason=why,
        continue_turn=nxt == me,
    )
    new = after(state, shooter=nxt, groups=groups, fouls=count_fouls(state, False),
                pocketed=_down(state, s))
    return out, new
