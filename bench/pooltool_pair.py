"""pooltool measured in the same run as termpool: `termpool bench speed`'s paired breaks.

Where pooltool is (`choose_python`): `--pooltool PYTHON`, else the TERMPOOL_POOLTOOL_PYTHON
environment variable, else this interpreter if it can import pooltool; else nowhere, and the
figures are null. That interpreter runs bench/pooltool_worker.py as one process kept alive:
it builds termpool's break in pooltool, runs it until numba has compiled (the warm-up), then
runs one break each time it is asked. The pairs alternate which side goes first; each side
times its own break with time.process_time() in its own process, and the ratio is taken pair
by pair, so load that comes and goes hits both sides of a pair alike. Two breaks are compared
(BREAKS): the scene's own, with its frozen rack, and the same with the rack opened by
pooltool's own spacing.
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
# The breaks compared, each the same on both sides: the scene's own (its frozen rack), and the
# rack opened so that neighbours' centres are 2R (1 + OPEN_GAP) apart, pooltool's own rack
# lattice (get_rack's spacing_factor) without its random wiggle: touching balls cost the two
# engines very differently, so both are shown. The target is on the scene's own break.
OPEN_GAP = 1e-3
BREAKS = {"frozen": ("", 0.0), "open": ("_open", OPEN_GAP)}  # name: (key infix, gap)
FIGURES = ("pooltool_version", *(
    f"{stem}{infix}{tail}" for infix, _ in BREAKS.values()
    for stem, tail in (("pooltool", "_break_cpu_ms"), ("pooltool", "_events"),
                       ("pooltool", "_pair_termpool_cpu_ms"), ("vs_pooltool", "_cpu"))))


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

    def setup(self, scene: Any, name: str = "", pos: Any = None, warm: int = WARM_BREAKS
              ) -> dict:
        request = {"op": "setup", "name": name, "warm": warm, **break_setup(scene, pos)}
        return self.ask(request, START_TIMEOUT_S)

    def run_break(self, name: str = "") -> dict:
        return self.ask({"op": "break", "name": name})

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


def open_rack(scene: Any, gap: float) -> Any:
    """The scene's positions with every ball but the cue ball moved away from the foot spot
    (the apex's) by the factor 1 + gap: touching neighbours' centres end 2R (1 + gap) apart."""
    import numpy as np

    pos = scene.pos.copy()
    spot = np.array(scene.table.foot_spot)
    moved = [i for i, bid in enumerate(scene.ids) if bid != "cue"]
    pos[moved] = spot + (1.0 + gap) * (pos[moved] - spot)
    return pos


def break_setup(scene: Any, pos: Any = None) -> dict:
    """What the worker needs to build termpool's break: the scene's table, balls (at `pos` if
    given), their starting motion and the physics figures pooltool has names for."""
    t, ph = scene.table, scene.physics
    pos = scene.pos if pos is None else pos
    return {
        "table": {k: float(getattr(t, k)) for k in (
            "length", "width", "corner_mouth", "side_mouth",
            "corner_hole_radius", "side_hole_radius")},
        "physics": {k: float(getattr(ph, k)) for k in (
            "mu_slide", "mu_roll", "mu_spin", "e_ball", "e_cushion", "mu_cushion",
            "cushion_height", "g")},
        "balls": [
            {"id": bid, "pos": [float(v) for v in pos[i]],
             "vel": [float(v) for v in scene.vel[i]], "w": [float(v) for v in scene.w[i]],
             "radius": float(scene.radius[i]), "mass": float(scene.mass[i])}
            for i, bid in enumerate(scene.ids)
        ],
        "cue": "cue" if "cue" in scene.ids else scene.ids[0],
    }


def alternate(term: Callable[[], float], pool: Callable[[], float], pairs: int, start: int = 0
              ) -> list[tuple[float, float]]:
    """(termpool, pooltool) CPU seconds of `pairs` pairs of runs, termpool first in the even
    pairs and pooltool first in the odd ones (counting from `start`), so neither side always
    follows the other."""
    out = []
    for k in range(start, start + pairs):
        if k % 2 == 0:
            t = term()
            p = pool()
        else:
            p = pool()
            t = term()
        out.append((t, p))
    return out


def summary(pairs: list[tuple[float, float]], events: list[int], infix: str = "") -> dict:
    """The flat figures of one break's paired runs."""
    return {
        f"pooltool{infix}_break_cpu_ms": 1e3 * statistics.median(p for _, p in pairs),
        f"pooltool{infix}_events": int(statistics.median_low(events)),
        f"pooltool{infix}_pair_termpool_cpu_ms": 1e3 * statistics.median(t for t, _ in pairs),
        f"vs_pooltool{infix}_cpu": statistics.median(p / t for t, p in pairs),
    }


def termpool_break(scene: Any, dt: float, pos: Any = None) -> Callable[[], float]:
    """CPU seconds of one termpool break as `bench speed` times it: Engine built, run to rest."""
    def run() -> float:
        c0 = time.process_time()
        make_engine(scene, pos).run(dt)
        return time.process_time() - c0

    return run


def termpool_events(scene: Any, dt: float, pos: Any = None) -> int:
    """The events of termpool's break (a recorded run, outside the timing)."""
    eng = make_engine(scene, pos, record=True)
    eng.run(dt)
    return len(eng.events[0])


def figures(worker: Worker | None, scene: Any, dt: float, pairs: int) -> dict:
    """The paired figures of every break in BREAKS, pair by pair in turn, with the details
    under "pooltool" (None, and every figure None, without pooltool)."""
    if worker is None:
        return {"pooltool": None, **dict.fromkeys(FIGURES)}
    sides, ready = {}, {}
    for name, (_, gap) in BREAKS.items():
        pos = open_rack(scene, gap) if gap else None
        ready[name] = worker.setup(scene, name, pos)
        sides[name] = termpool_break(scene, dt, pos)
        sides[name]()  # termpool's warm-up run, as bench speed's own break has one
    runs: dict[str, list[dict]] = {name: [] for name in BREAKS}
    cpu: dict[str, list[tuple[float, float]]] = {name: [] for name in BREAKS}

    def pool(name: str) -> Callable[[], float]:
        def run() -> float:
            runs[name].append(worker.run_break(name))
            return float(runs[name][-1]["cpu_s"])
        return run

    for k in range(pairs):
        for name in BREAKS:
            cpu[name] += alternate(sides[name], pool(name), 1, start=k)
    out: dict[str, Any] = {"pooltool_version": worker.version}
    details: dict[str, Any] = {"python": worker.python, "from": worker.origin, "pairs": pairs}
    for name, (infix, gap) in BREAKS.items():
        events = [int(r["events"]) for r in runs[name]]
        out.update(summary(cpu[name], events, infix))
        details[name] = {
            "rack_gap": gap,
            "termpool_events": termpool_events(scene, dt, open_rack(scene, gap) if gap else None),
            "warm_cpu_s": ready[name]["warm_cpu_s"],
            "termpool_cpu_ms": [1e3 * t for t, _ in cpu[name]],
            "pooltool_cpu_ms": [1e3 * p for _, p in cpu[name]],
            "pooltool_wall_ms": [1e3 * float(r["wall_s"]) for r in runs[name]],
            "events": events,
        }
    return {"pooltool": details, **out}


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
    lines = [f"against pooltool {r['pooltool_version']} ({d['python']}), {d['pairs']} paired "
             f"runs a break, CPU medians:"]
    for name, (infix, gap) in BREAKS.items():
        target = f" (target {r['targets'][KEY]}) {verdict}" if not infix else ""
        lines.append(
            f"  {name} rack{f' (gap {gap:g} x 2R)' if gap else ''}: termpool "
            f"{r[f'pooltool{infix}_pair_termpool_cpu_ms']:.1f} ms, pooltool "
            f"{r[f'pooltool{infix}_break_cpu_ms']:.1f} ms ({r[f'pooltool{infix}_events']} "
            f"events); pooltool/termpool {r[f'vs_pooltool{infix}_cpu']:.2f}{target}")
    return lines


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
