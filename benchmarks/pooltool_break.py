"""pooltool's own 8-ball break with a cue stick at 8 m/s, CPU and wall time.

    /path/to/pooltool-venv/bin/python benchmarks/pooltool_break.py [--runs N]

Needs pooltool 0.6 importable (installed apart from the game's environment; see cushions.py).
Prints one JSON object: the first run (numba compiles then, unless its cache is warm), then
the medians over N runs of `pt.simulate` alone, as `termpool bench speed` times its break:
CPU time (`time.process_time`, every thread of the process) and wall time, the events of
each run (pooltool racks with small random gaps, so they vary), and the CPU time of threads
other than the main one (Linux). Set NUMBA_CACHE_DIR to keep numba's cache out of the
installed package.

This is pooltool's break, not termpool's: a 7-ft table, gaps in the rack, and the cue ball
off at about 11 m/s (V0 is the stick's speed). `termpool bench speed --pooltool PYTHON` runs
termpool's own break in pooltool, paired with termpool's in the same run.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import threading
import time


def _other_threads_s() -> float:
    """CPU time of the process's threads other than this one (0 where /proc is missing)."""
    main, total = threading.get_native_id(), 0
    try:
        for tid in os.listdir("/proc/self/task"):
            if int(tid) != main:
                with open(f"/proc/self/task/{tid}/schedstat", encoding="ascii") as f:
                    total += int(f.read().split()[0])
    except OSError:
        return 0.0
    return total / 1e9


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--runs", type=int, default=7)
    args = p.parse_args()
    t0 = time.perf_counter()
    import pooltool as pt

    import_s = time.perf_counter() - t0

    def rack():
        table = pt.Table.default()
        shot = pt.System(table=table, balls=pt.get_rack(pt.GameType.EIGHTBALL, table),
                         cue=pt.Cue(cue_ball_id="cue"))
        shot.strike(V0=8.0, phi=pt.aim.at_ball(shot, "1"))
        return shot

    c0, w0 = time.process_time(), time.perf_counter()
    pt.simulate(rack(), inplace=True)
    first = (time.process_time() - c0, time.perf_counter() - w0)
    cpu, wall, others, events = [], [], [], []
    for _ in range(args.runs):
        shot = rack()
        o, c, w = _other_threads_s(), time.process_time(), time.perf_counter()
        pt.simulate(shot, inplace=True)
        cpu.append(time.process_time() - c)
        wall.append(time.perf_counter() - w)
        others.append(_other_threads_s() - o)
        events.append(len(shot.events))
    print(json.dumps({
        "import_s": round(import_s, 3),
        "first_cpu_s": round(first[0], 3),
        "first_wall_s": round(first[1], 3),
        "break_cpu_ms": round(1e3 * statistics.median(cpu), 1),
        "break_ms": round(1e3 * statistics.median(wall), 1),
        "other_threads_cpu_ms": round(1e3 * statistics.median(others), 1),
        "events": events,
    }))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
