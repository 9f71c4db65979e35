"""CPU time beside wall time of whole `termpool sim` processes: the break and a one-ball scene.

    python benchmarks/cpu.py [--runs N] [--tree DIR ...] [--threads default,1]

Each run is a fresh interpreter, so start-up is counted as a player meets it; the break's own
cost is the break minus the one-ball scene. CPU time is the child's user + system time over
all its threads (os.wait4), which a spinning BLAS worker raises and wall time does not show.
Several --tree checkouts (say, before and after a change) and thread settings ("default":
the BLAS thread variables unset; a number: all of them set to it) are run interleaved, run
by run, so that the load of a shared machine falls on all of them alike. Prints medians.
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

BREAK = ROOT / "bench" / "scenes" / "break.json"
ONE_BALL = '{"balls": [{"id": "cue", "x": 0.6, "y": 0.6}]}'


def _child(tree: Path, threads: str, scene: str) -> tuple[float, float]:
    """(CPU s, wall s) of `termpool sim` of the scene (a path, or JSON given on stdin)."""
    env = {k: v for k, v in os.environ.items() if k not in BLAS_THREADS}
    env["PYTHONPATH"] = str(tree)
    if threads != "default":
        env.update({name: threads for name in BLAS_THREADS})
    path = "-" if scene.startswith("{") else scene
    t0 = time.perf_counter()
    child = subprocess.Popen([sys.executable, "-m", "termpool", "sim", path], cwd=tree, env=env,
                             stdin=subprocess.PIPE, stdout=subprocess.DEVNULL)
    assert child.stdin is not None
    child.stdin.write(scene.encode() if path == "-" else b"")
    child.stdin.close()
    _, status, usage = os.wait4(child.pid, 0)
    wall = time.perf_counter() - t0
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit(f"cpu: termpool sim failed in {tree}")
    return usage.ru_utime + usage.ru_stime, wall


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--runs", type=int, default=7, help="runs of each (default 7)")
    p.add_argument("--tree", type=Path, nargs="+", default=[ROOT],
                   help="checkouts to run (default: this one)")
    p.add_argument("--threads", default="default,1",
                   help="comma-separated BLAS thread settings (default: default,1)")
    args = p.parse_args()
    configs = [(tree.resolve(), th) for tree in args.tree for th in args.threads.split(",")]
    times: dict = {(c, s): [] for c in configs for s in ("break", "one")}
    for _ in range(args.runs):
        for c in configs:
            times[c, "break"].append(_child(*c, str(BREAK)))
            times[c, "one"].append(_child(*c, ONE_BALL))
    print(f"medians of {args.runs} fresh `termpool sim` processes, ms (CPU / wall)")
    print(f"{'tree':40} {'BLAS threads':>12} {'break':>13} {'one ball':>13} {'difference':>13}")
    for c in configs:
        br = [statistics.median(x) * 1e3 for x in zip(*times[c, "break"], strict=True)]
        one = [statistics.median(x) * 1e3 for x in zip(*times[c, "one"], strict=True)]
        cells = [f"{a:5.0f} / {b:5.0f}" for a, b in (br, one, (br[0] - one[0], br[1] - one[1]))]
        print(f"{str(c[0])[-40:]:40} {c[1]:>12} " + " ".join(f"{x:>13}" for x in cells))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
