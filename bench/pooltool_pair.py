"""pooltool measured in the same run as termpool: `termpool bench speed`'s paired breaks.

Where pooltool is (`choose_python`): `--pooltool PYTHON`, else the TERMPOOL_POOLTOOL_PYTHON
environment variable, else this interpreter if it can import pooltool; else nowhere, and the
figures are null. That interpreter runs bench/pooltool_worker.py as one process kept alive:
it builds termpool's break in pooltool, runs it until numba has compiled (the warm-up), then
runs one break each time it is asked. The pairs alternate which side goes first; each side
times its own break with time.process_time() in its own process, and the ratio is taken pair
by pair, so load that comes and goes hits both sides of a pair alike.
"""

from __future__ import annotations

import importlib.util
import json
import os
import queue
import shutil
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable
from typing import Any

from bench.common import make_engine, positive_int

WORKER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "pooltool_worker.py")
ENV = "TERMPOOL_POOLTOOL_PYTHON"
KEY = "vs_pooltool_cpu"  # pooltool's CPU time over termpool's, the median of the pairs' ratios
TARGET = (">=", 4.0)
WARM_BREAKS = 2  # untimed breaks before the pairs: numba compiles in the first
START_TIMEOUT_S = 1800.0  # import and warm-up; numba's first compile takes 30-45 s here
BREAK_TIMEOUT_S = 300.0
FIGURES = ("pooltool_version", "pooltool_break_cpu_ms", "pooltool_events",
           "pooltool_pair_termpool_cpu_ms", KEY)


class WorkerError(RuntimeError):
    """The worker could not start or answer; the message is one line."""


def choose_python(given: str | None, skip: bool) -> tuple[str, str] | None:
    """(interpreter, where it was named) to run pooltool with, or None for no pooltool."""
    if skip:
        return None
    if given:
        return given, "--pooltool"
    if os.environ.get(ENV):
        return os.environ[ENV], ENV
    if importlib.util.find_spec("pooltool") is not None:
        return sys.executable, "this interpreter"
    return None


def check_python(python: str, origin: str) -> str:
    """The interpreter's path, or ValueError with one line naming `origin`."""
    found = shutil.which(python)
    if found is None or os.path.isdir(found):
        raise ValueError(f"{origin} '{python}': not an executable file or command")
    return found


class Worker:
    """pooltool's side: the worker process, one JSON line per request and per answer."""

    def __init__(self, python: str, origin: str, timeout: float = START_TIMEOUT_S) -> None:
        self.python, self.origin = python, origin
        self._err = tempfile.TemporaryFile(mode="w+", encoding="utf-8", errors="replace")
        try:
            self._proc = subprocess.Popen(
                [python, WORKER], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                stderr=self._err, text=True, bufsize=1,
            )
        except OSError as e:
            self._err.close()
            raise WorkerError(f"{origin} '{python}': cannot start ({e.strerror or e})") from None
        self._lines: queue.Queue[str | None] = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()
        self.version = str(self._answer(timeout)["version"])

    def _read(self) -> None:
        assert self._proc.stdout is not None
        for line in self._proc.stdout:
            self._lines.put(line)
        self._lines.put(None)

    def _fail(self, why: str) -> WorkerError:
        self._stop()
        self._err.seek(0)
        last = (self._err.read().strip().splitlines() or [""])[-1]
        detail = f": {last}" if last and last not in why else ""
        return WorkerError(f"{self.origin} '{self.python}': {why}{detail}")

    def _answer(self, timeout: float) -> dict:
        try:
            line = self._lines.get(timeout=timeout)
        except queue.Empty:
            raise self._fail(f"no answer in {timeout:g} s") from None
        if line is None:
            raise self._fail("the pooltool worker stopped")
        try:
            answer = json.loads(line)
            ok = answer["ok"]
        except (ValueError, TypeError, KeyError):
            raise self._fail(f"not a worker's answer: {line.strip()[:80]!r}") from None
        if not ok:
            raise self._fail(str(answer.get("error", "failed")))
        return answer

    def ask(self, request: dict, timeout: float = BREAK_TIMEOUT_S) -> dict:
        assert self._proc.stdin is not None
        try:
            self._proc.stdin.write(json.dumps(request) + "\n")
            self._proc.stdin.flush()
        except OSError:
            raise self._fail("the pooltool worker stopped") from None
        return self._answer(timeout)

    def setup(self, scene: Any, warm: int = WARM_BREAKS) -> dict:
        return self.ask({"op": "setup", "warm": warm, **break_setup(scene)}, START_TIMEOUT_S)

    def run_break(self) -> dict:
        return self.ask({"op": "break"})

    def _stop(self) -> None:
        """End the worker: its input closed, it exits (killed if it has not in 10 s)."""
        assert self._proc.stdin is not None
        try:
            self._proc.stdin.close()
        except OSError:
            pass
        try:
            self._proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self._proc.kill()
            self._proc.wait()

    def close(self) -> None:
        self._stop()
        self._err.close()

    def __enter__(self) -> Worker:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def break_setup(scene: Any) -> dict:
    """What the worker needs to build termpool's break: the scene's table, balls, their
    starting motion and the physics figures pooltool has names for, in plain numbers."""
    t, ph = scene.table, scene.physics
    return {
        "table": {k: float(getattr(t, k)) for k in (
            "length", "width", "corner_mouth", "side_mouth",
            "corner_hole_radius", "side_hole_radius")},
        "physics": {k: float(getattr(ph, k)) for k in (
            "mu_slide", "mu_roll", "mu_spin", "e_ball", "e_cushion", "mu_cushion",
            "cushion_height", "g")},
        "balls": [
            {"id": bid, "pos": [float(v) for v in scene.pos[i]],
             "vel": [float(v) for v in scene.vel[i]], "w": [float(v) for v in scene.w[i]],
             "radius": float(scene.radius[i]), "mass": float(scene.mass[i])}
            for i, bid in enumerate(scene.ids)
        ],
        "cue": "cue" if "cue" in scene.ids else scene.ids[0],
    }


def alternate(term: Callable[[], float], pool: Callable[[], float], pairs: int
              ) -> list[tuple[float, float]]:
    """(termpool, pooltool) CPU seconds of `pairs` pairs of runs, termpool first in the even
    pairs and pooltool first in the odd ones, so neither side always follows the other."""
    out = []
    for k in range(pairs):
        if k % 2 == 0:
            t = term()
            p = pool()
        else:
            p = pool()
            t = term()
        out.append((t, p))
    return out


def summary(version: str | None, pairs: list[tuple[float, float]], events: list[int]) -> dict:
    """The flat figures of the paired runs (all None without pooltool)."""
    if version is None:
        return dict.fromkeys(FIGURES)
    return {
        "pooltool_version": version,
        "pooltool_break_cpu_ms": 1e3 * statistics.median(p for _, p in pairs),
        "pooltool_events": int(statistics.median_low(events)),
        "pooltool_pair_termpool_cpu_ms": 1e3 * statistics.median(t for t, _ in pairs),
        KEY: statistics.median(p / t for t, p in pairs),
    }


def termpool_break(scene: Any, dt: float) -> Callable[[], float]:
    """CPU seconds of one termpool break as `bench speed` times it: Engine built, run to rest."""
    def run() -> float:
        c0 = time.process_time()
        make_engine(scene).run(dt)
        return time.process_time() - c0

    return run


def figures(worker: Worker | None, scene: Any, dt: float, pairs: int) -> dict:
    """The paired figures, with the details under "pooltool" (None without pooltool)."""
    if worker is None:
        return {"pooltool": None, **summary(None, [], [])}
    ready = worker.setup(scene)
    term = termpool_break(scene, dt)
    term()  # termpool's warm-up run, as bench speed's own break has one
    runs: list[dict] = []

    def pool() -> float:
        runs.append(worker.run_break())
        return float(runs[-1]["cpu_s"])

    cpu = alternate(term, pool, pairs)
    events = [int(r["events"]) for r in runs]
    details = {
        "python": worker.python,
        "from": worker.origin,
        "pairs": pairs,
        "warm_cpu_s": ready["warm_cpu_s"],
        "termpool_cpu_ms": [1e3 * t for t, _ in cpu],
        "pooltool_cpu_ms": [1e3 * p for _, p in cpu],
        "pooltool_wall_ms": [1e3 * float(r["wall_s"]) for r in runs],
        "events": events,
    }
    return {"pooltool": details, **summary(worker.version, cpu, events)}


def judge(out: dict) -> None:
    """Add the ratio's target to `out`'s targets and pass maps (pass None: not measured)."""
    op, bound = TARGET
    out["targets"][KEY] = f"{op} {bound:g}"
    value = out.get(KEY)
    out["pass"][KEY] = None if value is None else bool(value >= bound)


def format_lines(r: dict) -> list[str]:
    """The text report's lines about pooltool."""
    if r.get("pooltool") is None:
        return [f"pooltool: not measured (give --pooltool PYTHON or set {ENV})"]
    d, verdict = r["pooltool"], {True: "PASS", False: "MISS"}[r["pass"][KEY]]
    return [
        f"against pooltool {r['pooltool_version']} ({d['python']}), {d['pairs']} paired runs, "
        f"CPU medians: termpool {r['pooltool_pair_termpool_cpu_ms']:.1f} ms, pooltool "
        f"{r['pooltool_break_cpu_ms']:.1f} ms ({r['pooltool_events']} events); "
        f"pooltool/termpool {r[KEY]:.2f} (target {r['targets'][KEY]}) {verdict}",
    ]


def add_arguments(p: Any) -> None:
    """`bench speed`'s options for pooltool."""
    p.add_argument("--pooltool", metavar="PYTHON",
                   help=f"an interpreter that can import pooltool, run warm and paired with "
                        f"termpool's break (default: ${ENV}, else this interpreter if it has "
                        f"pooltool, else none)")
    p.add_argument("--no-pooltool", action="store_true", help="do not measure pooltool")
    p.add_argument("--pairs", type=positive_int, default=15,
                   help="paired termpool/pooltool break runs (default 15)")


def start(given: str | None, skip: bool) -> Worker | None:
    """The worker for the chosen interpreter (None without pooltool), imported and ready for
    setup. ValueError (one line: the command's bad input) when a named interpreter is not
    there or cannot import pooltool; WorkerError when this interpreter's fails."""
    chosen = choose_python(given, skip)
    if chosen is None:
        return None
    python, origin = chosen
    path = check_python(python, origin)
    try:
        return Worker(path, origin)
    except WorkerError as e:
        if origin == "this interpreter":
            raise
        raise ValueError(str(e)) from None
