"""`termpool bench speed`: the standard 8-ball break on a 9-ft table, timed.

    termpool bench speed [--json] [--repeat N] [--batch B] [--dt S]
                         [--pooltool PYTHON | --no-pooltool] [--pairs N]

One table from Engine construction to rest, B slightly different breaks batched in one Engine,
the import of the core in a fresh interpreter, `termpool sim`'s whole process on one ball
beside an empty interpreter's, and what the batch's event logs cost; it prints a small table
with targets and PASS/MISS, or one JSON object with --json. The break and the batch have CPU
time (every thread of the process) beside wall time. Where pooltool is installed, its break
is timed in the same run, paired run by run with termpool's (pooltool_pair.py). With
--games N, the computer's decision time (bench/decisions.py); with --calls, numpy calls per
event under valgrind (bench/npcalls.py).
"""

from __future__ import annotations

import math
import os
import statistics
import subprocess
import sys
import time
from typing import Any

from bench import pooltool_pair
from bench.common import (
    PROG,
    BenchParser,
    child_env,
    machine_info,
    machine_lines,
    make_engine,
    positive_int,
    seconds,
)
from termpool.files import json_safe, to_json
from termpool.physics.results import DT
from termpool.text import say

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
    "batch_breaks_per_s": (">=", 500.0),
    "import_s": ("<", 0.3),
    "batch_peak_kb_per_table": ("<=", 30.0),  # at --memory-batch tables (4096)
    "record_light_pct": ("<=", 20.0),
    "sim_start_s": ("<=", 0.08),
    "numpy_calls_per_event": ("<=", 100.0),  # one table, the break (--calls, under valgrind)
    "decision_cpu_s": ("<=", 0.3),  # the computer (hard), a decision in play: median ...
    "decision_cpu_s_max": ("<=", 1.0),  # ... and the largest
}
SIM_START_RUNS = 9
SIM_START_SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes",
                               "rolling.json")  # one ball


# ------------------------------------------------------------------------------------ speed


def break_scene():
    from termpool.scene import load_scene

    return load_scene(BREAK_SCENE)


def time_break(scene, dt: float, repeat: int) -> dict:
    """Wall and CPU time of one break from Engine construction to rest: one warm-up, then
    `repeat` runs. CPU time is the process's (time.process_time), which counts every thread:
    a library's helper threads would show here and not in the wall time."""
    walls, cpus = [], []
    eng = None
    for k in range(repeat + 1):
        t0, c0 = time.perf_counter(), time.process_time()
        eng = make_engine(scene)
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
    eng = make_engine(scene, pos, vel, w)
    t1 = time.perf_counter()
    eng.run_events()
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    t2, c2 = time.perf_counter(), time.process_time()
    stepped = make_engine(scene, pos, vel, w)
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


def batch_memory(batch: int) -> dict:
    """Peak memory of the batch to rest, per table (bench/memory.py: a fresh interpreter,
    the growth of its peak resident size); the target is for 4096 tables, where the figure
    is smaller (benchmarks/memory.py measures it there)."""
    from bench.memory import batch_peak

    r = batch_peak(batch, "rss")
    # The same run timed: how the rate grows with the batch (a pass's fixed costs are shared).
    return {"batch_peak_kb_per_table": r["kb_per_table"], "batch_peak_mb": r["peak_bytes"] / 1e6,
            "memory_batch": batch, "memory_batch_cpu_s": r["cpu_s"],
            "memory_batch_breaks_per_cpu_s": batch / r["cpu_s"]}


def time_import(runs: int = IMPORT_RUNS) -> dict:
    """Median time to import the core in a fresh interpreter (as measured inside it)."""
    env = child_env()
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


def time_record(scene, batch: int, rounds: int = 3) -> dict:
    """CPU time of the bench's batch run to rest with each event log (`record`: none, the
    light log the referee reads, the full log), the three run in turn `rounds` times: the
    logs' costs as ratios of each one's least time to the least without, in percent. (Other
    work on the machine only adds time, and by the run: a median of per-round ratios moved by
    +-15 points from one run to the next on a shared two-core machine.)"""
    from termpool.physics.log import LIGHT

    pos, vel, w = batch_breaks(scene, batch)
    cpu: dict = {False: [], LIGHT: [], True: []}
    for _ in range(rounds):
        for record in cpu:
            c0 = time.process_time()
            make_engine(scene, pos, vel, w, record=record).run_events()
            cpu[record].append(time.process_time() - c0)

    def pct(record) -> float:
        return 100.0 * (min(cpu[record]) / min(cpu[False]) - 1.0)

    return {"record_light_pct": pct(LIGHT), "record_full_pct": pct(True),
            "record_none_cpu_s": min(cpu[False])}


def _child_cpu() -> float:
    import resource

    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def time_sim_start(runs: int = SIM_START_RUNS) -> dict:
    """Whole processes, wall and CPU time (medians): `termpool sim` on a one-ball scene, and
    as anchors in the same run, in turn with it, an empty interpreter (`python -c pass`) and
    one that imports numpy (with one BLAS thread, as termpool starts it): the floor under
    any command that simulates."""
    from termpool.command import BLAS_THREADS

    env = child_env()
    one = dict(env, **{name: env.get(name, "1") for name in BLAS_THREADS})
    cmds = {"sim_start": ([sys.executable, "-m", "termpool", "sim", SIM_START_SCENE], env),
            "python_start": ([sys.executable, "-c", "pass"], env),
            "numpy_start": ([sys.executable, "-c", "import numpy"], one)}
    wall: dict = {k: [] for k in cmds}
    cpu: dict = {k: [] for k in cmds}
    for _ in range(runs):
        for k, (cmd, e) in cmds.items():
            t0, c0 = time.perf_counter(), _child_cpu()
            p = subprocess.run(cmd, env=e, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                               text=True, timeout=120)
            if p.returncode != 0:
                last = (p.stderr.strip().splitlines() or ["no output"])[-1]
                raise RuntimeError(f"{' '.join(cmd[1:])} failed: {last}")
            wall[k].append(time.perf_counter() - t0)
            cpu[k].append(_child_cpu() - c0)
    out: dict = {"sim_start_runs": runs}
    for k in cmds:
        out[f"{k}_s"] = statistics.median(wall[k])
        out[f"{k}_cpu_s"] = statistics.median(cpu[k])
    return out


def break_events(scene, dt: float) -> dict:
    """Event counts of the single break (recorded run), and run_events() wall time for it."""
    from collections import Counter

    eng = make_engine(scene, record=True)
    eng.run(dt)
    counts = Counter(ev["type"] for ev in eng.events[0])
    t0 = time.perf_counter()
    ref = make_engine(scene)
    ref.run_events()
    wall = time.perf_counter() - t0
    return {
        "events": dict(sorted(counts.items())),
        "events_total": sum(counts.values()),
        "run_events_ms": 1e3 * wall,
        "run_events_passes": int(ref.passes),
    }


def _check(value: float, op: str, bound: float) -> bool:
    return {"<=": value <= bound, ">=": value >= bound, "<": value < bound}[op]


def speed_figures(dt: float, repeat: int, batch: int, games: int = 0,
                  calls: bool = False, memory_batch: int = 0) -> dict:
    scene = break_scene()
    out: dict[str, Any] = {"dt": dt, "repeat": repeat}
    out.update(time_break(scene, dt, repeat))
    out.update(time_batch(scene, dt, batch))
    out.update(batch_memory(memory_batch or batch))
    out.update(time_import())
    out.update(time_sim_start())
    out.update(time_record(scene, batch))
    out.update(break_events(scene, dt))
    if calls:
        from bench.npcalls import calls_per_event

        out.update(calls_per_event(out["events_total"]))
    if games:
        from bench.decisions import time_decisions

        out.update(time_decisions(games))
    out["targets"] = {k: f"{op} {bound:g}" for k, (op, bound) in TARGETS.items()}
    out["pass"] = {k: _check(out[k], op, bound) for k, (op, bound) in TARGETS.items()
                   if out.get(k) is not None}
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
            f"  B={r['memory_batch']}",
            f"{r['memory_batch_breaks_per_cpu_s']:.0f} /s",
            ("", float("nan")),
            None,
            f"breaks a CPU second, the memory run's (CPU {r['memory_batch_cpu_s']:.2f} s); "
            f"B={r['batch']}: {r['batch'] / r['batch_cpu_s']:.0f} /s by CPU",
        ),
        (
            "peak memory",
            f"{r['batch_peak_kb_per_table']:.0f} KB",
            TARGETS["batch_peak_kb_per_table"],
            "batch_peak_kb_per_table",
            f"a table of a batch of {r['memory_batch']} to rest (peak RSS "
            f"+{r['batch_peak_mb']:.1f} MB, fresh interpreter)",
        ),
        (
            "import core",
            f"{r['import_s']:.3f} s",
            TARGETS["import_s"],
            "import_s",
            f"median of {len(r['import_s_runs'])} fresh interpreters",
        ),
        (
            "sim start-up",
            f"{r['sim_start_s']:.3f} s",
            TARGETS["sim_start_s"],
            "sim_start_s",
            f"one ball, whole process, median of {r['sim_start_runs']} (CPU "
            f"{r['sim_start_cpu_s']:.3f} s); python -c pass {r['python_start_s']:.3f} s, "
            f"import numpy {r['numpy_start_s']:.3f} s, so termpool's own "
            f"{r['sim_start_s'] - r['numpy_start_s']:+.3f} s",
        ),
        (
            "light event log",
            f"{r['record_light_pct']:+.0f} %",
            TARGETS["record_light_pct"],
            "record_light_pct",
            f"B={r['batch']} to rest, CPU against no log (full log {r['record_full_pct']:+.0f} %)",
        ),
    ]
    if "decision_cpu_s" in r:
        rows += [
            (
                "decision (hard)",
                f"{r['decision_cpu_s']:.3f} s",
                TARGETS["decision_cpu_s"],
                "decision_cpu_s",
                f"CPU, median of its decisions in play (not the break) over "
                f"{r['decision_games']} games against itself, {r['decision_shots']:.0f} shots",
            ),
            (
                "  slowest",
                f"{r['decision_cpu_s_max']:.3f} s",
                TARGETS["decision_cpu_s_max"],
                "decision_cpu_s_max",
                "CPU",
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
        *([f"numpy calls: {r['numpy_calls_per_event']:.0f} an event "
           f"({r['numpy_calls_per_break']:.0f} a break; target <= 100: "
           f"{ok[r['pass']['numpy_calls_per_event']]}), counted under valgrind"]
          if r.get("numpy_calls_per_event") is not None else []),
        "",
    ]
    m = r["machine"]
    lines += [
        *pooltool_pair.format_lines(r),
        "",
        *machine_lines(m),
    ]
    return "\n".join(lines) + "\n"


def main(argv: list[str]) -> int:
    p = BenchParser(
        prog=f"{PROG} speed",
        description=(
            "Time the standard 8-ball break on a 9-ft table: one table to rest, a batch of "
            "slightly different breaks in one Engine, and importing the core."
        ),
    )
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument(
        "--repeat",
        type=positive_int,
        default=15,
        help="timed single-break runs after one warm-up (default 15)",
    )
    p.add_argument(
        "--batch",
        type=positive_int,
        default=256,
        help="breaks batched in one Engine (default 256)",
    )
    p.add_argument(
        "--dt",
        type=seconds,
        default=DT,
        help="fixed time step in seconds (default 1/60; fractions like 1/120 work)",
    )
    pooltool_pair.add_arguments(p)
    p.add_argument(
        "--games",
        type=int,
        default=2,
        help="8-ball games of the computer (hard) against itself, for its decision time in "
        "play (default 2; 0 leaves them out)",
    )
    p.add_argument(
        "--memory-batch",
        type=positive_int,
        default=4096,
        help="breaks in the batch whose peak memory per table is measured (default 4096)",
    )
    p.add_argument(
        "--calls",
        action="store_true",
        help="count numpy calls per event of the break under valgrind (a minute or two)",
    )
    args = p.parse_args(argv)
    if args.games < 0:
        p.error("--games: must be 0 or more")
    try:
        worker = pooltool_pair.start(args.pooltool, args.no_pooltool)
    except (ValueError, pooltool_pair.WorkerError) as e:
        say(f"bench speed: {e}")
        return 2 if isinstance(e, ValueError) else 1
    try:
        result = speed_figures(args.dt, args.repeat, args.batch, args.games, args.calls,
                               args.memory_batch)
        result.update(pooltool_pair.figures(worker, break_scene(), args.dt, args.pairs))
        pooltool_pair.judge(result)
    except (RuntimeError, ValueError, subprocess.TimeoutExpired) as e:
        say(f"bench speed: {e}")
        return 1
    finally:
        if worker is not None:
            worker.close()
    if args.json:
        sys.stdout.write(to_json(json_safe(result)) + "\n")
    else:
        sys.stdout.write(format_speed(result))
    sys.stdout.flush()
    return 0
