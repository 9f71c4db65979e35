"""What a unit of the engine's work limit costs: CPU time per unit over runs of every kind.

python benchmarks/work.py

The work limit (docs/limits.md) is counted, not timed, so a run meets it at the same point on
every machine; this measures what it means in seconds here. Each run is timed once (process
CPU time) with no limit: a break, a batch of 64 breaks, a lossless ball bouncing for 600 s
(mostly steps), frozen packs of 30 and 60 balls struck hard (mostly cluster solves), and the
slowest cloth a scene may give (mostly steps and rolling).
"""

from __future__ import annotations

import math
import os
import platform
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, ROOT)

import numpy as np  # noqa: E402

from termpool.physics.engine import WORK_LIMIT, Engine  # noqa: E402
from termpool.physics.params import BALL_RADIUS as R  # noqa: E402
from termpool.physics.params import Physics  # noqa: E402
from termpool.physics.table import Table  # noqa: E402
from termpool.scene import load_scene  # noqa: E402


def from_scene(d: dict, batch: int = 0) -> Engine:
    sc = load_scene(d)
    arrays = [sc.pos, sc.vel, sc.w]
    if batch:
        arrays = [np.broadcast_to(a, (batch, *a.shape)) for a in arrays]
    return Engine(sc.table, sc.physics, *arrays, sc.radius, sc.mass, record=False,
                  max_work=math.inf)


def pack(n: int, speed: float) -> Engine:
    """n balls frozen in rows of up to 20 against the foot rail, struck from the head spot."""
    pos = []
    x = 2.54 - R - 1e-4
    while len(pos) < n:
        y0 = R + 1e-4 + (R if (len(pos) // 20) % 2 else 0.0)
        pos += [[x, y0 + 2 * R * k] for k in range(min(20, n - len(pos)))]
        x -= math.sqrt(3) * R
    pos = np.array([[0.635, 0.635], *pos])
    vel = np.zeros_like(pos)
    d = pos[1:].mean(axis=0) - pos[0]
    vel[0] = speed * d / np.hypot(*d)
    return Engine(Table(), Physics(), pos, vel, record=False, max_work=math.inf)


BREAK = {"balls": "8ball", "shot": {"speed": 8.0, "angle": 0.0}}
LOSSLESS = {"table": {"pockets": "none"},
            "physics": {"mu_slide": 0, "mu_roll": 0, "mu_spin": 0, "cushion": "simple",
                        "e_cushion": 1, "mu_cushion": 0},
            "balls": [{"x": 0.5, "y": 0.5}], "shot": {"speed": 3.0, "angle": 23.0}}
SLOWEST = {"table": {"pockets": "none"},
           "physics": {"mu_slide": 0.1, "mu_roll": 1e-3, "mu_spin": 1e-3, "g": 1.0},
           "balls": [{"x": 0.5, "y": 0.5}], "shot": {"speed": 3.0, "angle": 23.0, "top": 0.4}}
RUNS = [
    ("8-ball break at 8 m/s", lambda: from_scene(BREAK), None),
    ("64 breaks in one engine", lambda: from_scene(BREAK, 64), None),
    ("lossless ball, 600 s", lambda: from_scene(LOSSLESS), 600.0),
    ("slowest cloth, to rest", lambda: from_scene(SLOWEST), None),
    ("30-ball pack at 6 m/s", lambda: pack(30, 6.0), None),
    ("60-ball pack at 2 m/s", lambda: pack(60, 2.0), None),
]


def main() -> int:
    print(f"work limit {WORK_LIMIT:,} units; {platform.processor() or platform.machine()}, "
          f"Python {platform.python_version()}, numpy {np.__version__}, "
          f"{time.strftime('%Y-%m-%d')}")
    print(f"{'run':26} {'units':>12} {'CPU s':>8} {'us/unit':>8}")
    for name, make, duration in RUNS:
        eng = make()
        t0 = time.process_time()
        eng.run(1 / 60, duration=duration)
        cpu = time.process_time() - t0
        print(f"{name:26} {eng.work:>12,} {cpu:>8.2f} {1e6 * cpu / eng.work:>8.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
