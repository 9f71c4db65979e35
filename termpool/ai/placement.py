"""Where the computer puts the cue ball in hand, and how good a table is for a player
(`best_chance`)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from termpool.game.layout import head_string, spots_ok
from termpool.physics.params import Physics
from termpool.physics.table import Table
from termpool.rules.common import AREAS, State, legal_targets

from . import geometry as geo
from .balls import OnTable, read_inputs
from .candidates import BREAK_SAMPLES, Cands, break_cands, simulate
from .levels import LEVELS, Level
from .scoring import LEAVE_SIGMA, score_tables


def _spot_ok(xy: np.ndarray, t: OnTable, table: Table, area: str) -> np.ndarray:
    """Spots among xy (M, 2) where the game lets the cue ball be placed (`layout.spots_ok`),
    with a millimetre to spare."""
    others = [k for k in range(len(t.ids)) if k != t.cue]
    return spots_ok(table, xy, float(t.radius[t.cue]), area, t.pos[others], t.radius[others],
                    margin=1e-3)


def _cue_in_hand(ids, pos, on_table, table: Table):
    """pos and on_table with the cue ball on the table at the head spot (bad shapes are
    passed on unchanged for read_inputs to report)."""
    names = [str(b) for b in ids]
    try:
        p = np.array(pos, dtype=float)
        on = np.array(on_table)
    except (ValueError, TypeError):
        return pos, on_table
    n = len(names)
    if "cue" in names and p.shape == (n, 2) and on.shape == (n,) and on.dtype == bool:
        k = names.index("cue")
        p[k] = table.head_spot
        on[k] = True
        return p, on
    return pos, on_table


def _string_spot(t: OnTable, table: Table, area: str, share: float) -> np.ndarray | None:
    """The free point of the head string nearest the one `share` of the width across."""
    hx, hy = head_string(table), share * table.width
    xy = np.array([[hx, hy + s * k * 0.01] for k in range(130) for s in (1, -1)])
    ok = np.nonzero(_spot_ok(xy, t, table, area))[0]
    return xy[ok[0]] if len(ok) else None


def _break_spot(t: OnTable, table: Table, physics: Physics, state: State, area: str,
                lv: Level) -> np.ndarray:
    """Where the level breaks from: the free point of the head string nearest each of its
    break spots; with several, the one whose best break (`break_cands`, all in one batch)
    scores best on average over its samples."""
    spots = [xy for f in lv.break_spots if (xy := _string_spot(t, table, area, f)) is not None]
    if not spots:
        raise ValueError(f"area: no free spot for the cue ball in the {area}")
    if len(spots) == 1:
        return spots[0]
    targets = legal_targets(state, t.ids)
    cands, cue_at = Cands(), []
    for xy in spots:
        here = t._replace(pos=t.pos.copy())
        here.pos[t.cue] = xy
        one = break_cands(here, targets, lv)
        cands.extend(one)
        cue_at += [xy] * len(one)
    if len(cands) == 0:
        return spots[0]
    eng = simulate(t, cands, table, physics, np.array(cue_at))
    pockets = geo.pocket_geometry(table, float(t.radius[t.cue]))
    scores, *_ = score_tables(state, targets, t, cands, eng, table, pockets, lv)
    mean = scores.reshape(len(spots), -1, BREAK_SAMPLES).mean(axis=2).max(axis=1)
    return spots[int(np.argmax(mean))]


def _spot_chances(t: OnTable, table: Table, state: State, area: str, distances: int,
                  sigma: float) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """Legal spots for the cue ball in hand (M, 2) and the pot chances (M, N, P) each leaves:
    spots behind the ghost ball of each pot at a few cut angles and `distances` distances,
    then a coarse grid of the area. Also returns the legal targets."""
    r = float(t.radius[t.cue])
    pockets = geo.pocket_geometry(table, r)
    targets = legal_targets(state, t.ids)
    spots = []
    dists = (0.3, 0.15, 0.5)[:distances]
    for b in targets:
        i = t.ids.index(b)
        for k in range(len(pockets.names)):
            u = pockets.aim[k] - t.pos[i]
            u = u / max(float(np.linalg.norm(u)), 1e-9)
            if float(np.dot(u, pockets.out[k])) <= pockets.cos_limit[k]:
                continue
            ghost = t.pos[i] - (r + t.radius[i]) * u
            for cut in (0.0, 15.0, -15.0, 30.0, -30.0):
                c = math.radians(cut)
                d = np.array([u[0] * math.cos(c) - u[1] * math.sin(c),
                              u[0] * math.sin(c) + u[1] * math.cos(c)])
                for s in dists:
                    spots.append(ghost - s * d)
    hi = head_string(table) if area == "kitchen" else table.length
    gx = np.linspace(0.05, hi - 0.02, 12)
    gy = np.linspace(0.05, table.width - 0.05, 8)
    spots += [np.array([x, y]) for x in gx for y in gy]
    xy = np.array(spots)
    xy = xy[_spot_ok(xy, t, table, area)]
    if len(xy) == 0:
        raise ValueError(f"area: no free spot for the cue ball in the {area}")
    M, n = len(xy), len(t.ids)
    balls = np.broadcast_to(t.pos, (M, n, 2)).copy()
    balls[:, t.cue] = xy
    tmask = np.broadcast_to(np.array([b in targets for b in t.ids]), (M, n))
    chance, _ = geo.pot_chances(xy, balls, np.ones((M, n), bool), tmask, t.radius, t.cue,
                                pockets, table, sigma)
    return xy, chance, targets


def choose_placement(table: Table, physics: Physics, ids: Sequence[str], pos, radius, mass,
                     on_table, state: State, area: str, *, level: str = "normal",
                     seed: int = 0) -> tuple[float, float]:
    """Where to put the cue ball in hand: `area` "anywhere" or "kitchen" (behind the head
    string, x <= length / 4). Spots behind the ghost ball of each pot at a few cut angles and
    distances, and a coarse grid as a fallback, are scored by the shots they leave. On a
    break, the level's break spot on the head string (`_break_spot`).

    The cue ball's entries in `pos` and `on_table` are ignored (it is being placed: after a
    scratch it is still in a pocket); it must be in `ids`.
    """
    if area not in AREAS:
        raise ValueError(f"area: must be one of {', '.join(AREAS)}, not {area!r}")
    pos, on_table = _cue_in_hand(ids, pos, on_table, table)
    t = read_inputs(table, physics, ids, pos, radius, mass, on_table, state, level, seed)
    lv = LEVELS[level]
    if state.is_break:
        spot = _break_spot(t, table, physics, state, area, lv)
        return float(spot[0]), float(spot[1])
    xy, chance, targets = _spot_chances(t, table, state, area, lv.spots, LEAVE_SIGMA)
    value = geo.leave_value(chance)
    # Between spots of equal value (say, no pot anywhere), the one nearest a legal ball.
    legal = [k for k, b in enumerate(t.ids) if b in targets]
    if legal:
        near = np.linalg.norm(xy[:, None] - t.pos[legal][None], axis=-1).min(axis=1)
        value = value - 1e-3 * near / table.length
    best = int(np.argmax(value))
    spot = xy[best]
    if lv.spot_sd > 0:
        rng = np.random.default_rng(seed)
        moved = spot + rng.normal(0.0, lv.spot_sd, 2)
        if _spot_ok(moved[None], t, table, area)[0]:
            spot = moved
    return float(spot[0]), float(spot[1])


def best_chance(table: Table, physics: Physics, ids: Sequence[str], pos, radius, mass,
                on_table, state: State, *, area: str | None = None,
                sigma: float = LEAVE_SIGMA) -> float:
    """The best chance (0..1) of a straight pot for `state.shooter` under an aim error of
    `sigma` degrees: from where the cue ball lies, or with `area` ("anywhere", "kitchen") from
    the best spot for the cue ball in hand there. It measures what a shot leaves."""
    if area is not None and area not in AREAS:
        raise ValueError(f"area: must be one of {', '.join(AREAS)}, not {area!r}")
    if area is not None:
        pos, on_table = _cue_in_hand(ids, pos, on_table, table)
    t = read_inputs(table, physics, ids, pos, radius, mass, on_table, state, "normal", 0)
    if area is not None:
        _, chance, _ = _spot_chances(t, table, state, area, 3, sigma)
        return float(chance.max(initial=0.0))
    pockets = geo.pocket_geometry(table, float(t.radius[t.cue]))
    targets = legal_targets(state, t.ids)
    tmask = np.array([[b in targets for b in t.ids]])
    chance, _ = geo.pot_chances(t.pos[t.cue][None], t.pos[None], np.ones((1, len(t.ids)), bool),
                                tmask, t.radius, t.cue, pockets, table, sigma)
    return float(chance.max(initial=0.0))
