"""Decision time of the computer opponent (termpool.ai), and how well it plays.

python benchmarks/ai.py [--repeat N]

For three positions (the 8-ball break, an open table after a real break, an end game on the
8) and each level, prints the median wall time of `choose_shot` over N runs (after one
warm-up) and its median processor time, the number of candidates simulated, and what the
chosen shot does. Also times `choose_placement`: ball in hand anywhere on the open table, and
each level's break spot. Target: under 1.5 s a decision.

How strong each level plays whole games is measured by `termpool selfplay` (docs/ai.md).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from dataclasses import replace

if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

import numpy as np  # noqa: E402

from termpool import ai  # noqa: E402
from termpool.physics.cue import strike  # noqa: E402
from termpool.physics.engine import POCKETED, Engine  # noqa: E402
from termpool.rules.common import SOLIDS, STRIPES, State  # noqa: E402
from termpool.rules.events import summarize  # noqa: E402
from termpool.rules.referee import judge  # noqa: E402
from termpool.scene import load_scene  # noqa: E402

LEVELS = tuple(ai.LEVELS)


def _rack(mode: str):
    sc = load_scene({"table": "9ft", "balls": mode})
    return sc, sc.pos.copy(), np.ones(len(sc.ids), bool)


def _play(sc, pos, on, plan, state):
    """Strike `plan` on one table; returns (summary, outcome, next state, pos, on)."""
    keep = np.nonzero(on)[0]
    ids = [sc.ids[k] for k in keep]
    vel, w = np.zeros((len(ids), 2)), np.zeros((len(ids), 3))
    c = ids.index("cue")
    vel[c], w[c] = strike(plan.speed, plan.angle, plan.side, plan.top, float(sc.radius[0]))
    eng = Engine(sc.table, sc.physics, pos[keep], vel, w, sc.radius[keep], sc.mass[keep])
    eng.run_events()
    summary = summarize(eng.log[0], ids, is_break=state.is_break)
    out, nxt = judge(replace(state, called=plan.called), summary)
    pos, on = pos.copy(), on.copy()
    pos[keep] = eng.pos[0]
    on[keep] = eng.state[0] != POCKETED
    return summary, out, nxt, pos, on


def positions():
    """(name, scene, pos, on_table, state) for the three benchmark positions."""
    sc, pos, on = _rack("8ball")
    yield "break", sc, pos, on, State(mode="8ball", is_break=True)
    brk = ai.Plan(8.0, 0.3, 0.0, 0.0, None, 0.0, "")
    _, _, nxt, pos2, on2 = _play(sc, pos, on, brk, State(mode="8ball", is_break=True))
    yield "open table", sc, pos2, on2, replace(nxt, shooter=0)
    end = {"cue": (0.9, 0.5), "8": (1.9, 0.8), "10": (0.5, 1.0), "13": (2.2, 0.25)}
    pos3 = pos.copy()
    on3 = np.array([b in end for b in sc.ids])
    for b, xy in end.items():
        pos3[sc.index(b)] = xy
    down = tuple(b for b in (*SOLIDS, *STRIPES) if b not in end)
    yield "end game, on the 8", sc, pos3, on3, State(mode="8ball", pocketed=down,
                                                     groups={0: "solids", 1: "stripes"})


def time_decisions(repeat: int) -> None:
    print(f"choose_shot: median of {repeat} runs after a warm-up (seconds of wall time, and of "
          "processor time: what an idle core takes), candidates")
    print(f"{'position':20} {'level':7} {'median':>7} {'min':>6} {'max':>6} {'cpu':>6} "
          f"{'cands':>5}  plan")
    for name, sc, pos, on, state in positions():
        args = (sc.table, sc.physics, sc.ids, pos, sc.radius, sc.mass, on, state)
        for level in LEVELS:
            walls, cpus = [], []
            for k in range(repeat + 1):
                t0, c0 = time.perf_counter(), time.process_time()
                plan = ai.choose_shot(*args, level=level)
                if k:
                    walls.append(time.perf_counter() - t0)
                    cpus.append(time.process_time() - c0)
            n = len(ai.score_shots(*args, level=level))
            print(f"{name:20} {level:7} {statistics.median(walls):7.3f} {min(walls):6.3f} "
                  f"{max(walls):6.3f} {statistics.median(cpus):6.3f} {n:5d}  {plan.note}")
    name, sc, pos, on, state = list(positions())[1]
    walls, cpus = [], []
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        ai.choose_placement(sc.table, sc.physics, sc.ids, pos, sc.radius, sc.mass, on,
                            replace(state, shooter=1), "anywhere")
        walls.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
    print(f"choose_placement (open table, anywhere): median {statistics.median(walls):.3f} s, "
          f"cpu {statistics.median(cpus):.3f} s")
    # On a break a level with several break spots tries its break from each (the slowest
    # decision of a game).
    name, sc, pos, on, state = next(positions())
    for level in LEVELS:
        walls, cpus = [], []
        for _ in range(repeat):
            t0, c0 = time.perf_counter(), time.process_time()
            ai.choose_placement(sc.table, sc.physics, sc.ids, pos, sc.radius, sc.mass, on,
                                state, "kitchen", level=level)
            walls.append(time.perf_counter() - t0)
            cpus.append(time.process_time() - c0)
        print(f"choose_placement (the break, {level}): median {statistics.median(walls):.3f} s, "
              f"cpu {statistics.median(cpus):.3f} s")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="benchmarks/ai.py", description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    if args.repeat < 1:
        ap.error("--repeat must be at least 1")
    time_decisions(args.repeat)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
