"""`termpool sim`'s start-up in checkouts of the tree side by side, over its floors.

    python benchmarks/sim_trees.py --tree OLD --tree NEW [--rounds N]

Each round runs, in turn and each in a fresh process with one BLAS thread: `python -c pass`,
`python -c "import numpy"` (the floors no termpool can go under) and every tree's `python -m
termpool sim` of the bench's one-ball scene (its own `termpool`, its output thrown away).
Alternating round by round lets the load of a shared machine fall on all of them alike.
Prints the wall time's median and least of each, and each tree's share over `import numpy`.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from termpool.command import BLAS_THREADS  # noqa: E402

SCENE = ROOT / "bench" / "scenes" / "rolling.json"  # one ball, as `bench speed` starts it


def one(args: list[str], path: str | None) -> float:
    env = dict(os.environ, **{name: "1" for name in BLAS_THREADS})
    env.pop("PYTHONPATH", None)
    if path is not None:
        env["PYTHONPATH"] = path
    t = time.perf_counter()
    subprocess.run([sys.executable, *args], env=env, stdout=subprocess.DEVNULL, check=True,
                   cwd=path or ROOT)
    return time.perf_counter() - t


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tree", action="append", required=True, help="a checkout (repeat)")
    ap.add_argument("--rounds", type=int, default=15)
    args = ap.parse_args()
    runs = {"python -c pass": (["-c", "pass"], None),
            "import numpy": (["-c", "import numpy"], None),
            **{tree: (["-m", "termpool", "sim", str(SCENE)], tree) for tree in args.tree}}
    wall: dict[str, list[float]] = {name: [] for name in runs}
    for _ in range(args.rounds):
        for name, (cmd, path) in runs.items():
            wall[name].append(one(cmd, path))
    floor = statistics.median(wall["import numpy"])
    for name, xs in wall.items():
        m = statistics.median(xs)
        share = f"; {1e3 * (m - floor):+.1f} ms over import numpy" if name in args.tree else ""
        print(f"{name}: {1e3 * m:.1f} ms median, {1e3 * min(xs):.1f} ms least{share}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
