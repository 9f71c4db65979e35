"""`termpool play` (and `termpool` alone): options -> the app on a terminal or headless."""

from __future__ import annotations

import argparse
import json
import os
import signal
import sys
from contextlib import contextmanager

MODES = ("8ball", "9ball", "practice")
OPPONENTS = ("cpu", "human")
TABLES = ("7ft", "8ft", "9ft")
COLORS = ("auto", "truecolor", "256", "16", "mono")
INPUTS = ("auto", "kitty", "repeat", "classic")
LEVELS = ("easy", "normal", "hard", "pro")  # termpool.ai's levels (kept light: no numpy here)
MAX_SEED = 2 ** 64 - 1  # a seed is saved in the record, and read back
MAX_FRAMES = 1000


def _whole(lo: int, hi: int):
    """An argparse type: a whole number from lo to hi (the text is not echoed whole)."""
    def parse(text: str) -> int:
        digits = text.strip().removeprefix("-")
        if digits.isascii() and digits.isdigit() and len(digits) <= len(str(hi)):
            val = int(text)
            if lo <= val <= hi:
                return val
        short = text if len(text) <= 24 else text[:24] + "..."
        raise argparse.ArgumentTypeError(f"must be a whole number from {lo} to {hi}, "
                                         f"not '{short}'")

    return parse


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--mode", choices=MODES, help="skip the menu and play this game")
    p.add_argument("--opponent", choices=OPPONENTS, default="cpu",
                   help="the computer or a second player on the same keyboard (default cpu)")
    p.add_argument("--table", choices=TABLES, default="9ft", help="table size (default 9ft)")
    p.add_argument("--colors", choices=COLORS, default="auto",
                   help="colour depth (default: from the terminal; NO_COLOR gives mono)")
    p.add_argument("--frames", type=_whole(1, MAX_FRAMES), default=1,
                   help="play a match to N frames (default 1)")
    p.add_argument("--seed", type=_whole(0, MAX_SEED), default=None,
                   help=f"racks and the computer's choices (0 to {MAX_SEED}); without it "
                        "every game deals a new rack (its seed is in the --record)")
    p.add_argument("--level", choices=LEVELS, default="normal",
                   help="the computer's skill: easy (a beginner), normal (a club player), hard "
                        "(a strong amateur) or pro (default normal)")
    p.add_argument("--theme", choices=("standard", "classic"), default="standard",
                   help="ball colours: numbered solids and stripes, or reds and yellows")
    p.add_argument("--three-foul", action="store_true",
                   help="9-ball: three fouls in a row lose the frame")
    p.add_argument("--eight-break", choices=("respot", "rerack"), default="respot",
                   help="8-ball: the 8 pocketed on the break is re-spotted (default) or the "
                        "balls are re-racked for the same breaker")
    p.add_argument("--aid", choices=("full", "ghost", "off"), default="full",
                   help="the aim aid: every predicted path, the ghost ball only, or none (G "
                        "cycles them)")
    p.add_argument("--no-aid", action="store_true", help="start with the aim aid off (--aid off)")
    p.add_argument("--bell", action="store_true", help="ring the bell on a foul (N toggles)")
    p.add_argument("--input", choices=INPUTS, default="auto",
                   help="how Space charges: kitty (key releases), repeat (hold inferred from "
                        "auto-repeat), classic (press to start the meter, press to strike)")
    p.add_argument("--no-mouse", action="store_true",
                   help="leave the mouse to the terminal (by default a click or drag aims)")
    p.add_argument("--keymap", metavar="FILE", help="key bindings (default "
                   "$XDG_CONFIG_HOME/termpool/keys.conf)")
    p.add_argument("--headless", action="store_true",
                   help="no terminal: play --keys on a virtual screen, print the final screen")
    p.add_argument("--size", help="headless screen size (default 100x32)")
    p.add_argument("--keys", metavar="FILE", help="headless key script ('-' for stdin), e.g. "
                   "'right*5 wait 0.2 space-hold 1.5'")
    p.add_argument("--record", metavar="FILE",
                   help="write the match record (JSON, for `termpool replay`) to FILE at the "
                        "end, however the game ends ('-' for stdout)")
    p.add_argument("--force", action="store_true",
                   help="let --record replace an existing file (without it, one is refused)")


class PlayError(ValueError):
    pass


def _size(text: str) -> tuple[int, int]:
    try:
        c, r = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise PlayError(f"--size: must look like 100x32, not '{text}'") from None
    if c < 1 or r < 1 or c > 1000 or r > 1000:
        raise PlayError(f"--size: {text} is out of range")
    return c, r


def _options(args: argparse.Namespace):
    from termpool.ui.app import Options

    return Options(mode=args.mode, opponent=args.opponent, table=args.table, colors=args.colors,
                   frames=args.frames, seed=args.seed, level=args.level,
                   aid="off" if args.no_aid else args.aid,
                   bell=args.bell, theme=args.theme, three_foul=args.three_foul,
                   eight_break=args.eight_break)


def _keymap(path: str | None):
    from termpool.text import say
    from termpool.ui.controls import load_keymap

    try:
        return load_keymap(path, warn=lambda m: say(f"warning: {m}"))
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


def save_record(app, path: str | None, force: bool = False) -> int:
    """Write the match (--record) after play, however it ended; a shot still rolling is played
    out in simulation first. Says where the record went. Returns 0, or 1 when it could not go
    to `path` (it then goes to a new file in the data directory, if it can)."""
    from termpool.files import write_atomic, write_fallback, write_problem
    from termpool.text import say
    from termpool.ui.term import signals_held

    if not path:
        return 0
    with signals_held():
        match = app.record()
        for note in app.notes:
            say(note)
        if match is None:
            say("no match was played, so there is no record to save")
            return 0
        text = json.dumps(match.to_json(), indent=1) + "\n"
        n = len(match.history)
        what = f"{n} {'shot' if n == 1 else 'shots'}"
        if path == "-":
            sys.stdout.write(text)
            sys.stdout.flush()
            return 0
        existed = os.path.exists(path)
        why = write_problem(path, force=force)
        if why is None:
            try:
                write_atomic(path, text)
                replaced = "; it replaced the file that was there" if existed else ""
                say(f"record saved to {path} ({what}{replaced})")
                return 0
            except OSError as e:
                why = e.strerror or str(e)
        try:
            spare = write_fallback(text, "record")
        except OSError as e:
            say(f"cannot write the record to '{path}' ({why}) nor to the data directory "
                f"({e.strerror or e}): it is lost")
            return 1
        say(f"cannot write the record to '{path}' ({why}); it was saved to {spare} ({what})")
        return 1


@contextmanager
def _stoppable():
    """SIGTERM, SIGHUP and SIGQUIT end a headless run the way Ctrl-C does (an exception), so
    the record is still saved."""
    from termpool.ui.term import STOP_SIGNALS, Stop

    def stop(signum, frame):
        raise Stop(signum)

    old = {s: signal.signal(s, stop) for s in STOP_SIGNALS}
    try:
        yield
    finally:
        for sig, handler in old.items():
            signal.signal(sig, handler)


def run(args: argparse.Namespace) -> int:
    """Play; returns the exit status. Raises PlayError for bad options (one line, status 2).
    The record (--record) is saved on every way out: the end, Q, Ctrl-C, a signal, a crash."""
    opts = _options(args)
    if not args.headless:
        for flag, val in (("--size", args.size), ("--keys", args.keys)):
            if val is not None:
                raise PlayError(f"{flag}: only with --headless (a terminal has its own size "
                                "and keys)")
    _check_record(args)
    if args.headless:
        app, play = _headless(args, opts, _keymap(args.keymap))
    else:
        if not (os.isatty(sys.stdin.fileno()) and os.isatty(sys.stdout.fileno())):
            from termpool.ui.term import no_tty_message

            sys.stderr.write(no_tty_message() + "\n")
            return 2
        app, play = _terminal(args, opts, _keymap(args.keymap))
    try:
        rc = play()
    except BaseException:
        save_record(app, args.record, args.force)  # a crash keeps the match too
        raise
    saved = save_record(app, args.record, args.force)
    return rc or saved


def _terminal(args: argparse.Namespace, opts, keymap):
    from termpool.ui import term
    from termpool.ui.app import App

    mode = {"kitty": "release"}.get(args.input, args.input)
    app = App(opts, keymap, "repeat" if mode == "auto" else mode)

    def play() -> int:
        return term.run(app, app.depth, kitty=args.input in ("auto", "kitty"),
                        set_input_mode=app.set_input_mode if mode == "auto" else None,
                        mouse=not args.no_mouse)

    return app, play


def _headless(args: argparse.Namespace, opts, keymap):
    from termpool.files import MAX_SCRIPT_BYTES, FileError, read_text
    from termpool.ui.app import App
    from termpool.ui.headless import play as play_keys
    from termpool.ui.keys import legacy_events, parse_script
    from termpool.ui.term import Stop

    cols, rows = _size(args.size or "100x32")
    if not args.keys:
        raise PlayError("--headless needs --keys FILE (a key script; '-' reads stdin)")
    try:
        text = read_text(args.keys, MAX_SCRIPT_BYTES, "key script")
    except FileError as e:
        raise PlayError(f"--keys: {e}") from None
    try:
        events = parse_script(text)
    except ValueError as e:
        raise PlayError(f"--keys: {e}") from None
    mode = {"auto": "release", "kitty": "release"}.get(args.input, args.input)
    if mode != "release":  # without the kitty protocol a terminal never reports releases
        events = legacy_events(events)
    app = App(opts, keymap, mode)

    def play() -> int:
        try:
            with _stoppable():
                screen = play_keys(app, events, cols, rows)
        except KeyboardInterrupt:
            return 130
        except Stop as e:
            return 128 + e.signum
        sys.stdout.write(screen + "\n")
        return 0

    return app, play
