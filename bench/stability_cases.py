"""Stiff and extreme cases of the physics core, and the laws every run must keep.

One place for three things that `termpool bench stability` (bench/stability.py) and the tests
(tests/test_stability.py, tests/test_properties.py through tests/physics_laws.py) share:

- the laws, computed from the engine's public state only: finite numbers, no two balls
  interpenetrating by more than OVERLAP_TOL, every ball not pocketed within the cushion noses
  (to OVERLAP_TOL; in a pocket's mouth, clear of the jaws), kinetic energy that never rises
  (ENERGY_TOL relative between checks), a bound on the time to rest (rest_bound) and on the
  work (PASS_LIMIT event passes). `Watch` measures them; in strict mode (run_checked,
  check_state, check_positions: what the tests call) it raises AssertionError at the first
  violation instead;
- the scenes of the cases (builders returning an Engine, or its arguments), and the closed
  forms their figures are compared with;
- CASES: one `Case` per row of the bench. A case runs its scenes through a Watch, which checks
  the laws as it goes, and adds its own checks (a closed form, a count of contacts, a bound).
  `run_case` runs a case twice, compares the two runs bit for bit (final positions, velocities,
  spins, states, clocks, steps, passes and every recorded event), and returns
  (figure, ok, details): ok when every check and every law held; the figure is the worst
  failing check, or, when all passed, the case's chosen law or else its first own check,
  followed by any of overlap, cushion depth and energy rise that came within 10x of its limit.

Limits are those of the tests: 1 micrometre of overlap, 1e-9 relative energy rise between
checks (1e-12 where the test asks for it), under 5000 event passes for a run to rest.
"""

from __future__ import annotations

import hashlib
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from typing import Any

import numpy as np

from termpool.physics.engine import POCKETED, Engine
from termpool.physics.params import BALL_MASS, BALL_RADIUS, Physics
from termpool.physics.table import Table
from termpool.scene import load_scene, rack

OVERLAP_TOL = 1e-6  # m: the most two balls (or a ball and a cushion) may interpenetrate
ENERGY_TOL = 1e-9  # relative rise of kinetic energy tolerated from one check to the next
ENERGY_ABS = 1e-15  # J: absolute rise tolerated on top (rounding at near-zero energies)
PASS_LIMIT = 5000  # event passes a run to rest must stay under
LONG_RUN_S = 600.0  # simulated seconds of the frictionless long run
QUICK_LONG_RUN_S = 60.0  # ... with --quick
LONG_RUN_DT = 0.5
LONG_RUN_DRIFT = 1e-9  # relative energy drift allowed over the long run
LONG_PASSES_PER_S = 10  # event passes per simulated second the long run may use
CLOSE_CALL = 0.1  # a passing case's figure also names a law it kept within 10x of its limit
CLOSE_CALL_LAWS = ("overlap", "cushion", "energy")

R = BALL_RADIUS
M = BALL_MASS
PLAIN = Table(pockets="none")
POCKETS = Table(pockets="standard")
L, W = PLAIN.length, PLAIN.width
FRICTIONLESS_CLOTH = dict(mu_slide=0.0, mu_roll=0.0, mu_spin=0.0)
ELASTIC = dict(e_ball=1.0, ball_ball="frictionless")


# ==================================================================================== laws


def kinetic(eng: Engine) -> np.ndarray:
    """(B,) translational + rotational kinetic energy of every table (I = 2/5 m R^2)."""
    m, r = eng.mass, eng.radius
    v, w = eng.vel, eng.w
    return (0.5 * m * (v * v).sum(-1) + 0.2 * m * r * r * (w * w).sum(-1)).sum(-1)


def momentum(eng: Engine) -> np.ndarray:
    """(B, 2) total horizontal momentum of every table."""
    return (eng.mass[..., None] * eng.vel).sum(1)


def nose_reach(r: float, ph: Physics) -> float:
    """Horizontal distance from a ball's centre to the cushion nose (height h) it touches:
    sqrt(R^2 - (h - R)^2). For a ball the nose would (almost) miss, the model's contact is
    undefined; only the centre's staying 0.3 R inside is then required."""
    s = (ph.cushion_height - r) / r
    if abs(s) <= 0.95:
        return r * math.sqrt(1.0 - s * s)
    return 0.3 * r


RC = nose_reach(R, Physics())  # centre-to-nose distance of a standard ball at contact


def _reach(radius: np.ndarray, ph: Physics) -> np.ndarray:
    """nose_reach of every radius in an array."""
    return np.array([nose_reach(float(r), ph) for r in radius])


def seg_distance(tab: Table, q: np.ndarray) -> np.ndarray:
    """Distance from point q to every cushion segment (rail noses and jaws, with their ends)."""
    a, b = tab.seg_a, tab.seg_b
    d = b - a
    s = np.clip(((q - a) * d).sum(1) / (d * d).sum(1), 0.0, 1.0)
    return np.linalg.norm(a + s[:, None] * d - q, axis=1)


def _seg_min(tab: Table, q: np.ndarray) -> np.ndarray:
    """(K,) distance from each of K points to the nearest cushion segment."""
    a, d = tab.seg_a, tab.seg_b - tab.seg_a
    s = np.clip(((q[:, None] - a) * d).sum(-1) / (d * d).sum(1), 0.0, 1.0)
    return np.linalg.norm(a + s[..., None] * d - q[:, None], axis=-1).min(1)


def position_figures(tab: Table, ph: Physics, pos: np.ndarray, state: np.ndarray,
                     radius: np.ndarray) -> tuple[tuple[float, tuple], tuple[float, tuple]]:
    """pos (B, N, 2) (finite), state and radius (B, N) -> ((overlap, (b, i, j)), (depth, (b, i))):
    the largest interpenetration of two unpocketed balls, and the largest depth of an unpocketed
    ball's contact circle (its nose reach) into the cushions: past the rail lines, or, in a
    pocket's mouth where the centre may pass the rail line, into the jaws and jaw tips. Both are
    -inf when there is nothing to measure; positive values are penetrations."""
    overlap: tuple[float, tuple] = (-math.inf, ())
    depth: tuple[float, tuple] = (-math.inf, ())
    for b in range(pos.shape[0]):
        idx = np.flatnonzero(state[b] != POCKETED)
        if idx.size == 0:
            continue
        p, r = pos[b, idx], radius[b, idx]
        if idx.size > 1:
            d = np.linalg.norm(p[:, None] - p[None], axis=-1)
            over = (r[:, None] + r[None]) - d
            np.fill_diagonal(over, -np.inf)
            k = np.unravel_index(over.argmax(), over.shape)
            if over[k] > overlap[0]:
                overlap = (float(over[k]), (b, int(idx[k[0]]), int(idx[k[1]])))
        rc = _reach(r, ph)
        x, y = p[:, 0], p[:, 1]
        dep = rc - np.minimum(np.minimum(x, tab.length - x), np.minimum(y, tab.width - y))
        if tab.pockets == "standard":
            near = (np.linalg.norm(p[:, None] - tab.hole_c[None], axis=-1)
                    < tab.hole_r + 0.1).any(1)
            if near.any():
                dep[near] = np.minimum(dep[near], rc[near] - _seg_min(tab, p[near]))
        k = int(dep.argmax())
        if dep[k] > depth[0]:
            depth = (float(dep[k]), (b, int(idx[k])))
    return overlap, depth


def _overlap_text(where: str, pos: np.ndarray, ov: float, at: tuple, tol: float) -> str:
    b, i, j = at
    return (f"{where}: table {b} balls {i},{j} overlap by {ov:.4g} m (limit {tol:g}) "
            f"at {pos[b, i].tolist()}, {pos[b, j].tolist()}")


def _depth_text(where: str, pos: np.ndarray, dep: float, at: tuple, tol: float) -> str:
    b, i = at
    x, y = (float(c) for c in pos[b, i])
    return (f"{where}: table {b} ball {i} outside the cushions at ({x!r}, {y!r}): "
            f"{dep:.4g} m into the nearest cushion feature (limit {tol:g})")


def check_positions(tab: Table, ph: Physics, pos: np.ndarray, state: np.ndarray,
                    radius: np.ndarray, where: str, tol: float = OVERLAP_TOL) -> None:
    """pos (B, N, 2), state and radius (B, N): finite, no two unpocketed balls overlapping by
    more than tol, every unpocketed ball within the cushion noses (tol). Raises AssertionError."""
    pos = np.asarray(pos, float)
    if not np.isfinite(pos).all():
        raise AssertionError(f"{where}: non-finite positions {pos[~np.isfinite(pos)]}")
    (ov, ov_at), (dep, dep_at) = position_figures(tab, ph, pos, state, radius)
    if ov > tol:
        raise AssertionError(_overlap_text(where, pos, ov, ov_at, tol))
    if dep > tol:
        raise AssertionError(_depth_text(where, pos, dep, dep_at, tol))


def check_state(eng: Engine, where: str, tol: float = OVERLAP_TOL) -> None:
    """Finite pos/vel/w, no interpenetration, every unpocketed ball within the noses."""
    Watch(tol=tol, strict=True).look(eng, where, energy=False)


def rest_bound(eng: Engine) -> float:
    """A generous bound on the time to rest: a ball's free decay (slide, roll and spin) at
    the fastest speed and spin the table's energy allows, three times over, plus a second."""
    ph = eng.physics
    E = float(kinetic(eng).max())
    m, r = float(eng.mass.min()), float(eng.radius.min())
    vmax = math.sqrt(2 * E / m)
    wmax = math.sqrt(2 * E / (0.4 * m * r * r))
    t_slide = 2 * (vmax + r * wmax) / (7 * ph.mu_slide * ph.g)
    t_roll = vmax / (ph.mu_roll * ph.g)
    t_spin = 2 * r * wmax / (5 * ph.mu_spin * ph.g)
    return 3 * (t_slide + t_roll + t_spin) + 1.0


def run_checked(eng: Engine, dt: float, duration: float | None = None, every_first: int = 300,
                later: float = 0.05, tol: float = OVERLAP_TOL,
                energy_tol: float = ENERGY_TOL) -> list[float]:
    """Step by dt until at rest (or for `duration` s), checking the laws after every step for
    the first `every_first` steps and every `later` seconds after that. Energy must never rise
    between checks. Without a duration, the run must end within rest_bound(). Returns the
    energies seen. Raises AssertionError at the first violation."""
    return Watch(tol=tol, energy_tol=energy_tol, strict=True).run(
        eng, dt, duration, every_first, later)


# ================================================================================ checks


@dataclass
class Check:
    """One checked figure: `text` states it (with its value), `op` and `limit` decide it."""

    text: str
    value: Any
    op: str  # "<=", "<", ">=", ">", "=="
    limit: Any
    suffix: str | None = None  # how the limit is shown; default from op and limit

    @property
    def ok(self) -> bool:
        v = self.value
        if self.op == "==":
            return bool(v == self.limit)
        if isinstance(v, float) and math.isnan(v):
            return False
        lim = self.limit
        return bool({"<=": v <= lim, "<": v < lim, ">=": v >= lim, ">": v > lim}[self.op])

    @property
    def margin(self) -> float:
        """How close to (below 1) or how far beyond (above 1) its limit the figure is."""
        if self.op == "==":
            return 0.0 if self.ok else math.inf
        v, lim = float(self.value), float(self.limit)
        if math.isnan(v):
            return math.inf
        if self.op in ("<=", "<"):
            if lim > 0:
                return max(v, 0.0) / lim
            return 0.0 if self.ok else math.inf
        if v > 0 and lim > 0:
            return lim / v
        return 0.0 if self.ok else math.inf

    @property
    def figure(self) -> str:
        if self.suffix is not None:
            return f"{self.text} {self.suffix}".rstrip()
        lim = self.limit
        shown = f"{lim:g}" if isinstance(lim, float) else str(lim)
        suffix = {"<=": f"(limit {shown})", "<": f"(limit < {shown})",
                  ">=": f"(>= {shown})", ">": f"(> {shown})", "==": f"(must be {shown})"}[self.op]
        return f"{self.text} {suffix}"

    def as_dict(self) -> dict:
        return {"figure": self.figure, "value": _plain(self.value), "op": self.op,
                "limit": _plain(self.limit), "ok": self.ok}


def _plain(x: Any) -> Any:
    """A JSON-friendly scalar: numpy scalars as Python ones, non-finite floats as strings."""
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        x = float(x)
        return x if math.isfinite(x) else str(x)
    return x


def g(x: float, digits: int = 2) -> str:
    """A figure for a check's text: `digits` significant digits, an exact zero as 0."""
    x = float(x)
    return "0" if x == 0 else f"{x:.{digits}g}"


# ================================================================================= watch


class Watch:
    """Runs engines for a case and checks the laws as they go.

    Every engine a case uses is registered with `add`; `step`, `run`, `events_to`,
    `next_instant` and `until` drive it and `look` at its state afterwards: finite numbers,
    the largest ball-ball overlap and cushion depth, the largest relative rise of kinetic
    energy since the engine's previous look. `run` and `events_to(None)` (to rest) also record
    how long the table took against rest_bound(). With strict=True the first violation raises
    AssertionError (the tests' way); otherwise the worst figures are kept for `invariants()`.
    """

    def __init__(self, tol: float = OVERLAP_TOL, energy_tol: float = ENERGY_TOL,
                 strict: bool = False, pass_limit: int = PASS_LIMIT) -> None:
        self.tol, self.energy_tol, self.strict = tol, energy_tol, strict
        self.pass_limit = pass_limit
        self.engines: list[Engine] = []
        self.checks: list[Check] = []
        self.headline: str | None = None  # the law shown when the case has no check of its own
        self._energy: dict[int, float] = {}
        self.looks = 0
        self.nonfinite, self.nonfinite_at = 0, ""
        self.overlap, self.overlap_at = 0.0, ""
        self.depth, self.depth_at = 0.0, ""
        self.rise, self.rise_at = 0.0, ""
        self.rests: list[tuple[bool, float, float]] = []  # (at rest, time taken, bound)

    # ------------------------------------------------------------------- driving engines

    def add(self, eng: Engine) -> Engine:
        self.engines.append(eng)
        self.look(eng, "start")
        return eng

    def engine(self, *args, **kwargs) -> Engine:
        return self.add(Engine(*args, **kwargs))

    def step(self, eng: Engine, dt: float) -> None:
        eng.step(dt)
        self.look(eng, f"step {eng.steps} (t={eng.time:.6g})")

    def run(self, eng: Engine, dt: float, duration: float | None = None,
            every_first: int = 300, later: float = 0.05) -> list[float]:
        """Step by dt until at rest (or for `duration` more seconds), looking after every step
        for the first `every_first` steps and every `later` seconds after that. Returns the
        energies seen."""
        self.look(eng, "start")
        energies = [self._energy[id(eng)]]
        if duration is None:
            t_max = rest_bound(eng)
            max_steps = int(t_max / dt) + 2
        else:
            max_steps = int(math.ceil(duration / dt - 1e-9))
        stride = max(1, int(later / dt))
        n = 0
        while not eng.at_rest().all() and n < max_steps:
            eng.step(dt)
            n += 1
            if n <= every_first or n % stride == 0 or eng.at_rest().all() or n == max_steps:
                self.look(eng, f"step {n} (t={eng.time:.6g})")
                energies.append(self._energy[id(eng)])
        if duration is None:
            rest = bool(eng.at_rest().all())
            self.rests.append((rest, n * dt, t_max))
            if self.strict and not rest:
                raise AssertionError(
                    f"not at rest after {n} steps of {dt} s ({n * dt:.1f} s > bound "
                    f"{t_max:.1f} s)")
        return energies

    def events_to(self, eng: Engine, duration: float | None = None) -> None:
        """Engine.run_events(duration) (to rest without one), then look."""
        t0, bound = eng.time, rest_bound(eng) if duration is None else math.nan
        eng.run_events(duration=duration)
        self.look(eng, f"t={eng.time:.6g}")
        if duration is None:
            rest = bool(eng.at_rest().all())
            self.rests.append((rest, eng.time - t0, bound))

    def next_instant(self, eng: Engine) -> list[dict]:
        """Run exactly up to the table's next event instant; the events of that instant."""
        evs = first_event_state(eng)
        self.look(eng, f"event instant t={eng.time:.9g}")
        return evs

    def until(self, eng: Engine, kind: str, limit: int = 1000) -> list[dict]:
        """Hop from event instant to event instant until one has an event of `kind`."""
        for _ in range(limit):
            if eng.at_rest().all():
                raise AssertionError(f"came to rest before any {kind} event")
            evs = self.next_instant(eng)
            if any(e["type"] == kind for e in evs):
                return evs
        raise AssertionError(f"no {kind} event in {limit} event instants")

    # ------------------------------------------------------------------------ the laws

    def look(self, eng: Engine, where: str, energy: bool = True) -> None:
        """Check the engine's state now; energy against this engine's previous look."""
        self.looks += 1
        pos, vel, w = eng.pos, eng.vel, eng.w
        bad = 0
        for name, a in (("vel", vel), ("w", w), ("positions", pos)):
            fin = np.isfinite(a)
            if not fin.all():
                if self.strict:
                    raise AssertionError(f"{where}: non-finite {name}: {a[~fin]}")
                bad += int((~fin).sum())
        if bad:
            if not self.nonfinite:
                self.nonfinite_at = where
            self.nonfinite += bad
            return
        (ov, ov_at), (dep, dep_at) = position_figures(eng.table, eng.physics, pos, eng.state,
                                                      eng.radius)
        if self.strict:
            if ov > self.tol:
                raise AssertionError(_overlap_text(where, pos, ov, ov_at, self.tol))
            if dep > self.tol:
                raise AssertionError(_depth_text(where, pos, dep, dep_at, self.tol))
        if ov > self.overlap:
            self.overlap, self.overlap_at = ov, f"{where}, balls {ov_at[1]},{ov_at[2]}"
        if dep > self.depth:
            self.depth, self.depth_at = dep, f"{where}, ball {dep_at[1]}"
        e = float(kinetic(eng).sum())
        prev = self._energy.get(id(eng))
        self._energy[id(eng)] = e
        if not energy or prev is None:
            return
        if self.strict and not e <= prev * (1 + self.energy_tol) + ENERGY_ABS:
            raise AssertionError(
                f"{where}: kinetic energy rose from {prev!r} to {e!r} J "
                f"(relative {(e - prev) / prev:.3g})")
        excess = e - prev - ENERGY_ABS
        rise = 0.0 if excess <= 0 else (excess / prev if prev > 0 else math.inf)
        if rise > self.rise:
            self.rise, self.rise_at = rise, where

    def check(self, text: str, value: Any, op: str, limit: Any,
              suffix: str | None = None) -> bool:
        """A case's own check; returns whether it holds."""
        c = Check(text, value, op, limit, suffix)
        self.checks.append(c)
        return c.ok

    def invariants(self) -> dict[str, Check]:
        """The laws over everything this watch ran, by name."""
        out = {
            "finite": Check(f"non-finite numbers {self.nonfinite}", self.nonfinite, "==", 0,
                            "(limit 0)"),
            "overlap": Check(f"max overlap {g(self.overlap)} m", self.overlap, "<=", self.tol),
            "cushion": Check(f"max cushion depth {g(self.depth)} m", self.depth, "<=",
                             self.tol),
            "energy": Check(f"max energy rise {g(self.rise)} relative", self.rise, "<=",
                            self.energy_tol),
        }
        passes = max((e.passes for e in self.engines), default=0)
        out["passes"] = Check(f"passes {passes}", passes, "<", self.pass_limit,
                              f"(limit {self.pass_limit})")
        if self.rests:
            moving = [r for r in self.rests if not r[0]]
            if moving:
                _, t, bound = moving[0]
                out["rest"] = Check(f"still moving after {t:.3g} s", math.inf, "<=", bound,
                                    f"(bound {bound:.3g} s)")
            else:
                _, t, bound = max(self.rests, key=lambda r: r[1] / r[2])
                out["rest"] = Check(f"at rest after {t:.3g} s", t, "<=", bound,
                                    f"(bound {bound:.3g} s)")
        return out

    def digest(self) -> str:
        """sha256 of every engine's final state, clock, work and recorded events."""
        h = hashlib.sha256()
        for eng in self.engines:
            for a in (eng.pos, eng.vel, eng.w, eng.state):
                h.update(np.ascontiguousarray(a).tobytes())
            h.update(repr((eng.time, eng.steps, eng.passes, eng.events)).encode())
        return h.hexdigest()


# ====================================================================== closed forms, hops


def first_event_state(eng: Engine) -> list[dict]:
    """Run exactly up to the table's next event instant (every event at that instant)."""
    n = len(eng.events[0])
    eng.run_events(duration=float(eng.t_next[0]))
    return eng.events[0][n:]


def run_to_first(eng: Engine, kind: str, limit: int = 1000) -> list[dict]:
    """Hop from event instant to event instant until one contains an event of `kind`;
    returns the events of that instant."""
    for _ in range(limit):
        assert not eng.at_rest().all(), f"came to rest before any {kind} event"
        evs = first_event_state(eng)
        if any(e["type"] == kind for e in evs):
            return evs
    raise AssertionError(f"no {kind} event in {limit} event instants")


def slide_roll_distance(v: float, ph: Physics) -> float:
    """Distance a centre-struck ball (no spin) covers before stopping: slide then roll."""
    return 12 * v * v / (49 * ph.mu_slide * ph.g) + (5 * v / 7) ** 2 / (2 * ph.mu_roll * ph.g)


def slide_roll_time(v: float, ph: Physics) -> float:
    return 2 * v / (7 * ph.mu_slide * ph.g) + (5 * v / 7) / (ph.mu_roll * ph.g)


def spin_for(speed: float, top: float) -> float:
    """wy of a cue tip `top` R above the centre (top > 0 follow, < 0 draw) at `speed`."""
    return 2.5 * speed / R * top


def slide_roll_stop(speed: float, wy: float, ph: Physics) -> tuple[float, float]:
    """(distance, slide time) of a ball struck along x with spin wy: it slides with the slip
    u0 = v - R wy decaying at 3.5 mu_s g, then rolls at (5 v + 2 R wy) / 7 to a stop."""
    g_, mu = ph.g, ph.mu_slide
    u0 = speed - R * wy
    t_s = abs(u0) / (3.5 * mu * g_)
    a = -mu * g_ * math.copysign(1.0, u0)
    d_slide = speed * t_s + 0.5 * a * t_s * t_s
    v_roll = (5 * speed + 2 * R * wy) / 7
    d_roll = math.copysign(v_roll * v_roll / (2 * ph.mu_roll * g_), v_roll)
    return d_slide + d_roll, t_s


def head_on_law(v1: float, v2: float, m1: float, m2: float, e: float) -> np.ndarray:
    """Velocities after a head-on collision with restitution e."""
    u, p = v1 - v2, m1 * v1 + m2 * v2
    return np.array([(p - e * m2 * u) / (m1 + m2), (p + e * m1 * u) / (m1 + m2)])


def unfolded_x(x0: float, v: float, t: float) -> float:
    """x after t of a ball bouncing elastically between the rails along the long axis."""
    span = L - 2 * RC
    s = (x0 - RC + v * t) % (2 * span)
    return RC + (s if s <= span else 2 * span - s)


# ================================================================================ scenes
# Builders shared by the bench cases below and tests/test_stability.py.


def roll(v: float, ph: Physics | None = None) -> Engine:
    """One centre-struck ball at v m/s along x from the table's centre."""
    return Engine(PLAIN, ph or Physics(), [[L / 2, W / 2]], [[v, 0.0]])


def nudge() -> tuple[Engine, list]:
    """A 1 mm/s ball with 1 micrometre to go before it touches the next ball."""
    x0 = L / 2
    pos = [[x0, W / 2], [x0 + 2 * R + 1e-6, W / 2]]
    return Engine(PLAIN, Physics(), pos, [[1e-3, 0.0], [0.0, 0.0]]), pos


def fifty_hit() -> tuple[Engine, np.ndarray]:
    """50 m/s at a still ball 1.94 m ahead."""
    pos = np.array([[0.3, W / 2], [L - 0.3, W / 2]])
    return Engine(PLAIN, Physics(), pos, [[50.0, 0.0], [0.0, 0.0]]), pos


def fifty_hit_time(pos: np.ndarray, ph: Physics) -> float:
    """When the 50 m/s ball, sliding (x = v t - mu g t^2 / 2), reaches the other."""
    gap = pos[1, 0] - pos[0, 0] - 2 * R
    a = ph.mu_slide * ph.g
    return (50.0 - math.sqrt(50.0**2 - 2 * a * gap)) / a


def fifty_graze(offset: float) -> Engine:
    """50 m/s passing a still ball at a centre offset of `offset` R."""
    pos = np.array([[0.3, W / 2], [L - 0.5, W / 2 + offset * R]])
    return Engine(PLAIN, Physics(), pos, [[50.0, 0.0], [0.0, 0.0]])


FIFTY_ANGLES = (0.0, 27.0, 45.0, 90.0, 133.7)


def fifty_free(pockets: str, angle: float) -> Engine:
    """One ball at 50 m/s at `angle` degrees from near the centre."""
    a = math.radians(angle)
    return Engine(Table(pockets=pockets), Physics(), [[L / 2 + 0.1, W / 2 - 0.05]],
                  [[50 * math.cos(a), 50 * math.sin(a)]])


def close_break() -> dict:
    """The 8-ball rack with the cue ball 0.1 m from the apex at 8 m/s: the break happens in
    the first 20 ms. Engine arguments (table, physics, pos, vel, w)."""
    sc = load_scene({"table": "9ft", "balls": "8ball", "shot": {"speed": 8.0}})
    pos = sc.pos.copy()
    pos[0] = (pos[1, 0] - 0.1, pos[1, 1])
    return dict(table=sc.table, physics=sc.physics, pos=pos, vel=sc.vel, w=sc.w)


STEP_RUNS = ((1e-5, 0.02), (1e-4, 0.05), (1e-3, 0.3), (1e-2, 1.0), (0.1, 2.0))  # (dt, duration)
HEAD_ON_V = (2.0, -0.5)


def head_on(e: float, m2: float) -> Engine:
    """Frictionless balls on frictionless cloth, head on at 2 and -0.5 m/s, masses M and m2."""
    ph = Physics(e_ball=e, ball_ball="frictionless", **FRICTIONLESS_CLOTH)
    v1, v2 = HEAD_ON_V
    return Engine(PLAIN, ph, [[0.8, W / 2], [1.6, W / 2]], [[v1, 0.0], [v2, 0.0]], mass=[M, m2])


def cushion_rebound(e: float) -> Engine:
    """3 m/s straight into the foot rail, no cushion friction, no cloth friction."""
    ph = Physics(e_cushion=e, mu_cushion=0.0, **FRICTIONLESS_CLOTH)
    return Engine(PLAIN, ph, [[L - 0.5, W / 2]], [[3.0, 0.0]])


REFLECT = (0.7, 2.0, 10.0)  # x0, v, T


def reflection() -> Engine:
    """No friction anywhere, e_cushion = 1: one ball along the long axis, bouncing forever."""
    ph = Physics(e_cushion=1.0, mu_cushion=0.0, **FRICTIONLESS_CLOTH)
    x0, v, _ = REFLECT
    return Engine(PLAIN, ph, [[x0, W / 2]], [[v, 0.0]])


HUGE_MU = dict(mu_slide=100.0, mu_roll=100.0)
HUGE_SHOTS = ((5.0, 0.0), (5.0, 0.4), (0.3, -0.4), (20.0, 0.2))  # (speed, tip height / R)


def huge_friction(speed: float, top: float) -> Engine:
    """mu_slide = mu_roll = 100, a shot along x with tip height `top`."""
    return Engine(PLAIN, Physics(**HUGE_MU), [[L / 2, W / 2]], [[speed, 0.0]],
                  [[0.0, spin_for(speed, top), 0.0]])


def huge_friction_collision() -> tuple[Engine, list]:
    pos = [[L / 2, W / 2], [L / 2 + 2 * R + 0.01, W / 2]]
    return Engine(PLAIN, Physics(**HUGE_MU), pos, [[8.0, 0.0], [0.0, 0.0]]), pos


def mass_ratio(heavy_first: bool, ph: Physics | None = None) -> Engine:
    """1000:1 masses at 0.8 and 1.4 m, the first at 1.5 m/s at the still second."""
    m1, m2 = (1000 * M, M) if heavy_first else (M, 1000 * M)
    return Engine(PLAIN, ph or Physics(), [[0.8, W / 2], [1.4, W / 2]],
                  [[1.5, 0.0], [0.0, 0.0]], mass=[m1, m2])


def radius_break(scale: float, pockets: str) -> Engine:
    """A full 8-ball rack of balls `scale` times the standard radius broken at 8 m/s."""
    tab = Table(pockets=pockets)
    r = R * scale
    balls = rack("8ball", tab, radius=r)
    pos = np.array([[b["x"], b["y"]] for b in balls])
    vel = np.zeros_like(pos)
    vel[0] = (8.0, 0.0)
    return Engine(tab, Physics(), pos, vel, radius=r)


def rack_break(rack_name: str, speed: float = 20.0) -> Engine:
    sc = load_scene({"table": "9ft", "balls": rack_name, "shot": {"speed": speed}})
    return Engine(sc.table, sc.physics, sc.pos, sc.vel, sc.w)


def cradle(ph: Physics, v0: float = 2.0, gap: float = 0.3) -> tuple[Engine, float]:
    """Five touching balls in a row along the long axis; the cue ball `gap` m before the
    first, centre-struck at v0. Returns the engine and the cue's speed at impact from the
    sliding law v^2 = v0^2 - 2 mu_s g d."""
    x1 = L / 2 - 0.2
    pos = [[x1 - 2 * R - gap, W / 2]] + [[x1 + 2 * R * k, W / 2] for k in range(5)]
    vel = [[v0, 0.0]] + [[0.0, 0.0]] * 5
    eng = Engine(PLAIN, ph, pos, vel)
    assert gap < 12 * v0 * v0 / (49 * ph.mu_slide * ph.g)  # still sliding at impact
    return eng, math.sqrt(v0 * v0 - 2 * ph.mu_slide * ph.g * gap)


def wedge(ph: Physics) -> tuple[Engine, list]:
    """Ball 2 touching the foot rail, ball 1 touching ball 2, the cue ball 1 m away at 3 m/s."""
    xb = L - RC
    pos = [[xb - 2 * R - 1.0, W / 2], [xb - 2 * R, W / 2], [xb, W / 2]]
    eng = Engine(PLAIN, ph, pos, [[3.0, 0.0], [0.0, 0.0], [0.0, 0.0]])
    return eng, pos


WEDGE_ELASTIC = dict(e_cushion=1.0, mu_cushion=0.0, **ELASTIC, **FRICTIONLESS_CLOTH)


def travelling_pair(layout: str) -> tuple[Engine, np.ndarray]:
    """Two touching balls ("side_by_side" or "in_line") with the same velocity and spin."""
    x, y = L / 2, W / 2
    other = [x, y + 2 * R] if layout == "side_by_side" else [x + 2 * R, y]
    pos = np.array([[x, y], other])
    vel = np.array([[2.0, 0.3], [2.0, 0.3]])
    w = np.array([[10.0, -30.0, 40.0]] * 2)
    return Engine(PLAIN, Physics(), pos, vel, w), pos


MEET_CENTRE = np.array([L / 2, W / 2])
MEET_D = 0.3


def three_meet(ph: Physics, speed: float) -> Engine:
    """Three equal balls 120 degrees apart, MEET_D from MEET_CENTRE, heading for it."""
    ang = np.radians([90.0, 210.0, 330.0])
    u = np.stack([np.cos(ang), np.sin(ang)], axis=1)
    return Engine(PLAIN, ph, MEET_CENTRE + MEET_D * u, -speed * u)


def jaw_tip(pocket: str) -> tuple[np.ndarray, np.ndarray]:
    """A jaw tip of the side pocket or the head-right corner pocket, and a unit vector from it
    into the table along which a ball touching only that tip sits."""
    tab = POCKETS
    if pocket == "side":
        return (np.array([L / 2 + tab.side_mouth / 2, 0.0]),
                np.array([-0.5, math.sqrt(3) / 2]))
    return np.array([tab.corner_mouth / math.sqrt(2), 0.0]), np.array([-0.6, 0.8])


def jaw_ball(tip: np.ndarray, into: np.ndarray) -> np.ndarray:
    """A ball touching jaw tip `tip` only, its centre along unit vector `into` from it."""
    return tip + RC * into


def jaw_hit(pocket: str, speed: float) -> Engine:
    """A still ball touching a pocket's jaw tip, hit by another ball at `speed`."""
    b = jaw_ball(*jaw_tip(pocket))
    cue = b + np.array([0.15, 0.35])
    v = (b - cue) / np.linalg.norm(b - cue) * speed
    return Engine(POCKETS, Physics(), [cue, b], [v, [0.0, 0.0]])


SPIN = 5000.0  # rad/s: a cue gives at most about 2.5 v / R, ~200 rad/s at 3 m/s


def side_spin() -> Engine:
    return Engine(PLAIN, Physics(), [[L / 2, W / 2]], None, [[0.0, 0.0, SPIN]])


def back_spin() -> Engine:
    return Engine(PLAIN, Physics(), [[L / 2, W / 2]], [[1.0, 0.0]], [[0.0, -SPIN, 0.0]])


def spin_rack(pockets: str) -> Engine:
    sc = load_scene({"table": {"pockets": pockets}, "balls": "8ball"})
    vel = np.zeros_like(sc.pos)
    vel[0] = (3.0, 0.1)
    w = np.zeros((len(sc.pos), 3))
    w[0] = (SPIN, -SPIN, SPIN)
    return Engine(sc.table, sc.physics, sc.pos, vel, w)


def long_run() -> Engine:
    """No friction anywhere, e = 1 everywhere (and no inelastic threshold), pockets none,
    four balls."""
    ph = Physics(e_cushion=1.0, mu_cushion=0.0, v_inelastic=0.0, **ELASTIC, **FRICTIONLESS_CLOTH)
    pos = [[0.5, 0.4], [1.3, 0.7], [2.0, 0.3], [1.8, 1.0]]
    vel = [[1.3, 0.7], [-0.9, 1.1], [0.4, -1.6], [-1.2, -0.5]]
    return Engine(PLAIN, ph, pos, vel)


# ================================================================================= cases
# Each case function takes (watch, quick), runs its scenes through the watch and adds its own
# checks; its first check is its headline. They mirror tests/test_stability.py.


def _types(evs: list[dict]) -> list[str]:
    return [e["type"] for e in evs]


def _count(eng: Engine, kind: str) -> int:
    return sum(e["type"] == kind for e in eng.events[0])


def case_roll(w: Watch, quick: bool, v: float, tol: float) -> None:
    eng = w.add(roll(v))
    ph = eng.physics
    w.run(eng, 1 / 60)
    d = float(eng.pos[0, 0, 0] - L / 2)
    law = slide_roll_distance(v, ph)
    w.check(f"stop distance {g(d, 4)} m off the closed form by {g(abs(d - law))} m",
            abs(d - law), "<=", tol)
    side = abs(float(eng.pos[0, 0, 1]) - W / 2)
    w.check(f"sideways drift {g(side)} m", side, "==", 0.0, "(limit 0)")
    stop = [e["t"] for e in eng.events[0] if e["type"] == "roll_to_stop"]
    w.check(f"{len(stop)} roll_to_stop events", len(stop), "==", 1)
    if stop:
        dt = abs(stop[0] - slide_roll_time(v, ph))
        w.check(f"stop time off the law by {g(dt)} s", dt, "<=", 2e-4)


def case_nudge(w: Watch, quick: bool) -> None:
    eng, pos = nudge()
    w.add(eng)
    w.run(eng, 1 / 60)
    moved = float(eng.pos[0, 1, 0] - pos[1][0])
    w.check(f"object ball moved {g(moved)} m forward", moved, ">=", 0.0, "(>= 0)")
    w.check(f"ball_ball events {_count(eng, 'ball_ball')}", _count(eng, "ball_ball"), ">=", 1)


def case_fifty_hit(w: Watch, quick: bool, dt: float) -> None:
    eng, pos = fifty_hit()
    w.add(eng)
    while eng.time < 0.1 - 1e-12:
        w.step(eng, dt)
    contacts = [e for e in eng.events[0] if e["type"] in ("ball_ball", "cushion")]
    first = bool(contacts) and contacts[0]["type"] == "ball_ball" \
        and sorted(contacts[0]["i"]) == [0, 1]
    if first:
        err = abs(contacts[0]["t"] - fifty_hit_time(pos, eng.physics))
        w.check(f"hit 1.94 m ahead at the sliding law's time to {g(err)} s", err, "<=", 1e-9)
    w.check("first contact is the ball ahead" if first else
            f"first contact: {contacts[:1]}", first, "==", True, "")
    w.run(eng, dt, duration=3.0)


def case_fifty_graze(w: Watch, quick: bool, offset: float) -> None:
    eng = w.add(fifty_graze(offset))
    w.step(eng, 0.1)
    hit = any(e["type"] == "ball_ball" for e in eng.events[0])
    want = offset < 2
    w.check(f"offset {offset} R: {'hit' if hit else 'missed'} in one 0.1 s step", hit, "==",
            want, f"(must {'hit' if want else 'miss'})")
    w.run(eng, 0.1, duration=2.0)


def case_fifty_free(w: Watch, quick: bool, pockets: str) -> None:
    for angle in FIFTY_ANGLES:
        eng = w.add(fifty_free(pockets, angle))
        w.run(eng, 0.1, duration=5.0)
    w.headline = "cushion"


def case_step(w: Watch, quick: bool, dt: float, duration: float) -> None:
    sc = close_break()
    eng = w.add(Engine(**sc))
    w.run(eng, dt, duration=duration, every_first=10**9)
    ref = w.add(Engine(**sc))
    w.events_to(ref, duration)
    err = float(np.abs(eng.pos - ref.pos).max())
    w.check(f"positions at {duration:g} s off the event-to-event run by {g(err)} m", err, "<=",
            1e-9)
    same = bool(np.array_equal(eng.state, ref.state))
    w.check("same ball states as the reference" if same else "ball states differ", same, "==",
            True, "")
    n_bb = _count(eng, "ball_ball")
    w.check(f"ball_ball events {n_bb}", n_bb, ">=", 10)


def case_head_on(w: Watch, quick: bool, e: float) -> None:
    errs, gaps, kinds = [], [], []
    for m2 in (M, 2.5 * M):
        eng = w.add(head_on(e, m2))
        evs = w.next_instant(eng)
        kinds.append(_types(evs))
        law = head_on_law(*HEAD_ON_V, M, m2, e)
        errs.append(float(np.abs(eng.vel[0, :, 0] - law).max()))
        errs.append(float(np.abs(eng.vel[0, :, 1]).max()))
        w.run(eng, 1 / 60, duration=0.2)
        gaps.append(float(eng.pos[0, 1, 0] - eng.pos[0, 0, 0] - 2 * R))
    w.check(f"velocities off the law by {g(max(errs))} m/s (m2 = 1, 2.5 m1)", max(errs), "<=",
            1e-12)
    w.check(f"impact instants: {kinds}", kinds, "==", [["ball_ball"]] * 2,
            "(one ball_ball each)")
    u = HEAD_ON_V[0] - HEAD_ON_V[1]
    if e == 0.0:
        worst = max(abs(x) for x in gaps)
        w.check(f"e=0 pair's gap after 0.2 s {g(worst)} m", worst, "<=", 1e-6)
    else:
        w.check(f"e=1 pair separated {g(min(gaps), 3)} m in 0.2 s", min(gaps), ">=",
                0.2 * u * 0.9)


def case_cushion(w: Watch, quick: bool, e: float) -> None:
    eng = w.add(cushion_rebound(e))
    w.until(eng, "cushion")
    vx = float(eng.vel[0, 0, 0])
    w.check(f"rebound {g(vx, 4)} m/s off -e v by {g(abs(vx + e * 3.0))} m/s",
            abs(vx + e * 3.0), "<=", 1e-12)
    dx = abs(float(eng.pos[0, 0, 0]) - (L - RC))
    w.check(f"contact point off the nose by {g(dx)} m", dx, "<=", 1e-9)
    w.run(eng, 1 / 60, duration=1.0 - eng.time)


def case_reflection(w: Watch, quick: bool) -> None:
    w.energy_tol = 1e-12
    x0, v, T = REFLECT
    eng = w.add(reflection())
    w.run(eng, 1 / 30, duration=T)
    x = float(eng.pos[0, 0, 0])
    err = abs(x - unfolded_x(x0, v, T))
    w.check(f"x after {T:g} s off the unfolded path by {g(err)} m", err, "<=", 1e-9)
    dv = abs(float(eng.vel[0, 0, 0]) ** 2 / (v * v) - 1)
    w.check(f"speed^2 changed by {g(dv)} relative", dv, "<=", 1e-12)


def case_slow_frictionless(w: Watch, quick: bool) -> None:
    errs = []
    for v in (5e-4, 2e-3):
        eng = w.add(roll(v, Physics(**FRICTIONLESS_CLOTH)))
        w.run(eng, 1 / 60, duration=1.0)
        errs.append(abs(float(eng.vel[0, 0, 0]) - v) / v)
        errs.append(abs(float(eng.pos[0, 0, 0] - L / 2) - v) / v)
    w.check(f"speed and distance after 1 s off v, v t by {g(max(errs))} relative", max(errs),
            "<=", 1e-12)


def case_huge_friction(w: Watch, quick: bool, dt: float) -> None:
    back_x, back_v, worst, text = 0.0, 0.0, 0.0, ""
    for speed, top in HUGE_SHOTS:
        eng = w.add(huge_friction(speed, top))
        x_prev = L / 2
        for _ in range(10_000):
            w.step(eng, dt)
            x, vx = float(eng.pos[0, 0, 0]), float(eng.vel[0, 0, 0])
            if top >= 0:
                back_x, back_v = max(back_x, x_prev - x), max(back_v, -vx)
            x_prev = x
            if eng.at_rest().all():
                break
        w.rests.append((bool(eng.at_rest().all()), eng.time, 10_000 * dt))
        law, t_s = slide_roll_stop(speed, spin_for(speed, top), eng.physics)
        d = float(eng.pos[0, 0, 0] - L / 2)
        tol = 1e-9 + 1e-3 * t_s  # slips under 1 mm/s are completed at once by design
        if abs(d - law) / tol >= worst:
            worst = abs(d - law) / tol
            text = (f"stop distance off the closed form by {g(abs(d - law))} m at {speed:g} m/s"
                    f" (limit {tol:.2g})")
    w.check(f"no-draw shots moved back {g(back_x)} m, reversed to {g(back_v)} m/s",
            max(back_x, back_v), "<=", 0.0, "(limit 0)")
    w.check(text, worst, "<=", 1.0, "")


def case_huge_collision(w: Watch, quick: bool) -> None:
    eng, pos = huge_friction_collision()
    w.add(eng)
    w.run(eng, 1e-3)
    moved = float(eng.pos[0, 1, 0] - pos[1][0])
    w.check(f"object ball moved {g(moved, 3)} m forward", moved, ">=", 0.0, "(>= 0)")
    w.check(f"ball_ball events {_count(eng, 'ball_ball')}", _count(eng, "ball_ball"), ">=", 1)


def case_mass(w: Watch, quick: bool, heavy_first: bool) -> None:
    eng = w.add(mass_ratio(heavy_first, Physics(**ELASTIC, **FRICTIONLESS_CLOTH)))
    m1, m2 = (float(m) for m in eng.mass[0])
    v = 1.5
    E0, P0 = float(kinetic(eng)[0]), momentum(eng)[0]
    evs = w.next_instant(eng)
    law = np.array([(m1 - m2) / (m1 + m2) * v, 2 * m1 / (m1 + m2) * v])
    err = float(np.abs(eng.vel[0, :, 0] - law).max())
    w.check(f"e=1 velocities off the law by {g(err)} m/s", err, "<=", 1e-12 * v)
    w.check(f"impact instant: {_types(evs)}", _types(evs), "==", ["ball_ball"],
            "(one ball_ball)")
    dp = float(np.abs(momentum(eng)[0] - P0).max()) / abs(float(P0[0]))
    w.check(f"momentum changed by {g(dp)} relative", dp, "<=", 1e-12)
    dE = abs(float(kinetic(eng)[0]) - E0) / E0
    w.check(f"elastic impact changed energy by {g(dE)} relative", dE, "<=", 1e-12)
    w.run(w.add(mass_ratio(heavy_first)), 1 / 60)  # on cloth, to rest: the squeeze


def case_radius(w: Watch, quick: bool, scale: float) -> None:
    n_bb = []
    for pockets in ("none", "standard"):
        eng = w.add(radius_break(scale, pockets))
        w.run(eng, 1 / 60)
        n_bb.append(_count(eng, "ball_ball"))
    w.headline = "overlap"
    w.check(f"ball_ball events {min(n_bb)} (fewest of 2 tables)", min(n_bb), ">=", 15)


def case_rack(w: Watch, quick: bool, rack_name: str) -> None:
    for dt in (1 / 60, 0.1):
        w.run(w.add(rack_break(rack_name)), dt)
    w.headline = "overlap"


def case_cradle_elastic(w: Watch, quick: bool) -> None:
    eng, v_imp = cradle(Physics(**ELASTIC))
    w.add(eng)
    evs = w.until(eng, "ball_ball")
    n_bb = sum(e["type"] == "ball_ball" for e in evs)
    w.check(f"{n_bb} ball_ball contacts at the impact instant", n_bb, "==", 5, "(exactly 5)")
    vx = eng.vel[0, :, 0]
    err = abs(float(vx[5]) - v_imp) / v_imp
    w.check(f"last ball leaves at {float(vx[5]):.4f} m/s, impact {v_imp:.4f}: off by "
            f"{g(err)}", err, "<=", 1e-9)
    still = float(np.abs(eng.vel[0, :5]).max()) / v_imp
    w.check(f"others' speed {g(still)} of the impact speed", still, "<=", 1e-9)
    w.run(w.add(cradle(Physics(**ELASTIC))[0]), 1 / 60)  # follow spin pushes the row: to rest


def case_cradle_cloth(w: Watch, quick: bool) -> None:
    ph = Physics()
    eng, v_imp = cradle(ph)
    w.add(eng)
    t_imp = (2.0 - v_imp) / (ph.mu_slide * ph.g)
    w.events_to(eng, t_imp * (1 - 1e-9))
    P0, E0 = momentum(eng)[0], float(kinetic(eng)[0])
    evs = w.next_instant(eng)
    vx = eng.vel[0, :, 0]
    frac = float(vx[5]) / v_imp
    w.check(f"last ball {float(vx[5]):.2f} m/s of {v_imp:.2f}", frac, ">=", 0.85,
            f"({frac:.3f} >= 0.85)")
    w.check(f"last ball at {frac:.3f} of the impact speed", frac, "<=", 1.0)
    w.check(f"fastest is ball {int(vx.argmax())}", int(vx.argmax()), "==", 5)
    w.check(f"slowest ball {g(float(vx.min()), 3)} m/s", float(vx.min()), ">=", -1e-9,
            "(>= -1e-09: none goes back)")
    dt = abs(evs[0]["t"] - t_imp)
    w.check(f"impact time off the sliding law by {g(dt)} s", dt, "<=", 1e-9)
    n_bb = sum(e["type"] == "ball_ball" for e in evs)
    w.check(f"{n_bb} ball_ball contacts at the impact instant", n_bb, "<=", 15)
    dp = float(np.abs(momentum(eng)[0] - P0).max()) / abs(float(P0[0]))
    w.check(f"momentum changed by {g(dp)} relative at the impact", dp, "<=", 1e-9)
    dE = (float(kinetic(eng)[0]) - E0) / E0
    w.check(f"energy changed by {g(dE, 3)} relative at the impact", dE, "<=", 1e-9)
    w.run(eng, 1 / 60)


def case_wedge_elastic(w: Watch, quick: bool) -> None:
    eng, pos = wedge(Physics(**WEDGE_ELASTIC))
    w.add(eng)
    evs = w.until(eng, "ball_ball")
    vx = eng.vel[0, :, 0]
    err = abs(float(vx[0]) + 3.0)
    w.check(f"cue ball returns at {float(vx[0]):.6g} m/s, off -3 by {g(err)}", err, "<=", 1e-9)
    still = float(np.abs(eng.vel[0, 1:]).max())
    w.check(f"wedged balls' speed {g(still)} m/s", still, "<=", 1e-9)
    w.check(f"{len(evs)} events at the impact instant", len(evs), "<=", 15)
    into = float(eng.pos[0, 2, 0]) - pos[2][0]
    w.check(f"wedged ball pushed {g(into)} m into the rail", into, "<=", 1e-6)


def case_wedge(w: Watch, quick: bool) -> None:
    for dt in (1 / 60, 0.1):
        eng, _ = wedge(Physics())
        w.run(w.add(eng), dt)
    w.headline = "overlap"


def case_pair(w: Watch, quick: bool, layout: str) -> None:
    err, early, reached = 0.0, 0, True
    for dt in (1 / 60, 0.1):
        eng, pos = travelling_pair(layout)
        w.add(eng)
        for _ in range(1, 1000):
            w.step(eng, dt)
            kinds = _types(eng.events[0])
            cushion = "cushion" in kinds
            if cushion:
                kinds = kinds[: kinds.index("cushion")]
            early = max(early, kinds.count("ball_ball"))
            if cushion:
                break
            sep = (eng.pos[0, 1] - eng.pos[0, 0]) - (pos[1] - pos[0])
            err = max(err, float(np.abs(sep).max()))
        else:
            reached = False
        w.run(eng, dt)
    w.check(f"separation changed by {g(err)} m before the first cushion", err, "<=", 1e-12)
    w.check(f"ball_ball events before the first cushion {early}", early, "==", 0, "(limit 0)")
    w.check("reached a cushion" if reached else "never reached a cushion", reached, "==", True,
            "")


def case_three_elastic(w: Watch, quick: bool) -> None:
    w.energy_tol = 1e-12
    eng = w.add(three_meet(Physics(**ELASTIC, **FRICTIONLESS_CLOTH), 1.0))
    evs = w.until(eng, "ball_ball")
    t_meet = MEET_D - 2 * R / math.sqrt(3)
    dt = abs(evs[0]["t"] - t_meet)
    w.check(f"met at the geometric instant to {g(dt)} s", dt, "<=", 1e-9)
    p1 = float(np.abs(momentum(eng)[0]).max())
    w.run(eng, 1 / 60, duration=0.25)  # too short to reach a cushion even at sqrt(3) m/s
    p2 = float(np.abs(momentum(eng)[0]).max())
    w.check(f"total momentum {g(max(p1, p2))} kg m/s after the meeting", max(p1, p2), "<=",
            1e-12)
    d = float(np.linalg.norm(eng.pos[0] - MEET_CENTRE, axis=1).min())
    w.check(f"nearest ball {g(d, 3)} m from the meeting point after 0.25 s", d, ">", 2 * R,
            f"(> 2R = {2 * R:.4g})")


def case_three_cloth(w: Watch, quick: bool) -> None:
    w.run(w.add(three_meet(Physics(), 2.0)), 1 / 60)
    w.headline = "overlap"


def case_jaw(w: Watch, quick: bool, pocket: str) -> None:
    tip, into = jaw_tip(pocket)
    b = jaw_ball(tip, into)
    is_tip = any(np.allclose(tip, p) for p in POCKETS.points)
    w.check("placed on a jaw tip" if is_tip else "not a jaw tip", is_tip, "==", True, "")
    dist = float(seg_distance(POCKETS, b).min())
    w.check(f"placed ball off the nose reach by {g(abs(dist - RC))} m", abs(dist - RC), "<=",
            1e-12)
    n_bb = []
    for dt in (1 / 60, 0.1):
        for speed in (0.5, 4.0):
            eng = w.add(jaw_hit(pocket, speed))
            w.run(eng, dt)
            n_bb.append(_count(eng, "ball_ball"))
    w.headline = "cushion"
    w.check(f"ball_ball events {min(n_bb)} (fewest of 4 runs)", min(n_bb), ">=", 1)


def case_side_spin(w: Watch, quick: bool) -> None:
    eng = w.add(side_spin())
    p0 = eng.pos[0, 0].copy()
    w.events_to(eng)
    stops = [e["t"] for e in eng.events[0] if e["type"] == "spin_to_stop"]
    law = 2 * R * SPIN / (5 * eng.physics.mu_spin * eng.physics.g)
    err = abs(stops[0] - law) / law if len(stops) == 1 else math.inf
    w.check(f"spin stops at {law:.4g} s (law) to {g(err)} relative", err, "<=", 1e-9)
    moved = float(np.abs(eng.pos[0, 0] - p0).max())
    w.check(f"moved {g(moved)} m while spinning", moved, "==", 0.0, "(limit 0)")


def case_back_spin(w: Watch, quick: bool) -> None:
    worst = 0.0
    for dt in (1 / 60, 0.1):
        eng = w.add(back_spin())
        ph = eng.physics
        for _ in range(1, 200):
            w.step(eng, dt)
            if any(e["type"] == "cushion" for e in eng.events[0]):
                break
            law = 1.0 - ph.mu_slide * ph.g * eng.time
            worst = max(worst, abs(float(eng.vel[0, 0, 0]) - law) / max(1.0, abs(law)),
                        abs(float(eng.vel[0, 0, 1])))
        w.run(eng, dt)
    w.check(f"velocity off the sliding law v0 - mu g t by {g(worst)} m/s", worst, "<=", 1e-12)


def case_spin_rack(w: Watch, quick: bool) -> None:
    for pockets in ("none", "standard"):
        w.run(w.add(spin_rack(pockets)), 0.1)
    w.headline = "overlap"


def case_long_run(w: Watch, quick: bool) -> None:
    T = QUICK_LONG_RUN_S if quick else LONG_RUN_S
    w.pass_limit = int(LONG_PASSES_PER_S * T)
    eng = w.add(long_run())
    E0 = float(kinetic(eng)[0])
    drift = 0.0
    while eng.time < T - 1e-9:
        w.step(eng, LONG_RUN_DT)
        drift = max(drift, abs(float(kinetic(eng)[0]) - E0) / E0)
    w.check(f"energy drift {g(drift)} relative over {T:g} s", drift, "<=", LONG_RUN_DRIFT)
    n_c, n_bb = _count(eng, "cushion"), _count(eng, "ball_ball")
    w.check(f"cushion contacts {n_c}", n_c, ">", 1000 * T / LONG_RUN_S)
    w.check(f"ball_ball contacts {n_bb}", n_bb, ">", 10 * T / LONG_RUN_S)
    potted = int((eng.state[0] == POCKETED).sum())
    w.check(f"balls pocketed {potted}", potted, "==", 0, "(limit 0)")


@dataclass(frozen=True)
class Case:
    name: str
    group: str
    fn: Callable[[Watch, bool], None]


def _cases() -> list[Case]:
    c = []

    def add(group: str, name: str, fn: Callable, **kw: Any) -> None:
        c.append(Case(name, group, partial(fn, **kw) if kw else fn))

    add("speed", "roll 1 mm/s to rest", case_roll, v=1e-3, tol=5e-8)
    add("speed", "roll 2 mm/s to rest", case_roll, v=2e-3, tol=1e-12)
    add("speed", "1 mm/s nudge, 1 um gap", case_nudge)
    add("speed", "50 m/s hit, dt 0.1", case_fifty_hit, dt=0.1)
    add("speed", "50 m/s hit, dt 1/60", case_fifty_hit, dt=1 / 60)
    add("speed", "50 m/s graze 1.999 R", case_fifty_graze, offset=1.999)
    add("speed", "50 m/s graze 2.001 R", case_fifty_graze, offset=2.001)
    add("speed", "50 m/s x5 directions", case_fifty_free, pockets="none")
    add("speed", "50 m/s x5 dirs, pockets", case_fifty_free, pockets="standard")
    for dt, duration in STEP_RUNS:
        add("dt", f"break, dt {dt:g} s", case_step, dt=dt, duration=duration)
    add("restitution", "head-on e=0", case_head_on, e=0.0)
    add("restitution", "head-on e=1", case_head_on, e=1.0)
    add("restitution", "cushion e=0", case_cushion, e=0.0)
    add("restitution", "cushion e=1", case_cushion, e=1.0)
    add("friction", "frictionless rebounds, 10 s", case_reflection)
    add("friction", "frictionless, 0.5 and 2 mm/s", case_slow_frictionless)
    add("friction", "mu 100 stops, dt 1e-3", case_huge_friction, dt=1e-3)
    add("friction", "mu 100 stops, dt 0.1", case_huge_friction, dt=0.1)
    add("friction", "mu 100 collision", case_huge_collision)
    add("mass", "mass 1000:1, heavy hits", case_mass, heavy_first=True)
    add("mass", "mass 1000:1, light hits", case_mass, heavy_first=False)
    add("radius", "radius x0.5 break", case_radius, scale=0.5)
    add("radius", "radius x2 break", case_radius, scale=2.0)
    add("rack", "8-ball rack at 20 m/s", case_rack, rack_name="8ball")
    add("rack", "9-ball rack at 20 m/s", case_rack, rack_name="9ball")
    add("cradle", "cradle e=1 frictionless", case_cradle_elastic)
    add("cradle", "cradle e=0.95 on cloth", case_cradle_cloth)
    add("contact", "wedged, elastic", case_wedge_elastic)
    add("contact", "wedged, cloth", case_wedge)
    add("contact", "pair touching, abreast", case_pair, layout="side_by_side")
    add("contact", "pair touching, in line", case_pair, layout="in_line")
    add("contact", "three meet, elastic", case_three_elastic)
    add("contact", "three meet, cloth", case_three_cloth)
    add("contact", "jaw tip, side pocket", case_jaw, pocket="side")
    add("contact", "jaw tip, corner pocket", case_jaw, pocket="corner")
    add("spin", "side spin 5000 rad/s", case_side_spin)
    add("spin", "back spin 5000 rad/s", case_back_spin)
    add("spin", "spin 5000 into a rack", case_spin_rack)
    add("long run", "frictionless e=1 long run", case_long_run)
    return c


CASES: list[Case] = _cases()


# ================================================================================ runner


def _attempt(case: Case, quick: bool) -> tuple[Watch, str | None, float]:
    w = Watch()
    t0 = time.perf_counter()
    error = None
    try:
        with np.errstate(all="ignore"):
            case.fn(w, quick)
    except Exception as e:  # a case that crashes is a failed case, not a crashed bench
        lines = str(e).strip().splitlines() or [""]
        error = f"{type(e).__name__}: {lines[0][:160]}"
    return w, error, time.perf_counter() - t0


def run_case(case: Case, quick: bool = False) -> tuple[str, bool, dict]:
    """Run `case` twice; (figure, ok, details). See the module's docstring."""
    w, error, wall = _attempt(case, quick)
    w2, error2, wall2 = _attempt(case, quick)
    same = error is None and error2 is None and w.digest() == w2.digest()
    laws = w.invariants()
    laws["deterministic"] = Check(
        "bit-identical in 2 runs" if same else "2 runs differ", same, "==", True, "")
    checks = list(w.checks) + list(laws.values())
    if error is not None:
        checks.insert(0, Check(f"error: {error}", False, "==", True, ""))
    failing = [c for c in checks if not c.ok]
    if failing:
        shown = failing[0] if error is not None else max(failing, key=lambda c: c.margin)
    elif w.headline:
        shown = laws[w.headline]
    elif w.checks:
        shown = w.checks[0]
    else:
        shown = max(laws.values(), key=lambda c: c.margin)
    figure = shown.figure
    if not failing:  # a passing case also shows any law it kept within 10x of its limit
        close = [c for k, c in laws.items() if k in CLOSE_CALL_LAWS and c is not shown
                 and c.margin >= CLOSE_CALL]
        figure = "; ".join([figure] + [c.figure for c in close])
    engines = w.engines
    details = {
        "checks": [c.as_dict() for c in checks],
        "laws": {k: c.as_dict() for k, c in laws.items()},
        "wall_s": wall,
        "wall_s_repeat": wall2,
        "engines": len(engines),
        "steps": sum(e.steps for e in engines),
        "passes": sum(e.passes for e in engines),
        "max_passes": max((e.passes for e in engines), default=0),
        "sim_s": max((e.time for e in engines), default=0.0),
        "looks": w.looks,
        "overlap_m": w.overlap,
        "overlap_at": w.overlap_at,
        "cushion_m": w.depth,
        "cushion_at": w.depth_at,
        "energy_rise": w.rise,
        "energy_rise_at": w.rise_at,
        "deterministic": same,
        "digest": w.digest(),
        "error": error or error2,
    }
    return figure, not failing, details
