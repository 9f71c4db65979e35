"""Decision time of the computer opponent (termpool.ai), and how well it plays.

python benchmarks/ai.py [--repeat N] [--games N]

For three positions (the 8-ball break, an open table after a real break, an end game on the
8) and each level, prints the median wall time of `choose_shot` over N runs (after one
warm-up), the number of candidates simulated, and what the chosen shot does. Also times
`choose_placement` (ball in hand anywhere, on the open table). Target: under 1.5 s a decision.

With --games N, the AI plays N racks of 9-ball against itself per level (the breaker's cue
ball moved along the head string from rack to rack) and prints how the racks went: racks won
from the break without the opponent shooting (run-outs), fouls and shots per rack.
"""

from __future__ import annotations

import argparse
import math
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
    summary = summarize(eng.events[0], ids, is_break=state.is_break)
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
    print(f"choose_shot: median of {repeat} runs after a warm-up (seconds), candidates")
    print(f"{'position':20} {'level':7} {'median':>7} {'min':>6} {'max':>6} {'cands':>5}  plan")
    for name, sc, pos, on, state in positions():
        args = (sc.table, sc.physics, sc.ids, pos, sc.radius, sc.mass, on, state)
        for level in LEVELS:
            walls = []
            for k in range(repeat + 1):
                t0 = time.perf_counter()
                plan = ai.choose_shot(*args, level=level)
                if k:
                    walls.append(time.perf_counter() - t0)
            n = len(ai.score_shots(*args, level=level))
            print(f"{name:20} {level:7} {statistics.median(walls):7.3f} {min(walls):6.3f} "
                  f"{max(walls):6.3f} {n:5d}  {plan.note}")
    name, sc, pos, on, state = list(positions())[1]
    walls = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        ai.choose_placement(sc.table, sc.physics, sc.ids, pos, sc.radius, sc.mass, on,
                            replace(state, shooter=1), "anywhere")
        walls.append(time.perf_counter() - t0)
    print(f"choose_placement (open table, anywhere): median {statistics.median(walls):.3f} s")


def play_racks(games: int, level: str) -> dict:
    """The AI against itself at one level, 9-ball, `games` racks."""
    runouts = wins0 = fouls = shots = 0
    walls = []
    for g in range(games):
        sc, pos, on = _rack("9ball")
        pos[0, 1] += 0.3 * math.sin(1.7 * g)  # a different break each rack
        state = State(mode="9ball", is_break=True)
        opponent_shot = False
        for turn in range(80):
            args = (sc.table, sc.physics, sc.ids, pos, sc.radius, sc.mass, on, state)
            t0 = time.perf_counter()
            plan = ai.choose_shot(*args, level=level, seed=1000 * g + turn)
            walls.append(time.perf_counter() - t0)
            summary, out, nxt, pos, on = _play(sc, pos, on, plan, state)
            shots += 1
            fouls += out.foul is not None
            opponent_shot |= state.shooter == 1
            if out.winner is not None:
                wins0 += out.winner == 0
                runouts += out.winner == 0 and not opponent_shot
                break
            for b in out.respot:  # the 9 back on the foot spot (or just behind it)
                k = sc.index(b)
                spot = np.array(sc.table.foot_spot)
                while any(on[j] and np.linalg.norm(pos[j] - spot) < 2 * sc.radius[j]
                          for j in range(len(sc.ids)) if j != k):
                    spot[0] += 0.01
                pos[k], on[k] = spot, True
            state = replace(nxt, push_out="none")
            if out.ball_in_hand:
                on[0] = True
                pos[0] = ai.choose_placement(sc.table, sc.physics, sc.ids, pos, sc.radius,
                                             sc.mass, on, state, "anywhere", level=level,
                                             seed=g)
    return {"racks": games, "breaker_won": wins0, "runouts": runouts,
            "fouls_per_rack": fouls / games, "shots_per_rack": shots / games,
            "median_decision_s": statistics.median(walls)}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="benchmarks/ai.py", description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--games", type=int, default=0)
    args = ap.parse_args(argv)
    if args.repeat < 1 or args.games < 0:
        ap.error("--repeat must be at least 1 and --games at least 0")
    time_decisions(args.repeat)
    for level in LEVELS if args.games else ():
        r = play_racks(args.games, level)
        print(f"9-ball self-play, {level}: {r['racks']} racks, breaker won {r['breaker_won']}, "
              f"run-outs {r['runouts']}, fouls/rack {r['fouls_per_rack']:.2f}, "
              f"shots/rack {r['shots_per_rack']:.1f}, "
              f"median decision {r['median_decision_s']:.3f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
