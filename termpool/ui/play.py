"""`termpool play` (and `termpool` alone): options -> the app on a terminal or headless."""

from __future__ import annotations

import argparse
import json
import os
import sys

MODES = ("8ball", "9ball", "practice")
OPPONENTS = ("cpu", "human")
TABLES = ("7ft", "8ft", "9ft")
COLORS = ("auto", "truecolor", "256", "16", "mono")
INPUTS = ("auto", "kitty", "repeat", "classic")
LEVELS = ("easy", "normal", "hard")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--mode", choices=MODES, help="skip the menu and play this game")
    p.add_argument("--opponent", choices=OPPONENTS, default="cpu",
                   help="the computer or a second player on the same keyboard (default cpu)")
    p.add_argument("--table", choices=TABLES, default="9ft", help="table size (default 9ft)")
    p.add_argument("--colors", choices=COLORS, default="auto",
                   help="colour depth (default: from the terminal; NO_COLOR gives mono)")
    p.add_argument("--frames", type=int, default=1, help="play a match to N frames (default 1)")
    p.add_argument("--seed", type=int, default=0, help="racks and the computer's choices")
    p.add_argument("--level", choices=LEVELS, default="normal", help="the computer's skill")
    p.add_argument("--theme", choices=("standard", "classic"), default="standard",
                   help="ball colours: numbered solids and stripes, or reds and yellows")
    p.add_argument("--three-foul", action="store_true",
                   help="9-ball: three fouls in a row lose the frame")
    p.add_argument("--eight-break", choices=("respot", "rerack"), default="respot",
                   help="8-ball: the 8 pocketed on the break is re-spotted (default) or the "
                        "balls are re-racked for the same breaker")
    p.add_argument("--no-aid", action="store_true", help="start with the aim line off (G)")
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
                   help="write the match record (JSON, for `termpool replay`) to FILE at the end")


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

    if args.frames < 1:
        raise PlayError("--frames: must be at least 1")
    return Options(mode=args.mode, opponent=args.opponent, table=args.table, colors=args.colors,
                   frames=args.frames, seed=args.seed, level=args.level, aid=not args.no_aid,
                   bell=args.bell, theme=args.theme, three_foul=args.three_foul,
                   eight_break=args.eight_break)


def _keymap(path: str | None):
    from termpool.ui.controls import load_keymap

    try:
        return load_keymap(path)
    except (OSError, ValueError) as e:
        raise PlayError(str(e)) from None


def _write_record(app, path: str | None) -> None:
    match = app.record()
    if not path or match is None:
        return
    text = json.dumps(match.to_json(), indent=1) + "\n"
    if path == "-":
        sys.stdout.write(text)
    else:
        with open(path, "w") as f:
            f.write(text)


def run(args: argparse.Namespace) -> int:
    """Play; returns the exit status. Raises PlayError for bad options (one line, status 2)."""
    opts = _options(args)
    if not args.headless:
        for flag, val in (("--size", args.size), ("--keys", args.keys)):
            if val is not None:
                raise PlayError(f"{flag}: only with --headless (a terminal has its own size "
                                "and keys)")
    if args.headless:
        return _headless(args, opts, _keymap(args.keymap))
    if not (os.isatty(sys.stdin.fileno()) and os.isatty(sys.stdout.fileno())):
        from termpool.ui.term import no_tty_message

        sys.stderr.write(no_tty_message() + "\n")
        return 2
    keymap = _keymap(args.keymap)
    from termpool.ui import term
    from termpool.ui.app import App

    mode = {"kitty": "release"}.get(args.input, args.input)
    app = App(opts, keymap, "repeat" if mode == "auto" else mode)
    rc = term.run(app, app.depth, kitty=args.input in ("auto", "kitty"),
                  set_input_mode=app.set_input_mode if mode == "auto" else None,
                  mouse=not args.no_mouse)
    _write_record(app, args.record)
    return rc


def _headless(args: argparse.Namespace, opts, keymap) -> int:
    from termpool.ui.app import App
    from termpool.ui.headless import play
    from termpool.ui.keys import legacy_events, parse_script

    cols, rows = _size(args.size or "100x32")
    if not args.keys:
        raise PlayError("--headless needs --keys FILE (a key script; '-' reads stdin)")
    try:
        text = sys.stdin.read() if args.keys == "-" else open(args.keys).read()
    except OSError as e:
        raise PlayError(f"--keys: cannot read '{args.keys}': {e.strerror}") from None
    try:
        events = parse_script(text)
    except ValueError as e:
        raise PlayError(f"--keys: {e}") from None
    mode = {"auto": "release", "kitty": "release"}.get(args.input, args.input)
    if mode != "release":  # without the kitty protocol a terminal never reports releases
        events = legacy_events(events)
    app = App(opts, keymap, mode)
    screen = play(app, events, cols, rows)
    sys.stdout.write(screen + "\n")
    _write_record(app, args.record)
    return 0
