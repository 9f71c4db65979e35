"""The menu: a game against the computer or a second player, practice, the Settings and
Stats screens, the help, quit."""

from __future__ import annotations

from dataclasses import replace

from termpool.ui.phases.boxes import open_settings, open_stats
from termpool.ui.phases.lobby import open_lobby
from termpool.ui.phases.turn import new_match
from termpool.ui.state import Help, State, menu_entries


def key(s: State, key, action: str | None, t: float) -> State:
    if key.kind == "release":
        return s
    n = len(menu_entries(s))
    if key.name in ("up", "k") or action == "spin_up":
        return replace(s, menu_index=(s.menu_index - 1) % n)
    if key.name in ("down", "j") or action == "spin_down":
        return replace(s, menu_index=(s.menu_index + 1) % n)
    if key.name.isdigit() and 1 <= (int(key.name) or 10) <= n:  # 0 is the tenth, as on a phone
        return pick(replace(s, menu_index=(int(key.name) or 10) - 1))
    if action in ("confirm", "shoot"):
        return pick(s)
    return s


def pick(s: State) -> State:
    what = menu_entries(s)[s.menu_index][1]
    if what == "online":
        return open_lobby(s)
    if what == "quit":
        return replace(s, done=True)
    if what == "help":
        return replace(s, box=Help())
    if what == "settings":
        return open_settings(s)
    if what == "stats":
        return open_stats(s)
    return new_match(s, *what)
