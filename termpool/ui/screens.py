"""The Settings and Stats screens as they are drawn: boxes over the menu or the paused game.

Their state is in ui.state (`Settings`, `Stats`) and their keys in ui.phases.boxes; here are
the lines of their boxes. Neither touches a file until it closes (Settings) or opens (Stats).
"""

from __future__ import annotations

import textwrap
from typing import Any

from termpool.text import shown
from termpool.ui.help import BOX_EDGE
from termpool.ui.settings import MAX_NAME, SETTINGS
from termpool.ui.state import Settings, State, Stats

GROUPS = (("The game", ("level", "table", "frames", "theme", "colors")),
          ("Rules", ("three_foul", "eight_break")),
          ("Playing", ("aid", "power", "bell", "fast", "records")),
          ("Names", ("player1", "player2")))
USUAL_NAME = {"player1": "You / Player 1", "player2": "Player 2"}
TITLES = {Settings: "settings", Stats: "stats"}

LATER_NOTE = "Changes apply at once; a change marked * applies from the next game."
SETTINGS_SEEN = 5  # settings always in view (around the one chosen) on a short screen
BOX_TEXT_COLS = 70  # the Settings box's text width (less on a narrow screen)
STATS_ROWS = 24  # the screen's height the Stats screen pages by before it is first drawn
STATS_COLS = 80  # ... and its width
SIDE_STEP = 8  # columns ← and → scroll the Stats screen by


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


def _about(setting) -> str:
    """What a setting does, as the line under the settings says it."""
    if setting.kind == "name":
        return f"{setting.help} · Enter: type it"
    if setting.kind == "count":
        return f"{setting.allowed()} (type it, or ←→) · {setting.help}"
    return f"{setting.allowed()} · {setting.help}"


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
            if key == "level" and s.match is not None and s.opts.opponent != "cpu":
                mark += "  (not in this game)"
            line = f"{'▶' if sel else ' '} {setting.label:<18} {value}{mark}"
            body.append(line)
            headed.append(line)
    setting = SETTINGS[box.index]
    if box.editing is not None and setting.kind == "count":
        help_ = box.refused or f"type {setting.allowed()}"
    elif box.editing is not None:  # what was not typed, and why, until the name is done
        help_ = box.refused or (f"type a new name (up to {MAX_NAME} characters), or "
                                "Backspace to edit this one" if box.whole
                                else f"type the name (up to {MAX_NAME} characters)")
    else:
        help_ = _about(setting)
    about = textwrap.wrap(help_, width)
    # The rows every setting's words would take: the layout is made for the tallest, so that
    # nothing above them moves (headings, scrolling) as the choice moves.
    tall = max(len(about), *(len(textwrap.wrap(_about(x), width)) for x in SETTINGS))
    keys = ("Backspace deletes · Enter keeps it · Esc leaves it as it was"
            if box.editing is not None
            else "↑↓ choose · ←→ or Enter change · Esc done")
    if len(keys) > width:  # (a narrow screen: the short form)
        keys = "Backspace · Enter keeps · Esc leaves it" if box.editing is not None else keys
    prefs = s.files.prefs
    files = []
    if prefs is not None:
        path = shown(prefs.path)
        head = "closing saves the changes in"
        if len(head) + 1 + len(path) <= width:
            files.append(f"{head} {path}")
        else:  # the path on a line of its own, its end kept
            files += [head, path if len(path) <= width else "…" + path[1 - width:]]
        if prefs.warnings:
            files += textwrap.wrap(shown(prefs.warnings[0]), width)
    note = textwrap.wrap(LATER_NOTE, width) if later else []
    # Where the screen is short the settings scroll about the one chosen (a few always in
    # view), what the chosen one does is said whole if it can be, and the rest comes in
    # this order while there is room: the blank line above it, the note, the file's lines.
    space = rows - 2
    least = min(len(body), SETTINGS_SEEN)
    cap = max(1, space - 1 - least)
    if len(about) > cap:
        about = about[:cap]
        about[-1] = cut(about[-1] + " …", width)
    about += [""] * (min(tall, cap) - len(about))
    left = space - 1 - len(about) - least
    extra = {}
    for name, lines in (("gap", [""]), ("note", [*note, ""] if note else []), ("files", files)):
        if len(lines) <= left:
            extra[name] = lines
            left -= len(lines)
    rows_left = max(1, space - 1 - len(about) - sum(map(len, extra.values())))
    chosen = next(k for k, x in enumerate(body) if x.startswith("▶"))
    middle = headed if len(headed) <= rows_left else scrolled(body, chosen, rows_left)
    out = [*extra.get("note", []), *middle, *extra.get("gap", []), *about, keys,
           *extra.get("files", [])]
    return [out[0].ljust(width), *out[1:]]


def scrolled(lines: list[str], chosen: int, room: int) -> list[str]:
    """`room` of the lines, the chosen one among them, with "↑ more" and "↓ more" in place
    of the first and last where lines are hidden that way (room for them allowing)."""
    if len(lines) <= room:
        return lines
    start = min(max(0, chosen - room // 2), len(lines) - room)
    if room < 3:
        return lines[start:start + room]
    while True:
        above, below = start > 0, start + room < len(lines)
        first, last = start + above, start + room - below  # the lines shown whole
        if chosen < first:
            start -= 1
        elif chosen >= last:
            start += 1
        else:
            return [*(["  ↑ more"] if above else []), *lines[first:last],
                    *(["  ↓ more"] if below else [])]


def stats_room(rows: int) -> int:
    """Lines of the Stats screen a page holds on a screen `rows` high."""
    return max(1, rows - 4)  # the frame, a blank line and the keys


def stats_width(cols: int) -> int:
    """Columns of the Stats screen's text a screen `cols` wide shows."""
    return max(1, cols - BOX_EDGE)


def stats_top(box: Stats, rows: int) -> int:
    """The first line shown: the one asked for, or less where the rest fits above it."""
    return min(box.top, max(0, len(box.text) - stats_room(rows)))


def stats_left(box: Stats, cols: int) -> int:
    """The first column shown: the one asked for, or less where the rest fits left of it."""
    widest = max((len(x) for x in box.text), default=0)
    return min(box.left, max(0, widest - stats_width(cols)))


def stats_lines(box: Stats, cols: int, rows: int) -> list[str]:
    """The page of the stats on show, as wide as the screen has room for, and a line of keys
    that says where it is when there is more than the screen shows (lines below or above,
    columns to the right or left)."""
    room, width = stats_room(rows), stats_width(cols)
    top, left = stats_top(box, rows), stats_left(box, cols)
    window = [x[left:left + width] for x in box.text[top:top + room]]
    tall = len(box.text) > room
    widest = max((len(x) for x in box.text), default=0)
    wide = widest > width
    if not (tall or wide):
        return [*window, "", "any key closes this"]
    arrows = ("↑↓ " if tall else "") + ("←→ " if wide else "")
    where = []
    if tall:
        where.append(f"lines {top + 1}-{top + len(window)} of {len(box.text)}")
    if wide:
        where.append(f"columns {left + 1}-{min(widest, left + width)} of {widest}")
    forms = [f"{arrows}PgUp PgDn: {', '.join(where)} · Esc closes",
             f"{arrows}more: {', '.join(where)} · Esc",
             f"{arrows}more · Esc closes", f"{arrows}more"]
    return [*window, "", next((f for f in forms if len(f) <= width), forms[-1])]


def box_lines(s: State, box: Settings | Stats, cols: int, rows: int) -> list[str]:
    if isinstance(box, Settings):
        return settings_lines(s, box, cols, rows)
    return stats_lines(box, cols, rows)


def cut(text: str, width: int) -> str:
    return text if len(text) <= width else text[:width - 1] + "…"
