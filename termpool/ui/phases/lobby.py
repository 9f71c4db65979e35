"""The lobby (under `termpool serve`): the players online, a challenge to one of them, the
answer to one's own challenges, and the online match that starts when one is accepted."""

from __future__ import annotations

from dataclasses import replace

from termpool import wire
from termpool.ui.phases.turn import begin_match
from termpool.ui.settings import MAX_FRAMES
from termpool.ui.state import LOBBY_GAMES, Lobby, Menu, State

LOBBY_POLL_S = 0.1  # how often the lobby looks for news while it is on screen
REFUSALS = {wire.BUSY: "that player is busy: not in the lobby, or answering a challenge",
            wire.GONE: "that player has left", wire.BAD: "the server could not read that"}


def open_lobby(s: State) -> State:
    s.link.send(wire.WHERE, lobby=True)
    s.link.poll()
    return replace(s, part=Lobby(), message=())


def leave_lobby(s: State) -> State:
    if s.link.challenged is not None:
        s.link.send(wire.ANSWER, to=s.link.challenged.get("by"), yes=False)
        s.link.challenged = None
    s.link.send(wire.WHERE, lobby=False)
    return replace(s, part=Menu(), message=())


def challenge_game(s: State, mode: str) -> dict:
    """The match a challenge offers: the game chosen and this player's table settings."""
    import secrets

    o = s.opts
    return {"mode": mode, "table": o.table, "frames": o.frames, "seed": secrets.randbits(63),
            "three_foul": o.three_foul and mode == "9ball", "eight_break": o.eight_break,
            "theme": o.theme}


def key(s: State, key, action: str | None, t: float) -> State:
    if key.kind == "release":
        return s
    part, link = s.part, s.link
    if link.challenged is not None:  # a challenge to answer comes first
        if key.name in ("y", "n"):
            link.send(wire.ANSWER, to=link.challenged.get("by"), yes=key.name == "y")
            link.challenged = None
            return s
    others = link.others()
    if key.name == "escape" or action == "back":
        return leave_lobby(s)
    if key.name in ("up", "k"):
        return replace(s, part=replace(part, index=max(0, part.index - 1)))
    if key.name in ("down", "j"):
        return replace(s, part=replace(part, index=min(max(0, len(others) - 1),
                                                       part.index + 1)))
    if key.name in ("left", "right"):
        step = 1 if key.name == "right" else -1
        return replace(s, part=replace(part, game=(part.game + step) % len(LOBBY_GAMES)))
    if action in ("confirm", "shoot") and others and part.waiting is None:
        who = others[min(part.index, len(others) - 1)]
        if who.get("where") == "playing":  # their match, to watch
            link.send(wire.WATCH, to=who.get("id"))
            return replace(s, message=())
        link.send(wire.CHALLENGE, to=who.get("id"),
                  game=challenge_game(s, LOBBY_GAMES[part.game]))
        return replace(s, part=replace(part, waiting=str(who.get("name", ""))), message=())
    return s


def tick(s: State, t: float) -> State:
    link = s.link
    if link.poll():
        s = replace(s, part=replace(s.part))  # a new part: the screen shows the news
    if link.closed:
        return replace(s, part=Menu(), message=(("the server has gone", "foul"),))
    if link.start is not None:
        return start_online(s, link.start)
    part = s.part
    while link.news:
        kind, what = link.news.popleft()
        text = (f"{what} declined" if kind == wire.DECLINED else
                f"{what} withdrew the challenge" if kind == wire.WITHDRAWN else
                REFUSALS.get(what, "refused"))
        waiting = part.waiting if kind == wire.WITHDRAWN else None  # their answer came
        s = replace(s, part=replace(part, waiting=waiting), message=((text, "foul"),))
        part = s.part
    return s


def start_online(s: State, start: dict) -> State:
    """The match a challenge began: both games build it from the same settings, with the
    challenger as the first player; this game's player moves with the keys, the other's
    moves come over the link."""
    s.link.start = None
    game, names, seat = start.get("game") or {}, start.get("names"), start.get("seat")
    try:
        frames = game["frames"]
        if game["mode"] not in LOBBY_GAMES:
            raise ValueError(f"mode: not one of {', '.join(LOBBY_GAMES)}")
        if type(frames) is not int or not 1 <= frames <= MAX_FRAMES:
            raise ValueError(f"frames: not a whole number from 1 to {MAX_FRAMES}")
        # The match checks the rest (Match: a ValueError naming the setting).
        opts = replace(s.opts, mode=game["mode"], opponent="human", table=game["table"],
                       frames=frames, three_foul=game["three_foul"] is True,
                       eight_break=game["eight_break"], theme=game["theme"])
        if seat not in (0, 1, None) or not (isinstance(names, list) and len(names) == 2):
            raise ValueError("names")
        remote = (0, 1) if seat is None else (1 - seat,)  # None: watching
        return begin_match(s, opts, tuple(str(n) for n in names), int(game["seed"]),
                           (False, False), remote=remote)
    except (KeyError, TypeError, ValueError, OverflowError) as e:
        s.link.send(wire.LEAVE)
        return replace(s, part=Lobby(), message=((f"that match could not start: {e}",
                                                  "foul"),))
