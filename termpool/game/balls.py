"""The balls of a match between shots: where each is, which are on the table, and the chores
that move them (racks, re-spots, the cue ball waiting after a scratch, ball in hand).

The arrays are only ever changed in place, so views of them (a UI's) stay valid.
"""

from __future__ import annotations

import numpy as np

from termpool.physics.params import BALL_MASS, BALL_RADIUS
from termpool.physics.table import Table
from termpool.rules.words import RECORD, Voice

from . import layout


class Balls:
    """`ids` (the cue ball first), `radius`, `mass`, `pos` (N, 2) and `on_table` (N,) on
    `table`; a pocketed ball's `pos` is meaningless."""

    def __init__(self, table: Table, ids: list[str]) -> None:
        self.table = table
        self.ids = list(ids)
        n = len(self.ids)
        self.radius = np.full(n, BALL_RADIUS)
        self.mass = np.full(n, BALL_MASS)
        self.pos = np.zeros((n, 2))
        self.on_table = np.zeros(n, dtype=bool)

    def index(self, ball: str) -> int:
        return self.ids.index(ball)

    def present(self) -> list[str]:
        """The ids of the balls on the table."""
        return [b for b, on in zip(self.ids, self.on_table, strict=True) if on]

    def rack(self, mode: str, rng: np.random.Generator) -> None:
        """A fresh rack for `mode` (`layout.rack_balls`), every ball on the table."""
        for bid, (x, y) in layout.rack_balls(mode, self.table, rng, BALL_RADIUS).items():
            self.pos[self.index(bid)] = (x, y)
        self.on_table[:] = True

    def _others(self, skip: str) -> tuple[np.ndarray, np.ndarray]:
        keep = self.on_table.copy()
        keep[self.index(skip)] = False
        return self.pos[keep], self.radius[keep]

    def placement_error(self, x: float, y: float, area: str, v: Voice = RECORD) -> str | None:
        """Why the cue ball cannot be placed at (x, y) with ball in hand in `area`, in words
        (pockets named in the voice `v`); None when it can."""
        others = {b: (float(self.pos[i, 0]), float(self.pos[i, 1]), float(self.radius[i]))
                  for i, b in enumerate(self.ids) if self.on_table[i] and b != "cue"}
        return layout.placement_error(self.table, x, y, float(self.radius[self.index("cue")]),
                                      area, others, v)

    def waiting_spot(self) -> tuple[float, float]:
        """Where the cue ball waits for a ball in hand: the head spot, or the nearest free point
        behind it on the long string (then in front of it)."""
        return layout.cue_return_point(self.table, float(self.radius[self.index("cue")]),
                                       *self._others("cue"))

    def respot(self, ball: str) -> None:
        """Put `ball` back on the foot spot (or the nearest free point on the long string)."""
        i = self.index(ball)
        self.on_table[i] = False
        self.pos[i] = layout.respot_point(self.table, float(self.radius[i]),
                                          self.pos[self.on_table], self.radius[self.on_table])
        self.on_table[i] = True

    def settle(self, rows: np.ndarray, pos: np.ndarray, on: np.ndarray,
               respot: tuple[str, ...]) -> None:
        """The table at rest after a shot: the balls of `rows` at `pos`, those not `on` gone;
        then the `respot` balls put back, and a pocketed cue ball waiting for ball in hand."""
        self.pos[rows] = pos
        self.on_table[rows] = on
        for b in respot:
            self.respot(b)
        c = self.index("cue")
        if not self.on_table[c]:
            self.pos[c] = self.waiting_spot()
            self.on_table[c] = True

    def scene_balls(self) -> list[dict]:
        """The balls on the table as a scene lists them (at rest)."""
        return [{"id": b, "x": float(self.pos[i, 0]), "y": float(self.pos[i, 1]),
                 "radius": float(self.radius[i]), "mass": float(self.mass[i])}
                for i, b in enumerate(self.ids) if self.on_table[i]]

    def to_json(self) -> list[dict]:
        return [{"id": b, "x": float(self.pos[i, 0]), "y": float(self.pos[i, 1]),
                 "on_table": bool(self.on_table[i])} for i, b in enumerate(self.ids)]

    def snapshot(self) -> tuple[np.ndarray, np.ndarray]:
        return self.pos.copy(), self.on_table.copy()

    def restore(self, snap: tuple[np.ndarray, np.ndarray]) -> None:
        self.pos[:], self.on_table[:] = snap
