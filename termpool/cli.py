"""Command line: `termpool` (or `termpool play`) plays; `termpool sim SCENE` runs a scene and
prints JSON; `termpool bench` benchmarks; `termpool replay FILE` re-simulates a saved match and
checks it bit for bit (`--watch`: plays it on screen); `termpool rules` prints the rules;
`termpool stats` sums up the history of play; `termpool selfplay` plays the computer against itself.

Kept light: numpy, the scene loader and the engine are imported only inside the handlers.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Callable, Collection
from typing import Any

from termpool.command import Exit, Parser, one_blas_thread
from termpool.files import KEEP_RECORDS
from termpool.physics.results import DT, DT_RANGE, sim_result
from termpool.text import PROG, say

METHODS = ("fixed", "event")


def _fail(message: str) -> int:
    say(message)
    return 2


# What `sim` may be asked for: a step a replay would take (DT_RANGE), an hour of play at most,
# sampled at up to 1 kHz (beyond these a run only costs unbounded time or output).
MAX_DURATION = 3600.0  # s
MAX_SAMPLE_HZ = 1000.0


def _positive(what: str, lo: float = 0.0, hi: float = math.inf):
    def parse(text: str) -> float:
        try:
            val = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not a number: '{text[:24]}'") from None
        if not math.isfinite(val) or val <= 0:
            raise argparse.ArgumentTypeError(f"must be positive and finite, not '{text[:24]}'")
        if not lo <= val <= hi:
            span = f"above 0 and at most {hi:g}" if lo == 0 else f"from {lo:g} to {hi:g}"
            raise argparse.ArgumentTypeError(f"must be {span}, not {val:g}")
        return val

    parse.__name__ = what
    return parse


def bundled_example(name: str = "break.json") -> str:
    """Path of an example scene shipped inside the package."""
    from importlib.resources import files

    return str(files("termpool").joinpath("examples", name))


def _sim_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("scene", metavar="SCENE", help="scene file (JSON), or - for stdin")
    p.add_argument(
        "--dt",
        type=_positive("--dt", *DT_RANGE),
        default=DT,
        help="fixed time step in seconds (default 1/60; ignored by --method event)",
    )
    p.add_argument(
        "--duration",
        type=_positive("--duration", hi=MAX_DURATION),
        default=None,
        help="stop after this many simulated seconds (default: run until all balls are at rest)",
    )
    p.add_argument(
        "--method",
        choices=METHODS,
        default="fixed",
        help="fixed: batched fixed-step engine (default); event: event-to-event reference driver",
    )
    p.add_argument(
        "--sample-hz",
        type=_positive("--sample-hz", hi=MAX_SAMPLE_HZ),
        default=None,
        metavar="N",
        help="also output ball positions sampled N times per simulated second",
    )


def _play_arguments(p: argparse.ArgumentParser) -> None:
    from termpool.ui.play import add_arguments

    add_arguments(p)


def _replay_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", metavar="FILE", help="replay file (JSON), or - for stdin")
    p.add_argument("--json", action="store_true", help="print the per-shot results as JSON")
    p.add_argument("--watch", action="store_true",
                   help="play the match on screen as it was played (Space pauses, ← → step "
                        "a shot, F ×4, H help, Q quits)")
    from termpool.ui.settings import BY_KEY

    p.add_argument("--colors", choices=BY_KEY["colors"].values,
                   default=None, help="--watch: colour depth (default: the settings', as play)")
    p.add_argument("--headless", action="store_true",
                   help="--watch without a terminal: play --keys on a virtual screen, print "
                        "the last screen")
    p.add_argument("--size", help="--headless: screen size (default 100x32)")
    p.add_argument("--keys", metavar="FILE", help="--headless: a file of keys to play ('-' for "
                   "stdin), such as: wait 5 right space")


def _rules_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("game", nargs="?", choices=("8ball", "9ball", "practice"),
                   help="the game (default: all)")


def _stats_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--json", action="store_true", help="print the same figures as JSON")


def _serve_arguments(p: argparse.ArgumentParser) -> None:
    from termpool.serve import add_arguments

    add_arguments(p)


def _records_arguments(p: argparse.ArgumentParser) -> None:
    from termpool.ui.play import whole_number

    p.add_argument("--last", type=whole_number(1), default=None, metavar="N",
                   help="only the newest N (default: all that are kept)")


def _selfplay_arguments(p: argparse.ArgumentParser) -> None:
    from termpool.selfplay import add_arguments

    add_arguments(p)


# Each command: its one-line help, its description, and what adds its arguments (None: the
# command parses its own, as `bench` does).
_COMMANDS: dict[str, tuple[str, str, Callable[[argparse.ArgumentParser], None] | None]] = {
    "sim": (
        "simulate a scene and print the result as JSON",
        "Load a scene (JSON, see docs/scenes.md), run it until every ball is at rest (or for "
        "--duration simulated seconds) and print the final balls, the event log and, with "
        "--sample-hz, sampled positions as JSON on stdout. A scene with a `game` block "
        "also gets the referee's \"outcome\" of the shot.",
        _sim_arguments,
    ),
    "play": (
        "play pool in the terminal (the default command)",
        "Play pool in the terminal: 8-ball, 9-ball or practice, against the "
        "computer or a second player. --headless plays a key script on a virtual screen.",
        _play_arguments,
    ),
    "replay": (
        "watch a saved match again (--watch), or check that it replays identically",
        "Re-simulate every shot of a replay file (a saved match, see docs/rules.md) from its "
        "scene and shot parameters and check that the events, the final balls and the "
        "referee's outcome are identical, floats bit for bit. Exit 0 when every shot "
        "matches, 1 when any differs, 2 for a malformed file.",
        _replay_arguments,
    ),
    "rules": (
        "print the rules of 8-ball, 9-ball or practice (the page H shows in the game)",
        "Print the rules the referee plays by, in plain words: the page the "
        "game's help (H) shows. Without a game, all three.",
        _rules_arguments,
    ),
    "stats": (
        "the history of play: totals, per opponent, the last 20 matches",
        "Sum up the history of play (one line per player per match, in the data directory: "
        "$XDG_DATA_HOME/termpool/history.jsonl, else ~/.local/share/termpool/): the totals, "
        "the totals per opponent (the computer's level, a second player, practice), a chart "
        "of the pot rate and the last 20 matches, as the menu's Stats screen shows them. "
        "Corrupt lines are skipped with one line of warning.",
        _stats_arguments,
    ),
    "records": (
        "list the matches kept for `termpool replay` (the newest first)",
        "List the records of the matches played, newest first: each match is kept in the "
        "data directory's records/ folder ($XDG_DATA_HOME/termpool/records/, else "
        f"~/.local/share/termpool/records/), written after every shot; the newest {KEEP_RECORDS} "
        "are kept. `termpool replay FILE --watch` shows one again. `termpool play --no-record` "
        "(or the setting Keep records) keeps none.",
        _records_arguments,
    ),
    "selfplay": (
        "play the computer against itself and print how each level played",
        "Play N games between two levels of the computer (the break alternating) and "
        "print each level's wins, pot rate, fouls, break-and-run rate, safeties and "
        "decision times (see docs/ai.md). Deterministic for a --seed, whatever --jobs. "
        "Ctrl-C prints the figures of the games finished so far.",
        _selfplay_arguments,
    ),
    "serve": (
        "let people play over SSH: each connection gets the game at its own size",
        "Listen for SSH connections (needs asyncssh: pip install 'termpool[ssh]'). Whoever "
        "connects with `ssh -t -p PORT NAME@HOST` plays the whole game as NAME, with their "
        "own settings, history and records (under DIR/players/NAME). Without "
        "--authorized-keys anyone who can reach the port may play. SIGINT, SIGTERM or "
        "SIGHUP stop it, and every game saves on its way out. See docs/serve.md.",
        _serve_arguments,
    ),
    "bench": ("benchmark the physics engine (see `termpool bench --help`)", "", None),
}


def _parser(commands: Collection[str] | None = None) -> Parser:
    """The command line's parser: with `commands`, those commands only, with their
    arguments; else (None or empty) every command listed, with their arguments only for
    None, since the game's bring in the UI: `termpool sim` imports no more than it needs.
    The closing hint (the bundled example's path) is for the help without a command."""
    every = commands is None
    p = Parser(
        prog=PROG,
        description="Pool in the terminal: 8-ball, 9-ball and practice, against the computer "
                    "or a friend at the same keyboard.",
        epilog=None if commands else (
            "With no arguments, termpool starts the game (the same as `termpool play`). "
            "Every match is kept in the data directory's records/: `termpool records` "
            "lists them, `termpool replay FILE --watch` shows one again on screen "
            "(`termpool play --record match.json` keeps them in files of your choosing). "
            "Without a terminal, try "
            "`termpool sim` on the bundled example break scene: termpool sim "
            + bundled_example() + "."
        ),
    )
    from termpool import __version__

    p.add_argument("--version", action="version", version=f"{PROG} {__version__}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    # A command given is the only one built: each parser costs argparse's message lookups
    # (gettext searches the locale directories every time), a fifth of `sim`'s own start-up.
    listed = {k: _COMMANDS[k] for k in commands} if commands else _COMMANDS
    for name, (help_, description, add) in listed.items():
        if add is None:
            sub.add_parser(name, help=help_, add_help=False)
            continue
        c = sub.add_parser(name, help=help_, description=description)
        if every or name in commands:
            add(c)
    return p


# ---------------------------------------------------------------------------------- sim


def dump_json(result: dict) -> str:
    """JSON with one line per top-level scalar and per item of a top-level list. Raises
    ValueError naming a NaN or an infinity (files.to_json)."""
    from termpool.files import to_json

    def one(v: Any, where: str = "") -> str:
        return to_json(v, where, separators=(", ", ": "))

    parts = []
    for key, val in result.items():
        if isinstance(val, list) and val:
            items = ",\n".join("  " + one(v, f"{key}[{k}]") for k, v in enumerate(val))
            parts.append(f" {one(key)}: [\n{items}\n ]")
        else:
            parts.append(f" {one(key)}: {one(val, key)}")
    return "{\n" + ",\n".join(parts) + "\n}\n"


def _sim(args: argparse.Namespace) -> int:
    from termpool.scene import SceneError, load_scene

    try:
        scene = load_scene(args.scene)
        if scene.game is not None:  # the rules are imported only for a scene that has a game
            from termpool.rules.referee import check_game

            check_game(scene)
    except SceneError as e:
        return _fail(str(e))
    from termpool.physics.engine import Engine

    ph = scene.physics
    frictionless = [k for k in ("mu_slide", "mu_roll", "mu_spin") if getattr(ph, k) == 0]
    moving = bool(abs(scene.vel).any() or abs(scene.w).any())
    if args.duration is None and moving and frictionless:
        return _fail(f"physics.{frictionless[0]} is 0, so the balls never come to rest: "
                     "pass --duration")
    try:
        eng = Engine(
            scene.table,
            scene.physics,
            scene.pos,
            scene.vel,
            scene.w,
            scene.radius,
            scene.mass,
            record=True,
        )
    except ValueError as e:
        return _fail(str(e))
    from termpool.physics.engine import WorkLimit

    t0 = time.perf_counter()
    try:
        if args.method == "fixed":
            samples = eng.run(args.dt, duration=args.duration, sample_hz=args.sample_hz)
        else:
            samples = eng.run_events(duration=args.duration, sample_hz=args.sample_hz)
    except WorkLimit as e:
        return _fail(str(e))
    wall = time.perf_counter() - t0
    dt = args.dt if args.method == "fixed" else None
    samples = (samples or []) if args.sample_hz is not None else None
    result = sim_result(scene.ids, scene.table.hole_names, eng, samples, args.method, dt, wall)
    if scene.game is not None:
        from termpool.rules.referee import referee

        result["outcome"] = referee(scene.game, scene.ids, eng.log[0])
    try:
        text = dump_json(result)
    except ValueError as e:
        return _fail(f"sim: the result cannot be written: {e}")
    sys.stdout.write(text)
    sys.stdout.flush()
    return 0


# ------------------------------------------------------------------------------- replay


def _replay(args: argparse.Namespace) -> int:
    from termpool.game.record import ReplayError, read_replays, replay

    if args.watch:
        if args.json:
            return _fail("--json: not with --watch")
        from termpool.ui.watch import WatchError, run

        try:
            return run(args)
        except WatchError as e:
            return _fail(f"replay: {e}")
    given = [f for f, v in (("--headless", args.headless), ("--size", args.size),
                            ("--keys", args.keys), ("--colors", args.colors)) if v]
    if given:
        return _fail(f"{given[0]}: only with --watch")

    from termpool.rules import words

    try:
        matches = read_replays(args.file)
        # The verdicts in the players' names on screen, as the record says them in JSON
        # (the names are checked by read_replays).
        names = [m.get("match", {}).get("players") for m in matches]
        checked = [replay(m, words.voice(p) if p and not args.json else words.RECORD)
                   for m, p in zip(matches, names, strict=True)]
    except ReplayError as e:
        return _fail(str(e))
    from termpool.text import shown

    bad = sum(not s["ok"] for shots in checked for s in shots)
    if args.json:
        from termpool.files import to_json

        one = [{"identical": all(s["ok"] for s in shots), "shots": shots} for shots in checked]
        try:
            text = to_json(one[0] if len(one) == 1 else
                           {"identical": not bad, "matches": one}, indent=1)
        except ValueError as e:
            return _fail(f"replay: the result cannot be written: {e}")
        sys.stdout.write(text + "\n")
    else:
        for k, (shots, players) in enumerate(zip(checked, names, strict=True), 1):
            if len(checked) > 1:
                mode = matches[k - 1].get("match", {}).get("mode")
                mode = words.MODE_NAMES.get(mode, "") if isinstance(mode, str) else ""
                who = "" if not players or players[0] == players[1] else " v ".join(players)
                said = " · ".join(x for x in (mode, who) if x)
                sys.stdout.write(shown(f"match {k} of {len(checked)}"
                                       + (f" ({said})" if said else "") + ":") + "\n")
            _replay_lines(shots, players)
        if len(checked) > 1:
            n = sum(map(len, checked))
            verdict = "all identical" if not bad else f"{bad} differ"
            sys.stdout.write(f"{len(checked)} matches, {n} shots: {verdict}\n")
        if len(checked) == 1 and args.file != "-" and sys.stdout.isatty():
            # Someone at a terminal may have meant to watch it: say how, once.
            import shlex

            sys.stdout.write(shown(f"to watch it: termpool replay {shlex.quote(args.file)} "
                                   "--watch") + "\n")
    sys.stdout.flush()
    return 1 if bad else 0


def _replay_lines(shots: list[dict], players: list[str] | None) -> None:
    """One match's shots as `termpool replay` says them, and its verdict."""
    from termpool.text import shown

    for s in shots:
        who = (players[s["player"]] if players and s["player"] in (0, 1)
               else f"player {s['player']}")
        head = f"shot {s['n']} (frame {s['frame']}, {who}): "
        if s["ok"]:
            sys.stdout.write(shown(f"{head}identical, {s['events']} events; {s['reason']}")
                             + "\n")
        else:
            sys.stdout.write(shown(f"{head}DIFFERS: {'; '.join(s['differences'])}") + "\n")
    n = len(shots)
    bad = sum(not s["ok"] for s in shots)
    verdict = "all identical" if not bad else f"{bad} differ"
    sys.stdout.write(f"{n} {'shot' if n == 1 else 'shots'}: {verdict}\n")


# -------------------------------------------------------------------------------- rules


def _rules(args: argparse.Namespace) -> int:
    from termpool.rules.words import MODE_NAMES, rules_text

    pages = [rules_text(m) for m in ([args.game] if args.game else MODE_NAMES)]
    sys.stdout.write("\n\n".join("\n".join(p) for p in pages) + "\n")
    sys.stdout.flush()
    return 0


# -------------------------------------------------------------------------------- stats


def _stats(args: argparse.Namespace) -> int:
    from termpool.game.history import history_path, read_history, summary
    from termpool.text import shown
    from termpool.ui.stats import stats_lines

    path = history_path()
    lines, warning, readable = read_history(path)
    if warning:
        say(f"warning: {warning}")
    figures = summary(lines)
    if args.json:
        from termpool.files import to_json

        try:
            text = to_json({"file": str(path), **figures}, indent=1) + "\n"
        except ValueError as e:
            return _fail(f"stats: the figures cannot be written: {e}")
    else:
        text = "".join(shown(line) + "\n" for line in stats_lines(figures))
    sys.stdout.write(text)
    sys.stdout.flush()
    return 0 if readable else 1


# ------------------------------------------------------------------------------ records


def _outline(path) -> str:
    """Who played a kept match and how it stands ("ann v bob · ann won 2-1", "You · 12
    shots"), or why that cannot be said."""
    from termpool.game.record import ReplayError, read_replay

    try:
        data = read_replay(path)
        match, current = data["match"], data.get("current") or {}
        names, shots = match["players"], len(data["shots"])
        if match.get("mode") == "practice":
            return f"{names[0]} · {shots} {'shot' if shots == 1 else 'shots'}"
        a, b = current.get("scores") or (0, 0)
        winner = current.get("winner")
        how = (f"{names[winner]} won {max(a, b)}-{min(a, b)}" if winner in (0, 1)
               else f"unfinished {a}-{b}")
        return f"{names[0]} v {names[1]} · {how}"
    except (ReplayError, KeyError, TypeError, ValueError, IndexError):
        return "(cannot be read)"


def _kept_name(path) -> tuple[str, str, int, str]:
    """A kept match's name (`files.KEPT_NAME`) read: the day and time it began, its number
    in that second (0 for the first) and its mode."""
    day, clock, *rest = path.name.split(".")[0].split("-")
    return day, clock, int(rest[0]) if len(rest) > 1 else 0, rest[-1]


def _records(args: argparse.Namespace) -> int:
    from termpool.files import kept_records, records_dir
    from termpool.text import shown

    folder = records_dir()
    # Newest first by when each began, the time the list shows (a match left open and
    # written last may have begun before one played through since).
    kept = sorted(kept_records(folder), key=lambda p: _kept_name(p)[:3], reverse=True)
    if not kept:
        sys.stdout.write(f"no match is kept in {shown(folder)} yet\n")
        return 0
    shown_ = kept[:args.last] if args.last else kept
    lines = [f"{len(kept)} {'match' if len(kept) == 1 else 'matches'} kept in "
             f"{shown(folder)} (newest first):"]
    for p in shown_:
        day, clock, _, mode = _kept_name(p)
        when = f"{day[:4]}-{day[4:6]}-{day[6:]} {clock[:2]}:{clock[2:4]}:{clock[4:]}"
        try:
            size = f"{p.stat().st_size / 1024:.0f} KiB"
        except OSError:
            size = "?"
        lines.append(f"  {when}  {mode:<8} {shown(_outline(p)):<34} {size:>8}  {shown(p)}")
    lines.append("watch one with: termpool replay FILE --watch")
    sys.stdout.write("\n".join(lines) + "\n")
    sys.stdout.flush()
    return 0


# -------------------------------------------------------------------------------- bench


def _bench(argv: list[str]) -> int:
    """The benchmarks are the `bench` package beside `termpool` in a source checkout (the
    README's editable install); the installed game does not carry them."""
    import importlib
    import os

    import termpool

    checkout = os.path.dirname(os.path.dirname(os.path.abspath(termpool.__file__)))
    if not os.path.isfile(os.path.join(checkout, "bench", "__init__.py")):
        return _fail("bench: the benchmarks are not installed with the game; run them from a "
                     "source checkout (pip install -e .)")
    if checkout not in sys.path:
        sys.path.insert(0, checkout)
    bench = importlib.import_module("bench")
    rc = bench.main(argv)
    return rc if isinstance(rc, int) else 0


# --------------------------------------------------------------------------------- play


def _play(args: argparse.Namespace) -> int:
    from termpool.physics.engine import WorkLimit
    from termpool.ui.play import PlayError, run

    try:
        return run(args)
    except PlayError as e:
        return _fail(f"play: {e}")
    except WorkLimit as e:  # the record is saved on the way out
        return _fail(f"play: {e}")


# ----------------------------------------------------------------------------- selfplay


def _selfplay(args: argparse.Namespace) -> int:
    from termpool.selfplay import SelfplayError, run

    try:
        return run(args)
    except SelfplayError as e:
        return _fail(str(e))


# --------------------------------------------------------------------------------- main


def main(argv: list[str] | None = None) -> int:
    """Entry point of the `termpool` command; returns the exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    one_blas_thread()
    try:
        if argv and argv[0] == "bench":
            return _bench(argv[1:])
        if not argv or (argv[0].startswith("-") and argv[0] not in ("-h", "--help",
                                                                      "--version")):
            argv = ["play", *argv]  # play is the default command: `termpool --colors 16`
        args = _parser([argv[0]] if argv[0] in _COMMANDS else []).parse_args(argv)
        if args.command == "sim":
            return _sim(args)
        if args.command == "play":
            return _play(args)
        if args.command == "replay":
            return _replay(args)
        if args.command == "rules":
            return _rules(args)
        if args.command == "stats":
            return _stats(args)
        if args.command == "records":
            return _records(args)
        if args.command == "selfplay":
            return _selfplay(args)
        if args.command == "serve":
            from termpool.serve import run as serve

            return serve(args)
        return _fail("missing command (try termpool --help)")
    except Exit as e:
        return e.code
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        # The reader went away (e.g. `| head`); silence the flush at exit.
        import os

        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 1
