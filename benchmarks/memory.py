"""Peak memory per table of a batch of breaks, from Engine construction to rest.

python benchmarks/memory.py [--batch B ...] [--method rss|tracemalloc] [--tree DIR ...]

Each measurement runs in a fresh interpreter: it builds the bench's batch of B breaks
(`bench.speed.batch_breaks`), runs one small engine first (so that what every run allocates
once, imports and caches, is not counted), then builds the Engine of the B breaks and runs it
to rest (`run_events`, record off, as the computer opponent uses a batch; no work limit, which
a batch this big would meet). The figure is the
peak's growth over that start, divided by B, in KB (1000 bytes):

- `rss` (default): the process's peak resident size (`ru_maxrss`), after against before; it
  counts everything the process touched, at page granularity, and costs nothing while it runs.
- `tracemalloc`: the peak of the memory Python and numpy allocate (numpy reports its buffers
  to tracemalloc); exact to the byte, but the run takes several times as long.

With --tree, each tree (a checkout's root) is measured in turn, alternating, so that old and
new code meet the same load. Prints one line per measurement.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

CHILD = r"""
import json, resource, sys, time, tracemalloc
from bench.speed import batch_breaks, break_scene
from termpool.physics.engine import Engine
batch, method = int(sys.argv[1]), sys.argv[2]
scene = break_scene()
def make_engine(scene, pos, vel, w):  # a big batch does more work than the default limit
    return Engine(scene.table, scene.physics, pos, vel, w, scene.radius, scene.mass,
                  record=False, max_work=float("inf"))
make_engine(scene, *batch_breaks(scene, 2)).run_events()  # imports, caches: not counted
pos, vel, w = batch_breaks(scene, batch)
if method == "tracemalloc":
    tracemalloc.start()
    base = tracemalloc.get_traced_memory()[0]
else:
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
t0 = time.process_time()
eng = make_engine(scene, pos, vel, w)
eng.run_events()
cpu = time.process_time() - t0
if method == "tracemalloc":
    peak = tracemalloc.get_traced_memory()[1]
else:
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
print(json.dumps({"batch": batch, "method": method, "peak_bytes": peak - base,
                  "kb_per_table": (peak - base) / batch / 1e3, "cpu_s": cpu,
                  "at_rest": int(eng.at_rest().sum())}))
"""


def measure(tree: Path, batch: int, method: str) -> dict:
    """One measurement in a fresh interpreter running the code of `tree`."""
    env = dict(os.environ, PYTHONPATH=str(tree))
    p = subprocess.run([sys.executable, "-c", CHILD, str(batch), method], env=env,
                       capture_output=True, text=True, cwd=tree)
    if p.returncode != 0:
        last = (p.stderr.strip().splitlines() or ["no output"])[-1]
        raise RuntimeError(f"memory: the run in {tree} failed: {last}")
    return json.loads(p.stdout.strip().splitlines()[-1])


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(prog="benchmarks/memory.py", description=__doc__.split("\n")[0])
    ap.add_argument("--batch", type=int, nargs="+", default=[4096], help="batch sizes (4096)")
    ap.add_argument("--method", choices=("rss", "tracemalloc"), default="rss")
    ap.add_argument("--tree", type=Path, nargs="+", default=[ROOT],
                    help="checkout roots to measure, alternating (default: this one)")
    ap.add_argument("--runs", type=int, default=1, help="measurements of each (1)")
    args = ap.parse_args(argv)
    for batch in args.batch:
        for _ in range(args.runs):
            for tree in args.tree:
                r = measure(tree.resolve(), batch, args.method)
                print(f"{tree}  B={batch}  {args.method}: {r['kb_per_table']:.1f} KB/table "
                      f"(peak +{r['peak_bytes'] / 1e6:.1f} MB), CPU {r['cpu_s']:.1f} s, "
                      f"{r['at_rest']} tables at rest", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
