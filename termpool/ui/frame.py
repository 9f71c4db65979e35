"""Whole frames: the table, the balls and a small panel, as cells and as escape strings.

`Renderer` keeps a layout, the table's cached background and a `Screen`, and turns ball
positions into the (diffed) string to write; `render_scene_text` gives the full first frame of
a position in one call (tests, `python -m termpool.ui.demo`, a future headless mode).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from termpool.physics.engine import POCKETED
from termpool.physics.table import Table
from termpool.ui.canvas import put_text, to_cells
from termpool.ui.output import Screen, resolve_depth
from termpool.ui.palette import (
    BACKDROP_C,
    CUE,
    DIM_TEXT_C,
    EIGHT,
    STRIPE,
    STRIPE_WHITE_C,
    TEXT_C,
    ball_style,
    mono_glyph,
)
from termpool.ui.table_view import MIN_COLS, MIN_ROWS, Layout, TableView, layout

BLACK = (0, 0, 0)


def _on_table(ids: Sequence[str], state) -> list[int]:
    if state is None:
        return list(range(len(ids)))
    st = np.asarray(state).reshape(-1)
    return [k for k in range(len(ids)) if st[k] != POCKETED]


def _ball_tokens(ids: Sequence[str], which: list[int], mono: bool,
                 theme: str = "standard") -> list[tuple]:
    """Panel labels (text, fg, bg) for balls: solids as the number on the ball's colour,
    stripes as the number in the colour on white, the cue ball as 'c'."""
    out = []
    for k in which:
        st = ball_style(ids[k], k, theme)
        if mono:
            out.append((mono_glyph(st) + st.number, None, None))
        elif st.tag == STRIPE:
            out.append((f"{st.number:>2}", st.colour.rgb, STRIPE_WHITE_C.rgb))
        elif st.tag == CUE:
            out.append((" c", BLACK, st.colour.rgb))
        else:
            r, g, b = st.colour.rgb
            light = 0.299 * r + 0.587 * g + 0.114 * b > 110 and st.tag != EIGHT
            out.append((f"{st.number:>2}", BLACK if light else TEXT_C.rgb, st.colour.rgb))
    return out


def draw_panel(cells, lay: Layout, ids: Sequence[str], state=None, title: str = "termpool",
               mono: bool = False) -> None:
    """A minimal panel: a title, then the balls on the table and the balls pocketed."""
    col, row, ncols, nrows = lay.panel_rect
    if ncols <= 2 or nrows <= 0:
        return
    c0, width = col + 1, ncols - 2
    on = _on_table(ids, state)
    on_set = set(on)
    gone = [k for k in range(len(ids)) if k not in on_set]
    r = row
    put_text(cells, r, c0, title[:width], TEXT_C.rgb, BACKDROP_C.rgb)
    r += 1
    for label, which in (("on the table", on), ("pocketed", gone)):
        if not which or r >= row + nrows:
            continue
        put_text(cells, r, c0, label[:width], DIM_TEXT_C.rgb, BACKDROP_C.rgb)
        r += 1
        c = c0
        for text, fg, bg in _ball_tokens(ids, which, mono):
            if c + len(text) > c0 + width:
                r, c = r + 1, c0
            if r >= row + nrows:
                break
            put_text(cells, r, c, text, fg, bg)
            c += len(text) + 1
        r += 1


def message_cells(cols: int, rows: int, lines: Sequence[str], mono: bool = False):
    """Blank cells with lines of text centred: the 'window too small' screen."""
    chars = np.full((rows, cols), " ", dtype="<U1")
    fg = bg = None
    if not mono:
        fg = np.zeros((rows, cols, 3), dtype=np.uint8)
        bg = np.zeros((rows, cols, 3), dtype=np.uint8)
        bg[...] = BACKDROP_C.rgb
    cells = (chars, fg, bg)
    top = max(0, (rows - len(lines)) // 2)
    for k, line in enumerate(lines):
        put_text(cells, top + k, max(0, (cols - len(line)) // 2), line, TEXT_C.rgb,
                 BACKDROP_C.rgb)
    return cells


def too_small_lines(cols: int, rows: int) -> list[str]:
    return ["make the window at least", f"{MIN_COLS}x{MIN_ROWS} (now {cols}x{rows})"]


class Renderer:
    """Frames of one table on a cols x rows terminal: positions in, diffed escape string out."""

    def __init__(self, table: Table, cols: int, rows: int, depth: str = "auto",
                 sync: bool = False, env: Mapping[str, str] | None = None,
                 title: str = "termpool"):
        self.table = table
        self.title = title
        self.depth = resolve_depth(depth, env)
        self.screen = Screen(cols, rows, self.depth, sync)
        self._setup(cols, rows)

    def _setup(self, cols: int, rows: int) -> None:
        self.cols, self.rows = cols, rows
        self.layout = layout(cols, rows, self.table)
        self.view = TableView(self.table, self.layout) if self.layout is not None else None

    def resize(self, cols: int, rows: int) -> None:
        self._setup(cols, rows)
        self.screen.resize(cols, rows)

    @property
    def mono(self) -> bool:
        return self.depth == "mono"

    def cells(self, ids: Sequence[str], pos, state=None, radius=None):
        """(chars, fg, bg) of the whole terminal (fg, bg None in mono)."""
        if self.view is None:
            return message_cells(self.cols, self.rows, too_small_lines(self.cols, self.rows),
                                 self.mono)
        if self.mono:
            cells = (self.view.mono(ids, pos, state, radius), None, None)
        else:
            cells = to_cells(self.view.draw(ids, pos, state, radius))
        draw_panel(cells, self.layout, ids, state, self.title, self.mono)
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
