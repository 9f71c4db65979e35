"""Peak memory per table of a batch of breaks, from Engine construction to rest.

python benchmarks/memory.py [--batch B ...] [--method rss|tracemalloc] [--tree DIR ...] [--runs N]

Each measurement runs in a fresh interpreter (bench/memory.py says how: the peak's growth
over the start of the run, divided by the batch, in KB). With --tree, each tree (a checkout's
root) is measured in turn, alternating, so that old and new code meet the same load. Prints
one line per measurement. The default batch, 4096, is the target's size (about 35 s of CPU
each on a 2-core Xeon virtual machine).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def main(argv: list[str]) -> int:
    sys.path.insert(0, str(ROOT))
    from bench.memory import METHODS, batch_peak

    ap = argparse.ArgumentParser(prog="benchmarks/memory.py", description=__doc__.split("\n")[0])
    ap.add_argument("--batch", type=int, nargs="+", default=[4096], help="batch sizes (4096)")
    ap.add_argument("--method", choices=METHODS, default="rss")
    ap.add_argument("--tree", type=Path, nargs="+", default=[ROOT],
                    help="checkout roots to measure, alternating (default: this one)")
    ap.add_argument("--runs", type=int, default=1, help="measurements of each (1)")
    args = ap.parse_args(argv)
    for batch in args.batch:
        for _ in range(args.runs):
            for tree in args.tree:
                r = batch_peak(batch, args.method, tree.resolve())
                print(f"{tree}  B={batch}  {args.method}: {r['kb_per_table']:.1f} KB/table "
                      f"(peak +{r['peak_bytes'] / 1e6:.1f} MB), CPU {r['cpu_s']:.1f} s, "
                      f"{r['at_rest']} tables at rest", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
