"""The Settings and Stats screens as they are drawn: boxes over the menu or the paused game.

Their state is in ui.state (`Settings`, `Stats`) and their keys in ui.phases.boxes; here are
the lines of their boxes. Neither touches a file until it closes (Settings) or opens (Stats).
"""

from __future__ import annotations

import textwrap
from typing import Any

from termpool.text import shown
from termpool.ui.settings import SETTINGS
from termpool.ui.state import Settings, State, Stats

GROUPS = (("The game", ("level", "table", "frames", "theme", "colors")),
          ("Playing", ("aid", "power", "bell", "fast")),
          ("Names", ("player1", "player2")))
USUAL_NAME = {"player1": "You / Player 1", "player2": "Player 2"}
TITLES = {Settings: "settings", Stats: "stats"}

BOX_TEXT_COLS = 70  # the Settings box's text width (less on a narrow screen)
STATS_ROWS = 24  # the screen's height the Stats screen pages by before it is first drawn


def current(s: State, key: str) -> Any:
    """A setting's value as the screen shows it: a change waiting for the next game, else
    the one in force."""
    return s.pending.get(key, getattr(s.opts, key))


def _value(s: State, setting) -> str:
    v = current(s, setting.key)
    if setting.kind == "switch":
        return "on" if v else "off"
    if setting.kind == "name":
        return shown(v) if v else f"({USUAL_NAME[setting.key]})"
    if setting.key == "colors" and v == "auto":
        return f"auto ({s.depth})"
    return str(v)


def settings_lines(s: State, box: Settings, cols: int, rows: int) -> list[str]:
    # One width for every row chosen: the box must not change size as the selection (and
    # the help under it) moves.
    width = min(BOX_TEXT_COLS, max(20, cols - 6))
    later = s.match is not None
    body: list[str] = []
    headed: list[str] = []
    for head, keys in GROUPS:
        headed.append(head)
        for key in keys:
            k = next(i for i, x in enumerate(SETTINGS) if x.key == key)
            setting = SETTINGS[k]
            sel = k == box.index
            if sel and box.editing is not None:
                value = f"{shown(box.editing)}_"
            else:
                value = _value(s, setting)
                value = f"‹ {value} ›" if sel and setting.kind != "name" else value
            mark = "  * next game" if setting.key in s.pending else ""
            line = f"{'▶' if sel else ' '} {setting.label:<18} {value}{mark}"
            body.append(line)
            headed.append(line)
    setting = SETTINGS[box.index]
    if box.editing is not None:
        help_ = "type the name · Enter keeps it · Esc leaves it as it was"
    elif setting.kind == "name":
        help_ = f"{setting.help} · Enter: type it"
    else:
        help_ = f"{setting.allowed()} · {setting.help}"
    tail = ["", *(cut(x, width) for x in textwrap.wrap(help_, width)[:2])]
    tail.append("↑↓ choose · ←→ change · Esc done")
    prefs = s.files.prefs
    if prefs is not None:
        path = shown(prefs.path)
        room = width - len("saved in ")
        tail.append(f"saved in {path if len(path) <= room else '…' + path[1 - room:]}")
        if prefs.warnings:
            tail.append(cut(shown(prefs.warnings[0]), width))
    head = ["Changes apply at once; those marked * from the next game.", ""] if later else []
    rows_left = rows - 2 - len(tail) - len(head)
    middle = headed if len(headed) <= rows_left else body
    out = [*head, *middle, *tail]
    return [out[0].ljust(width), *out[1:]]


def stats_room(rows: int) -> int:
    """Lines of the Stats screen a page holds on a screen `rows` high."""
    return max(1, rows - 4)  # the frame, a blank line and the keys


def stats_top(box: Stats, rows: int) -> int:
    """The first line shown: the one asked for, or less where the rest fits above it."""
    return min(box.top, max(0, len(box.text) - stats_room(rows)))


def stats_lines(box: Stats, rows: int) -> list[str]:
    room = stats_room(rows)
    top = stats_top(box, rows)
    window = box.text[top:top + room]
    more = len(box.text) > room
    keys = (f"↑↓ PgUp PgDn: lines {top + 1}-{top + len(window)} of {len(box.text)} · "
            "Esc closes") if more else "any key closes this"
    return [*window, "", keys]


def box_lines(s: State, box: Settings | Stats, cols: int, rows: int) -> list[str]:
    if isinstance(box, Settings):
        return settings_lines(s, box, cols, rows)
    return stats_lines(box, rows)


def cut(text: str, width: int) -> str:
    return text if len(text) <= width else text[:width - 1] + "…"
