"""`termpool bench accuracy`: each stepping scheme against the event-to-event reference.

    termpool bench accuracy [--json] [--scenes DIR|FILE] [--closed NAMES] [--dts S ...]
                            [--schemes A,B] [--png PATH | --no-png]

For every scene (default: the files in `bench/scenes/`) the reference is `Engine.run_events()`.
Each scheme is then run at each dt from the scene's start until every ball is at rest (or
MAX_TIME simulated seconds):

- `engine`: `Engine.step(dt)`, the game's fixed-step engine;
- `naive`: the seed game's scheme (`bench/naive.py: NaiveSim`), the baseline;
- `substep`: the naive scheme with SUBSTEPS frames of dt / SUBSTEPS inside every dt; it is run
  only where dt / SUBSTEPS is not below the finest dt asked for (finer rows would only repeat
  the naive scheme at a smaller step, for ten times its largest cost);
- `euler`: the engine's own model stepped the naive way (`EulerSim`): its error is the stepping
  error alone.

Per row: wall time (construction plus the time inside `step()`, events recorded, the
comparisons below not counted), steps, the largest position error of any ball at fixed
checkpoints and at rest, the largest event-time error, whether the event sequence is the
same, and how long the run agrees with the reference (the first compared time at which some
ball is more than AGREE_MM away, and how many reference events came before it).

Positions are compared at step ends only, the times the scheme itself produces: at the step
nearest each checkpoint, and every step (every few steps below 1/COMPARE_HZ s) for the
agreement time; the reference is evaluated at exactly those times. Pocketed balls count as
sitting at their pocket's hole centre in every scheme. Events are matched in order by
type and ball ids; for the engine every event counts, for the frame schemes only contacts
(ball-ball, cushion, pocket), since they have no motion transitions; a cushion event must
also hit the same feature (rail, jaw, tip) and a pocket event the same pocket. When the
sequences differ the event-time error covers the matched part before the first difference.

The engine cannot err against its own event driver, so a second section (closed.py)
measures every scheme against references that do not come from the engine: scenes whose
answer is derived on paper from the model's equations (closed_form.py, closed_cases.py).
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time

import numpy as np

from bench import closed_cases
from bench.closed import closed_figures, format_closed
from bench.common import PROG, BenchParser, machine_info, machine_lines, seconds
from bench.schemes import (
    COMPARE_HZ,
    CONTACTS,
    MAX_TIME,
    SCHEMES,
    SUBSTEPS,
    all_at_rest,
    fmt_dt,
    fmt_mm,
    make_sim,
    positions,
    table_lines,
)
from termpool.files import json_safe, to_json
from termpool.scene import SceneError, load_scene
from termpool.text import say

DTS = (1 / 15, 1 / 30, 1 / 60, 1 / 120, 1 / 240, 1 / 1000, 1 / 4000)
CHECKPOINTS = (0.25, 0.5, 1.0, 2.0)  # s
AGREE_MM = 1.0
FLOOR_MM = 1e-9  # where a zero error sits on the log-scale charts
PNG_DEFAULT = "accuracy.png"
SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes")
CHART_W, CHART_H = 64, 18


# ------------------------------------------------------------------------------ scenes


def scene_paths(where: str | None = None) -> list[str]:
    """The scene files in `where` (a directory or one .json file); default: bench/scenes."""
    if where is None:
        where = SCENES
    if os.path.isfile(where):
        return [where]
    if not os.path.isdir(where):
        raise ValueError(f"--scenes: no such file or directory: '{where}'")
    paths = sorted(os.path.join(where, f) for f in os.listdir(where) if f.endswith(".json"))
    if not paths:
        raise ValueError(f"--scenes: no .json scene files in '{where}'")
    return paths


def _name(path: str) -> str:
    return os.path.splitext(os.path.basename(path))[0]


# ------------------------------------------------------------------------------ running


def _events(sim, ids: list[str]) -> list[tuple[float, str, tuple[str, ...], str]]:
    """(t, type, ball ids, where) of every event: `where` is the cushion feature (rail, jaw,
    tip) or the pocket's name, else empty."""
    log = sim.events[0] if sim.events and isinstance(sim.events[0], list) else sim.events
    out = []
    for ev in log:
        names = [ids[i] for i in ev["i"]]
        if ev["type"] == "ball_ball":
            names.sort()
        where = ev.get("feature") or ev.get("pocket") or ""
        out.append((float(ev["t"]), ev["type"], tuple(names), where))
    out.sort(key=lambda e: e[0])
    return out


def _err_mm(a: np.ndarray, b: np.ndarray) -> float:
    d = a - b
    return 1e3 * float(np.sqrt((d * d).sum(axis=1)).max())


def reference(scene) -> dict:
    """The event-to-event reference run: final positions, events, time and wall time (of a
    second run: the first warms up the engine's code paths for every row that follows)."""
    for _ in range(2):
        t0 = time.perf_counter()
        eng = make_sim("engine", scene)
        eng.run_events()
        wall = time.perf_counter() - t0
    events = _events(eng, scene.ids)
    return {
        "time": float(eng.time),
        "wall_s": wall,
        "passes": int(eng.passes),
        "events": events,
        "final": positions(eng, len(scene.ids)).copy(),
    }


def compare_plan(dt: float) -> tuple[int, dict[int, float]]:
    """Compare every `stride` steps, and at the step nearest each checkpoint (step -> time)."""
    stride = max(1, math.ceil(1.0 / (COMPARE_HZ * dt) - 1e-9))
    ckpt = {max(1, round(c / dt)): c for c in CHECKPOINTS}
    return stride, ckpt


def reference_at_steps(scene, dt: float, ref_time: float, stride: int,
                       ckpt_steps) -> dict[int, np.ndarray]:
    """Reference positions at the ends of the steps a scheme compares, up to the reference's
    rest (later, its final positions hold). Times are accumulated as the schemes do (t += dt),
    so the reference is evaluated at bit-identical times."""
    eng = make_sim("engine", scene, record=False)
    n = len(scene.ids)
    out = {}
    last = max(ckpt_steps)
    t, k = 0.0, 0
    while True:
        t += dt
        k += 1
        if t > ref_time and k > last:
            break
        if k % stride == 0 or k in ckpt_steps:
            if t <= ref_time:
                eng.run_events(duration=t)
                out[k] = positions(eng, n).copy()
    return out


def _match(ref: list, got: list, types) -> tuple[int, bool, float | None]:
    """(matched events, same sequence, largest time error of the matched ones)."""
    a = [e for e in ref if e[1] in types]
    b = [e for e in got if e[1] in types]
    k, worst = 0, None
    for ea, eb in zip(a, b, strict=False):
        if ea[1:] != eb[1:]:
            break
        k += 1
        err = abs(ea[0] - eb[0])
        worst = err if worst is None else max(worst, err)
    return k, k == len(a) == len(b), worst


def run_scheme(scheme: str, scene, dt: float, ref: dict, ref_steps: dict, stride: int,
               ckpt: dict[int, float]) -> dict:
    n = len(scene.ids)
    final_ref = ref["final"]
    t0 = time.perf_counter()
    sim = make_sim(scheme, scene)
    wall = time.perf_counter() - t0
    ckpt_err: dict[float, float] = {}
    diverge_t = None
    k = 0

    def compare(step: int, t: float, pos: np.ndarray) -> None:
        nonlocal diverge_t
        err = _err_mm(pos, ref_steps.get(step, final_ref))
        if step in ckpt:
            ckpt_err[ckpt[step]] = err
        if diverge_t is None and err > AGREE_MM:
            diverge_t = t

    while not all_at_rest(sim) and sim.time < MAX_TIME:
        t1 = time.perf_counter()
        sim.step(dt)
        wall += time.perf_counter() - t1
        k += 1
        if k % stride == 0 or k in ckpt:
            compare(k, sim.time, positions(sim, n))
    at_rest = all_at_rest(sim)
    pos = positions(sim, n).copy()
    # The scheme has stopped; the reference may still be moving and checkpoints may lie ahead:
    # the scheme's balls stay where they are.
    t, step = sim.time, k
    for s in sorted(x for x in set(ref_steps) | set(ckpt) if x > k):
        while step < s:
            step += 1
            t += dt
        compare(s, t, pos)
    err_rest = _err_mm(pos, final_ref)
    got = _events(sim, scene.ids)
    all_types = {e[1] for e in ref["events"]} | {e[1] for e in got}
    types = all_types if scheme == "engine" else set(CONTACTS)
    matched, same, dt_err = _match(ref["events"], got, types)
    end = max(ref["time"], float(sim.time))
    agree_t = end if diverge_t is None else diverge_t
    return {
        "scheme": scheme,
        "dt": dt,
        "wall_s": wall,
        "steps": int(sim.steps),
        "sim_s": float(sim.time),
        "at_rest": at_rest,
        "ckpt_mm": {f"{c:g}": ckpt_err.get(c, 0.0) for c in CHECKPOINTS},
        "err_ckpt_mm": max(ckpt_err.values(), default=0.0),
        "err_rest_mm": err_rest,
        "err_mm": max(max(ckpt_err.values(), default=0.0), err_rest),
        "events": len([e for e in got if e[1] in types]),
        "events_ref": len([e for e in ref["events"] if e[1] in types]),
        "events_matched": matched,
        "same_events": same,
        "event_dt_max_s": dt_err,
        "agree_s": agree_t,
        "agree_whole": diverge_t is None,
        "agree_events": sum(1 for e in ref["events"] if diverge_t is None or e[0] < diverge_t),
    }


def run_scene(path: str, dts, schemes) -> dict:
    scene = load_scene(path)
    ref = reference(scene)
    rows = []
    finest = min(dts)
    for dt in dts:
        stride, ckpt = compare_plan(dt)
        ref_steps = reference_at_steps(scene, dt, ref["time"], stride, ckpt)
        for scheme in schemes:
            if scheme == "substep" and dt / SUBSTEPS < finest * (1 - 1e-9):
                continue
            rows.append(run_scheme(scheme, scene, dt, ref, ref_steps, stride, ckpt))
    order = {s: k for k, s in enumerate(schemes)}
    rows.sort(key=lambda r: (order[r["scheme"]], -r["dt"]))
    events = ref["events"]
    return {
        "name": _name(path),
        "description": scene.raw.get("description", ""),
        "balls": len(scene.ids),
        "reference": {
            "time": ref["time"],
            "wall_s": ref["wall_s"],
            "passes": ref["passes"],
            "events": len(events),
            "contacts": sum(1 for e in events if e[1] in CONTACTS),
        },
        "rows": rows,
    }


def summarize(scenes: list[dict]) -> list[dict]:
    """Per (scheme, dt), over all scenes: total wall time, median and largest error."""
    groups: dict[tuple[str, float], list[dict]] = {}
    for sc in scenes:
        for r in sc["rows"]:
            groups.setdefault((r["scheme"], r["dt"]), []).append(r)
    out = []
    for (scheme, dt), rows in groups.items():
        errs = [r["err_mm"] for r in rows]
        out.append({
            "scheme": scheme,
            "dt": dt,
            "scenes": len(rows),
            "wall_s": sum(r["wall_s"] for r in rows),
            "steps": sum(r["steps"] for r in rows),
            "err_median_mm": statistics.median(errs),
            "err_max_mm": max(errs),
            "same_events": sum(1 for r in rows if r["same_events"]),
        })
    return out


def accuracy_figures(paths: list[str], dts, schemes, closed: list[str] | None = None) -> dict:
    """Figures for the scene files and for the closed-form cases named in `closed` (all when
    None, none when empty)."""
    scenes = [run_scene(p, dts, schemes) for p in paths]
    return {
        "dts": list(dts),
        "checkpoints": list(CHECKPOINTS),
        "agree_mm": AGREE_MM,
        "schemes": {s: SCHEMES[s][1] for s in schemes},
        "substeps": SUBSTEPS,
        "scenes": scenes,
        "summary": summarize(scenes),
        "closed_form": closed_figures(closed, dts, schemes),
        "machine": machine_info(),
    }


# ------------------------------------------------------------------------------ output


def _agree(r: dict) -> str:
    if r["agree_whole"]:
        return f"whole run ({r['agree_events']} ev)"
    return f"{r['agree_s']:.3f} s, {r['agree_events']} ev"


def format_scene(sc: dict) -> list[str]:
    ref = sc["reference"]
    lines = [
        f"{sc['name']} ({sc['balls']} ball{'s' if sc['balls'] != 1 else ''}): "
        f"{sc['description']}",
        f"  reference run_events(): {ref['time']:.3f} s simulated, {ref['events']} events "
        f"({ref['contacts']} contacts), {1e3 * ref['wall_s']:.1f} ms",
    ]
    header = ["scheme", "dt", "wall ms", "steps", "ckpt mm", "rest mm", "event ms", "same",
              f"agrees to {AGREE_MM:g} mm"]
    rows = []
    for r in sc["rows"]:
        ev = "-" if r["event_dt_max_s"] is None else fmt_mm(1e3 * r["event_dt_max_s"])
        rest = fmt_mm(r["err_rest_mm"]) + ("" if r["at_rest"] else "*")
        rows.append([r["scheme"], fmt_dt(r["dt"]), f"{1e3 * r['wall_s']:.1f}", str(r["steps"]),
                     fmt_mm(r["err_ckpt_mm"]), rest, ev,
                     f"{'yes' if r['same_events'] else 'no'} {r['events_matched']}/"
                     f"{r['events_ref']}", _agree(r)])
    return lines + table_lines(header, rows, left=(0, 7, 8))


def format_summary(summary: list[dict], n_scenes: int) -> list[str]:
    header = ["scheme", "dt", "wall s", "steps", "median mm", "max mm", "same events"]
    rows = [[s["scheme"], fmt_dt(s["dt"]), f"{s['wall_s']:.3f}", str(s["steps"]),
             fmt_mm(s["err_median_mm"]), fmt_mm(s["err_max_mm"]),
             f"{s['same_events']}/{s['scenes']}"] for s in summary]
    return [f"summary over {n_scenes} scenes (error: the larger of checkpoint and rest error, "
            "per scene)", *table_lines(header, rows)]


def _log10(x: float) -> float:
    return math.log10(max(x, FLOOR_MM))


def text_chart(summary: list[dict], width: int = CHART_W, height: int = CHART_H) -> list[str]:
    """Median error against total wall time, log-log, one letter per scheme (a digit-free
    scatter: '*' where two schemes share a cell). Zero errors sit on the floor."""
    if not summary:
        return []
    xs = [math.log10(max(s["wall_s"], 1e-9)) for s in summary]
    ys = [_log10(s["err_median_mm"]) for s in summary]
    x0, x1 = math.floor(min(xs)), math.ceil(max(xs))
    y0, y1 = math.floor(min(ys)), math.ceil(max(ys))
    x1, y1 = max(x1, x0 + 1), max(y1, y0 + 1)
    grid = [[" "] * width for _ in range(height)]
    for s, x, y in zip(summary, xs, ys, strict=True):
        col = round((x - x0) / (x1 - x0) * (width - 1))
        row = height - 1 - round((y - y0) / (y1 - y0) * (height - 1))
        mark = SCHEMES[s["scheme"]][0]
        cell = grid[row][col]
        grid[row][col] = mark if cell in (" ", mark) else "*"
    labels = {}
    for d in range(y0, y1 + 1):
        row = height - 1 - round((d - y0) / (y1 - y0) * (height - 1))
        labels.setdefault(row, f"1e{d:+03d}")
    lines = ["work-precision: median error (mm) over the scenes against total wall time (s), "
             "log-log",
             "  " + "   ".join(f"{SCHEMES[k][0]} {k}" for k in dict.fromkeys(
                 s["scheme"] for s in summary)) + f"   (* shared cell; 0 drawn at {FLOOR_MM:g})"]
    for r in range(height):
        lines.append(f"{labels.get(r, ''):>6} |" + "".join(grid[r]).rstrip())
    lines.append(" " * 7 + "+" + "-" * width)
    ticks = [" "] * (width + 8)
    for d in range(x0, x1 + 1):
        col = 8 + round((d - x0) / (x1 - x0) * (width - 1))
        text = f"1e{d:+03d}"
        start = min(max(col - len(text) // 2, 0), len(ticks) - len(text))
        ticks[start:start + len(text)] = list(text)
    lines.append("".join(ticks).rstrip() + "  s")
    return lines


def png_chart(summary: list[dict], path: str) -> str | None:
    """Write the work-precision chart as a PNG if matplotlib is installed; returns the path."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return None
    fig, ax = plt.subplots(figsize=(7, 5))
    for scheme in dict.fromkeys(s["scheme"] for s in summary):
        pts = sorted((s for s in summary if s["scheme"] == scheme), key=lambda s: -s["dt"])
        x = [s["wall_s"] for s in pts]
        y = [max(s["err_median_mm"], FLOOR_MM) for s in pts]
        ax.plot(x, y, marker="o", label=f"{scheme}: {SCHEMES[scheme][1]}")
        for s, xi, yi in zip(pts, x, y, strict=True):
            ax.annotate(fmt_dt(s["dt"]), (xi, yi), fontsize=7, xytext=(3, 3),
                        textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("total wall time over the scenes (s)")
    ax.set_ylabel(f"median position error (mm); 0 drawn at {FLOOR_MM:g}")
    ax.set_title("termpool bench accuracy: work-precision")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def format_accuracy(r: dict) -> str:
    ckpts = ", ".join(f"{c:g}" for c in r["checkpoints"])
    lines = [
        f"termpool bench accuracy: {len(r['scenes'])} scene(s), every scheme against the "
        "reference Engine.run_events()",
        f"dt (s): {' '.join(fmt_dt(d) for d in r['dts'])}"
        + (f"; substep only where dt/{r['substeps']} >= {fmt_dt(min(r['dts']))}"
           if "substep" in r["schemes"] else ""),
        "schemes:",
        *(f"  {SCHEMES[k][0]} {k:<8} {v}" for k, v in r["schemes"].items()),
        "columns:",
        f"  ckpt mm   largest error of any ball at the steps nearest {ckpts} s",
        f"  rest mm   largest error of any ball at rest (* still moving after {MAX_TIME:g} s)",
        "  event ms  largest event-time error of the events matched before the first difference",
        "  same      same event sequence; events matched / reference events, by type, balls and",
        "            feature or pocket (engine: all events; frame schemes: contacts only)",
        f"  agrees    time until some ball is more than {r['agree_mm']:g} mm off, and the "
        "reference events before it",
        "",
    ]
    for sc in r["scenes"]:
        lines += format_scene(sc) + [""]
    lines += format_summary(r["summary"], len(r["scenes"])) + [""]
    lines += text_chart(r["summary"]) + [""]
    png = r.get("png")
    lines.append(f"chart: {png}" if png else "chart: no PNG (" + r.get("png_note", "") + ")")
    if r["closed_form"]["cases"]:
        lines += [""] + format_closed(r["closed_form"]) + [""]
    m = r["machine"]
    lines += [
        *machine_lines(m),
    ]
    return "\n".join(lines) + "\n"


# ------------------------------------------------------------------------------ command


def _schemes(text: str) -> list[str]:
    names = [s.strip() for s in text.split(",") if s.strip()]
    bad = [s for s in names if s not in SCHEMES]
    if bad or not names:
        raise argparse.ArgumentTypeError(
            f"unknown scheme '{bad[0] if bad else text}' (use {', '.join(SCHEMES)})")
    return list(dict.fromkeys(names))


def _closed(text: str) -> list[str] | None:
    """Closed-form cases: 'all' (None), 'none' ([]) or comma-separated names."""
    if text.strip() == "all":
        return None
    if text.strip() == "none":
        return []
    names = [s.strip() for s in text.split(",") if s.strip()]
    bad = [s for s in names if s not in closed_cases.NAMES]
    if bad or not names:
        raise argparse.ArgumentTypeError(
            f"unknown closed-form scene '{bad[0] if bad else text}' (use all, none or "
            f"{','.join(closed_cases.NAMES)})")
    return list(dict.fromkeys(names))


def main(argv: list[str]) -> int:
    p = BenchParser(
        prog=f"{PROG} accuracy",
        description=(
            "Run each scene with the event-to-event reference and with every stepping scheme "
            "at every dt; report position, event-time and event-sequence errors, wall time, "
            "and a work-precision chart; then every scheme against closed-form answers "
            "derived from the model's equations."
        ),
    )
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--scenes", metavar="DIR", default=None,
                   help="a directory of scene files, or one scene file (default: bench/scenes)")
    p.add_argument("--closed", metavar="NAMES", type=_closed, default=None,
                   help="closed-form scenes: all (default), none, or a comma-separated subset "
                        f"of {','.join(closed_cases.NAMES)}")
    p.add_argument("--dts", metavar="S", nargs="+", type=seconds, default=list(DTS),
                   help="time steps in seconds, fractions like 1/60 work (default: "
                        + " ".join(fmt_dt(d) for d in DTS) + ")")
    p.add_argument("--schemes", type=_schemes, default=list(SCHEMES),
                   help=f"comma-separated subset of {','.join(SCHEMES)} (default: all)")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--png", metavar="PATH", default=PNG_DEFAULT,
                   help=f"where to write the chart when matplotlib is installed "
                        f"(default {PNG_DEFAULT})")
    g.add_argument("--no-png", action="store_true", help="do not write the PNG chart")
    args = p.parse_args(argv)
    dts = sorted(dict.fromkeys(args.dts), reverse=True)
    try:
        paths = scene_paths(args.scenes)
        result = accuracy_figures(paths, dts, args.schemes, args.closed)
    except (SceneError, ValueError, RuntimeError) as e:
        say(f"bench accuracy: {e}")
        return 1
    result["png"] = None
    if args.no_png:
        result["png_note"] = "--no-png"
    else:
        result["png"] = png_chart(result["summary"], args.png)
        if result["png"] is None:
            result["png_note"] = "matplotlib is not installed"
    if args.json:
        sys.stdout.write(to_json(json_safe(result)) + "\n")
    else:
        sys.stdout.write(format_accuracy(result))
    sys.stdout.flush()
    return 0
