"""`termpool selfplay`: games of the computer against itself, and how each level played.

Plays N games between two levels (`games.play_game`), the break alternating
(the first level breaks the even games), in parallel processes with --jobs, and prints the
figures (`games.figures`) as a table or JSON. Every game's seed comes from
the run's seed and the game's number, so the figures are the same for a seed whatever the
number of processes (the wall times aside). A progress bar goes to stderr; Ctrl-C (or SIGTERM,
SIGHUP, SIGQUIT) stops the run and prints the figures of the games finished so far (exit
status 128 + the signal); --record-dir keeps every game, the unfinished ones too, as a replay
file.
"""

from __future__ import annotations

import argparse
import os
import queue
import secrets
import signal
import sys
import time
import traceback
from pathlib import Path
from typing import Any

MODES = ("8ball", "9ball")
MAX_GAMES = 100_000


def add_arguments(p: argparse.ArgumentParser) -> None:
    from termpool.ui.play import MAX_SEED, whole_number
    from termpool.ui.settings import BY_KEY

    p.add_argument("--games", type=whole_number(1, MAX_GAMES), default=10, metavar="N",
                   help="games to play (default 10)")
    p.add_argument("--mode", choices=MODES, default="8ball", help="the game (default 8ball)")
    p.add_argument("--levels", default="normal,normal", metavar="A,B",
                   help="the two levels, e.g. hard,normal (default normal,normal)")
    p.add_argument("--seed", type=whole_number(0, MAX_SEED), default=None, metavar="S",
                   help="racks and every choice; without it a new seed, which is printed")
    p.add_argument("--table", choices=BY_KEY["table"].values, default="9ft",
                   help="table size (default 9ft)")
    p.add_argument("--json", action="store_true", help="print the figures as JSON")
    p.add_argument("--record-dir", metavar="DIR",
                   help="save every game as a replay file in DIR (created if need be)")
    p.add_argument("--force", action="store_true",
                   help="let --record-dir replace game files already there")
    p.add_argument("--jobs", type=whole_number(1, 256), default=None, metavar="N",
                   help="games played at once, in separate processes (default: one per core)")
    p.add_argument("--candidates", type=whole_number(8, 4096), default=256, metavar="N",
                   help="the computer's candidate budget per shot (default 256, as in play)")
    p.add_argument("--max-shots", type=whole_number(1, 10_000), default=None, metavar="N",
                   help="stop a game without a winner after this many shots (default 300)")


class SelfplayError(ValueError):
    """Bad settings (one line, exit status 2)."""


def _levels(text: str) -> tuple[str, str]:
    from termpool.ai import LEVELS

    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 2:
        raise SelfplayError(f"--levels: must be two levels, e.g. hard,normal, not "
                            f"'{text[:40]}'")
    for p in parts:
        if p not in LEVELS:
            raise SelfplayError(f"--levels: '{p[:24]}' is not a level (use "
                                f"{', '.join(LEVELS)})")
    return parts[0], parts[1]


def _record_paths(args: argparse.Namespace) -> list[Path] | None:
    """The game files of --record-dir, checked before play (SelfplayError if they cannot be
    written)."""
    from termpool.files import write_problem

    if args.record_dir is None:
        return None
    if args.record_dir == "":
        raise SelfplayError("--record-dir: needs a directory")
    d = Path(args.record_dir)
    try:
        d.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise SelfplayError(f"--record-dir: cannot make '{d}': {e.strerror or e}") from None
    width = max(3, len(str(args.games)))
    paths = [d / f"game-{k + 1:0{width}d}.json" for k in range(args.games)]
    taken = [p for p in paths if p.exists()]
    if taken and not args.force:
        raise SelfplayError(f"--record-dir: {taken[0]} exists (pass --force to replace the "
                            "game files, or use another directory)")
    why = write_problem(paths[0], force=True)
    if why:
        raise SelfplayError(f"--record-dir: cannot write '{paths[0]}': {why}")
    return paths


def settings(args: argparse.Namespace) -> dict:
    """What every game of the run shares, checked (SelfplayError)."""
    from termpool.selfplay.games import MAX_SHOTS

    return {"levels": _levels(args.levels), "mode": args.mode, "table": args.table,
            "seed": secrets.randbits(63) if args.seed is None else args.seed,
            "candidates": args.candidates,
            "max_shots": MAX_SHOTS if args.max_shots is None else args.max_shots,
            "records": _record_paths(args)}


def play_index(st: dict, index: int, stop=lambda: False) -> dict:
    """Game `index` of the run: the first level breaks the even games, the second the odd."""
    from termpool.selfplay.games import game_seed, play_game

    a, b = st["levels"]
    return play_game((a, b) if index % 2 == 0 else (b, a), mode=st["mode"], table=st["table"],
                     seed=game_seed(st["seed"], index), candidates=st["candidates"],
                     max_shots=st["max_shots"],
                     record=None if st["records"] is None else st["records"][index], stop=stop)


# ------------------------------------------------------------------------------ progress


class Progress:
    """A bar on stderr: redrawn in place on a terminal, a line per game otherwise (a log)."""

    WIDTH = 24

    def __init__(self, total: int, stream=None) -> None:
        self.total, self.stream = total, stream or sys.stderr
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self.t0 = time.monotonic()

    def show(self, done: int) -> None:
        fill = round(self.WIDTH * done / self.total)
        line = (f"selfplay [{'#' * fill}{'.' * (self.WIDTH - fill)}] {done}/{self.total} "
                f"games, {time.monotonic() - self.t0:.0f} s")
        try:
            self.stream.write(f"\r{line}" if self.tty else f"{line}\n")
            self.stream.flush()
        except (OSError, ValueError):
            pass

    def close(self) -> None:
        if self.tty:
            try:
                self.stream.write("\n")
                self.stream.flush()
            except (OSError, ValueError):
                pass


# ------------------------------------------------------------------------------- playing


def _serial(st: dict, games: int, progress: Progress) -> tuple[dict, int | None]:
    from termpool.ui.term import Stop

    done: dict[int, dict] = {}
    try:
        for k in range(games):
            done[k] = play_index(st, k)
            progress.show(len(done))
    except KeyboardInterrupt:
        return done, signal.SIGINT
    except Stop as e:
        return done, e.signum
    return done, None


def _worker(st: dict, tasks, results) -> None:
    """A process of --jobs: plays the games it takes from `tasks` until a None. Ctrl-C is
    the parent's to handle; SIGTERM (the parent stopping the run) ends the game at the next
    shot, its record saved."""
    from termpool.ui.term import STOP_SIGNALS

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    stopping = []
    for sig in STOP_SIGNALS:
        signal.signal(sig, lambda *_: stopping.append(True))
    while not stopping:
        index = tasks.get()
        if index is None:
            return
        try:
            results.put(("game", index, play_index(st, index, stop=lambda: bool(stopping))))
        except Exception:
            results.put(("error", index, traceback.format_exc()))
            return


class _Failed(Exception):
    pass


def _parallel(st: dict, games: int, jobs: int, progress: Progress) -> tuple[dict, int | None]:
    import multiprocessing as mp

    from termpool.ui.term import STOP_SIGNALS, Stop

    ctx = mp.get_context("fork" if "fork" in mp.get_all_start_methods() else "spawn")
    tasks, results = ctx.Queue(), ctx.Queue()
    for k in range(games):
        tasks.put(k)
    for _ in range(jobs):
        tasks.put(None)
    procs = [ctx.Process(target=_worker, args=(st, tasks, results), daemon=True)
             for _ in range(jobs)]
    for p in procs:
        p.start()
    done: dict[int, dict] = {}

    def take(msg) -> None:
        kind, index, payload = msg
        if kind == "error":
            raise _Failed(f"game {index + 1} failed: {payload.strip().splitlines()[-1]}\n"
                          f"{payload}")
        if payload["finished"]:
            done[index] = payload
            progress.show(len(done))

    stopped = None
    try:
        while len(done) < games:
            try:
                take(results.get(timeout=0.5))
            except queue.Empty:
                if not any(p.is_alive() for p in procs):
                    raise _Failed("the game processes ended before the games") from None
    except KeyboardInterrupt:
        stopped = signal.SIGINT
    except Stop as e:
        stopped = e.signum
    finally:
        # A second Ctrl-C or signal: the games still stop and their records are saved.
        old = {s: signal.signal(s, signal.SIG_IGN) for s in (signal.SIGINT, *STOP_SIGNALS)}
        try:
            for p in procs:
                if p.is_alive():
                    p.terminate()  # SIGTERM: the game stops at its next shot, record saved
            deadline = time.monotonic() + 120
            while any(p.is_alive() for p in procs) and time.monotonic() < deadline:
                try:
                    msg = results.get(timeout=0.2)
                    if msg[0] == "game" and msg[2]["finished"]:
                        done[msg[1]] = msg[2]
                except queue.Empty:
                    pass
            for p in procs:
                if p.is_alive():
                    p.kill()
                p.join()
            while True:  # what came in last
                try:
                    msg = results.get_nowait()
                except queue.Empty:
                    break
                if msg[0] == "game" and msg[2]["finished"]:
                    done[msg[1]] = msg[2]
        finally:
            for sig, handler in old.items():
                signal.signal(sig, handler)
    return done, stopped


# -------------------------------------------------------------------------------- output


def report(st: dict, done: dict, interrupted: bool, wall: float, jobs: int) -> dict:
    """The figures of the finished games, in game order, with the run's settings."""
    from termpool.selfplay.games import figures, rounded

    fig = figures([done[k] for k in sorted(done)], st["levels"])
    head = {k: fig.pop(k) for k in ("games", "levels")}
    out: dict[str, Any] = {"games": head["games"], "mode": st["mode"],
                           "levels": head["levels"]}
    for k in ("wins", "pot_rate", "fouls_per_game", "break_and_run_rate", "safeties_per_game",
              "shots_per_game", "decision_s", "decision_s_max"):
        out[k] = fig.pop(k)
    out["wall_s"] = wall
    out |= fig
    out |= {"table": st["table"], "seed": st["seed"], "candidates": st["candidates"],
            "max_shots": st["max_shots"], "jobs": jobs, "interrupted": interrupted}
    return rounded(out)


def _pct(x: float | None) -> str:
    return "-" if x is None else f"{100 * x:.1f}%"


def _num(x: float | None, fmt: str = ".2f") -> str:
    return "-" if x is None else format(x, fmt)


def table_text(r: dict) -> str:
    """The figures as a table: a column per level."""
    names = list(dict.fromkeys(r["levels"]))
    rows = [
        ("wins", lambda lv: str(r["wins"][lv])),
        ("pot rate", lambda lv: _pct(r["pot_rate"][lv])),
        ("pot attempts", lambda lv: str(r["pot_attempts"][lv])),
        ("pot rate after a pot", lambda lv: _pct(r["pot_rate_after_pot"][lv])),
        ("fouls per game", lambda lv: _num(r["fouls_per_game"][lv])),
        ("break-and-run rate", lambda lv: _pct(r["break_and_run_rate"][lv])),
        ("safeties per game", lambda lv: _num(r["safeties_per_game"][lv])),
        ("opponent's chance before a safety",
         lambda lv: _num(r["safeties"][lv]["opponent_chance_before"])),
        ("... and after it", lambda lv: _num(r["safeties"][lv]["opponent_chance_after"])),
        ("safeties that lowered it", lambda lv: _pct(r["safeties"][lv]["lowered"])),
        ("kicks per game (snookered)", lambda lv: _num(r["kicks_per_game"][lv])),
        ("opponent's chance before a kick",
         lambda lv: _num(r["kicks"][lv]["opponent_chance_before"])),
        ("... and after it ", lambda lv: _num(r["kicks"][lv]["opponent_chance_after"])),
        ("median decision (s)", lambda lv: _num(r["decision_s"][lv], ".3f")),
        ("slowest decision (s)", lambda lv: _num(r["decision_s_max"][lv], ".3f")),
        ("median decision, CPU (s)", lambda lv: _num(r["decision_cpu_s"][lv], ".3f")),
    ]
    first = max(len(name) for name, _ in rows)
    width = max(10, *(len(n) for n in names))
    stopped = " (stopped: the games finished so far)" if r["interrupted"] else ""
    lines = [f"selfplay: {r['games']} games of {r['mode']} on a {r['table']} table, "
             f"{' vs '.join(r['levels'])}, seed {r['seed']}, {r['candidates']} candidates"
             f"{stopped}",
             " " * first + "".join(f"  {n:>{width}}" for n in names)]
    for name, cell in rows:
        lines.append(f"{name:<{first}}" + "".join(f"  {cell(lv):>{width}}" for lv in names))
    lines.append(f"shots per game {_num(r['shots_per_game'], '.1f')}, games without a winner "
                 f"{r['undecided']}, wall time {r['wall_s']:.1f} s ({r['jobs']} "
                 f"{'process' if r['jobs'] == 1 else 'processes'})")
    return "\n".join(lines) + "\n"


def run(args: argparse.Namespace) -> int:
    """Play the games and print the figures; returns the exit status (SelfplayError for bad
    settings)."""
    st = settings(args)
    cores = (len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity")
             else os.cpu_count() or 1)
    jobs = max(1, min(args.jobs or cores, args.games))
    progress = Progress(args.games)
    t0 = time.perf_counter()
    from termpool.ui.term import stoppable

    try:
        with stoppable():  # SIGTERM, SIGHUP and SIGQUIT end it as Ctrl-C does
            if jobs == 1:
                done, stopped = _serial(st, args.games, progress)
            else:
                done, stopped = _parallel(st, args.games, jobs, progress)
    except _Failed as e:
        progress.close()
        from termpool.text import say

        first, _, rest = str(e).partition("\n")
        sys.stderr.write(rest)
        say(f"selfplay: {first}")
        return 1
    progress.close()
    from termpool.files import json_safe, to_json

    r = report(st, done, stopped is not None, time.perf_counter() - t0, jobs)
    sys.stdout.write(to_json(json_safe(r), indent=1) + "\n" if args.json else table_text(r))
    sys.stdout.flush()
    return 0 if stopped is None else 128 + stopped
