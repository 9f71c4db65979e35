"""The Settings and Stats screens: boxes over the menu or the paused game.

A screen takes the app's key presses while it is open (`key`), gives the lines of its box
(`lines`) and sets `closed` when it is done; the app then goes back to `back` (the pause box,
or nothing). Neither touches a file until it closes (Settings) or opens (Stats).
"""

from __future__ import annotations

import textwrap
from typing import Any

from termpool.text import shown
from termpool.ui.settings import BY_KEY, MAX_NAME, SETTINGS, check_name

GROUPS = (("The game", ("level", "table", "frames", "theme", "colors")),
          ("Playing", ("aid", "power", "bell", "fast")),
          ("Names", ("player1", "player2")))
USUAL_NAME = {"player1": "You / Player 1", "player2": "Player 2"}

BOX_TEXT_COLS = 70  # the Settings box's text width (less on a narrow screen)


def current(app, key: str) -> Any:
    """A setting's value as the screen shows it: a change waiting for the next game, else
    the one in force."""
    return app.pending.get(key, getattr(app.opts, key))


def apply_pending(app) -> None:
    """The changes held for the next game take effect (a new match starts)."""
    for key, value in app.pending.items():
        setattr(app.opts, key, value)
    app.pending.clear()


def set_value(app, key: str, value: Any) -> None:
    """Change a setting: at once, or (one that shapes a match, while a match is on) from the
    next game."""
    if BY_KEY[key].later and app.match is not None:
        app.pending[key] = value
        if value == getattr(app.opts, key):
            del app.pending[key]
        return
    setattr(app.opts, key, value)
    if key == "colors":
        from termpool.ui.output import resolve_depth

        app.depth = resolve_depth(value, app.env)
    elif key == "power":
        app.set_input_mode(app.input_mode)


def _step(setting, value: Any, d: int) -> Any:
    """The value d steps on (choices go round; a count stops at its ends)."""
    if setting.kind == "switch":
        return not value
    if setting.kind == "count":
        return min(setting.hi, max(setting.lo, value + d))
    vals = setting.values
    return vals[(vals.index(value) + d) % len(vals)]


def _typed(key) -> str | None:
    """The character a key types into a name, or None."""
    if key.ctrl or key.alt:
        return None
    if key.name == "space":
        return " "
    if len(key.name) == 1 and key.name.isprintable():
        return key.name.upper() if key.shift and key.name.isalpha() else key.name
    return None


class SettingsScreen:
    title = "settings"

    def __init__(self, app, back: str | None = None) -> None:
        self.back = back
        self.closed = False
        self.index = 0
        self.editing: str | None = None  # the name being typed
        if app.match is None:
            apply_pending(app)
        self.before = {s.key: current(app, s.key) for s in SETTINGS}

    @property
    def setting(self):
        return SETTINGS[self.index]

    def key(self, app, key, action) -> None:
        if key.kind == "release":
            return
        s = self.setting
        if self.editing is not None:
            self._type(app, key)
        elif key.name in ("up", "k") or (key.name == "tab" and key.shift):
            self.index = (self.index - 1) % len(SETTINGS)
        elif key.name in ("down", "j", "tab"):
            self.index = (self.index + 1) % len(SETTINGS)
        elif key.name in ("left", "right") and s.kind != "name":
            d = -1 if key.name == "left" else 1
            set_value(app, s.key, _step(s, current(app, s.key), d))
        elif s.kind == "name" and (key.name == "enter" or action == "confirm"):
            self.editing = current(app, s.key)
        elif key.name in ("esc", "q", "enter") or action in ("cancel", "quit", "confirm"):
            self._close(app)

    def _type(self, app, key) -> None:
        if key.name == "esc":
            self.editing = None
        elif key.name == "enter":  # only printable characters can be typed (see _typed)
            set_value(app, self.setting.key, check_name(self.editing.strip()))
            self.editing = None
        elif key.name == "backspace":
            self.editing = self.editing[:-1]
        else:
            ch = _typed(key)
            if ch is not None and len(self.editing) < MAX_NAME:
                self.editing += ch

    def _close(self, app) -> None:
        """Done: the changes made here are saved (the flags of this run are not)."""
        self.closed = True
        changes = {k: current(app, k) for k, v in self.before.items() if current(app, k) != v}
        if changes and app.prefs is not None:
            warning = app.prefs.save(changes)
            if warning:
                app.message = [(warning, "foul")]
                app.notes.append(warning)

    # ------------------------------------------------------------------------ drawing
    def _value(self, app, s) -> str:
        v = current(app, s.key)
        if s.kind == "switch":
            text = "on" if v else "off"
        elif s.kind == "name":
            text = shown(v) if v else f"({USUAL_NAME[s.key]})"
        elif s.key == "colors" and v == "auto":
            text = f"auto ({app.depth})"
        else:
            text = str(v)
        return text

    def lines(self, app, cols: int, rows: int) -> list[str]:
        # One width for every row chosen: the box must not change size as the selection
        # (and the help under it) moves.
        width = min(BOX_TEXT_COLS, max(20, cols - 6))
        later = app.match is not None
        body: list[str] = []
        headed: list[str] = []
        for head, keys in GROUPS:
            headed.append(head)
            for key in keys:
                k = next(i for i, s in enumerate(SETTINGS) if s.key == key)
                s = SETTINGS[k]
                sel = k == self.index
                if sel and self.editing is not None:
                    value = f"{shown(self.editing)}_"
                else:
                    value = self._value(app, s)
                    value = f"‹ {value} ›" if sel and s.kind != "name" else value
                mark = "  * next game" if s.key in app.pending else ""
                line = f"{'▶' if sel else ' '} {s.label:<18} {value}{mark}"
                body.append(line)
                headed.append(line)
        s = self.setting
        if self.editing is not None:
            help_ = "type the name · Enter keeps it · Esc leaves it as it was"
        elif s.kind == "name":
            help_ = f"{s.help} · Enter: type it"
        else:
            help_ = f"{s.allowed()} · {s.help}"
        tail = ["", *(_cut(x, width) for x in textwrap.wrap(help_, width)[:2])]
        tail.append("↑↓ choose · ←→ change · Esc done")
        if app.prefs is not None:
            path = shown(app.prefs.path)
            room = width - len("saved in ")
            tail.append(f"saved in {path if len(path) <= room else '…' + path[1 - room:]}")
            if app.prefs.warnings:
                tail.append(_cut(shown(app.prefs.warnings[0]), width))
        head = ["Changes apply at once; those marked * from the next game.", ""] if later \
            else []
        rows_left = rows - 2 - len(tail) - len(head)
        middle = headed if len(headed) <= rows_left else body
        out = [*head, *middle, *tail]
        return [out[0].ljust(width), *out[1:]]


class StatsScreen:
    title = "stats"

    def __init__(self, app, back: str | None = None) -> None:
        from termpool.game.history import history_path, read_history, summary
        from termpool.ui.stats import stats_lines

        self.back = back
        self.closed = False
        self.top = 0
        self.rows = 24  # the screen's height when last drawn: a page is what fits
        path = app.history.path if app.history is not None else history_path(app.env)
        found, warning, _ = read_history(path)
        self.text = [shown(x) for x in ([warning, ""] if warning else []) +
                     stats_lines(summary(found))]

    def _room(self, rows: int) -> int:
        return max(1, rows - 4)  # the frame, a blank line and the keys

    def key(self, app, key, action) -> None:
        if key.kind == "release":
            return
        page = self._room(self.rows)
        most = max(0, len(self.text) - page)
        moves = {"up": -1, "k": -1, "down": 1, "j": 1, "pageup": -page, "pagedown": page,
                 "space": page, "home": -len(self.text), "end": len(self.text)}
        if key.name in moves and most:
            self.top = min(most, max(0, self.top + moves[key.name]))
        else:
            self.closed = True

    def lines(self, app, cols: int, rows: int) -> list[str]:
        self.rows = rows
        room = self._room(rows)
        self.top = min(self.top, max(0, len(self.text) - room))
        window = self.text[self.top:self.top + room]
        more = len(self.text) > room
        keys = (f"↑↓ PgUp PgDn: lines {self.top + 1}-{self.top + len(window)} of "
                f"{len(self.text)} · Esc closes") if more else "any key closes this"
        return [*window, "", keys]


def _cut(text: str, width: int) -> str:
    return text if len(text) <= width else text[:width - 1] + "…"

