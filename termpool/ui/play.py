"""`termpool play` (and `termpool` alone): options -> the app on a terminal or headless."""

from __future__ import annotations

import argparse
import os
import sys

MODES = ("8ball", "9ball", "practice")
OPPONENTS = ("cpu", "human")
INPUTS = ("auto", "kitty", "repeat", "classic")
MAX_SEED = 2 ** 64 - 1  # a seed is saved in the record, and read back


def whole_number(lo: int, hi: int | None = None):
    """An argparse type: a whole number from lo to hi, or from lo up with no hi (the text is
    not echoed whole)."""
    most = len(str(hi)) if hi is not None else 4000  # (int() reads no more than 4300 digits)

    def parse(text: str) -> int:
        digits = text.strip().removeprefix("-")
        if digits.isascii() and digits.isdigit() and len(digits) <= most:
            val = int(text)
            if lo <= val and (hi is None or val <= hi):
                return val
        short = text if len(text) <= 24 else text[:24] + "..."
        span = f"from {lo} up" if hi is None else f"from {lo} to {hi}"
        raise argparse.ArgumentTypeError(f"must be a whole number {span}, not '{short}'")

    return parse


def add_arguments(p: argparse.ArgumentParser) -> None:
    from termpool.ui.settings import add_flags

    p.add_argument("--mode", choices=MODES, help="skip the menu and play this game")
    p.add_argument("--opponent", choices=OPPONENTS, default="cpu",
                   help="the computer or a second player on the same keyboard (default cpu)")
    p.add_argument("--seed", type=whole_number(0, MAX_SEED), default=None,
                   help=f"racks and the computer's choices (0 to {MAX_SEED}); without it "
                        "every game deals a new rack (its seed is in the --record)")
    add_flags(p)  # the settings: each flag overrides the settings file for this run
    p.add_argument("--no-aid", action="store_true", help="start with the aim aid off (--aid off)")
    p.add_argument("--input", choices=INPUTS, default="auto",
                   help="how the terminal tells a held Space: kitty (key releases), repeat "
                        "(inferred from auto-repeat); classic: no holds at all, so the "
                        "swinging meter (--power meter)")
    p.add_argument("--no-mouse", action="store_true",
                   help="leave the mouse to the terminal (by default a click or drag aims)")
    p.add_argument("--keymap", metavar="FILE", help="key bindings, a line 'action = key, key' "
                   "each, e.g. 'shoot = space, enter' (default "
                   "$XDG_CONFIG_HOME/termpool/keys.conf; the actions: docs/play.md)")
    p.add_argument("--headless", action="store_true",
                   help="no terminal: play --keys on a virtual screen, print the final screen "
                   "(to stderr with --record -)")
    p.add_argument("--size", help="headless screen size (default 100x32)")
    p.add_argument("--keys", metavar="FILE", help="headless: a file of keys to play ('-' for "
                   "stdin), such as: right*5 wait 0.2 space-hold 1.5")
    p.add_argument("--record", metavar="FILE",
                   help="keep every match played (JSON, for `termpool replay`) in FILE "
                        "instead of the data directory's records/: the first in FILE, the "
                        "next in FILE-2, FILE-3 ..., each written after every shot and on "
                        "every way out ('-': all to stdout at the end)")
    p.add_argument("--no-record", dest="records", action="store_false", default=None,
                   help="keep no record of this run's matches (the same as --no-records; by "
                        "default each is kept in the data directory's records/)")
    p.add_argument("--force", action="store_true",
                   help="let --record replace an existing file (without it, one is refused)")


class PlayError(ValueError):
    pass


def _settings(args: argparse.Namespace):
    """The settings file (its warnings said, one line each) and this run's values: the
    file's, with the flags on top."""
    from termpool.text import say
    from termpool.ui.settings import from_flags, load_settings

    store = load_settings()
    for warning in store.warnings:  # said again on the game's first screen (warn_on_screen)
        say(f"warning: {warning}")
    values = from_flags(store.saved, args)
    if args.no_aid:
        values["aid"] = "off"
    if args.input == "classic" and args.power is None:  # no holds: the meter
        values["power"] = "meter"
    return store, values


def _options(args: argparse.Namespace, values: dict):
    from termpool.ui.state import Options

    return Options(mode=args.mode, opponent=args.opponent, seed=args.seed, **values)


def _keymap(path: str | None):
    """The key map, and the default file's warning if it has one (said now, and on the
    game's first screen)."""
    from termpool.text import say
    from termpool.ui.controls import load_keymap

    warnings: list[str] = []

    def warn(message: str) -> None:
        say(f"warning: {message}")
        warnings.append(message)

    try:
        return load_keymap(path, warn=warn), warnings
    except ValueError as e:
        raise PlayError(str(e)) from None


def _check_record(args: argparse.Namespace) -> None:
    """Before play: the --record file can be written (one line, status 2, if not)."""
    from termpool.files import write_problem

    if args.record == "":
        raise PlayError("--record: needs a file name ('-' for stdout)")
    if args.record and args.record != "-":
        why = write_problem(args.record, force=args.force)
        if why:
            raise PlayError(f"--record: cannot write '{args.record}': {why}")


def run(args: argparse.Namespace) -> int:
    """Play; returns the exit status. Raises PlayError for bad options (one line, status 2).
    The records (the data directory's records/, or --record) are saved after every shot and
    on every way out: the end, Q, Ctrl-C, a signal, a crash."""
    store, values = _settings(args)
    opts = _options(args, values)
    if not args.headless:
        for flag, val in (("--size", args.size), ("--keys", args.keys)):
            if val is not None:
                raise PlayError(f"{flag}: only with --headless (a terminal has its own size "
                                "and keys)")
    _check_record(args)
    from termpool.files import records_dir
    from termpool.game.history import Recorder
    from termpool.ui.records import Records

    records = Records(args.record, args.force, folder=records_dir())
    files = {"prefs": store, "history": Recorder(), "records": records}
    if args.headless:
        keymap, key_warnings = _keymap(args.keymap)
        app, play = _headless(args, opts, keymap, files)
    else:
        if not (os.isatty(sys.stdin.fileno()) and os.isatty(sys.stdout.fileno())):
            from termpool.ui.term import no_tty_message

            sys.stderr.write(no_tty_message() + "\n")
            return 2
        keymap, key_warnings = _keymap(args.keymap)
        app, play = _terminal(args, opts, keymap, files)
    warn_on_screen(app, store.warnings)
    warn_on_screen(app, key_warnings, "keys")
    try:
        rc = play()
    except BaseException:
        _leave(app, args)  # a crash keeps the match too
        raise
    saved = _leave(app, args)
    return rc or saved


def _leave(app, args: argparse.Namespace) -> int:
    """However the game ended: the match in play is saved (its record) and goes into the
    history, and what is left to say is said: where each match of the session went. Returns
    0, or 1 when a record could not go where asked."""
    from termpool.text import say
    from termpool.ui.term import signals_held

    with signals_held():
        lines, status = app.leave()  # a shot still rolling is played out first
    for line in lines:
        say(line)
    return status


def warn_on_screen(app, warnings: list[str], what: str = "settings") -> None:
    """A file's warnings (`what`: the settings, the keys), said before the game took the
    screen, shown on its first screen too (how many, and the first)."""
    from dataclasses import replace

    if warnings:
        n = len(warnings)
        head = f"{what}: " + (f"{n} warnings (all said after play), the first: " if n > 1
                              else "")
        line = (head + warnings[0], "foul")
        app.state = replace(app.state, message=(*app.state.message, line))


def _terminal(args: argparse.Namespace, opts, keymap, files: dict):
    from termpool.ui import term
    from termpool.ui.app import App
    from termpool.ui.link import Link
    from termpool.wire import lobby_address

    mode = {"kitty": "release"}.get(args.input, args.input)
    # Under `termpool serve`, the lobby: playing someone online.
    link = Link.open(lobby_address())
    app = App(opts, keymap, "repeat" if mode == "auto" else mode, **files, link=link)

    def play() -> int:
        return term.run(app, app.depth, kitty=args.input in ("auto", "kitty"),
                        set_input_mode=app.set_input_mode if mode == "auto" else None,
                        mouse=not args.no_mouse)

    return app, play


def _headless(args: argparse.Namespace, opts, keymap, files: dict):
    from termpool.files import FileError
    from termpool.ui.app import App
    from termpool.ui.headless import play as play_keys
    from termpool.ui.headless import screen_size
    from termpool.ui.keys import legacy_events, parse_script, read_script
    from termpool.ui.term import Stop, stoppable

    try:
        cols, rows = screen_size(args.size or "100x32")
    except ValueError as e:
        raise PlayError(str(e)) from None
    if not args.keys:
        raise PlayError("--headless needs --keys FILE (a key script; '-' reads stdin)")
    try:
        text = read_script(args.keys)
    except FileError as e:
        raise PlayError(f"--keys: {e}") from None
    try:
        events = parse_script(text)
    except ValueError as e:
        raise PlayError(f"--keys: {e}") from None
    mode = {"auto": "release", "kitty": "release"}.get(args.input, args.input)
    if mode != "release":  # without the kitty protocol a terminal never reports releases
        events = legacy_events(events)
    app = App(opts, keymap, mode, **files)

    def play() -> int:
        try:
            with stoppable():
                screen = play_keys(app, events, cols, rows)
        except KeyboardInterrupt:
            return 130
        except Stop as e:
            return 128 + e.signum
        # With --record - standard output carries the matches: the screen goes to stderr.
        (sys.stderr if args.record == "-" else sys.stdout).write(screen + "\n")
        return 0

    return app, play
