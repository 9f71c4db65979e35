"""Do the computer's safeties hide the table? Many defensive shots, measured one by one.

python benchmarks/safety.py [--tables N] [--levels easy,normal,hard,pro] [--strikes K]
                            [--seed S] [--candidates N] [--no-flukes] [--json] [--cases FILE]

Whole games (`termpool selfplay`) give a few safeties an hour; this asks each level for its
shot on N seeded mid-game 8-ball tables made for defence: groups assigned (the shooter has
solids), one to five balls of each group and the 8 scattered over the bed, kept only when
the shooter's best straight pot is poor: on odd tables, for a club player (blocked, long or
thin: a chance under 0.2 at `ai.LEAVE_SIGMA`); on even tables, for anyone (under 0.3 at an
aim error of 0.1 degrees: blocked, or no pocket to send it to). Where a level plays a safety
or a kick, it measures the opponent's best straight-pot chance (`ai.best_chance` at
selfplay's CHANCE_SIGMA; with ball in hand after a foul, from the best spot there):

- before: on the table as it lies;
- as meant: on the table the plan leaves when played exactly (what the level chose);
- as struck: on the tables it leaves struck K times with the level's errors (`ai.as_struck`,
  seeds drawn from the table's), which is what a game sees.

The figures are over the shots that passed the turn (a foul included, with the opponent's
chance from the best spot in hand); a shot that pots or ends the game is left out. Comparing
"as meant" with "before" judges the choice; "as struck" with "as meant", the execution. Pots
(most of them, on these tables, shots the batch saw drop a ball by a kiss or a bank) are
listed too: how many dropped as struck, and what a miss left. With --no-flukes such pots
count for nothing (`ai.scoring.FLUKE` = 0), so the levels play safe where they would have played
for one: many more safeties to measure. Deterministic for a seed (the times aside).
"""

from __future__ import annotations

import argparse
import json
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
from termpool.physics.engine import Engine  # noqa: E402
from termpool.physics.state import POCKETED  # noqa: E402
from termpool.rules.common import SOLIDS, STRIPES, State  # noqa: E402
from termpool.rules.events import summarize  # noqa: E402
from termpool.rules.referee import judge  # noqa: E402
from termpool.scene import load_scene  # noqa: E402
from termpool.selfplay.games import CHANCE_SIGMA  # noqa: E402

# A table is kept when the shooter's best pot is below this chance at this aim error
# (degrees): odd tables a poor pot for a club player, even ones a poor pot for anyone.
POOR = {1: (0.2, ai.LEAVE_SIGMA), 0: (0.3, 0.1)}
GAP = 0.005  # m between balls placed at random
STATE = State(mode="8ball", groups={0: "solids", 1: "stripes"})


def table_for(sc, rng: np.random.Generator):
    """A random mid-game layout: (pos, on_table, state) with the shooter on solids."""
    r = float(sc.radius[0])
    count = {"solids": int(rng.integers(1, 6)), "stripes": int(rng.integers(1, 6))}
    balls = ["cue", "8", *rng.choice(SOLIDS, count["solids"], replace=False).tolist(),
             *rng.choice(STRIPES, count["stripes"], replace=False).tolist()]
    pos = np.full((len(sc.ids), 2), np.nan)
    placed: list[np.ndarray] = []
    for b in balls:
        while True:
            xy = np.array([rng.uniform(r + 0.005, sc.table.length - r - 0.005),
                           rng.uniform(r + 0.005, sc.table.width - r - 0.005)])
            if not sc.table.on_bed(float(xy[0]), float(xy[1]), r):
                continue
            if (np.hypot(*(sc.table.hole_c - xy).T) < 3 * r).any():  # not in a jaw
                continue
            if all(float(np.linalg.norm(xy - p)) > 2 * r + GAP for p in placed):
                break
        placed.append(xy)
        pos[sc.index(b)] = xy
    on = np.array([b in balls for b in sc.ids])
    down = tuple(b for b in (*SOLIDS, *STRIPES) if b not in balls)
    return pos, on, replace(STATE, pocketed=down)


def play(sc, pos, on, plan: ai.Plan, state: State):
    """Strike `plan` on one table to rest; returns (outcome, next state, pos, on)."""
    keep = np.nonzero(on)[0]
    ids = [sc.ids[k] for k in keep]
    vel, w = np.zeros((len(ids), 2)), np.zeros((len(ids), 3))
    c = ids.index("cue")
    vel[c], w[c] = strike(plan.speed, plan.angle, plan.side, plan.top, float(sc.radius[0]))
    eng = Engine(sc.table, sc.physics, pos[keep], vel, w, sc.radius[keep], sc.mass[keep],
                 record=True)
    eng.run_events()
    summary = summarize(eng.log[0], ids, is_break=False)
    out, nxt = judge(replace(state, called=plan.called), summary)
    pos, on = pos.copy(), on.copy()
    pos[keep] = eng.pos[0]
    on[keep] = eng.state[0] != POCKETED
    return out, nxt, pos, on


def chance(sc, pos, on, state: State, area: str | None = None,
           sigma: float = CHANCE_SIGMA) -> float:
    if area is not None:  # ball in hand: where the cue ball lies does not matter
        pos, on = pos.copy(), on.copy()
        on[sc.index("cue")] = True
        pos[sc.index("cue")] = sc.table.head_spot
    return ai.best_chance(sc.table, sc.physics, sc.ids, pos, sc.radius, sc.mass, on, state,
                          area=area, sigma=sigma)


def outcome(sc, pos, on, plan: ai.Plan, state: State) -> dict:
    """What one strike of `plan` did: "turn" ("kept", "passed", "won", "lost"), "foul",
    "dropped" (a pot: its ball went into its pocket) and "after" (the opponent's chance when
    the turn passed, else None)."""
    out, nxt, pos2, on2 = play(sc, pos, on, plan, state)
    dropped = None
    if plan.kind in ("pot", "combo"):
        keep = [sc.ids[k] for k in np.nonzero(on)[0]]
        dropped = plan.ball in keep and not on2[sc.index(plan.ball)]
    turn = ("won" if out.winner == state.shooter else "lost" if out.winner is not None
            else "kept" if out.continue_turn else "passed")
    after = None
    if turn == "passed":
        area = out.ball_in_hand_area if out.ball_in_hand else None
        after = chance(sc, pos2, on2, nxt, area)
    return {"turn": turn, "foul": out.foul is not None, "dropped": dropped, "after": after}


def measure(args) -> dict:
    sc = load_scene({"table": "9ft", "balls": "8ball"})
    levels = args.levels
    cases: list[dict] = []
    kept = tried = 0
    t0 = time.perf_counter()
    seeds = np.random.SeedSequence(args.seed).spawn(args.tables * 100)
    k = 0
    while kept < args.tables:
        rng = np.random.default_rng(seeds[k])
        k += 1
        tried += 1
        pos, on, state = table_for(sc, rng)
        most, sigma = POOR[(kept + 1) % 2]
        if chance(sc, pos, on, state, sigma=sigma) >= most:
            continue
        kept += 1
        before = chance(sc, pos, on, replace(state, shooter=1))
        base = (sc.table, sc.physics, sc.ids, pos, sc.radius, sc.mass, on, state)
        for level in levels:
            t1 = time.process_time()
            plan = ai.choose_shot(*base, level=level, seed=kept,
                                  max_candidates=args.candidates)
            cpu = time.process_time() - t1
            seeds_struck = rng.integers(2**31, size=args.strikes)
            cases.append({
                "table": kept, "level": level, "kind": plan.kind, "note": plan.note,
                "cpu_s": cpu, "before": before, "plan": list(plan[:4]),
                "meant": outcome(sc, pos, on, plan, state),
                "struck": [outcome(sc, pos, on, ai.as_struck(plan, level, int(s)), state)
                           for s in seeds_struck]})
        if not args.json:
            sys.stderr.write(f"\rtables {kept}/{args.tables}")
    if not args.json:
        sys.stderr.write("\n")
    return {"cases": cases, "tables": kept, "tried": tried,
            "wall_s": time.perf_counter() - t0}


def _mean(xs) -> float | None:
    return statistics.fmean(xs) if xs else None


KINDS = {"safety": ("safety",), "kick": ("kick",), "pot": ("pot", "combo")}


def summary(res: dict, levels) -> dict:
    """Per level and kind of shot: how many, the opponent's chance before, and after as meant
    and as struck (over the shots that passed the turn: a foul included, a pot or an end of
    the game left out), the share that lowered it, the fouls; for pots, how many dropped."""
    out = {}
    for level in levels:
        rows = [c for c in res["cases"] if c["level"] == level]
        fig: dict = {"decisions": len(rows),
                     "cpu_s": statistics.median([c["cpu_s"] for c in rows]) if rows else None}
        for name, kinds in KINDS.items():
            mine = [c for c in rows if c["kind"] in kinds]
            meant = [(c["before"], c["meant"]) for c in mine if c["meant"]["turn"] == "passed"]
            every = [(c["before"], s) for c in mine for s in c["struck"]]
            struck = [(b, s) for b, s in every if s["turn"] == "passed"]
            fig[name] = {
                "count": len(mine),
                "before_zero": sum(c["before"] == 0 for c in mine),
                "before": _mean([c["before"] for c in mine]),
                "meant_passed": len(meant),
                "meant_after": _mean([s["after"] for _, s in meant]),
                "meant_lowered": _share(sum(s["after"] < b for b, s in meant), len(meant)),
                "meant_fouls": sum(s["foul"] for _, s in meant),
                "strikes": len(every),
                "struck_passed": len(struck),
                "struck_before": _mean([b for b, _ in struck]),
                "struck_after": _mean([s["after"] for _, s in struck]),
                "struck_lowered": _share(sum(s["after"] < b for b, s in struck), len(struck)),
                "struck_fouls": _share(sum(s["foul"] for _, s in every), len(every)),
                "struck_dropped": _share(sum(bool(s["dropped"]) for _, s in every), len(every))
                if name == "pot" else None,
            }
        out[level] = fig
    return out


def _share(n: float, d: float) -> float | None:
    return None if d == 0 else n / d


def _f(x, fmt=".2f") -> str:
    return "-" if x is None else format(x, fmt)


def print_table(fig: dict, res: dict, args) -> None:
    print(f"safety benchmark: {res['tables']} tables (of {res['tried']} drawn), seed "
          f"{args.seed}, {args.strikes} strikes each, {args.candidates} candidates"
          f"{', no flukes' if args.no_flukes else ''}, {res['wall_s']:.0f} s")
    print(f"the opponent's best straight-pot chance (aim error {CHANCE_SIGMA:g} deg) before "
          "the shot, and after it where the turn passed: as meant, and as struck "
          f"{args.strikes} times; low%: share lowered")
    print(f"{'level':7} {'kind':6} {'n':>4} {'b=0':>4} {'before':>6} {'meant':>6} {'low%':>5} "
          f"{'foul':>4} {'passed':>6} {'struck':>6} {'low%':>5} {'foul%':>5} {'drop%':>5} "
          f"{'cpu s':>6}")
    for level, f in fig.items():
        for kind in KINDS:
            k = f[kind]
            print(f"{level:7} {kind:6} {k['count']:4d} {k['before_zero']:4d} "
                  f"{_f(k['before']):>6} {_f(k['meant_after']):>6} {_pct(k['meant_lowered'])} "
                  f"{k['meant_fouls']:4d} {k['struck_passed']:6d} {_f(k['struck_after']):>6} "
                  f"{_pct(k['struck_lowered'])} {_pct(k['struck_fouls'])} "
                  f"{_pct(k['struck_dropped'])} {_f(f['cpu_s'], '.3f'):>6}")


def _pct(x: float | None) -> str:
    return f"{'-' if x is None else format(100 * x, '.0f'):>5}"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="benchmarks/safety.py", description=__doc__.split("\n")[0])
    ap.add_argument("--tables", type=int, default=100)
    ap.add_argument("--levels", default=",".join(ai.LEVELS))
    ap.add_argument("--strikes", type=int, default=4)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--candidates", type=int, default=256)
    ap.add_argument("--json", action="store_true", help="print the figures as JSON")
    ap.add_argument("--cases", metavar="FILE", help="write every case as JSON to FILE")
    ap.add_argument("--no-flukes", action="store_true",
                    help="value a pot the batch did not aim at (a kiss, a bank) as nothing, "
                         "so that the levels play safe where they would play for one")
    args = ap.parse_args(argv)
    args.levels = [s.strip() for s in args.levels.split(",")]
    for level in args.levels:
        if level not in ai.LEVELS:
            ap.error(f"--levels: '{level}' is not a level (use {', '.join(ai.LEVELS)})")
    if args.tables < 1 or args.strikes < 1:
        ap.error("--tables and --strikes must be at least 1")
    if args.no_flukes:
        ai.scoring.FLUKE = 0.0
    res = measure(args)
    fig = summary(res, args.levels)
    if args.cases:
        with open(args.cases, "w") as fh:
            json.dump(res["cases"], fh)
    if args.json:
        print(json.dumps({"tables": res["tables"], "tried": res["tried"], "seed": args.seed,
                          "strikes": args.strikes, "candidates": args.candidates,
                          "no_flukes": args.no_flukes,
                          "wall_s": res["wall_s"], "levels": fig}, indent=1))
    else:
        print_table(fig, res, args)
    return 0 if math.isfinite(res["wall_s"]) else 1


if __name__ == "__main__":
    raise SystemExit(main())
