"""CPU time of the bench's 256-break batch run to rest, in checkouts of the tree side by side.

    python benchmarks/batch_trees.py --tree OLD --tree NEW [--rounds N] [--batches K] [--size B]

Any checkout since the speed figures began (2026-11-27) will do. Each round runs every tree
in turn in a fresh interpreter (its own `termpool` and `bench`, one BLAS thread): the batch
once to warm up, then K times, keeping the least CPU time (`time.process_time`).
Alternating the trees round by round lets the load of a shared machine fall on all of them
alike. Prints each tree's median over the rounds, its breaks a second, and the change from
the first tree.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from termpool.command import BLAS_THREADS  # noqa: E402

BATCH = 256  # breaks, as `termpool bench speed` batches them by default
# What a child runs, in the tree it is given (its working directory and import path).
# (Trees from before 2026-12-01 kept the benchmarks inside the package: termpool/bench.py.)
CHILD = """
import sys, time
try:
    from bench.common import make_engine
    from bench.speed import batch_breaks
    from termpool.scene import load_scene
    scene = load_scene("bench/scenes/break.json")
except ImportError:
    from termpool.bench import _break_scene, _engine as make_engine, batch_breaks
    scene = _break_scene()
pos, vel, w = batch_breaks(scene, int(sys.argv[2]))
best = []
for k in range(int(sys.argv[1]) + 1):
    c = time.process_time()
    eng = make_engine(scene, pos, vel, w)
    eng.max_work = float("inf")  # (a big batch meets the work limit, where a tree has one)
    eng.run_events()
    if k:
        best.append(time.process_time() - c)
print(min(best))
"""


def one(tree: str, batches: int, size: int) -> float:
    env = dict(os.environ, PYTHONPATH=tree, **{name: "1" for name in BLAS_THREADS})
    out = subprocess.run([sys.executable, "-c", CHILD, str(batches), str(size)], cwd=tree,
                         env=env, capture_output=True, text=True, check=True)
    return float(out.stdout)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tree", action="append", required=True, help="a checkout (repeat)")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--batches", type=int, default=3, help="timed batches a process")
    ap.add_argument("--size", type=int, default=BATCH, help="breaks in a batch")
    args = ap.parse_args()
    cpu: dict[str, list[float]] = {t: [] for t in args.tree}
    for _ in range(args.rounds):
        for tree in args.tree:
            cpu[tree].append(one(tree, args.batches, args.size))
    first = statistics.median(cpu[args.tree[0]])
    for tree, xs in cpu.items():
        m = statistics.median(xs)
        runs = ", ".join(f"{1e3 * x:.0f}" for x in xs)
        print(f"{tree}: {1e3 * m:.1f} ms CPU, {args.size / m:.0f} breaks/s ({runs} ms);"
              f" {100 * (m / first - 1):+.1f} %")
    return 0


if __name__ == "__main__":
    sys.exit(main())
