"""The boxes over any phase take the keys while they are open: the help's pages, the pause,
the quit question, and the Settings and Stats screens (their lines: ui.screens)."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

from termpool.game.history import history_path, read_history, summary
from termpool.text import one_column, shown
from termpool.ui.help import page_key
from termpool.ui.output import resolve_depth
from termpool.ui.phases.turn import (
    apply_pending,
    concede_online,
    quit_game,
    set_input_mode,
    to_menu,
)
from termpool.ui.screens import (
    SIDE_STEP,
    STATS_COLS,
    STATS_ROWS,
    current,
    stats_left,
    stats_room,
    stats_top,
    stats_width,
)
from termpool.ui.settings import BY_KEY, MAX_NAME, ONE_COLUMN, SETTINGS
from termpool.ui.state import Help, Pause, Quit, Seen, Settings, State, Stats, help_of
from termpool.ui.stats import stats_lines


def key(s: State, key, action: str | None, seen: Seen | None) -> State:
    box = s.box
    if isinstance(box, Settings):
        return settings_key(s, box, key, action)
    if isinstance(box, Stats):
        size = (seen.cols, seen.rows) if seen is not None else (STATS_COLS, STATS_ROWS)
        return stats_key(s, box, key, *size)
    if key.kind != "press":
        return s
    if isinstance(box, Pause) and key.name == "s" and not (key.ctrl or key.alt):
        return open_settings(s, Pause())
    if isinstance(box, Quit):
        if key.name in ("y", "q") or action == "quit":
            return quit_game(s)
        if key.name == "m" and not (key.ctrl or key.alt):
            return to_menu(concede_online(s))
        if key.name == "n" or action in ("cancel", "confirm"):
            return replace(s, box=None)
        return s
    if isinstance(box, Help):
        # The pages are the ones the screen showed last (they depend on its size).
        pages = len(help_of(s, seen.cols, seen.rows)) if seen is not None else 1
        page, close = page_key(key.name, min(box.page, pages - 1), pages)
        return replace(s, box=None if close else Help(page))
    return replace(s, box=None)  # any key ends the pause


# ---------------------------------------------------------------------------- Settings
def open_settings(s: State, back: Pause | None = None) -> State:
    if s.match is None:
        s = apply_pending(s)
    return replace(s, box=Settings({x.key: current(s, x.key) for x in SETTINGS}, back,
                                   index=s.settings_row))


def set_value(s: State, key: str, value: Any) -> State:
    """Change a setting: at once, or (one that shapes a match, while a match is on) from the
    next game."""
    if BY_KEY[key].later and s.match is not None:
        pending = {**s.pending, key: value}
        if value == getattr(s.opts, key):
            del pending[key]
        return replace(s, pending=pending)
    s = replace(s, opts=replace(s.opts, **{key: value}))
    if key == "colors":
        return replace(s, depth=resolve_depth(value, s.env))
    if key == "power":
        return set_input_mode(s, s.input_mode)
    return s


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
    if len(key.name) == 1 and key.name.isprintable() and one_column(key.name):
        return key.name.upper() if key.shift and key.name.isalpha() else key.name
    return None


def settings_key(s: State, box: Settings, key, action: str | None) -> State:
    if key.kind == "release":
        return s
    setting = SETTINGS[box.index]
    if box.editing is not None:
        return _type(s, box, key)
    if key.name in ("up", "k") or (key.name == "tab" and key.shift):
        return replace(s, box=replace(box, index=(box.index - 1) % len(SETTINGS)))
    if key.name in ("down", "j", "tab"):
        return replace(s, box=replace(box, index=(box.index + 1) % len(SETTINGS)))
    touched = replace(box, touched=box.touched | {setting.key})
    if setting.kind == "count" and key.digit is not None:  # a number starts with a digit
        return replace(s, box=replace(box, editing=key.name, refused=None, whole=False))
    if key.name in ("left", "right") and setting.kind != "name":
        d = -1 if key.name == "left" else 1
        s = set_value(s, setting.key, _step(setting, current(s, setting.key), d))
        return replace(s, box=touched)
    if key.name == "enter" or action == "confirm":
        if setting.kind == "name":  # typing starts over it; Backspace edits it
            return replace(s, box=replace(box, editing=current(s, setting.key), whole=True))
        # (Enter changes the value, as → does: the box closes with Esc or Q)
        s = set_value(s, setting.key, _step(setting, current(s, setting.key), 1))
        return replace(s, box=touched)
    if key.name in ("esc", "q") or action in ("cancel", "quit"):
        return _close(s, box)
    return s


def _type(s: State, box: Settings, key) -> State:
    """A name or a number being typed."""
    # (A refusal stays said until the name is done: keys typed after it would hide it.)
    setting = SETTINGS[box.index]
    if key.name == "esc":
        return replace(s, box=replace(box, editing=None, refused=None, whole=False))
    if key.name == "enter":  # only what check_name takes can be typed (see _typed)
        try:
            value = setting.parse(box.editing.strip())
        except ValueError as e:  # (a number out of its range)
            return replace(s, box=replace(box, refused=str(e)))
        s = set_value(s, setting.key, value)
        return replace(s, box=replace(box, editing=None, refused=None, whole=False,
                                      touched=box.touched | {setting.key}))
    if key.name == "backspace":
        return replace(s, box=replace(box, editing=box.editing[:-1], whole=False))
    if setting.kind == "count":
        if key.digit is None:
            if len(key.name) == 1 and not (key.ctrl or key.alt):
                return replace(s, box=replace(box, refused=f"not typed: {setting.allowed()}"))
            return s
        if len(box.editing) >= len(str(setting.hi)):
            return replace(s, box=replace(box, refused=setting.allowed()))
        return replace(s, box=replace(box, editing=box.editing + key.name, refused=None))
    ch = _typed(key)
    if ch is None:
        if len(key.name) == 1 and not (key.ctrl or key.alt):  # a character, refused
            return replace(s, box=replace(box, refused=f"not typed: {ONE_COLUMN}"))
        return s
    if box.whole:  # the first character typed is a new name's first
        return replace(s, box=replace(box, editing=ch, whole=False))
    if len(box.editing) >= MAX_NAME:
        return replace(s, box=replace(box, refused=f"a name holds {MAX_NAME} characters at most"))
    return replace(s, box=replace(box, editing=box.editing + ch))


def _close(s: State, box: Settings) -> State:
    """Done: the changes made here are saved (the flags of this run are not, unless set
    here: what the box showed is what is saved), and the box it came from is back."""
    s = replace(s, box=box.back, settings_row=box.index)
    changes = {k: current(s, k) for k, v in box.before.items()
               if current(s, k) != v or k in box.touched}
    if changes and s.files.prefs is not None:
        warning = s.files.prefs.save(changes)
        if warning:
            return replace(s, message=((warning, "foul"),), notes=(*s.notes, warning))
    return s


# ------------------------------------------------------------------------------- Stats
def open_stats(s: State, back: Pause | None = None) -> State:
    history = s.files.history
    path = history.path if history is not None else history_path(s.env)
    found, warning, _ = read_history(path)
    text = tuple(shown(x) for x in ([warning, ""] if warning else []) +
                 stats_lines(summary(found)))
    return replace(s, box=Stats(text, back))


def stats_key(s: State, box: Stats, key, cols: int, rows: int) -> State:
    """The arrows and pages scroll (by the page the screen last showed; ← → where the lines
    are wider than it); any other key closes the box."""
    if key.kind == "release":
        return s
    page = stats_room(rows)
    most = max(0, len(box.text) - page)
    top = stats_top(box, rows)
    moves = {"up": -1, "k": -1, "down": 1, "j": 1, "pageup": -page, "pagedown": page,
             "space": page, "home": -len(box.text), "end": len(box.text)}
    if key.name in moves and most:
        return replace(s, box=replace(box, top=min(most, max(0, top + moves[key.name]))))
    widest = max((len(x) for x in box.text), default=0)
    side = max(0, widest - stats_width(cols))
    steps = {"left": -SIDE_STEP, "h": -SIDE_STEP, "right": SIDE_STEP, "l": SIDE_STEP}
    if key.name in steps and side:
        left = stats_left(box, cols) + steps[key.name]
        return replace(s, box=replace(box, left=min(side, max(0, left))))
    return replace(s, box=box.back)
