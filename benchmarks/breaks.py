"""How often a level's break keeps the turn, by where it breaks from and how hard.

python benchmarks/breaks.py [--samples N] [--levels pro,hard] [--spots 0.275,0.5]
                            [--speeds 7,8,9] [--table 9ft]

For each level, spot (the cue ball on the head string, at this share of the width from the
side cushion) and speed (m/s, centre ball at the apex), the break is struck N times, each on
a different rack (`Match` seeds 0..N-1: the racks differ in the numbers on the balls, and so
in the order the engine meets their contacts, which a frozen rack is sensitive to) with the
level's errors (`ai.as_struck`, seeds 0..N-1), all in one batch, and the referee's verdict
counted: breaks that keep the turn (a ball pocketed, no foul) and scratches.

Then, with --played N, each level breaks N racks as it does in a game: it picks its spot
(`ai.choose_placement`) and its break (`ai.choose_shot`) on that rack, and strikes it with its
errors (`ai.as_struck`); the same count. A level with several break spots tries its break from
each on the rack in front of it, which a fixed spot cannot match.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time

if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

import numpy as np  # noqa: E402

from termpool import ai  # noqa: E402
from termpool.game import Match  # noqa: E402
from termpool.physics.cue import strike  # noqa: E402
from termpool.physics.engine import Engine  # noqa: E402
from termpool.rules.common import State  # noqa: E402
from termpool.rules.events import summarize  # noqa: E402
from termpool.rules.referee import judge  # noqa: E402


def breaks(level: str, spot: float, speed: float, samples: int, table: str) -> tuple[int, int]:
    """(breaks that kept the turn, scratches) of `samples` strikes."""
    racks = [Match("8ball", table=table, seed=k) for k in range(samples)]
    m = racks[0]
    cue = m.ids.index("cue")
    pos = np.stack([r.pos for r in racks])
    pos[:, cue] = (m.table.head_spot[0], spot * m.table.width)
    apex = min((k for k in range(len(m.ids)) if k != cue), key=lambda k: pos[0, k, 0])
    d = pos[0, apex] - pos[0, cue]
    plan = ai.Plan(speed, math.degrees(math.atan2(d[1], d[0])), 0.0, 0.0, None, 0.0, "break",
                   "break")
    n = len(m.ids)
    vel, w = np.zeros((samples, n, 2)), np.zeros((samples, n, 3))
    for k in range(samples):
        s = ai.as_struck(plan, level, k)
        vel[k, cue], w[k, cue] = strike(s.speed, s.angle, s.side, s.top, float(m.radius[cue]))
    eng = Engine(m.table, m.physics, pos, vel, w, m.radius, m.mass, record=True)
    eng.run_events(duration=ai.SIM_SECONDS)
    kept = scratched = 0
    for b in range(samples):
        summary = summarize(eng.events[b], m.ids, is_break=True)
        out, _ = judge(State(mode="8ball", is_break=True), summary)
        kept += out.continue_turn
        scratched += summary.scratch
    return kept, scratched


def played(level: str, racks: int, table: str) -> tuple[int, int]:
    """(breaks that kept the turn, scratches) of the level's own breaks on `racks` racks."""
    from termpool.game import Shot

    kept = scratched = 0
    for k in range(racks):
        m = Match("8ball", table=table, seed=k)
        args = (m.table, m.physics, m.ids, m.pos, m.radius, m.mass, m.on_table)
        m.place_cue(*ai.choose_placement(*args, m.state, "kitchen", level=level, seed=k))
        plan = ai.as_struck(ai.choose_shot(*args, m.state, level=level, seed=k), level, k)
        out = m.begin(Shot(plan.speed, plan.angle, plan.side, plan.top)).finish()
        kept += out.continue_turn
        scratched += out.foul == "scratch"
    return kept, scratched


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="benchmarks/breaks.py", description=__doc__.split("\n")[0])
    ap.add_argument("--samples", type=int, default=32)
    ap.add_argument("--levels", default=",".join(ai.LEVELS))
    ap.add_argument("--spots", default="0.16,0.275,0.5")
    ap.add_argument("--speeds", default="7,8,9")
    ap.add_argument("--table", default="9ft", choices=("7ft", "8ft", "9ft"))
    ap.add_argument("--played", type=int, default=0, metavar="N")
    args = ap.parse_args(argv)
    levels = args.levels.split(",")
    if args.samples < 1 or args.played < 0 or any(lv not in ai.LEVELS for lv in levels):
        ap.error(f"--samples must be at least 1, --played at least 0 and --levels among "
                 f"{', '.join(ai.LEVELS)}")
    spots = [float(v) for v in args.spots.split(",")]
    speeds = [float(v) for v in args.speeds.split(",")]
    t0 = time.perf_counter()
    print(f"8-ball breaks on a {args.table} table, {args.samples} strikes each with the level's "
          "errors: kept the turn / scratched")
    print(f"{'level':7} {'spot':>6} " + " ".join(f"{f'{v:g} m/s':>10}" for v in speeds))
    for level in levels:
        for spot in spots:
            cells = []
            for speed in speeds:
                kept, scratched = breaks(level, spot, speed, args.samples, args.table)
                cells.append(f"{kept:>3}/{args.samples} {scratched:>2}s".rjust(10))
            print(f"{level:7} {spot:6.3f} " + " ".join(cells))
    for level in levels if args.played else ():
        kept, scratched = played(level, args.played, args.table)
        print(f"{level:7} as it breaks in a game: kept the turn {kept}/{args.played}, "
              f"scratched {scratched}")
    print(f"({time.perf_counter() - t0:.0f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
