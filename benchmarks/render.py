"""Micro-benchmark of the terminal renderer (figures only, no thresholds enforced).

python benchmarks/render.py

- frame build time at 200x60: canvas + balls + cells + diffed escape string, per frame, for
  the frames of a simulated break (and for a full first frame);
- bytes written per frame during the break at 80x24, diffed frames at 60 Hz, per colour depth;
- idle frames (nothing moved): bytes written.

Targets (issue 5): build <= 3 ms at 200x60; average <= 3 KB per frame during a break at
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
from termpool.ui.frame import Renderer  # noqa: E402

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
    print("targets: build <= 3 ms at 200x60, <= 3 KB/frame during a break at 80x24, idle 0 B")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
