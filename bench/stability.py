"""`termpool bench stability`: the stiff and extreme cases, pass or fail.

    termpool bench stability [--json] [--quick] [--case TEXT ...]

Runs every case of `bench/stability_cases.py` (the same scenes and limits as
tests/test_stability.py) twice and prints one row per case: its group, name, PASS or FAIL, how
many checks held, the figure that decided it and the wall time of one run. Every case checks
the physics laws on top of its own figures: finite numbers, no overlap beyond a micrometre,
no ball into or through a cushion (pocketed balls excepted), no rise of kinetic energy, bounded
event passes, at rest within a bound (or the stated run length), and the two runs bit-identical.
--quick runs the frictionless long run for QUICK_LONG_RUN_S instead of LONG_RUN_S simulated
seconds. The exit status is 1 when any case fails.
"""

from __future__ import annotations

import sys
import time

from bench.common import PROG, BenchParser, machine_info, machine_lines
from bench.stability_cases import (
    CASES,
    ENERGY_TOL,
    LONG_RUN_S,
    OVERLAP_TOL,
    PASS_LIMIT,
    QUICK_LONG_RUN_S,
    Case,
    run_case,
)
from termpool.files import json_safe, to_json
from termpool.text import say

LAWS = (
    "finite numbers",
    f"ball-ball overlap <= {OVERLAP_TOL:g} m",
    f"depth into a cushion or jaw <= {OVERLAP_TOL:g} m (pocketed balls excepted)",
    f"kinetic energy rise <= {ENERGY_TOL:g} relative between checks",
    f"event passes < {PASS_LIMIT} (long run: 10 per simulated second)",
    "at rest within the rest bound",
    "2 runs bit-identical",
)


def select(patterns: list[str] | None) -> list[Case]:
    """The cases whose name or group contains one of the patterns (all without patterns)."""
    if not patterns:
        return list(CASES)
    pats = [p.lower() for p in patterns]
    return [c for c in CASES if any(p in c.name.lower() or p == c.group for p in pats)]


def stability_figures(cases: list[Case], quick: bool) -> dict:
    rows = []
    t0 = time.perf_counter()
    for case in cases:
        figure, ok, details = run_case(case, quick)
        rows.append({"case": case.name, "group": case.group, "ok": ok, "figure": figure,
                     **details})
    wall = time.perf_counter() - t0
    passed = sum(r["ok"] for r in rows)

    def worst(key: str) -> dict:
        r = max(rows, key=lambda r: r[key])
        return {"value": r[key], "case": r["case"]}

    return {
        "quick": quick,
        "long_run_s": QUICK_LONG_RUN_S if quick else LONG_RUN_S,
        "laws": list(LAWS),
        "limits": {"overlap_m": OVERLAP_TOL, "cushion_m": OVERLAP_TOL,
                   "energy_rise": ENERGY_TOL, "passes": PASS_LIMIT},
        "cases": rows,
        "passed": passed,
        "failed": len(rows) - passed,
        "all_passed": passed == len(rows),
        "wall_s": wall,
        "worst": {k: worst(k) for k in ("overlap_m", "cushion_m", "energy_rise", "max_passes")},
        "looks": sum(r["looks"] for r in rows),
        "machine": machine_info(),
    }


def format_stability(r: dict) -> str:
    mode = f", long run {r['long_run_s']:g} s" + (" (--quick)" if r["quick"] else "")
    lines = [
        f"termpool bench stability: {len(r['cases'])} stiff and extreme cases, each run "
        f"twice{mode}",
        "laws checked in every case: " + "; ".join(r["laws"]),
        "",
    ]
    table = [("group", "case", "result", "checks", "figure that decided it", "wall")]
    for c in r["cases"]:
        n_ok = sum(ch["ok"] for ch in c["checks"])
        table.append((c["group"], c["case"], "PASS" if c["ok"] else "FAIL",
                      f"{n_ok}/{len(c['checks'])}", c["figure"], f"{1e3 * c['wall_s']:.1f} ms"))
    widths = [max(len(row[k]) for row in table) for k in range(6)]
    for row in table:
        cells = [row[k].ljust(widths[k]) for k in range(5)] + [row[5].rjust(widths[5])]
        lines.append("  ".join(cells).rstrip())
    w = r["worst"]
    lines += [
        "",
        f"{len(r['cases'])} cases: {r['passed']} PASS, {r['failed']} FAIL; "
        f"{r['wall_s']:.1f} s (every case twice), laws checked at {r['looks']} states",
        f"worst of all cases: overlap {w['overlap_m']['value']:.2g} m ({w['overlap_m']['case']}); "
        f"cushion depth {w['cushion_m']['value']:.2g} m ({w['cushion_m']['case']}); "
        f"energy rise {w['energy_rise']['value']:.2g} ({w['energy_rise']['case']}); "
        f"passes {w['max_passes']['value']} ({w['max_passes']['case']})",
    ]
    failed = [c for c in r["cases"] if not c["ok"]]
    for c in failed:
        lines.append(f"FAIL {c['case']}:")
        lines += [f"    {ch['figure']}" for ch in c["checks"] if not ch["ok"]]
    m = r["machine"]
    lines += [
        "",
        *machine_lines(m),
    ]
    return "\n".join(lines) + "\n"


def main(argv: list[str]) -> int:
    p = BenchParser(
        prog=f"{PROG} stability",
        description=(
            "Run the stiff and extreme cases of the physics core (tiny and huge speeds, steps "
            "and frictions, restitution 0 and 1, 1000:1 masses, clusters, absurd spin, a long "
            "frictionless run) twice each, check the laws in every one, and print PASS or "
            "FAIL with the deciding figure."
        ),
    )
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--quick", action="store_true",
                   help=f"run the frictionless long run for {QUICK_LONG_RUN_S:g} simulated "
                        f"seconds instead of {LONG_RUN_S:g}")
    p.add_argument("--case", metavar="TEXT", action="append",
                   help="only the cases whose name contains TEXT, or whose group is TEXT "
                        "(repeatable)")
    args = p.parse_args(argv)
    cases = select(args.case)
    if not cases:
        groups = ", ".join(dict.fromkeys(c.group for c in CASES))
        say(f"bench stability: no case matches {', '.join(args.case)} (groups: {groups})")
        return 2
    result = stability_figures(cases, args.quick)
    if args.json:
        sys.stdout.write(to_json(json_safe(result)) + "\n")
    else:
        sys.stdout.write(format_stability(result))
    sys.stdout.flush()
    return 0 if result["all_passed"] else 1
