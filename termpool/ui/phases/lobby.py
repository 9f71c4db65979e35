"""The lobby (under `termpool serve`): the players online, a challenge to one of them, the
answer to one's own challenges, and the online match that starts when one is accepted."""

from __future__ import annotations

from dataclasses import replace

from termpool import wire
from termpool.rules.words import MODE_NAMES
from termpool.text import shown
from termpool.ui.phases import remote
from termpool.ui.phases.turn import begin_match, to_menu
from termpool.ui.settings import MAX_FRAMES
from termpool.ui.state import LOBBY_GAMES, Lobby, Menu, State, lobby_choice

LOBBY_POLL_S = 0.1  # how often the lobby looks for news while it is on screen
REFUSALS = {wire.BUSY: "busy: not in the lobby, or in a challenge already",
            wire.GONE: "that player has left", wire.BAD: "the server could not read that",
            wire.SELF: "that is you, on another screen"}


def open_lobby(s: State) -> State:
    s.link.news.clear()  # what happened while away is over
    s.link.send(wire.WHERE, lobby=True)
    s.link.poll()
    return replace(s, part=Lobby(), message=())


def challenge_game(s: State, mode: str) -> dict:
    """The match a challenge offers: the game chosen and this player's table settings."""
    import secrets

    o = s.opts
    return {"mode": mode, "table": o.table, "frames": o.frames, "seed": secrets.randbits(63),
            "three_foul": o.three_foul and mode == "9ball", "eight_break": o.eight_break,
            "theme": o.theme}


def key(s: State, key, action: str | None, t: float) -> State | None:
    """The lobby's keys; None for those it leaves to every screen (help, quit)."""
    if key.kind == "release":
        return s
    part, link = s.part, s.link
    cancel = action == "cancel" or key.name == "esc"
    if link.challenged is not None:  # a challenge to answer comes first
        if key.name in ("y", "n") or cancel:
            by = link.challenged
            link.send(wire.ANSWER, to=by.get("by"), yes=key.name == "y")
            link.challenged = None
            words = () if key.name == "y" else \
                ((f"declined {shown(str(by.get('name', '')))[:16]}", "dim"),)
            return replace(s, message=words)
        return None if action in ("help", "quit") else s
    if cancel:
        if part.waiting is not None:  # the challenge is taken back; the lobby stays
            link.send(wire.WHERE, lobby=False)
            link.send(wire.WHERE, lobby=True)
            return replace(s, part=replace(part, waiting=None),
                           message=(("challenge taken back", "dim"),))
        return to_menu(s)  # out of the lobby, as by the quit box
    others, k = lobby_choice(s)
    if key.name in ("up", "k", "down", "j") and others:
        k = max(0, min(len(others) - 1, k + (1 if key.name in ("down", "j") else -1)))
        return replace(s, part=replace(part, chosen=others[k].get("id")))
    if key.name in ("left", "right") and part.waiting is None:
        step = 1 if key.name == "right" else -1
        return replace(s, part=replace(part, game=(part.game + step) % len(LOBBY_GAMES)))
    if action in ("confirm", "shoot"):
        if not others or part.waiting is not None:
            return s
        who = others[k]
        if who.get("where") == "playing":  # their match, to watch
            link.send(wire.WATCH, to=who.get("id"))
            return replace(s, message=())
        mode = LOBBY_GAMES[part.game]
        link.send(wire.CHALLENGE, to=who.get("id"), game=challenge_game(s, mode))
        waiting = f"{shown(str(who.get('name', '')))[:16]} ({MODE_NAMES[mode]})"
        return replace(s, part=replace(part, chosen=who.get("id"), waiting=waiting),
                       message=())
    return None


def menu_tick(s: State, t: float) -> State:
    """The menu under a server: a match this player is back in (their connection had
    dropped) starts at once, its moves so far made first (ui.phases.remote)."""
    link = s.link
    link.poll()
    if link.start is None:
        return s
    seat = link.start.get("seat")
    s = start_online(s, link.start)
    if s.match is None or seat not in (0, 1) or link.resume is not None:
        return s  # ... with moves to make: said when they are made
    return replace(s, message=(remote.back_in(s, seat),))


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
        # None: watching. A player back in their match (its moves so far to make) makes
        # them as a watcher does, and then plays their side (remote.tick).
        s.link.resume = seat if seat is not None and s.link.backlog else None
        remote = (0, 1) if seat is None or s.link.resume is not None else (1 - seat,)
        s = begin_match(s, opts, tuple(str(n) for n in names), int(game["seed"]),
                        (False, False), remote=remote)
        if s.link.resume is not None and s.files.records is not None:
            s.files.records.adopt(s.match)  # its record from before the drop goes on
        return s
    except (KeyError, TypeError, ValueError, OverflowError) as e:
        s.link.send(wire.LEAVE)
        return replace(s, part=Lobby(), message=((f"that match could not start: {e}",
                                                  "foul"),))
