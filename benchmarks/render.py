"""Micro-benchmark of the terminal renderer (figures only, no thresholds enforced).

python benchmarks/render.py

- frame build time at 200x60: canvas + balls + cells + diffed escape string, per frame, for
  the frames of a simulated break (and for a full first frame);
- bytes written per frame during the break at 80x24, diffed frames at 60 Hz, per colour depth;
- idle frames (nothing moved): bytes written;
- aiming at 200x60: frames of the rack at rest with the aim sweeping one quarter degree a
  frame, the stick charging and the spin face and power bar in the panel; the whole frame and
  the overlays alone (draw_prediction / mono_prediction of the aid's prediction for that aim
  (a rack: the ghost ball), draw_cue_stick, the two widgets; the prediction itself is timed
  in benchmarks/aid.py).

- the game itself: the app breaking in practice mode, with its panel, at 200x60 (time per
  frame, and the strike, when the whole shot is simulated) and 80x24 (bytes per frame).

Targets: build <= 3 ms at 200x60; average <= 3 KB per frame during a break at
80x24; idle frames 0 bytes.
"""

from __future__ import annotations

import os
import statistics
import sys
import time

if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from termpool.physics.engine import Engine  # noqa: E402
from termpool.scene import load_scene  # noqa: E402
from termpool.ui.canvas import to_cells  # noqa: E402
from termpool.ui.frame import Renderer  # noqa: E402
from termpool.ui.overlay import (  # noqa: E402
    blit_cells,
    draw_cue_stick,
    draw_prediction,
    mono_prediction,
    power_meter_cells,
    spin_face_cells,
)
from termpool.ui.panel import draw_ball_list  # noqa: E402

BREAK = {"table": "9ft", "balls": "8ball", "shot": {"speed": 8.0, "angle": 0}}


def break_samples(hz: float = 60):
    scene = load_scene(BREAK)
    eng = Engine(scene.table, scene.physics, scene.pos, scene.vel, scene.w, scene.radius,
                 scene.mass, record=False)
    return scene, eng.run(1 / 60, sample_hz=hz)


def build_times(scene, samples, cols: int, rows: int, depth: str, repeat: int = 3):
    full, diff = [], []
    for _ in range(repeat):
        r = Renderer(scene.table, cols, rows, depth)
        t0 = time.perf_counter()
        r.frame(scene.ids, scene.pos, None, scene.radius)
        full.append(time.perf_counter() - t0)
        for _t, pos, state in samples:
            t0 = time.perf_counter()
            r.frame(scene.ids, pos[0], state[0], scene.radius)
            diff.append(time.perf_counter() - t0)
    return full, diff


def frame_bytes(scene, samples, cols: int, rows: int, depth: str):
    r = Renderer(scene.table, cols, rows, depth)
    first = len(r.frame(scene.ids, scene.pos, None, scene.radius).encode())
    sizes = [len(r.frame(scene.ids, pos[0], state[0], scene.radius).encode())
             for _t, pos, state in samples]
    _t, pos, state = samples[-1]
    idle = [len(r.frame(scene.ids, pos[0], state[0], scene.radius).encode()) for _ in range(10)]
    return first, sizes, idle


def aim_times(scene, cols: int, rows: int, depth: str, frames: int = 240):
    """Per-frame build time of aiming frames, whole and overlays only (s)."""
    from termpool.game import Match, Shot
    from termpool.ui.predict import Predictor

    r = Renderer(scene.table, cols, rows, depth)
    lay, view = r.layout, r.view
    m = Match("8ball")
    predictor = Predictor(m)
    ids, pos, rad = m.ids, m.pos, m.radius
    cue = ids.index("cue")
    col, row, ncols, _nrows = lay.panel_rect
    whole, over = [], []
    r.frame(ids, pos, None, rad)
    for k in range(frames):
        angle, pull = -30.0 + 0.25 * k, (k % 60) / 60
        aim = predictor.shot(Shot(6.0, angle))
        t0 = time.perf_counter()
        if r.mono:
            cells = (view.mono(ids, pos, None, rad), None, None)
        else:
            cv = view.draw(ids, pos, None, rad)
        t1 = time.perf_counter()
        if r.mono:
            mono_prediction(cells[0], lay, aim)
        else:
            draw_prediction(cv, lay, aim, rad[cue])
            draw_cue_stick(cv, lay, pos[cue], rad[cue], angle, pull)
        face = spin_face_cells(0.2, -0.1, mono=r.mono)
        power = power_meter_cells(pull, ncols - 2, "power")
        t2 = time.perf_counter()
        if not r.mono:
            cells = to_cells(cv)
        draw_ball_list(cells, lay, ids, None, r.title, r.mono)
        t3 = time.perf_counter()
        blit_cells(cells, face, row + 6, col + 1)
        blit_cells(cells, power, row + 11, col + 1)
        t4 = time.perf_counter()
        r.screen.render(*cells)
        t5 = time.perf_counter()
        whole.append(t5 - t0)
        over.append((t2 - t1) + (t4 - t3))
    return whole, over


def app_break(cols: int, rows: int, depth: str):
    """The real game (termpool.ui.app) breaking in practice mode, frame by frame at 60 Hz:
    the strike (the whole shot is simulated then), each frame's build time (cells with the
    panel, diffed string) and bytes, and the bytes of one idle frame after the balls stop."""
    from termpool.ui.app import App, Options
    from termpool.ui.keys import Key
    from termpool.ui.output import Screen
    from termpool.ui.state import Phase

    app = App(Options(mode="practice", colors=depth))
    screen = Screen(cols, rows, depth, sync=True)
    app.key(Key("enter"), 0.0)
    app.key(Key("space"), 0.1)
    t0 = time.perf_counter()
    app.key(Key("space", kind="release"), 1.3)  # full power
    strike = time.perf_counter() - t0
    screen.render(*app.cells(cols, rows))
    times, sizes = [], []
    k = 0
    while app.state.phase is Phase.RUN and k < 60 * 60:
        k += 1
        t0 = time.perf_counter()
        app.tick(1.3 + k / 60)
        out = screen.render(*app.cells(cols, rows)) if app.dirty else ""
        times.append(time.perf_counter() - t0)
        sizes.append(len(out.encode()))
    app.tick(1.3 + (k + 1) / 60)
    idle = len(screen.render(*app.cells(cols, rows)).encode()) if app.dirty else 0
    return times, sizes, idle, strike


def main() -> int:
    scene, samples = break_samples()
    print(f"break: {len(samples)} frames at 60 Hz ({samples[-1][0]:.2f} s to rest)")
    print()
    print("frame build at 200x60 (ms)          median    p95     max   full first frame")
    for depth in ("truecolor", "256", "16", "mono"):
        full, diff = build_times(scene, samples, 200, 60, depth)
        diff_ms = sorted(d * 1e3 for d in diff)
        p95 = diff_ms[int(0.95 * (len(diff_ms) - 1))]
        print(f"  {depth:<10} diffed frames       {statistics.median(diff_ms):6.2f} "
              f"{p95:6.2f}  {diff_ms[-1]:6.2f}   {statistics.median(full) * 1e3:6.2f}")
    print()
    print("bytes per frame during the break at 80x24   mean  mean 1st s   max  first(full)  idle")
    for depth in ("truecolor", "256", "16", "mono"):
        first, sizes, idle = frame_bytes(scene, samples, 80, 24, depth)
        moving = sizes[: next((k for k in range(len(sizes) - 1, -1, -1) if sizes[k]), 0) + 1]
        print(f"  {depth:<10}                       {statistics.mean(moving):7.0f} "
              f"{statistics.mean(sizes[:60]):9.0f} {max(sizes):7d}   {first:7d}     {max(idle)}")
    print()
    print("aiming at 200x60 (ms): rack at rest,     whole frame        overlays alone")
    print("aim sweeping, stick charging             median    p95      median    p95")
    for depth in ("truecolor", "256", "16", "mono"):
        whole, over = aim_times(scene, 200, 60, depth)
        w_ms = sorted(x * 1e3 for x in whole)
        o_ms = sorted(x * 1e3 for x in over)
        print(f"  {depth:<10}                             {statistics.median(w_ms):6.2f} "
              f"{w_ms[int(0.95 * (len(w_ms) - 1))]:6.2f}    {statistics.median(o_ms):6.2f} "
              f"{o_ms[int(0.95 * (len(o_ms) - 1))]:6.2f}")
    print()
    print("the game itself (ui.app, practice break at full power, 60 Hz):")
    print("                 frame ms at 200x60 (cells+diff)   bytes/frame at 80x24   strike")
    print("                 median    p95     max              mean    max   idle      ms")
    for depth in ("truecolor", "256", "16", "mono"):
        times, _, _, strike = app_break(200, 60, depth)
        _, sizes, idle, _ = app_break(80, 24, depth)
        ms = sorted(x * 1e3 for x in times)
        print(f"  {depth:<10}    {statistics.median(ms):6.2f} {ms[int(0.95 * (len(ms) - 1))]:6.2f} "
              f"{ms[-1]:7.2f}            {statistics.mean(sizes):7.0f} {max(sizes):6d} "
              f"{idle:6d}  {strike * 1e3:7.1f}")
    print("  (strike: the whole break simulated when it is struck, so no frame waits on physics)")
    print()
    print("targets: build <= 3 ms at 200x60, <= 3 KB/frame during a break at 80x24, idle 0 B")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
