"""The engine does without BLAS: the same bits on any processor and thread count, one core.

numpy's BLAS (OpenBLAS in the wheels) picks kernels for the processor (with or without fused
multiply-adds) and splits large products and solves over threads, both of which change last
bits, and its idle workers spin while they wait. The engine writes its products and solves
out instead. Each test runs a fresh interpreter, since OpenBLAS reads its settings as numpy
loads: OPENBLAS_NUM_THREADS, and OPENBLAS_CORETYPE, which makes it take the kernels of
another x86-64 processor (elsewhere it does nothing, and such a test passes trivially).
"""

from __future__ import annotations

import json
import math
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import pytest

from termpool.command import BLAS_THREADS
from termpool.physics.params import BALL_RADIUS, Physics, nose_reach

ROOT = Path(__file__).resolve().parents[1]
BREAK = ROOT / "bench" / "scenes" / "break.json"
ARRIVE = 0.004  # m/s: the pack's speed at the rail, below v_inelastic (a slow contact)


def _env(threads: int | None, **extra: str) -> dict[str, str]:
    """The environment with BLAS's thread count set, or (None) left to the library."""
    env = {k: v for k, v in os.environ.items() if k not in BLAS_THREADS}
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    if threads is not None:
        env.update({name: str(threads) for name in BLAS_THREADS})
    env.update(extra)
    return env


def _pack(rows: int = 7, cols: int = 9, gap: float = 1e-4) -> dict:
    """A hexagonal pack of touching balls rolling together into the foot rail: they arrive
    at ARRIVE, so the rail's slow contact is solved with the whole pack at once, a system of
    about a hundred contacts (many of them redundant)."""
    ph, R = Physics(), BALL_RADIUS
    length, width = 2.54, 1.27
    reach = float(nose_reach(R, ph.cushion_height))
    # Rolling, a ball slows at mu_roll g: the speed that leaves ARRIVE after the travel
    # to the rail (the gap and the nose's reach inside the radius).
    v0 = math.sqrt(ARRIVE ** 2 + 2 * ph.mu_roll * ph.g * (gap + R - reach))
    front = length - R - gap
    balls = []
    for i in range(rows):
        for j in range(cols):
            x = front - 2 * R * (cols - 1) + 2 * R * j + R * (i % 2)
            if x <= front:
                y = width / 2 + (i - (rows - 1) / 2) * math.sqrt(3) * R
                balls.append({"x": x, "y": y, "vx": v0, "w": [0.0, v0 / R, 0.0]})
    return {"table": "9ft", "balls": balls}


def _sim(scene: Path, threads: int | None, **extra: str) -> str:
    """`termpool sim` of the scene in a fresh interpreter: its JSON without the wall time."""
    p = subprocess.run([sys.executable, "-m", "termpool", "sim", str(scene)], cwd=ROOT,
                       env=_env(threads, **extra), capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    out = json.loads(p.stdout)
    out.pop("wall_time")
    return json.dumps(out)


def test_a_pack_against_a_rail_gives_the_same_bits_with_one_blas_thread_or_two(tmp_path):
    pack = _pack()
    scene = tmp_path / "pack.json"
    scene.write_text(json.dumps(pack))
    one, two = _sim(scene, 1), _sim(scene, 2)
    result = json.loads(one)
    # The pack did arrive at the rail and stop there.
    assert len(result["balls"]) == len(pack["balls"]) == 60
    assert all(b["state"] == "stationary" for b in result["balls"])
    assert max(b["x"] for b in result["balls"]) > 2.54 - BALL_RADIUS
    assert one == two


X86 = pytest.mark.skipif(platform.machine().lower() not in ("x86_64", "amd64"),
                         reason="OpenBLAS's kernels for another x86-64 processor")
OLDER = "Nehalem"  # an x86-64 processor without fused multiply-adds (any x86-64 runs its code)


@X86
def test_a_break_gives_the_same_bits_with_another_processors_blas_kernels():
    here, older = _sim(BREAK, 1), _sim(BREAK, 1, OPENBLAS_CORETYPE=OLDER)
    assert len(json.loads(here)["events"]) > 100
    assert here == older


CUSHION_TIMES = """
import hashlib
import numpy as np
from termpool.physics.engine import Engine
from termpool.physics.params import Physics
from termpool.physics.table import Table
eng = Engine(Table(), Physics(), np.array([[0.5, 0.5]]))
rng = np.random.default_rng(5)
M = 2000
p = np.column_stack([rng.uniform(0.03, 2.51, M), rng.uniform(0.03, 1.24, M)])
v, a = rng.normal(0.0, 2.0, (M, 2)), rng.normal(0.0, 1.0, (M, 2))
rc, horizon = np.full(M, eng.rc[0, 0]), np.full(M, 2.0)
with np.errstate(all="ignore"):
    q = np.concatenate([p.T, v.T, a.T])  # the balls as planes: x, y, vx, vy, ax, ay
    print(hashlib.sha256(eng.features.lines(q, rc, horizon).tobytes()).hexdigest())
"""


@X86
def test_cushion_contact_times_are_the_same_bits_with_another_processors_blas_kernels():
    """The balls' distances to the cushion lines are dot products of two terms: through a
    matrix product, a processor with fused multiply-adds rounds them otherwise."""
    runs = [subprocess.run([sys.executable, "-c", CUSHION_TIMES], cwd=ROOT, env=_env(1, **extra),
                           capture_output=True, text=True, timeout=300)
            for extra in ({}, {"OPENBLAS_CORETYPE": OLDER})]
    assert all(p.returncode == 0 for p in runs), [p.stderr for p in runs]
    assert runs[0].stdout == runs[1].stdout


CLI_RUN = """
import json, sys, time
from termpool.cli import main
status = main(["sim", sys.argv[1]])
print(json.dumps([time.process_time(), time.thread_time()]), file=sys.stderr)
sys.exit(status)
"""


@pytest.mark.skipif(not hasattr(os, "wait4"), reason="needs the child's CPU time (wait4)")
def test_a_break_keeps_to_one_core():
    """One break through termpool's command line, with the thread settings a user has by
    default: the process's CPU time (every thread's) is not more than its wall time, give
    or take the scheduler's accounting, and no thread but the main one ran at all (a BLAS
    pool's workers spin for a moment as numpy loads, when termpool does not ask for one
    thread)."""
    t0 = time.perf_counter()
    child = subprocess.Popen([sys.executable, "-c", CLI_RUN, str(BREAK)], cwd=ROOT,
                             env=_env(None), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                             text=True)
    _, status, usage = os.wait4(child.pid, 0)
    wall = time.perf_counter() - t0
    err = child.stderr.read() if child.stderr else ""
    assert os.waitstatus_to_exitcode(status) == 0, err
    cpu = usage.ru_utime + usage.ru_stime
    assert cpu <= 1.3 * wall, (cpu, wall)
    process, main = json.loads(err.splitlines()[-1])
    assert process - main <= 0.002, (process, main)


ENGINE_RUN = """
import json, sys, time
from termpool.physics.engine import Engine
from termpool.scene import load_scene
time.sleep(0.5)  # a BLAS pool's workers spin for a moment after numpy loads: let them sleep
scene = load_scene(json.loads(sys.argv[1]))
cpu, own = time.process_time(), time.thread_time()
Engine(scene.table, scene.physics, scene.pos, scene.vel, scene.w, scene.radius,
       scene.mass).run(1 / 60)
print(json.dumps([time.process_time() - cpu, time.thread_time() - own]))
"""


def test_the_engine_wakes_no_blas_thread():
    """The engine as a library, with BLAS's default threads (as a program importing termpool
    has them): solving the pack's large contact system takes no CPU on any thread but the
    caller's."""
    p = subprocess.run([sys.executable, "-c", ENGINE_RUN, json.dumps(_pack())], cwd=ROOT,
                       env=_env(None), capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    cpu, own = json.loads(p.stdout)
    assert own > 0
    assert cpu - own <= 0.05 * own, (cpu, own)
