"""The closed-form section of `termpool bench accuracy`: every scheme against answers derived
on paper from the model's equations (closed_form.py, scenes in closed_cases.py), not against
the engine.

For each case the engine's reference driver `run_events()` and then each scheme at each dt run
the case's scene from the shot until every ball is at rest (or MAX_TIME). Positions are
compared at step ends (every few steps below 1/COMPARE_HZ s, and the last) with the closed
form at exactly those times; the final positions with the closed form's; and every event of
the closed form (contacts and, for the engine, the slide-to-roll and stop transitions) with
the run's event of the same type and balls, in order of occurrence. Extra events are the
run's events of those types that the closed form has no counterpart for (the cradle's push
is one body in the closed form, many slow contacts in the engine).

The seed-style schemes (`naive`, `substep`) step a different model, no sliding and no spin:
they are measured against the engine's model's closed form (`model`: mostly the model's
difference) and against the closed form of their own model (`own`: their stepping error).
`engine` and `euler` step the engine's model: only `model` applies.
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Sequence

import numpy as np

from bench import closed_cases, closed_form
from bench.schemes import (
    COMPARE_HZ,
    CONTACTS,
    MAX_TIME,
    SUBSTEPS,
    all_at_rest,
    fmt_dt,
    fmt_mm,
    make_sim,
    positions,
    table_lines,
)
from termpool.scene import Scene, load_scene

SEED_SCHEMES = ("naive", "substep")  # they step the seed game's model


def pick(names: list[str] | None) -> list[closed_cases.Case]:
    """The cases named (all when None, none for an empty list)."""
    every = closed_cases.cases()
    if names is None:
        return every
    by_name = {c.name: c for c in every}
    return [by_name[n] for n in names]


def _log(sim) -> list[dict]:
    log = sim.events[0] if sim.events and isinstance(sim.events[0], list) else sim.events
    return sorted(log, key=lambda e: e["t"])


def match_events(expected: list[dict], got: list[dict], types: set[str]) -> dict:
    """Pair each expected event with the run's event of the same type and ball ids, in order
    of occurrence: matched and expected counts, extra events of those types, and the largest
    time error of the matched ones."""
    exp = [e for e in expected if e["type"] in types]
    pool: dict[tuple, list[float]] = {}
    for e in got:
        if e["type"] in types:
            pool.setdefault((e["type"], tuple(e["i"])), []).append(float(e["t"]))
    seen: dict[tuple, int] = {}
    worst, matched = None, 0
    for e in exp:
        key = (e["type"], tuple(e["i"]))
        k = seen.get(key, 0)
        seen[key] = k + 1
        times = pool.get(key, [])
        if k < len(times):
            matched += 1
            err = abs(times[k] - e["t"])
            worst = err if worst is None else max(worst, err)
    total = sum(len(v) for v in pool.values())
    return {"matched": matched, "expected": len(exp), "extra": total - matched,
            "event_ms": None if worst is None else 1e3 * worst}


def errors(answer: closed_form.Answer, times: np.ndarray, pos: np.ndarray, final: np.ndarray,
           events: list[dict], types: set[str]) -> dict:
    """A run's errors against one closed-form answer; positions pos (M, N, 2) at times."""
    path = 0.0
    if len(times):
        d = pos - answer.positions(times)
        path = 1e3 * float(np.sqrt((d * d).sum(axis=2)).max())
    d = final - answer.final
    rest = 1e3 * float(np.sqrt((d * d).sum(axis=1)).max())
    return {"path_mm": path, "rest_mm": rest, "err_mm": max(path, rest),
            **match_events(answer.events, events, types)}


def within(case: closed_cases.Case, e: dict) -> bool:
    """Whether a run's errors against the model's answer are within the case's tolerance,
    with every closed-form event found."""
    return (e["err_mm"] <= case.tol_mm and e["matched"] == e["expected"]
            and (e["event_ms"] or 0.0) <= case.tol_ms)


def reference(case: closed_cases.Case, scene: Scene, timed: bool = True) -> dict:
    """The engine's event-to-event run: its errors and the case's facts measured on it; with
    `timed`, the wall time of a second run without sampling (the first warms up)."""
    n = len(scene.ids)
    eng = make_sim("engine", scene)
    samples = eng.run_events(sample_hz=COMPARE_HZ)
    events = _log(eng)
    final = positions(eng, n).copy()
    wall = None
    if timed:
        t0 = time.perf_counter()
        make_sim("engine", scene).run_events()
        wall = time.perf_counter() - t0
    times = np.array([s[0] for s in samples])
    pos = np.array([np.asarray(s[1]).reshape(-1, n, 2)[0] for s in samples])
    model = case.model
    err = errors(model, times, pos, final, events, {e["type"] for e in model.events})
    facts = []
    for f in case.facts:
        want = f.measure(model.events, model.start, model.final)
        got = f.measure(events, model.start, final)
        facts.append({"label": f.label, "unit": f.unit, "closed_form": want, "engine": got,
                      "error": got - want})
    return {"time": float(eng.time), "wall_s": wall, "passes": int(eng.passes),
            "events": len(events), **err, "within": within(case, err), "facts": facts}


def run_scheme(case: closed_cases.Case, scene: Scene, scheme: str, dt: float) -> dict:
    n = len(scene.ids)
    stride = max(1, int(np.ceil(1.0 / (COMPARE_HZ * dt) - 1e-9)))
    t0 = time.perf_counter()
    sim = make_sim(scheme, scene)
    wall = time.perf_counter() - t0
    times, pos = [], []
    k = 0
    while not all_at_rest(sim) and sim.time < MAX_TIME:
        t1 = time.perf_counter()
        sim.step(dt)
        wall += time.perf_counter() - t1
        k += 1
        if k % stride == 0:
            times.append(sim.time)
            pos.append(positions(sim, n).copy())
    final = positions(sim, n).copy()
    if not times or times[-1] != sim.time:
        times.append(sim.time)
        pos.append(final)
    times_a, pos_a = np.array(times), np.array(pos)
    events = _log(sim)
    model_types = {e["type"] for e in case.model.events}
    if scheme != "engine":
        model_types &= set(CONTACTS)
    row = {
        "scheme": scheme, "dt": dt, "wall_s": wall, "steps": int(sim.steps),
        "sim_s": float(sim.time), "at_rest": all_at_rest(sim),
        "model": errors(case.model, times_a, pos_a, final, events, model_types),
        "own": None,
    }
    if scheme in SEED_SCHEMES:
        own_types = {e["type"] for e in case.seed.events} & set(CONTACTS)
        row["own"] = errors(case.seed, times_a, pos_a, final, events, own_types)
    if scheme == "engine":
        row["within"] = within(case, row["model"])
    return row


def run_case(case: closed_cases.Case, dts: Sequence[float], schemes: Sequence[str]) -> dict:
    scene = load_scene(case.scene)
    ref = reference(case, scene)
    finest = min(dts)
    rows = []
    for scheme in schemes:
        for dt in dts:
            if scheme == "substep" and dt / SUBSTEPS < finest * (1 - 1e-9):
                continue
            rows.append(run_scheme(case, scene, scheme, dt))
    return {
        "name": case.name,
        "description": case.description,
        "balls": len(scene.ids),
        "scene": case.scene,
        "tolerance": {"mm": case.tol_mm, "ms": case.tol_ms, "why": case.tol_why},
        "reference": ref,
        "rows": rows,
    }


def summarize(cases: list[dict]) -> list[dict]:
    """Per (scheme, dt), over the cases: total wall time, median and largest error against
    the model's closed form and (seed-style schemes) their own."""
    groups: dict[tuple[str, float], list[dict]] = {}
    for c in cases:
        for r in c["rows"]:
            groups.setdefault((r["scheme"], r["dt"]), []).append(r)
    out = []
    for (scheme, dt), rows in groups.items():
        model = [r["model"]["err_mm"] for r in rows]
        own = [r["own"]["err_mm"] for r in rows if r["own"] is not None]
        out.append({
            "scheme": scheme, "dt": dt, "cases": len(rows),
            "wall_s": sum(r["wall_s"] for r in rows),
            "steps": sum(r["steps"] for r in rows),
            "model_median_mm": statistics.median(model), "model_max_mm": max(model),
            "own_median_mm": statistics.median(own) if own else None,
            "own_max_mm": max(own) if own else None,
            "within": sum(1 for r in rows if r.get("within")) if scheme == "engine" else None,
        })
    return out


def closed_figures(names: list[str] | None, dts: Sequence[float],
                   schemes: Sequence[str]) -> dict:
    cases = [run_case(c, dts, schemes) for c in pick(names)]
    return {"cases": cases, "summary": summarize(cases)}


# ------------------------------------------------------------------------------ output


def _ms(x: float | None) -> str:
    return "-" if x is None else fmt_mm(x)


def _events(e: dict) -> str:
    return f"{e['matched']}/{e['expected']}" + (f" +{e['extra']}" if e["extra"] else "")


def _num(x: float) -> str:
    return f"{x:.10g}"


def format_case(c: dict) -> list[str]:
    ref, tol = c["reference"], c["tolerance"]
    lines = [
        f"{c['name']} ({c['balls']} ball{'s' if c['balls'] != 1 else ''}): {c['description']}",
        f"  engine tolerance {tol['mm']:.3g} mm, {tol['ms']:.3g} ms: {tol['why']}",
        f"  run_events(): {ref['time']:.3f} s simulated, {ref['events']} events, "
        f"{ref['passes']} passes, {1e3 * ref['wall_s']:.1f} ms; path {fmt_mm(ref['path_mm'])} "
        f"mm, rest {fmt_mm(ref['rest_mm'])} mm, events {_ms(ref['event_ms'])} ms "
        f"({_events(ref)}): {'within' if ref['within'] else 'OUTSIDE'} tolerance",
    ]
    facts = [[f"{f['label']}" + (f" ({f['unit']})" if f["unit"] else ""), _num(f["closed_form"]),
              _num(f["engine"]), f"{f['error']:.1e}"] for f in ref["facts"]]
    lines += table_lines(["fact", "closed form", "engine", "error"], facts)
    header = ["scheme", "dt", "wall ms", "steps", "path mm", "rest mm", "event ms", "events",
              "| own: path mm", "rest mm", "event ms", "events"]
    rows = []
    for r in c["rows"]:
        m, o = r["model"], r["own"]
        rest = fmt_mm(m["rest_mm"]) + ("" if r["at_rest"] else "*")
        row = [r["scheme"], fmt_dt(r["dt"]), f"{1e3 * r['wall_s']:.1f}", str(r["steps"]),
               fmt_mm(m["path_mm"]), rest, _ms(m["event_ms"]), _events(m)]
        if o is None:
            row += ["", "", "", ""]
        else:
            row += [fmt_mm(o["path_mm"]), fmt_mm(o["rest_mm"]), _ms(o["event_ms"]), _events(o)]
        rows.append(row)
    return lines + table_lines(header, rows, left=(0, 7, 11))


def format_summary(summary: list[dict], n: int) -> list[str]:
    header = ["scheme", "dt", "wall s", "steps", "median mm", "max mm", "| own: median mm",
              "max mm", "within tol"]
    rows = []
    for s in summary:
        own = s["own_median_mm"] is not None
        rows.append([s["scheme"], fmt_dt(s["dt"]), f"{s['wall_s']:.3f}", str(s["steps"]),
                     fmt_mm(s["model_median_mm"]), fmt_mm(s["model_max_mm"]),
                     fmt_mm(s["own_median_mm"]) if own else "",
                     fmt_mm(s["own_max_mm"]) if own else "",
                     f"{s['within']}/{s['cases']}" if s["within"] is not None else ""])
    return [f"closed-form summary over {n} scenes (error: the larger of path and rest error, "
            "per scene)", *table_lines(header, rows)]


def format_closed(r: dict) -> list[str]:
    lines = [
        f"closed-form references: {len(r['cases'])} scene(s) whose answer is derived on paper "
        "from the model's equations (closed_form.py, closed_cases.py), not from the engine",
        "  model  the engine's equations (sliding, rolling, spin, impulses); each scene's physics",
        "         makes its answer exact: frictionless ball-ball contact, e_ball = 1 (draw_e95:",
        "         0.95), no pockets, no cushion within reach",
        "  own    the seed game's model that naive and substep step: NO SLIDING AND NO SPIN,",
        "         every ball slows at mu_r g from its full speed. A different model: against",
        "         'model' their error is mostly the model's; against 'own' it is their stepping",
        "         error alone",
        "columns:",
        "  path mm   largest distance of any ball from the closed form at the compared step ends",
        f"            (every step, or every few at least {COMPARE_HZ} times a simulated second)",
        f"  rest mm   the same for the final positions (* still moving after {MAX_TIME:g} s)",
        "  event ms  largest time error of the closed form's events found in the run (frame",
        "            schemes: contacts only; they have no transitions)",
        "  events    closed-form events found / expected, +extra events of those types in the run",
        "",
    ]
    for c in r["cases"]:
        lines += format_case(c) + [""]
    lines += format_summary(r["summary"], len(r["cases"]))
    return lines
