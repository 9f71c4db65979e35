"""Cost of the aim aid (figures only, no thresholds enforced).

python benchmarks/aid.py [--layouts N] [--json]

The aid is the engine's prediction of the shot being aimed (termpool.ui.predict), run again
whenever the aim, the power, the spin or the table change. The app runs the first AID_STEP
event times of a new prediction in the frame in which the aim moves and the rest a share a
frame after it, so what a frame pays is bounded. Measured on practice tables after a break
(N seeds; the cue ball where it stopped), with the aim swept round in 3-degree steps at two
powers and three tip offsets:

- layout: building the predictor for a table (once a turn: the scene loaded and checked);
- update: what the frame in which the aim moves pays (a new engine, AID_STEP event times, the
  paths so far) -- the figure the budget is about;
- whole: the complete prediction, at once, and the frames the app takes to finish it;
- frame: the whole app frame at 120x40 in which an aim key turns the aim (the key, the tick,
  the cells with the aid drawn), and at 200x60.

CPU time (time.process_time) is given beside the wall time: on a machine shared with other
jobs the wall time includes waiting for a core.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import statistics
import sys
import time
from dataclasses import replace

if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from termpool.game import Match, Shot  # noqa: E402
from termpool.ui.aid import AID_STEP  # noqa: E402
from termpool.ui.app import App, Options  # noqa: E402
from termpool.ui.keys import Key  # noqa: E402
from termpool.ui.phases.turn import start_turn  # noqa: E402
from termpool.ui.predict import Predictor  # noqa: E402
from termpool.ui.shots import power_to_speed  # noqa: E402


def broken(seed: int) -> Match:
    m = Match("practice", seed=seed)
    m.place_cue(*m.table.head_spot)
    m.begin(Shot(8.0, 0.5 + seed % 3)).finish()
    if m.ball_in_hand:
        m.place_cue(*m.waiting_spot())
    return m


def _clock():
    return time.perf_counter(), time.process_time()


def _since(t0):
    w, c = _clock()
    return (w - t0[0]) * 1e3, (c - t0[1]) * 1e3


def stats(xs: list[float]) -> dict:
    s = sorted(xs)
    return {"median": statistics.median(s), "p95": s[int(0.95 * (len(s) - 1))], "max": s[-1]}


def measure(layouts: int) -> dict:
    out: dict = {"layout": ([], []), "update": ([], []), "whole": ([], []), "frames": []}
    for seed in range(layouts):
        m = broken(seed)
        t0 = _clock()
        pred = Predictor(m)
        for k, v in zip(out["layout"], _since(t0), strict=True):
            k.append(v)
        for angle in range(0, 360, 3):
            for level in (0.3, 0.6):
                for side, top in ((0.0, 0.0), (0.0, 0.3), (0.2, -0.3)):
                    shot = Shot(power_to_speed(level), float(angle), side, top)
                    t0 = _clock()
                    job = pred.start(shot)
                    job.run(AID_STEP)
                    job.result()
                    for k, v in zip(out["update"], _since(t0), strict=True):
                        k.append(v)
                    t0 = _clock()
                    whole = pred.start(shot)
                    whole.run()
                    whole.result()
                    for k, v in zip(out["whole"], _since(t0), strict=True):
                        k.append(v)
                    out["frames"].append(-(-whole.instants // AID_STEP))
    return out


def app_frames(cols: int, rows: int, seed: int = 1) -> tuple[list[float], list[float]]:
    """The app's frames in which a tap turns the aim (key + tick + cells), ms wall and CPU."""
    app = App(Options(mode="practice", colors="truecolor"))
    app.state = start_turn(replace(app.state, match=broken(seed)))
    t = 1.0
    app.cells(cols, rows)
    wall, cpu = [], []
    for k in range(240):
        t += 0.2
        t0 = _clock()
        app.key(Key("left" if k % 80 < 40 else "right"), t)
        app.tick(t)
        app.cells(cols, rows)
        w, c = _since(t0)
        wall.append(w)
        cpu.append(c)
        while app.wake_in(t) == 0.0:  # the frames that finish the prediction
            t += 1 / 60
            app.tick(t)
            app.cells(cols, rows)
    return wall, cpu


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--layouts", type=int, default=5)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    res = measure(args.layouts)
    report = {k: {"wall_ms": stats(res[k][0]), "cpu_ms": stats(res[k][1])}
              for k in ("layout", "update", "whole")}
    report["frames_to_finish"] = stats([float(f) for f in res["frames"]])
    report["finished_in_first_frame"] = sum(f <= 1 for f in res["frames"]) / len(res["frames"])
    for size in ((120, 40), (200, 60)):
        w, c = app_frames(*size)
        report[f"app_frame_{size[0]}x{size[1]}"] = {"wall_ms": stats(w), "cpu_ms": stats(c)}
    report["predictions"] = len(res["frames"])
    report["aid_step"] = AID_STEP
    report["machine"] = {"platform": platform.platform(), "cpu": platform.processor(),
                         "python": platform.python_version(), "cores": os.cpu_count(),
                         "load": os.getloadavg()[0],
                         "date": datetime.datetime.now(datetime.UTC)
                         .strftime("%Y-%m-%d %H:%M UTC")}
    if args.json:
        print(json.dumps(report, indent=1))
        return 0
    print(f"aim aid: {report['predictions']} predictions on {args.layouts} tables after a "
          f"break; AID_STEP = {AID_STEP} event times a frame")
    print("                                 wall ms: median   p95    max |  CPU ms: median"
          "   p95    max")
    for k, label in (("layout", "predictor for a table (a turn)"),
                     ("update", "update when the aim moves"), ("whole", "whole prediction"),
                     ("app_frame_120x40", "app frame 120x40, aim turned"),
                     ("app_frame_200x60", "app frame 200x60, aim turned")):
        w, c = report[k]["wall_ms"], report[k]["cpu_ms"]
        print(f"  {label:<31} {w['median']:7.2f} {w['p95']:6.2f} {w['max']:6.2f} | "
              f"{c['median']:13.2f} {c['p95']:6.2f} {c['max']:6.2f}")
    f = report["frames_to_finish"]
    print(f"  frames to finish a prediction: median {f['median']:.0f}, p95 {f['p95']:.0f}, "
          f"max {f['max']:.0f}; finished in the first frame: "
          f"{100 * report['finished_in_first_frame']:.0f}%")
    m = report["machine"]
    print(f"  {m['platform']}, {m['cores']} cores, Python {m['python']}, load "
          f"{m['load']:.1f}, {m['date']}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
