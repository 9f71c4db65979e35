"""`termpool bench`: benchmarks of the physics core.

    termpool bench speed [--json] [--repeat N] [--batch B] [--dt S]
    termpool bench accuracy [--json] [--scenes DIR] [--closed NAMES] [--dts S ...]
                            [--schemes A,B] [--png PATH]
    termpool bench stability [--json] [--quick] [--case TEXT ...]

`speed` times the standard 8-ball break on a 9-ft table: one table from Engine construction to
rest, B slightly different breaks batched in one Engine, and the import of the core in a fresh
interpreter; it prints a small table with targets and PASS/MISS, or one JSON object with --json.
The break and the batch have CPU time (every thread of the process) beside wall time.

`accuracy` (in bench_accuracy.py) runs a set of scenes with every stepping scheme at every dt
against the event-to-event reference and prints errors, wall times and a work-precision chart;
then every scheme against closed-form answers derived from the model's equations
(bench_closed.py).

`stability` (in bench_stability.py, cases in stability_cases.py) runs the stiff and extreme
cases of issue 3 twice each and prints PASS/FAIL per case with the figure that decided it.

Subcommands are registered in SUBCOMMANDS (name -> handler taking the remaining arguments and
returning an exit status). Like the CLI, numpy and the engine are imported only inside the
handlers.
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import statistics
import subprocess
import sys
import time
from collections.abc import Callable
from datetime import datetime
from fractions import Fraction
from typing import Any, NoReturn

from termpool import cli
from termpool.cli import _Exit
from termpool.files import json_safe, to_json
from termpool.text import say as _say

PROG = "termpool bench"

# The standard break: 8-ball rack on a 9-ft table, cue ball on the head spot, 8 m/s straight on.
BREAK_SCENE = {"table": "9ft", "balls": "8ball", "shot": {"speed": 8.0, "angle": 0}}
BREAK_SPEED = 8.0  # m/s
APEX_ID = "1"  # the ball on the foot spot
SPREAD_Y = 0.2  # m: batched breaks put the cue ball within +-this of the head spot's y
SPREAD_AIM = 0.5  # degrees of aim jitter about the line to the apex ball
SEED = 20240601
IMPORT_RUNS = 5
IMPORT_CODE = (
    "import time; t=time.perf_counter(); import termpool.physics.engine, termpool.scene; "
    "print(time.perf_counter()-t)"
)

# Targets: figure -> (comparison, bound); a figure meeting it is PASS, otherwise MISS.
TARGETS = {
    "break_ms": ("<=", 60.0),
    "batch_breaks_per_s": (">=", 200.0),
    "import_s": ("<", 0.3),
}


# ------------------------------------------------------------------------- argument parsing


class _Parser(cli._Parser):
    """The CLI's parser (one `termpool: ...` line and exit status 2 on errors), naming the
    bench subcommand in its messages."""

    def error(self, message: str) -> NoReturn:
        _say(f"bench {self.prog.split()[-1]}: {message}")
        raise _Exit(2)


def _positive_int(text: str) -> int:
    try:
        val = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not an integer: '{text}'") from None
    if val <= 0:
        raise argparse.ArgumentTypeError(f"must be a positive integer, not '{text}'")
    return val


def _seconds(text: str) -> float:
    """A positive finite number of seconds; fractions such as 1/60 are accepted."""
    try:
        val = float(Fraction(text.strip())) if "/" in text else float(text)
    except (ValueError, ZeroDivisionError):
        raise argparse.ArgumentTypeError(f"not a number: '{text}'") from None
    if not math.isfinite(val) or val <= 0:
        raise argparse.ArgumentTypeError(f"must be positive and finite, not '{text}'")
    return val


# ------------------------------------------------------------------------------------ speed


def _break_scene():
    from termpool.scene import load_scene

    return load_scene(BREAK_SCENE)


def _engine(scene, pos=None, vel=None, w=None, record: bool = False):
    from termpool.physics.engine import Engine

    return Engine(
        scene.table,
        scene.physics,
        scene.pos if pos is None else pos,
        scene.vel if vel is None else vel,
        scene.w if w is None else w,
        scene.radius,
        scene.mass,
        record=record,
    )


def time_break(scene, dt: float, repeat: int) -> dict:
    """Wall and CPU time of one break from Engine construction to rest: one warm-up, then
    `repeat` runs. CPU time is the process's (time.process_time), which counts every thread:
    a library's helper threads would show here and not in the wall time."""
    walls, cpus = [], []
    eng = None
    for k in range(repeat + 1):
        t0, c0 = time.perf_counter(), time.process_time()
        eng = _engine(scene)
        eng.run(dt)
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        if k:
            walls.append(wall)
            cpus.append(cpu)
    assert eng is not None
    return {
        "break_ms": 1e3 * statistics.median(walls),
        "break_ms_min": 1e3 * min(walls),
        "break_ms_max": 1e3 * max(walls),
        "break_cpu_ms": 1e3 * statistics.median(cpus),
        "break_steps": int(eng.steps),
        "break_passes": int(eng.passes),
        "break_sim_s": float(eng.time),
    }


def batch_breaks(scene, batch: int, seed: int = SEED):
    """(pos, vel, w) of `batch` breaks: the cue ball moved along the head string by up to
    +-SPREAD_Y and aimed at the apex ball with up to +-SPREAD_AIM degrees of jitter."""
    import numpy as np

    from termpool.physics.cue import strike

    rng = np.random.default_rng(seed)
    cue = scene.index("cue")
    apex = scene.pos[scene.index(APEX_ID)]
    radius = float(scene.radius[cue])
    n = len(scene.ids)
    pos = np.broadcast_to(scene.pos, (batch, n, 2)).copy()
    vel = np.zeros((batch, n, 2))
    w = np.zeros((batch, n, 3))
    pos[:, cue, 1] += rng.uniform(-SPREAD_Y, SPREAD_Y, batch)
    jitter = rng.uniform(-SPREAD_AIM, SPREAD_AIM, batch)
    for b in range(batch):
        dx, dy = apex - pos[b, cue]
        angle = math.degrees(math.atan2(dy, dx)) + float(jitter[b])
        v, spin = strike(BREAK_SPEED, angle, 0.0, 0.0, radius)
        vel[b, cue] = v
        w[b, cue] = spin
    return pos, vel, w


def time_batch(scene, dt: float, batch: int) -> dict:
    """Wall time for `batch` different breaks in one Engine, construction to rest.

    Two ways: to rest in one call (event to event, as the computer opponent and shot previews
    use a batch: only the outcome matters), and in fixed steps of dt (as the game draws
    frames). The engine is exact inside a step, so both give the same final tables.
    """
    pos, vel, w = batch_breaks(scene, batch)
    t0, c0 = time.perf_counter(), time.process_time()
    eng = _engine(scene, pos, vel, w)
    t1 = time.perf_counter()
    eng.run_events()
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    t2, c2 = time.perf_counter(), time.process_time()
    stepped = _engine(scene, pos, vel, w)
    stepped.run(dt)
    wall_stepped, cpu_stepped = time.perf_counter() - t2, time.process_time() - c2
    return {
        "batch": batch,
        "batch_breaks_per_s": batch / wall,
        "batch_wall_s": wall,
        "batch_cpu_s": cpu,
        "batch_build_s": t1 - t0,
        "batch_passes": int(eng.passes),
        "batch_sim_s": float(eng.time),
        "batch_at_rest": int(eng.at_rest().sum()),
        "batch_stepped_breaks_per_s": batch / wall_stepped,
        "batch_stepped_wall_s": wall_stepped,
        "batch_stepped_cpu_s": cpu_stepped,
        "batch_steps": int(stepped.steps),
        "batch_stepped_passes": int(stepped.passes),
        "batch_same_result": bool((stepped.pos == eng.pos).all()),
    }


def time_import(runs: int = IMPORT_RUNS) -> dict:
    """Median time to import the core in a fresh interpreter (as measured inside it)."""
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    env = dict(os.environ)
    env["PYTHONPATH"] = root + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    times = []
    for _ in range(runs):
        p = subprocess.run(
            [sys.executable, "-c", IMPORT_CODE],
            env=env,
            capture_output=True,
            text=True,
            timeout=120,
        )
        if p.returncode != 0:
            last = (p.stderr.strip().splitlines() or ["no output"])[-1]
            raise RuntimeError(f"importing the core failed: {last}")
        times.append(float(p.stdout.strip().splitlines()[-1]))
    return {"import_s": statistics.median(times), "import_s_runs": times}


def break_events(scene, dt: float) -> dict:
    """Event counts of the single break (recorded run), and run_events() wall time for it."""
    from collections import Counter

    eng = _engine(scene, record=True)
    eng.run(dt)
    counts = Counter(ev["type"] for ev in eng.events[0])
    t0 = time.perf_counter()
    ref = _engine(scene)
    ref.run_events()
    wall = time.perf_counter() - t0
    return {
        "events": dict(sorted(counts.items())),
        "events_total": sum(counts.values()),
        "run_events_ms": 1e3 * wall,
        "run_events_passes": int(ref.passes),
    }


def machine_info() -> dict:
    import numpy as np

    info = {
        "platform": platform.platform(),
        "machine": platform.machine(),
        "cpu": _cpu_model(),
        "cpu_count": os.cpu_count(),
        "python": f"{platform.python_implementation()} {platform.python_version()}",
        "numpy": np.__version__,
        "date": datetime.now().astimezone().isoformat(timespec="seconds"),
    }
    return info


def _cpu_model() -> str:
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.lower().startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def machine_lines(m: dict) -> list[str]:
    """The machine and date lines every benchmark prints under its figures."""
    return [
        f"machine: {m['platform']}; {m['cpu']} ({m['cpu_count']} cpus)",
        f"python {m['python']}, numpy {m['numpy']}; {m['date']}",
    ]


def _check(value: float, op: str, bound: float) -> bool:
    return {"<=": value <= bound, ">=": value >= bound, "<": value < bound}[op]


def speed_figures(dt: float, repeat: int, batch: int) -> dict:
    scene = _break_scene()
    out: dict[str, Any] = {"dt": dt, "repeat": repeat}
    out.update(time_break(scene, dt, repeat))
    out.update(time_batch(scene, dt, batch))
    out.update(time_import())
    out.update(break_events(scene, dt))
    out["targets"] = {k: f"{op} {bound:g}" for k, (op, bound) in TARGETS.items()}
    out["pass"] = {k: _check(out[k], op, bound) for k, (op, bound) in TARGETS.items()}
    out["machine"] = machine_info()
    return out


def format_speed(r: dict) -> str:
    ok = {True: "PASS", False: "MISS"}
    rows = [
        (
            "break (1 table)",
            f"{r['break_ms']:.1f} ms",
            TARGETS["break_ms"],
            "break_ms",
            f"median of {r['repeat']}; min {r['break_ms_min']:.1f}, "
            f"max {r['break_ms_max']:.1f} ms; CPU {r['break_cpu_ms']:.1f} ms",
        ),
        (
            "batch breaks",
            f"{r['batch_breaks_per_s']:.0f} /s",
            TARGETS["batch_breaks_per_s"],
            "batch_breaks_per_s",
            f"B={r['batch']} to rest in one call, {r['batch_wall_s']:.2f} s "
            f"(CPU {r['batch_cpu_s']:.2f} s), {r['batch_passes']} passes",
        ),
        (
            "  in 1/60 s steps",
            f"{r['batch_stepped_breaks_per_s']:.0f} /s",
            ("", float("nan")),
            None,
            f"{r['batch_stepped_wall_s']:.2f} s (CPU {r['batch_stepped_cpu_s']:.2f} s), "
            f"{r['batch_steps']} steps, "
            f"{r['batch_stepped_passes']} passes; same tables: {r['batch_same_result']}",
        ),
        (
            "import core",
            f"{r['import_s']:.3f} s",
            TARGETS["import_s"],
            "import_s",
            f"median of {len(r['import_s_runs'])} fresh interpreters",
        ),
    ]
    table = [("figure", "value", "target", "result", "notes")]
    for label, value, (op, bound), key, note in rows:
        target = f"{op} {bound:g}" if key else ""
        table.append((label, value, target, ok[r["pass"][key]] if key else "", note))
    widths = [max(len(row[c]) for row in table) for c in range(4)]
    lines = [f"termpool bench speed: 8-ball break, 9-ft table, 8 m/s, dt {r['dt']:.6g} s", ""]
    for row in table:
        cells = [
            row[0].ljust(widths[0]),
            row[1].rjust(widths[1]),
            row[2].ljust(widths[2]),
            row[3].ljust(widths[3]),
            row[4],
        ]
        lines.append("  ".join(cells).rstrip())
    ev = ", ".join(f"{k} {v}" for k, v in r["events"].items())
    lines += [
        "",
        f"single break: {r['break_steps']} steps, {r['break_passes']} passes, "
        f"{r['break_sim_s']:.2f} s simulated",
        f"events ({r['events_total']}): {ev}",
        f"run_events() reference: {r['run_events_ms']:.1f} ms ({r['run_events_passes']} passes)",
        "",
    ]
    m = r["machine"]
    lines += [
        *machine_lines(m),
    ]
    return "\n".join(lines) + "\n"


def speed(argv: list[str]) -> int:
    p = _Parser(
        prog=f"{PROG} speed",
        description=(
            "Time the standard 8-ball break on a 9-ft table: one table to rest, a batch of "
            "slightly different breaks in one Engine, and importing the core."
        ),
    )
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument(
        "--repeat",
        type=_positive_int,
        default=15,
        help="timed single-break runs after one warm-up (default 15)",
    )
    p.add_argument(
        "--batch",
        type=_positive_int,
        default=256,
        help="breaks batched in one Engine (default 256)",
    )
    p.add_argument(
        "--dt",
        type=_seconds,
        default=1 / 60,
        help="fixed time step in seconds (default 1/60; fractions like 1/120 work)",
    )
    args = p.parse_args(argv)
    try:
        result = speed_figures(args.dt, args.repeat, args.batch)
    except (RuntimeError, ValueError, subprocess.TimeoutExpired) as e:
        _say(f"bench speed: {e}")
        return 1
    if args.json:
        sys.stdout.write(to_json(json_safe(result)) + "\n")
    else:
        sys.stdout.write(format_speed(result))
    sys.stdout.flush()
    return 0


# --------------------------------------------------------------------------------- accuracy


def accuracy(argv: list[str]) -> int:
    """`termpool bench accuracy`: see termpool/bench_accuracy.py."""
    from termpool.bench_accuracy import main as accuracy_main

    return accuracy_main(argv)


# -------------------------------------------------------------------------------- stability


def stability(argv: list[str]) -> int:
    """`termpool bench stability`: see termpool/bench_stability.py."""
    from termpool.bench_stability import main as stability_main

    return stability_main(argv)


# ------------------------------------------------------------------------------------- main

SUBCOMMANDS: dict[str, tuple[Callable[[list[str]], int], str]] = {
    "speed": (speed, "time the standard break, a batch of breaks and the core import"),
    "accuracy": (accuracy, "every stepping scheme against the event-to-event reference"),
    "stability": (stability, "stiff and extreme cases: PASS/FAIL with the deciding figure"),
}

USAGE = f"usage: {PROG} {{{','.join(SUBCOMMANDS)}}} [options]   (try {PROG} SUBCOMMAND --help)\n"


def _help() -> str:
    lines = [USAGE.rstrip(), "", "benchmarks of the physics core:", ""]
    width = max(len(name) for name in SUBCOMMANDS)
    for name, (_, text) in SUBCOMMANDS.items():
        lines.append(f"  {name.ljust(width)}  {text}")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    """Entry point of `termpool bench`; argv is what follows `bench`. Returns the exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    cli.one_blas_thread()
    if not argv:
        _say(f"bench: missing subcommand (use {', '.join(SUBCOMMANDS)})")
        return 2
    name, rest = argv[0], argv[1:]
    if name in ("-h", "--help"):
        sys.stdout.write(_help())
        return 0
    if name not in SUBCOMMANDS:
        _say(f"bench: unknown subcommand '{name}' (use {', '.join(SUBCOMMANDS)})")
        return 2
    try:
        return SUBCOMMANDS[name][0](rest)
    except _Exit as e:
        return e.code


if __name__ == "__main__":
    raise SystemExit(main())
