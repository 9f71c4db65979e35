"""Shared law checks for the engine tests (test_properties.py, test_stability.py).

Each check states a law of the model and is computed from the engine's public state only:
finite numbers, kinetic energy that never rises, no interpenetration, balls kept within the
cushion noses, and a generous physical bound on the time a table takes to come to rest.
"""

from __future__ import annotations

import math

import numpy as np

from termpool.physics.engine import POCKETED, Engine
from termpool.physics.params import Physics
from termpool.physics.table import Table

OVERLAP_TOL = 1e-6  # m: the most two balls (or a ball and a cushion) may interpenetrate
ENERGY_TOL = 1e-9  # relative rise of kinetic energy tolerated from one step to the next


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


def seg_distance(tab: Table, q: np.ndarray) -> np.ndarray:
    """Distance from point q to every cushion segment (rail noses and jaws, with their ends)."""
    a, b = tab.seg_a, tab.seg_b
    d = b - a
    s = np.clip(((q - a) * d).sum(1) / (d * d).sum(1), 0.0, 1.0)
    return np.linalg.norm(a + s[:, None] * d - q, axis=1)


def check_positions(tab: Table, ph: Physics, pos: np.ndarray, state: np.ndarray,
                    radius: np.ndarray, where: str, tol: float = OVERLAP_TOL) -> None:
    """pos (B, N, 2), state and radius (B, N): finite, no two unpocketed balls overlapping by
    more than tol, every unpocketed ball within the cushion noses (tol)."""
    assert np.isfinite(pos).all(), f"{where}: non-finite positions {pos[~np.isfinite(pos)]}"
    for b in range(pos.shape[0]):
        idx = np.flatnonzero(state[b] != POCKETED)
        p, r = pos[b, idx], radius[b, idx]
        if idx.size > 1:
            d = np.linalg.norm(p[:, None] - p[None], axis=-1)
            over = (r[:, None] + r[None]) - d
            np.fill_diagonal(over, -np.inf)
            k = np.unravel_index(over.argmax(), over.shape)
            assert over[k] <= tol, (
                f"{where}: table {b} balls {idx[k[0]]},{idx[k[1]]} overlap by {over[k]:.4g} m "
                f"(limit {tol:g}) at {p[k[0]].tolist()}, {p[k[1]].tolist()}")
        for q, rq, i in zip(p, r, idx, strict=True):
            x, y = q
            rc = nose_reach(float(rq), ph)
            ok = tab.inside(x, y, rc - tol)
            if not ok and tab.pockets == "standard":
                # In a pocket's mouth the centre may pass the rail line, but the ball must
                # still keep clear of the jaws and the jaw tips.
                near = (np.linalg.norm(tab.hole_c - q, axis=1) < tab.hole_r + 0.1).any()
                ok = bool(near) and seg_distance(tab, q).min() >= rc - tol
            assert ok, (f"{where}: table {b} ball {i} outside the cushions at "
                        f"({float(x)!r}, {float(y)!r}): {rc - seg_distance(tab, q).min():.4g} m "
                        f"into the nearest cushion feature (limit {tol:g})")


def check_state(eng: Engine, where: str, tol: float = OVERLAP_TOL) -> None:
    """Finite pos/vel/w, no interpenetration, every unpocketed ball within the noses."""
    pos, vel, w = eng.pos, eng.vel, eng.w
    for name, a in (("vel", vel), ("w", w)):
        assert np.isfinite(a).all(), f"{where}: non-finite {name}: {a[~np.isfinite(a)]}"
    check_positions(eng.table, eng.physics, pos, eng.state, eng.radius, where, tol)


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
    energies seen."""
    energies = [float(kinetic(eng).sum())]
    check_state(eng, "start", tol)
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
            check_state(eng, f"step {n} (t={eng.time:.6g})", tol)
            e = float(kinetic(eng).sum())
            assert e <= energies[-1] * (1 + energy_tol) + 1e-15, (
                f"step {n} (t={eng.time:.6g}): kinetic energy rose from {energies[-1]!r} to "
                f"{e!r} J (relative {(e - energies[-1]) / energies[-1]:.3g})")
            energies.append(e)
    if duration is None:
        assert eng.at_rest().all(), (
            f"not at rest after {n} steps of {dt} s ({n * dt:.1f} s > bound {t_max:.1f} s)")
    return energies
