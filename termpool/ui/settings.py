"""Settings: the player's choices, kept from game to game in `settings.conf` beside keys.conf.

`SETTINGS` is the one table of them: each setting's name, its allowed values and its default.
The Settings screen (`ui.settings_screen`), the file reader here and the `termpool play` flags
(`add_flags`, `from_flags`) all read it.

The file is UTF-8 text, one `key = value` a line (`level = hard`); blank lines and lines
starting with `#` are skipped, and a value runs to the end of its line (so a name may hold a
`#`). It is read at start; flags override it for one run; the Settings screen writes it back
whole, atomically, when it closes with something changed. A line that is wrong (no `=`, an
unknown key, a key given twice, a value not allowed) is one warning naming its line and key,
and that key keeps its default; a file that cannot be read at all is one warning, and every
key keeps its default.
"""

from __future__ import annotations

import argparse
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from termpool.files import KEEP_RECORDS, MAX_CONFIG_BYTES, FileError, read_text, write_atomic
from termpool.text import one_column
from termpool.ui.controls import config_path

FILE_NAME = "settings.conf"
MAX_NAME = 16  # characters in a player's name: it has to fit the panel's player line
MAX_FRAMES = 1000


@dataclass(frozen=True)
class Setting:
    """One setting. `kind`: "choice" (one of `values`), "switch" (off or on: a bool),
    "count" (a whole number from `lo` to `hi`) or "name" (a player's name; empty: the usual
    one). `later`: it shapes a match, so a change made during one applies to the next."""

    key: str
    label: str
    help: str
    default: Any
    kind: str = "choice"
    values: tuple[str, ...] = ()
    lo: int = 0
    hi: int = 0
    later: bool = False

    def parse(self, text: str) -> Any:
        """A value as written in the file or on the command line; ValueError (what is
        allowed, and what was given) when it is not one."""
        shown = text if len(text) <= 24 else text[:24] + "..."
        if self.kind == "choice":
            if text not in self.values:
                raise ValueError(f"must be one of {', '.join(self.values)}, not '{shown}'")
            return text
        if self.kind == "switch":
            if text not in ("off", "on"):
                raise ValueError(f"must be on or off, not '{shown}'")
            return text == "on"
        if self.kind == "count":
            if not (text.isascii() and text.isdigit() and len(text) <= len(str(self.hi))
                    and self.lo <= int(text) <= self.hi):
                raise ValueError(f"must be a whole number from {self.lo} to {self.hi}, "
                                 f"not '{shown}'")
            return int(text)
        return check_name(text)

    def text(self, value: Any) -> str:
        """A value as the file writes it (the inverse of `parse`)."""
        if self.kind == "switch":
            return "on" if value else "off"
        return str(value)

    def allowed(self) -> str:
        """The allowed values in words, for the file's comments and the screen."""
        if self.kind == "choice":
            return ", ".join(self.values)
        if self.kind == "switch":
            return "off, on"
        if self.kind == "count":
            return f"a whole number from {self.lo} to {self.hi}"
        return f"up to {MAX_NAME} characters; empty: the usual name"

    @property
    def flag(self) -> str:
        return f"--{self.key.replace('_', '-')}"


# (The screen is drawn a character a cell: a wide one would push the rest of its line along.)
ONE_COLUMN = "only characters one column wide (no emoji or wide characters)"


def check_name(text: str) -> str:
    """A player's name: at most MAX_NAME printable characters, no spaces at either end (an
    empty name means the usual one). ValueError says what is wrong."""
    if text != text.strip():
        raise ValueError("must not start or end with a space")
    if len(text) > MAX_NAME:
        raise ValueError(f"at most {MAX_NAME} characters, not {len(text)}")
    if not text.isprintable():
        raise ValueError("must be printable (no control characters)")
    if not all(one_column(c) for c in text):
        raise ValueError(ONE_COLUMN)
    return text


# The levels, sizes, themes and depths are the ones the game has (tests hold them to ai,
# physics.table, rules.words, ui.predict and ui.output); written here too because the command
# line is parsed before numpy is imported.
SETTINGS: tuple[Setting, ...] = (
    Setting("level", "Computer's level", "the computer's skill: easy (a beginner), normal (a "
            "club player), hard (a strong amateur), pro (a professional)", "normal",
            values=("easy", "normal", "hard", "pro"), later=True),
    Setting("table", "Table", "table size", "9ft", values=("7ft", "8ft", "9ft"), later=True),
    Setting("frames", "Frames to win", "a match is a race to this many frames", 1,
            kind="count", lo=1, hi=MAX_FRAMES, later=True),
    Setting("theme", "Theme", "ball colours: numbered solids and stripes, or reds and "
            "yellows (8-ball; 9-ball keeps its colours)", "standard",
            values=("standard", "classic"), later=True),
    Setting("colors", "Colour depth", "colour depth (auto: from the terminal; NO_COLOR "
            "gives mono)", "auto", values=("auto", "truecolor", "256", "16", "mono")),
    Setting("three_foul", "Three-foul rule", "9-ball: three fouls in a row lose the "
            "frame", False, kind="switch", later=True),
    Setting("eight_break", "8 on the break", "8-ball: the 8 pocketed on the break is "
            "re-spotted, or the balls are re-racked for the same breaker", "respot",
            values=("respot", "rerack"), later=True),
    Setting("aid", "Aim aid", "the aim aid: every predicted path, the ghost ball only, or "
            "none (G cycles them)", "full", values=("full", "ghost", "off")),
    Setting("power", "Power", "how Space gives power: hold it (released to strike), a "
            "swinging meter (press, press), or digits 1-0 set it and Space strikes", "hold",
            values=("hold", "meter", "digits")),
    Setting("bell", "Bell", "ring the bell on a pot or a foul (N toggles)", False,
            kind="switch"),
    Setting("fast", "Fast-forward", "shots start at x4: never, the computer's, or every "
            "shot (F toggles during one)", "off", values=("off", "computer", "always")),
    Setting("records", "Keep records", "keep every match for `termpool replay`, in the data "
            f"directory's records/ (the last {KEEP_RECORDS}; `termpool records` lists them)", True,
            kind="switch"),
    Setting("player1", "Player 1", "player 1's name (empty: You against the computer, "
            "Player 1 in a two-player game)", "", kind="name", later=True),
    Setting("player2", "Player 2", "player 2's name in a two-player game (empty: Player 2)",
            "", kind="name", later=True),
)
BY_KEY: dict[str, Setting] = {s.key: s for s in SETTINGS}
DEFAULTS: dict[str, Any] = {s.key: s.default for s in SETTINGS}


def player_names(player1: str, player2: str, mode: str, opponent: str) -> tuple[str, str]:
    """The names a match is played under: the settings' names, else the usual ones."""
    if mode == "practice":
        one = player1 or "You"
        return one, one
    if opponent == "cpu":
        return player1 or "You", "Computer"
    return player1 or "Player 1", player2 or "Player 2"


# ------------------------------------------------------------------------------ the file


def settings_path(env: Mapping[str, str] | None = None) -> Path:
    """settings.conf, in the directory of keys.conf."""
    return config_path(env).parent / FILE_NAME


def parse_settings(text: str, name: str = FILE_NAME) -> tuple[dict[str, Any], list[str]]:
    """A settings file's text -> (the values it sets, one warning line per wrong line)."""
    values: dict[str, Any] = {}
    seen: dict[str, int] = {}
    warnings: list[str] = []
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        key, eq, value = line.partition("=")
        key, value = key.strip(), value.strip()
        where = f"{name} line {n}"
        short = line if len(line) <= 40 else line[:40] + "..."
        if not eq or not key:
            warnings.append(f"{where}: expected 'key = value', not '{short}'")
            continue
        setting = BY_KEY.get(key)
        if setting is None:
            key = key if len(key) <= 24 else key[:24] + "..."
            warnings.append(f"{where}: unknown setting '{key}' (known: "
                            f"{', '.join(BY_KEY)})")
            continue
        if key in seen:
            warnings.append(f"{where}: {key} is already set on line {seen[key]}; this line "
                            "is left out")
            continue
        seen[key] = n
        try:
            values[key] = setting.parse(value)
        except ValueError as e:
            warnings.append(f"{where}: {key}: {e}; using {setting.text(setting.default)!r}")
    return values, warnings


def format_settings(values: Mapping[str, Any]) -> str:
    """The file's text for `values` (every setting, with its allowed values as a comment)."""
    out = ["# termpool settings: one 'key = value' a line. The Settings screen (from the",
           "# menu, or S while paused) writes this file; flags override it for one run."]
    for s in SETTINGS:
        out += ["", f"# {s.label}: {s.allowed()}", f"{s.key} = {s.text(values[s.key])}"]
    return "\n".join(out) + "\n"


@dataclass
class Store:
    """The settings file: where it is, the values it holds (defaults for the keys it lacks or
    got wrong) and the warnings reading it gave."""

    path: Path
    saved: dict[str, Any]
    warnings: list[str]

    def save(self, changes: Mapping[str, Any]) -> str | None:
        """Write the file with `changes` made (creating its directory); None when it was
        written, else the one-line warning saying why not (the changes then hold for this
        run only)."""
        values = {**self.saved, **changes}
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            write_atomic(self.path, format_settings(values))
        except OSError as e:
            return (f"cannot save the settings to '{self.path}': {e.strerror or e}; they hold "
                    "for this game only")
        self.saved = values
        return None


def load_settings(path: str | os.PathLike[str] | None = None,
                  env: Mapping[str, str] | None = None) -> Store:
    """The settings file (default: `settings_path(env)`), read. A missing file is the
    defaults, silently; any other trouble is in `warnings`, one line each."""
    p = Path(path) if path is not None else settings_path(env)
    values: dict[str, Any] = {}
    warnings: list[str] = []
    try:
        text = read_text(p, MAX_CONFIG_BYTES, "settings file")
    except FileError as e:
        if not e.missing:
            warnings.append(f"{e}; using the default settings")
    else:
        values, warnings = parse_settings(text, p.name or str(p))
    return Store(p, {**DEFAULTS, **values}, warnings)


# ------------------------------------------------------------------------------ the flags


def _type(setting: Setting) -> Callable[[str], Any]:
    def parse(text: str) -> Any:
        try:
            return setting.parse(text)
        except ValueError as e:
            raise argparse.ArgumentTypeError(str(e)) from None

    parse.__name__ = setting.key
    return parse


def add_flags(p: argparse.ArgumentParser) -> None:
    """A flag for every setting (`--level hard`, `--bell`/`--no-bell`, `--player1 Ann`): each
    overrides the settings file for this run."""
    for s in SETTINGS:
        default = s.text(s.default) or "empty"
        help_ = f"{s.help} (default: the settings file's, else {default})"
        if s.kind == "switch":
            p.add_argument(s.flag, action=argparse.BooleanOptionalAction, default=None,
                           help=help_)
        elif s.kind == "choice":
            p.add_argument(s.flag, choices=s.values, default=None, help=help_)
        else:
            p.add_argument(s.flag, type=_type(s), default=None,
                           metavar="N" if s.kind == "count" else "NAME", help=help_)


def from_flags(store_values: Mapping[str, Any], args: argparse.Namespace) -> dict[str, Any]:
    """The values for this run: the file's, with every flag given on top."""
    out = dict(store_values)
    for s in SETTINGS:
        given = getattr(args, s.key, None)
        if given is not None:
            out[s.key] = given
    return out
