"""Peak memory of a batch of breaks run to rest, per table, measured in a fresh interpreter.

The interpreter builds the speed benchmark's batch of B breaks (`speed.batch_breaks`), runs one
small engine first (so that what every run allocates once, imports and caches, is not
counted), then builds the Engine of the B breaks and runs it to rest (`run_events`, record
off, as the computer opponent uses a batch; no work limit, which a big batch would meet). The
figure is the peak's growth over that start, divided by B, in KB (1000 bytes):

- "rss": the process's peak resident size (VmHWM in /proc/self/status; `ru_maxrss` where
  there is no /proc, though Linux carries that over from the parent across exec), after
  against before; it counts everything the process touched, at page granularity, and costs
  nothing while it runs;
- "tracemalloc": the peak of what Python and numpy allocate (numpy reports its buffers to
  tracemalloc); exact to the byte, but the run takes several times as long.

The per-table figure falls as B grows (a pass's bounded temporaries are shared by more
tables): `benchmarks/memory.py` measures it at B = 4096, the target's size.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

METHODS = ("rss", "tracemalloc")

CHILD = r"""
import json, resource, sys, time, tracemalloc
def peak_rss():
    try:
        with open("/proc/self/status") as f:
            return next(int(x.split()[1]) for x in f if x.startswith("VmHWM:")) * 1024
    except (OSError, StopIteration):
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
from bench.speed import batch_breaks, break_scene
from termpool.physics.engine import Engine
batch, method = int(sys.argv[1]), sys.argv[2]
scene = break_scene()
def make(pos, vel, w):
    return Engine(scene.table, scene.physics, pos, vel, w, scene.radius, scene.mass,
                  record=False, max_work=float("inf"))
make(*batch_breaks(scene, 2)).run_events()
pos, vel, w = batch_breaks(scene, batch)
if method == "tracemalloc":
    tracemalloc.start()
    base = tracemalloc.get_traced_memory()[0]
else:
    base = peak_rss()
t0 = time.process_time()
eng = make(pos, vel, w)
eng.run_events()
cpu = time.process_time() - t0
if method == "tracemalloc":
    peak = tracemalloc.get_traced_memory()[1]
else:
    peak = peak_rss()
print(json.dumps({"batch": batch, "method": method, "peak_bytes": peak - base,
                  "kb_per_table": (peak - base) / batch / 1e3, "cpu_s": cpu,
                  "at_rest": int(eng.at_rest().sum())}))
"""


def batch_peak(batch: int, method: str = "rss", root: Path | None = None) -> dict:
    """Peak memory of `batch` breaks to rest in a fresh interpreter running the code of the
    checkout at `root` (default: this one): {"batch", "method", "peak_bytes",
    "kb_per_table", "cpu_s", "at_rest"}. Raises RuntimeError if the run fails."""
    if method not in METHODS:
        raise ValueError(f"method: {method!r} is not one of {', '.join(METHODS)}")
    root = Path(__file__).resolve().parent.parent if root is None else root
    env = dict(os.environ, PYTHONPATH=str(root))
    p = subprocess.run([sys.executable, "-c", CHILD, str(batch), method], env=env,
                       capture_output=True, text=True, cwd=root, timeout=3600)
    if p.returncode != 0:
        last = (p.stderr.strip().splitlines() or ["no output"])[-1]
        raise RuntimeError(f"memory: the batch of {batch} in {root} failed: {last}")
    return json.loads(p.stdout.strip().splitlines()[-1])
