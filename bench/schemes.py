"""What the two sections of `termpool bench accuracy` share (accuracy.py against the engine's
reference, closed.py against closed forms): the stepping schemes, how a run is read and
stopped, and how its figures are printed."""

from __future__ import annotations

import numpy as np

from bench.common import make_engine
from bench.naive import EulerSim, NaiveSim

COMPARE_HZ = 240  # positions are compared at least this often (per simulated second)
MAX_TIME = 60.0  # s: a scheme still moving then is stopped and reported as not at rest
SUBSTEPS = 10
CONTACTS = ("ball_ball", "cushion", "pocket")
# name -> (chart letter, description)
SCHEMES = {
    "engine": ("E", "Engine.step(dt): exact inside each step"),
    "naive": ("N", "seed game: explicit Euler, no spin, contacts at frame ends"),
    "substep": ("S", f"naive with {SUBSTEPS} substeps per frame"),
    "euler": ("U", "engine's model (spin, jaws) by explicit Euler, contacts at frame ends"),
}


def make_sim(scheme: str, scene, record: bool = True):
    args = (scene.table, scene.physics, scene.pos, scene.vel, scene.w, scene.radius, scene.mass)
    if scheme == "engine":
        return make_engine(scene, record=record)
    if scheme == "naive":
        return NaiveSim(*args, record=record)
    if scheme == "substep":
        return NaiveSim(*args, substeps=SUBSTEPS, record=record)
    if scheme == "euler":
        return EulerSim(*args, record=record)
    raise ValueError(f"unknown scheme '{scheme}'")


def positions(sim, n: int) -> np.ndarray:
    return np.asarray(sim.pos, float).reshape(-1, n, 2)[0]


def all_at_rest(sim) -> bool:
    return bool(np.all(sim.at_rest()))


def fmt_dt(dt: float) -> str:
    inv = 1.0 / dt
    if abs(inv - round(inv)) < 1e-6 * inv:
        return f"1/{round(inv)}"
    return f"{dt:.3g}"


def fmt_mm(x: float) -> str:
    """An error in mm: exactly 0 prints as 0."""
    if x == 0:
        return "0"
    return f"{x:.1e}" if x < 0.01 else f"{x:.3g}"


def table_lines(header: list[str], rows: list[list[str]], left=(0,)) -> list[str]:
    """Columns in `left` are left-aligned, the others (numbers) right-aligned."""
    widths = [max(len(r[c]) for r in [header, *rows]) for c in range(len(header))]
    out = []
    for r in [header, *rows]:
        cells = [c.ljust(w) if k in left else c.rjust(w) for k, (c, w) in
                 enumerate(zip(r, widths, strict=True))]
        out.append("  " + "  ".join(cells).rstrip())
    return out
