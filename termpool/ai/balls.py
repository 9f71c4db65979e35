"""The balls the computer reads: the arguments of its functions, checked once (one-line
ValueErrors naming the argument), as the balls on the table."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from termpool.physics.params import Physics
from termpool.physics.table import Table
from termpool.rules.common import State

from .levels import LEVELS


class OnTable(NamedTuple):
    """The balls on the table, in the order given; `cue` is the cue ball's index."""

    ids: list[str]
    pos: np.ndarray  # (n, 2)
    radius: np.ndarray  # (n,)
    mass: np.ndarray  # (n,)
    cue: int


def _per_ball(x, n: int, name: str) -> np.ndarray:
    try:
        arr = np.broadcast_to(np.asarray(x, dtype=float), (n,)).copy()
    except (ValueError, TypeError):
        raise ValueError(f"{name}: must be a number or one number per ball ({n})") from None
    if not (np.isfinite(arr).all() and (arr > 0).all()):
        raise ValueError(f"{name}: must be positive and finite")
    return arr


def read_inputs(table, physics, ids, pos, radius, mass, on_table, state, level, seed) -> OnTable:
    if not isinstance(table, Table):
        raise ValueError("table: must be a termpool Table")
    if not isinstance(physics, Physics):
        raise ValueError("physics: must be a termpool Physics")
    if not isinstance(state, State):
        raise ValueError("state: must be a termpool.rules State")
    if level not in LEVELS:
        raise ValueError(f"level: must be one of {', '.join(LEVELS)}, not {level!r}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)):
        raise ValueError(f"seed: must be an integer, not {seed!r}")
    ids = [str(b) for b in ids]
    n = len(ids)
    if "cue" not in ids:
        raise ValueError("ids: no cue ball 'cue'")
    if len(set(ids)) != n:
        raise ValueError("ids: duplicate ball ids")
    try:
        p = np.asarray(pos, dtype=float)
    except (ValueError, TypeError):
        raise ValueError("pos: must be numbers, shape (N, 2)") from None
    if p.shape != (n, 2):
        raise ValueError(f"pos: shape {p.shape} does not fit {n} ids (need ({n}, 2))")
    r = _per_ball(radius, n, "radius")
    m = _per_ball(mass, n, "mass")
    on = np.asarray(on_table)
    if on.shape != (n,) or on.dtype != bool:
        raise ValueError(f"on_table: must be {n} booleans, one per ball")
    cue = ids.index("cue")
    if not on[cue]:
        raise ValueError("on_table: the cue ball is not on the table")
    if not np.isfinite(p[on]).all():  # balls off the table may be anywhere, NaN included
        raise ValueError("pos: must be finite for the balls on the table")
    keep = np.nonzero(on)[0]
    sub = [ids[k] for k in keep]
    return OnTable(sub, p[keep], r[keep], m[keep], sub.index("cue"))
