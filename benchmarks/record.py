"""What the engine's event log costs a batch: none, the light log (what the referee reads) and
the full log (every event with its balls' states), run in turn.

python benchmarks/record.py [--rounds N] [--tree DIR]

Two batches, each run to rest (`run_events`) with each log in turn, `--rounds` times, by CPU
time (`time.process_time`): the bench's 256 breaks (`bench.speed.batch_breaks`), and the
computer's batch of candidates for its hard level on the open table after a break (the
position `benchmarks/ai.py` times, caught as `choose_shot` builds it). Prints each log's cost
as the median of its per-round ratios to the run without. `--tree` measures another checkout
(one without the light log measures none and full only).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _decision_batch():
    """(args, kwargs) of the largest batch `choose_shot` simulates on the open table at hard."""
    import numpy as np

    import termpool.ai.candidates as cand
    from termpool import ai
    from termpool.physics.engine import Engine

    sys.path.insert(0, os.path.join(ROOT, "benchmarks"))
    from ai import positions  # benchmarks/ai.py

    caught = []

    class Catch(Engine):
        def __init__(self, *args, **kw) -> None:
            caught.append((args, kw))
            super().__init__(*args, **kw)

    _, sc, pos, on, state = list(positions())[1]
    cand.Engine = Catch
    try:
        ai.choose_shot(sc.table, sc.physics, sc.ids, pos, sc.radius, sc.mass, on, state,
                       level="hard")
    finally:
        cand.Engine = Engine
    return max(caught, key=lambda c: np.asarray(c[0][2]).size)


def _cost(with_log: list[float], without: list[float]) -> float:
    """Percent more than without the log: the median of the rounds' ratios."""
    return 100 * (statistics.median(a / b for a, b in zip(with_log, without, strict=True)) - 1)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="benchmarks/record.py", description=__doc__.split("\n")[0])
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--tree", default=ROOT, help="the checkout to measure (default: this one)")
    a = ap.parse_args(argv)
    sys.path.insert(0, os.path.abspath(a.tree))
    import termpool.physics.log as log
    from bench.speed import batch_breaks, break_scene
    from termpool.ai.candidates import SIM_SECONDS
    from termpool.physics.engine import Engine

    modes = [False, True] + ([log.LIGHT] if hasattr(log, "LIGHT") else [])
    sc = break_scene()
    pos, vel, w = batch_breaks(sc, 256)
    args, kw = _decision_batch()

    def breaks(record) -> None:
        Engine(sc.table, sc.physics, pos, vel, w, sc.radius, sc.mass,
               record=record).run_events()

    def decision(record) -> None:
        Engine(*args, **{**kw, "record": record}).run_events(duration=SIM_SECONDS)

    print(f"{os.path.abspath(a.tree)}: {time.strftime('%Y-%m-%d %H:%M %Z')}, "
          f"median of {a.rounds} rounds, CPU")
    for name, run, shape in (("256 breaks", breaks, pos.shape),
                             ("decision batch", decision, args[2].shape)):
        run(False)  # warm-up
        cpu: dict = {m: [] for m in modes}
        for _ in range(a.rounds):
            for m in modes:
                c0 = time.process_time()
                run(m)
                cpu[m].append(time.process_time() - c0)
        none = statistics.median(cpu[False])
        costs = "; ".join(f"{'full' if m is True else m}: {_cost(cpu[m], cpu[False]):+.1f} %"
                          for m in modes[1:])
        print(f"  {name} {shape[:2]}: no log {1e3 * none:.0f} ms; {costs}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
