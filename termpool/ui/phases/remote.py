"""An online match, the other player's turn: their moves (an option's answer, the ball in
hand, a shot) arrive over the link (ui.link) and are made here on this screen's copy of the
match, exactly as theirs made them. A move made on a match that differs from the mover's
(their digests disagree), one that cannot be read, or the other player leaving, ends it."""

from __future__ import annotations

import math
from dataclasses import replace

from termpool import wire
from termpool.game.record import ReplayError, check_shot_params
from termpool.physics.cue import clamp_tip
from termpool.rules import words
from termpool.rules.codes import Choice
from termpool.text import shown
from termpool.ui import aid
from termpool.ui.link import digest
from termpool.ui.phases.place import clamp
from termpool.ui.phases.turn import finish_shot, give_match, shoot, start_turn, to_menu
from termpool.ui.state import Aim, Pause, Place, Run, State, Waiting, shooter_is_remote

REMOTE_POLL_S = 0.05  # how often a waiting screen looks for the other player's move
OUT_OF_STEP = "the two screens' matches differ; the match has ended (it is kept)"
UNREADABLE = "the other screen sent a move this one cannot make; the match has ended"


def ended(s: State, why: str) -> State:
    """Leave the online match for the menu, saying why."""
    s = to_menu(s)
    return replace(s, message=((why, "foul"),))


def check(s: State) -> State:
    """Any phase of an online match: the link is read, and the match ends if the other
    player has left or the server has gone."""
    link = s.link
    link.poll()
    while link.said:
        kind, name = link.said.popleft()
        if s.match is not None and s.match.winner is None:  # an end on show stays as it is
            line = (f"{name}'s connection dropped: the match waits for them (Q leaves it)",
                    "foul") if kind == wire.AWAY else (f"{name} is back", "news")
            s = replace(s, message=(line,))
    if link.left is not None:
        name, link.left = link.left, None
        if s.match is not None and s.match.winner is not None:  # over: its end stays on show
            return replace(s, message=(*s.message, (f"{name} has left", "dim")))
        if len(s.remote) == 2:  # watching
            return ended(s, f"{name} has left the match")
        s = give_match(s, s.remote[0])  # (their leaving may come as a shot rolls here)
        return ended(s, f"{name} has left the match: you win it (it is kept in your history)")
    if link.closed:
        return ended(s, "the server has gone; the match is kept in your history")
    return s


def share(s: State, t: float) -> None:
    """This screen's player aiming or placing, or paused: the other screens are shown it
    (ui.link)."""
    part = s.part
    if isinstance(s.box, Pause):
        s.link.share_aim(("pause",), t)
    elif isinstance(part, Place):
        s.link.share_aim(("place", *map(float, part.cursor)), t)
    elif isinstance(part, Aim):
        st = s.stroke
        s.link.share_aim(("stick", float(st.angle), float(st.side), float(st.top),
                          float(aid.aim_power(s))), t)


def shown_aim(s: State) -> State:
    """The other player's stick or ball in hand as it last came (ui.link), on show."""
    aim, part = s.link.aim, s.part
    try:
        kind, values = aim["kind"], [float(v) for v in aim["values"]]
        if kind == "pause" and not values:
            return s if part.paused else replace(s, part=replace(part, paused=True))
        if kind == "stick" and len(values) in (3, 4) and all(map(math.isfinite, values)):
            angle, side, top, *power = values  # the power their aid has (not sent before)
            side, top = clamp_tip(side, top)
            power = min(max(power[0], 0.0), 1.0) if power else None
            if (part.stick and (angle, side, top, power) ==
                    (s.stroke.angle, s.stroke.side, s.stroke.top, part.power)):
                return s
            return replace(s, part=replace(part, stick=True, cursor=None, power=power,
                                           paused=False),
                           stroke=replace(s.stroke, angle=angle % 360.0, side=side, top=top))
        if kind == "place" and len(values) == 2 and s.match.ball_in_hand and not part.placed:
            x, y = clamp(s, *values)
            return s if part.cursor == (x, y) and not part.paused else replace(s, part=replace(
                part, cursor=(x, y), stick=False, paused=False))
    except (KeyError, TypeError, ValueError):
        pass
    return s  # a sign of life that cannot be shown is not worth ending a match over


def tick(s: State, t: float) -> State:
    """Make the other player's next move, if it has come; meanwhile show their aim."""
    if not isinstance(s.part, Waiting):
        return s
    if not s.link.moves:
        return shown_aim(s) if s.link.aim is not None else s
    move = s.link.moves.popleft()
    behind = s.link.backlog > 0  # a move made before this screen came to watch
    s.link.backlog = max(0, s.link.backlog - 1)
    if behind and not s.link.backlog and s.link.resume is not None:
        # A player back in their match: its last move so far is made as the others were
        # (their own, made before the drop, is not sent again), then they play their side
        # again, from that move's turn on.
        seat, s.link.resume = s.link.resume, None
        s = _make(s, move, behind)
        if s.match is None:  # it ended
            return s
        s = replace(s, remote=(1 - seat,))
        if isinstance(s.part, Waiting) and not shooter_is_remote(s):  # their turn now
            s = start_turn(s)
        return replace(s, message=(back_in(s, seat), *s.message))
    return _make(s, move, behind)


def back_in(s: State, seat: int) -> tuple[str, str]:
    """The line that tells a player back in their match (on side `seat`) whom it is with."""
    return f"back in your match against {shown(s.match.players[1 - seat])[:16]}", "news"


def _make(s: State, move, behind: bool) -> State:
    """The other player's `move` made on this screen's match (`behind`: one made before
    this screen came, played out at once)."""
    m = s.match
    if not isinstance(move, dict) or move.get("at") != digest(m):
        return ended(s, OUT_OF_STEP)
    kind = move.get("kind")
    try:
        if kind == "place":
            m.place_cue(float(move["x"]), float(move["y"]))  # ValueError: not there, not finite
            if not shooter_is_remote(s):  # one's own, before the connection dropped
                return start_turn(s)
            return replace(s, part=Waiting(placed=True))  # their shot comes next
        if kind == "choose":
            choice = Choice(move["choice"])
            line = (words.chose(m.players[m.shooter], choice), "dim")
            m.choose(choice)
            return start_turn(replace(s, message=(line,)))
        if kind == "shot":
            check_shot_params(move, "move")
            called = tuple(move["called"]) if move.get("called") is not None else None
            side, top = float(move["side"]), float(move["top"])
            angle = float(move["angle"])
            s = replace(s, stroke=replace(s.stroke, angle=angle, side=side, top=top))
            s = shoot(s, float(move["speed"]), angle, side, top, called,
                      bool(move.get("push_out", False)))
            if isinstance(s.part, Run):
                # A match joined to watch catches up at once: the shots made before are
                # played out without being shown (and so is a shot when more are waiting).
                return finish_shot(s) if behind or s.link.moves else s
            # Refused here, though the mover's match took it: the copies differ.
            return ended(s, OUT_OF_STEP)
    except (KeyError, TypeError, ValueError, ReplayError):
        pass
    return ended(s, UNREADABLE)
