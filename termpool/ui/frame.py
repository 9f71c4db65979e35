"""Frames of a scene on its own (no match): the table, the balls and a panel listing them, as
cells and as escape strings, drawn by the game's own stack (`table_view`, `panel`, `output`).

`Renderer` keeps one table's geometry and a `Screen`, and turns ball positions into the
(diffed) string to write; `render_scene_text` gives the full first frame of a position in one
call (tests, `python -m termpool.ui.demo`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from termpool.physics.table import Table
from termpool.ui.output import Screen, resolve_depth
from termpool.ui.panel import draw_ball_list, message_cells, too_small_lines
from termpool.ui.table_view import Geometry, Layout, TableView


class Renderer:
    """Frames of one table on a cols x rows terminal: positions in, diffed escape string out."""

    def __init__(self, table: Table, cols: int, rows: int, depth: str = "auto",
                 sync: bool = False, env: Mapping[str, str] | None = None,
                 title: str = "termpool"):
        self.table = table
        self.title = title
        self.depth = resolve_depth(depth, env)
        self.screen = Screen(cols, rows, self.depth, sync)
        self.geometry = Geometry()
        self.cols, self.rows = cols, rows

    def resize(self, cols: int, rows: int) -> None:
        self.cols, self.rows = cols, rows
        self.screen.resize(cols, rows)

    @property
    def layout(self) -> Layout | None:
        return self.geometry.get(self.cols, self.rows, self.table)[0]

    @property
    def view(self) -> TableView | None:
        return self.geometry.get(self.cols, self.rows, self.table)[1]

    @property
    def mono(self) -> bool:
        return self.depth == "mono"

    def cells(self, ids: Sequence[str], pos, state=None, radius=None):
        """(chars, fg, bg) of the whole terminal (fg, bg None in mono)."""
        lay, view = self.geometry.get(self.cols, self.rows, self.table)
        if view is None:
            return message_cells(self.cols, self.rows, too_small_lines(self.cols, self.rows),
                                 self.mono)
        # A scene's frames show the balls without their numbers (the game's carry them).
        cells = view.cells(ids, pos, state, radius, self.mono, numbered=False)
        draw_ball_list(cells, lay, ids, state, self.title, self.mono)
        return cells

    def frame(self, ids: Sequence[str], pos, state=None, radius=None) -> str:
        """The string to write for this position: only what changed since the last frame."""
        return self.screen.render(*self.cells(ids, pos, state, radius))


def render_scene_text(table: Table, ids: Sequence[str], pos, state=None, cols: int = 80,
                      rows: int = 24, depth: str = "truecolor", radius=None,
                      sync: bool = False, title: str = "termpool") -> str:
    """The full first frame (escape string) of the balls at `pos` on `table`, at cols x rows.
    pos (N, 2) or (1, N, 2); state the engine's codes or None (all on the table)."""
    r = Renderer(table, cols, rows, depth, sync=sync, title=title)
    return r.frame(ids, pos, state, radius)
