"""Drawing a table and its balls onto a pixel canvas, scaled to the terminal.

Pixels are square (a terminal cell is about 1:2 and holds two pixels, one above the other), so
the playing area keeps the table's true proportions (2:1 for the standard tables). The table
is seen from above with the head rail on the left: x (the length) runs right, y (across) runs
up, so "left" as seen from the head end is the top of the screen.

`layout(cols, rows)` places the table and a side or bottom panel on a terminal, or returns None
when the terminal is smaller than `MIN_COLS` x `MIN_ROWS`; `TableView` caches the table's
background for a layout and draws the balls over a copy of it (`cells`: the table as screen
cells, with what the caller paints over it); `Geometry` keeps one screen's layout and view
while its size and table stay.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from termpool.physics.engine import POCKETED
from termpool.physics.params import BALL_RADIUS
from termpool.physics.table import Table
from termpool.scene import table_to_dict
from termpool.ui.canvas import Canvas, mono_cells, mono_tags, to_cells
from termpool.ui.palette import (
    BACKDROP,
    BACKDROP_C,
    CUE,
    CUSHION,
    CUSHION_C,
    DIAMOND,
    DIAMOND_C,
    FELT,
    FELT_C,
    POCKET,
    POCKET_C,
    RAIL,
    RAIL_C,
    STRIPE,
    STRIPE_WHITE_C,
    ball_style,
    mono_mark,
    mono_numbers,
    number_colour,
)

MIN_COLS, MIN_ROWS = 40, 12
PANEL_COLS = 26  # width of a side panel, in cells
PANEL_ROWS = 4  # minimum height of a bottom panel, in cells ...
PANEL_ROWS_TALL = 5  # ... on terminals of TALL_ROWS rows or more: a row for each player's
TALL_ROWS = 20  # balls when they do not fit side by side, the status, the key help
MIN_PLAY_PX = 8  # the playing area must be at least this many pixels high
CUSHION_M = 0.05  # cushion width, nose to rail (m)
RAIL_M = 0.10  # visible wooden rail width (m)
DIAMOND_M = 0.014  # half diagonal of a sight diamond (m)
MIN_BALL_PX = 1.0  # a ball is drawn at least this radius (pixels), so it never vanishes
NUMBER_MIN_CELLS = 3  # a ball this many cells wide, or wider, carries its number


@dataclass(frozen=True)
class Layout:
    """Where things go on a cols x rows terminal, in pixels (x right, y down; 2 per cell row)."""

    cols: int
    rows: int
    length: float  # playing area, m
    width: float
    px: int  # playing area (cushion noses): left, top, width, height in pixels
    py: int
    pw: int
    ph: int
    cushion: int  # cushion and rail widths in pixels
    rail: int
    panel: str  # "side" or "bottom"
    panel_rect: tuple[int, int, int, int]  # col, row, cols, rows (cells)

    @property
    def sx(self) -> float:
        """Pixels per metre along the length."""
        return self.pw / self.length

    @property
    def sy(self) -> float:
        return self.ph / self.width

    @property
    def scale(self) -> float:
        return (self.sx + self.sy) / 2

    @property
    def border(self) -> int:
        return self.cushion + self.rail

    @property
    def outer(self) -> tuple[int, int, int, int]:
        """The whole table with its rails: left, top, width, height in pixels."""
        b = self.border
        return (self.px - b, self.py - b, self.pw + 2 * b, self.ph + 2 * b)

    @property
    def canvas_size(self) -> tuple[int, int]:
        return (self.cols, 2 * self.rows)

    def to_pixels(self, x, y) -> tuple[np.ndarray, np.ndarray]:
        """Table coordinates (m) to canvas pixel coordinates (pixel (i, j) spans [i, i+1))."""
        x = np.asarray(x, dtype=float)
        y = np.asarray(y, dtype=float)
        return self.px + x * self.sx, self.py + (self.width - y) * self.sy

    def to_table(self, col: int, row: int) -> tuple[float, float] | None:
        """The table point (m) at the centre of the cell (col, row); None for a cell off the
        table and its rails (the panel, or beside the table)."""
        ox, oy, ow, oh = self.outer
        if not (ox <= col < ox + ow and oy <= 2 * row + 1 < oy + oh):
            return None
        return (col + 0.5 - self.px) / self.sx, self.width - (2 * row + 1 - self.py) / self.sy


def min_size() -> tuple[int, int]:
    return (MIN_COLS, MIN_ROWS)


def _borders(ph: int, width: float) -> tuple[int, int]:
    s = ph / width
    return max(1, round(CUSHION_M * s)), max(2, round(RAIL_M * s))


def _fit(aw: int, ah: int, length: float, width: float):
    """Largest playing area (pw, ph, cushion, rail) whose table fits in aw x ah pixels."""
    for ph in range(ah, MIN_PLAY_PX - 1, -1):
        pw = round(ph * length / width)
        c, r = _borders(ph, width)
        b = c + r
        if pw + 2 * b <= aw and ph + 2 * b <= ah:
            return pw, ph, c, r
    return None


def layout(cols: int, rows: int, table: Table | None = None, *, panel_cols: int = PANEL_COLS,
           panel_rows: int | None = None) -> Layout | None:
    """Place the table (as large as it goes, true proportions) and a side or bottom panel.

    Tries a panel of `panel_cols` on the right and one of at least `panel_rows` below, keeps the
    one giving the bigger table (the side panel on a tie); a bottom panel gets every row below
    the table. None when the terminal is under MIN_COLS x MIN_ROWS or the table cannot fit.
    """
    if cols < MIN_COLS or rows < MIN_ROWS:
        return None
    if panel_rows is None:
        panel_rows = PANEL_ROWS_TALL if rows >= TALL_ROWS else PANEL_ROWS
    L, W = (table.length, table.width) if table is not None else (2.54, 1.27)
    best = None
    side = _fit(cols - panel_cols, 2 * rows, L, W) if cols - panel_cols >= MIN_COLS // 2 else None
    bottom = _fit(cols, 2 * (rows - panel_rows), L, W)
    if side is not None:
        pw, ph, c, r = side
        b = c + r
        ox = (cols - panel_cols - (pw + 2 * b)) // 2
        oy = (2 * rows - (ph + 2 * b)) // 2
        best = Layout(cols, rows, L, W, ox + b, oy + b, pw, ph, c, r, "side",
                      (cols - panel_cols, 0, panel_cols, rows))
    if bottom is not None and (best is None or bottom[1] > best.ph):
        pw, ph, c, r = bottom
        b = c + r
        ox = (cols - (pw + 2 * b)) // 2
        top_rows = -(-(ph + 2 * b) // 2)  # cell rows the table covers
        best = Layout(cols, rows, L, W, ox + b, b, pw, ph, c, r, "bottom",
                      (0, top_rows, cols, rows - top_rows))
    return best


# ----------------------------------------------------------------------------- background


def _jaw_directions(table: Table) -> dict[tuple[float, float], np.ndarray]:
    out = {}
    for a, b, kind in zip(table.seg_a, table.seg_b, table.seg_kind, strict=True):
        if kind == "jaw":
            d = b - a
            out[(round(a[0], 9), round(a[1], 9))] = d / np.linalg.norm(d)
    return out


def _cushion_quads(table: Table, c_m: float) -> list[np.ndarray]:
    """Each cushion as a quadrilateral in table coordinates: its nose, and its back edge c_m
    further out, cut along the jaw lines at the pockets (mitred at plain corners)."""
    jaws = _jaw_directions(table)
    quads = []
    for a, b, n, kind in zip(table.seg_a, table.seg_b, table.seg_n, table.seg_kind, strict=True):
        if kind != "rail":
            continue
        out = -n
        u = (b - a) / np.linalg.norm(b - a)
        corners = []
        for p, along in ((a, -u), (b, u)):
            d = jaws.get((round(p[0], 9), round(p[1], 9)))
            if d is None or float(d @ out) < 1e-6:
                d = out + along  # plain corner: a 45-degree mitre
            corners.append(p + d * (c_m / float(d @ out)))
        quads.append(np.array([a, b, corners[1], corners[0]]))
    return quads


def _in_convex(X, Y, poly: np.ndarray) -> np.ndarray:
    inside_pos = np.ones(X.shape, dtype=bool)
    inside_neg = np.ones(X.shape, dtype=bool)
    k = len(poly)
    for i in range(k):
        x0, y0 = poly[i]
        x1, y1 = poly[(i + 1) % k]
        cross = (x1 - x0) * (Y - y0) - (y1 - y0) * (X - x0)
        inside_pos &= cross >= 0
        inside_neg &= cross <= 0
    return inside_pos | inside_neg


def _spots(table: Table, off: float) -> list[tuple[float, float]]:
    """The 18 sights: 3 between the pockets on each half of the long rails, 3 on each short
    rail, `off` metres out from the cushion noses."""
    L, W = table.length, table.width
    pts = []
    for k in (1, 2, 3, 5, 6, 7):
        pts += [(L * k / 8, -off), (L * k / 8, W + off)]
    for k in (1, 2, 3):
        pts += [(-off, W * k / 4), (L + off, W * k / 4)]
    return pts


def draw_background(table: Table, lay: Layout) -> Canvas:
    """The table without balls: rails with diamonds, cushions, felt and pockets."""
    cw, ch = lay.canvas_size
    cv = Canvas(cw, ch, BACKDROP_C.rgb, BACKDROP)
    ox, oy, ow, oh = lay.outer
    x0, y0 = max(ox, 0), max(oy, 0)
    x1, y1 = min(ox + ow, cw), min(oy + oh, ch)
    if x1 <= x0 or y1 <= y0:
        return cv
    # Pixel centres of the table's box, as canvas pixels and as table coordinates.
    X, Y = np.meshgrid(np.arange(x0, x1) + 0.5, np.arange(y0, y1) + 0.5)
    tx = (X - lay.px) / lay.sx
    ty = lay.width - (Y - lay.py) / lay.sy
    box = (slice(y0, y1), slice(x0, x1))
    rgb = cv.rgb[box]
    tag = cv.tag[box]

    def paint(mask, colour, t):
        rgb[mask] = colour.rgb
        tag[mask] = t

    paint(np.ones(X.shape, dtype=bool), RAIL_C, RAIL)
    c = lay.cushion
    band = ((X >= lay.px - c) & (X < lay.px + lay.pw + c) & (Y >= lay.py - c)
            & (Y < lay.py + lay.ph + c))
    paint(band, POCKET_C, POCKET)  # the pocket throats, where no cushion covers the band
    c_m = c / lay.scale
    for quad in _cushion_quads(table, c_m):
        paint(band & _in_convex(tx, ty, quad), CUSHION_C, CUSHION)
    play = (X >= lay.px) & (X < lay.px + lay.pw) & (Y >= lay.py) & (Y < lay.py + lay.ph)
    paint(play, FELT_C, FELT)
    for (hx, hy), hr in zip(table.hole_c, table.hole_r, strict=True):
        paint((tx - hx) ** 2 + (ty - hy) ** 2 <= hr * hr, POCKET_C, POCKET)
    # Diamonds, in the middle of the wooden rail.
    off = c_m + (lay.rail / lay.scale) / 2
    rd = int(DIAMOND_M * lay.scale + 0.25)  # 0: one pixel; 1: a plus; 2: a small diamond
    for sx_, sy_ in _spots(table, off):
        cx, cy = lay.to_pixels(sx_, sy_)
        ci, cj = math.floor(cx + 1e-6) + 0.5, math.floor(cy + 1e-6) + 0.5
        m = np.abs(X - ci) + np.abs(Y - cj) <= rd + 0.1
        paint(m & (tag == RAIL), DIAMOND_C, DIAMOND)
    return cv


# ----------------------------------------------------------------------------------- balls


def disc_mask(cx: float, cy: float, rr: float):
    """Pixels of a disc of radius rr (pixels) centred near (cx, cy): (j0, i0, mask).

    The diameter is rounded to whole pixels d (at least 2) and the centre snapped to a pixel
    corner (d even) or a pixel centre (d odd), so every ball of a size has the same shape:
    2x2, a plus, 4x4 without corners, ... as round as the pixels allow.
    """
    d = max(2, int(round(2 * rr)))
    if d % 2:
        sx, sy = math.floor(cx) + 0.5, math.floor(cy) + 0.5
    else:
        sx, sy = float(round(cx)), float(round(cy))
    h = d / 2
    i0, j0 = int(math.floor(sx - h)), int(math.floor(sy - h))
    offs = np.arange(d) + 0.5 - h
    mask = offs[None, :] ** 2 + offs[:, None] ** 2 <= h * h - 0.3
    return j0, i0, mask, offs


def draw_ball(cv: Canvas, cx: float, cy: float, rr: float, style) -> None:
    """A ball of radius rr pixels centred at (cx, cy) (canvas pixels). Stripes are white caps
    above and below a coloured band through the middle, at least one pixel row of each."""
    H, W = cv.height, cv.width
    j0, i0, mask, offs = disc_mask(cx, cy, rr)
    d = mask.shape[0]
    # Clip to the canvas.
    a, b = max(0, -i0), min(d, W - i0)
    c, e = max(0, -j0), min(d, H - j0)
    if b <= a or e <= c:
        return
    mask = mask[c:e, a:b]
    ys = offs[c:e]
    i0, j0, i1, j1 = i0 + a, j0 + c, i0 + b, j0 + e
    box = (slice(j0, j1), slice(i0, i1))
    cv.rgb[box][mask] = style.colour.rgb
    cv.tag[box][mask] = style.tag
    if style.tag != STRIPE:
        return
    rows = np.flatnonzero(mask.any(axis=1))
    n = rows.size
    if n <= 1:
        return
    dy = np.abs(ys[rows])
    if n == 2:
        white = rows[:1]
    elif n == 3:
        white = rows[[0, 2]]
    else:
        white = rows[dy > 0.5 * (d / 2)]
        if white.size == 0:
            white = rows[[0, -1]]
        elif white.size == n:
            white = rows[dy > dy.min()]
    cap = np.zeros_like(mask)
    cap[white] = True
    cap &= mask
    cv.rgb[box][cap] = STRIPE_WHITE_C.rgb
    # The caps keep the STRIPE tag: mono mode draws every cell of the ball as a stripe.


class TableView:
    """A table drawn for one layout: the background is built once; `draw` adds the balls."""

    def __init__(self, table: Table, lay: Layout, theme: str = "standard"):
        self.table, self.layout, self.theme = table, lay, theme
        self.background = draw_background(table, lay)
        self._canvas = self.background.copy()
        self._styles: dict[tuple[str, int], object] = {}
        self._felt: np.ndarray | None = None  # the cells of cloth (mono), when first needed

    def style(self, ball_id: str, index: int):
        key = (ball_id, index)
        st = self._styles.get(key)
        if st is None:
            st = self._styles[key] = ball_style(ball_id, index, self.theme)
        return st

    def _balls(self, ids, pos, state, radius):
        """(pixel x, pixel y, radius px, style) of each ball on the table, cue ball last."""
        pos = np.asarray(pos, dtype=float).reshape(-1, 2)
        n = len(ids)
        if pos.shape[0] != n:
            raise ValueError(f"draw: {n} ids but {pos.shape[0]} positions")
        st = None if state is None else np.asarray(state).reshape(-1)
        rad = np.broadcast_to(np.asarray(BALL_RADIUS if radius is None else radius, float), (n,))
        lay = self.layout
        X, Y = lay.to_pixels(pos[:, 0], pos[:, 1])
        out = []
        for k in sorted(range(n), key=lambda k: self.style(ids[k], k).tag == CUE):
            if st is not None and st[k] == POCKETED:
                continue
            x, y = float(X[k]), float(Y[k])
            if math.isfinite(x) and math.isfinite(y):
                out.append((x, y, max(MIN_BALL_PX, rad[k] * lay.scale), self.style(ids[k], k)))
        return out

    def draw(self, ids, pos, state=None, radius=None, canvas: Canvas | None = None) -> Canvas:
        """Background plus the balls not pocketed (cue ball last, on top). pos (N, 2) or
        (1, N, 2); state the engine's codes (POCKETED = 4) or None; radius (N,) or a number.

        Returns `canvas`, or an internal canvas reused from call to call."""
        cv = self._canvas if canvas is None else canvas
        cv.copy_from(self.background)
        for x, y, rr, style in self._balls(ids, pos, state, radius):
            draw_ball(cv, x, y, rr, style)
        return cv

    def numbers(self, cells, ids, pos, state=None, radius=None) -> None:
        """Write each numbered ball's number on it, in the cells (chars, fg, bg) of `draw`'s
        canvas, where the ball is NUMBER_MIN_CELLS cells wide or more: centred on the cell row
        of its centre, on the ball's colour (a stripe's band)."""
        chars, fg, bg = cells
        rows, cols = chars.shape
        for x, y, rr, style in self._balls(ids, pos, state, radius):
            if style.tag == CUE or int(round(2 * rr)) < NUMBER_MIN_CELLS or not style.number:
                continue
            text = style.number
            r = int(math.floor(y)) // 2
            c0 = int(math.floor(x - len(text) / 2 + 0.5))
            if not (0 <= r < rows and 0 <= c0 and c0 + len(text) <= cols):
                continue
            chars[r, c0:c0 + len(text)] = list(text)
            if fg is not None:
                fg[r, c0:c0 + len(text)] = number_colour(style.colour).rgb
                bg[r, c0:c0 + len(text)] = style.colour.rgb

    def cells(self, ids, pos, state=None, radius=None, mono: bool = False, *,
              paint: Callable[[Canvas], None] | None = None,
              mark: Callable[[np.ndarray], None] | None = None, numbered: bool = True):
        """The table and its balls as (chars, fg, bg) cells (fg and bg None in mono). `paint`
        draws over the colour canvas before it becomes cells (the balls' numbers then go on
        top, unless not `numbered`); in mono, `mark` marks the characters."""
        if mono:
            chars = self.mono(ids, pos, state, radius)
            if mark is not None:
                mark(chars)
            return chars, None, None
        cv = self.draw(ids, pos, state, radius)
        if paint is not None:
            paint(cv)
        cells = to_cells(cv)
        if numbered:
            self.numbers(cells, ids, pos, state, radius)
        return cells

    def mono(self, ids, pos, state=None, radius=None) -> np.ndarray:
        """Glyph cells for the monochrome mode: the table's glyphs, and each ball as one glyph
        in the cell holding its centre (a ball never smears over several cells). Balls closer
        than a cell (a rack, a cluster) would share one and hide each other: each ball after
        the first in a cell goes to the free cell of cloth nearest its centre (`mono_spots`),
        so that every ball on the table is drawn, as the colour modes draw them all."""
        chars = mono_cells(self.background)
        if self._felt is None:
            self._felt = mono_tags(self.background) == FELT
        balls = self._balls(ids, pos, state, radius)
        numbers = mono_numbers([self.style(b, k) for k, b in enumerate(ids)])
        for (c, r), (_x, _y, _rr, style) in zip(mono_spots(balls, self._felt), balls,
                                                strict=True):
            if c is not None:
                chars[r, c] = mono_mark(style, numbers)
        return chars


MONO_REACH = 3  # cells (each way) a ball may move in mono to a cell of its own


def mono_spots(balls, felt: np.ndarray) -> list[tuple[int | None, int | None]]:
    """The cell (col, row) of each ball of `balls` ((pixel x, pixel y, radius, style), as
    `TableView._balls` gives them) in mono: the cell holding its centre, or, where an earlier
    ball (the cue ball first, then in order) has that one, the free cell of cloth (`felt`,
    rows x cols) nearest its centre within MONO_REACH cells; (None, None) if none is free.
    Balls on cells of their own stay exactly where they are."""
    rows, cols = felt.shape
    order = sorted(range(len(balls)), key=lambda k: balls[k][3].tag != CUE)
    out: list[tuple[int | None, int | None]] = [(None, None)] * len(balls)
    taken: set[tuple[int, int]] = set()
    for k in order:
        x, y = balls[k][0], balls[k][1]
        c, r = int(math.floor(x)), int(math.floor(y)) // 2
        if not (0 <= r < rows and 0 <= c < cols):
            continue
        if (c, r) in taken:
            best = None
            for rr in range(max(0, r - MONO_REACH), min(rows, r + MONO_REACH + 1)):
                for cc in range(max(0, c - MONO_REACH), min(cols, c + MONO_REACH + 1)):
                    if (cc, rr) in taken or not felt[rr, cc]:
                        continue
                    # pixels are square-ish: a cell is 1 wide and 2 tall
                    d = (cc + 0.5 - x) ** 2 + (2 * rr + 1 - y) ** 2
                    if best is None or d < best[0]:
                        best = (d, cc, rr)
            if best is None:
                continue
            c, r = best[1], best[2]
        taken.add((c, r))
        out[k] = (c, r)
    return out


class Geometry:
    """One screen's layout and table view, kept while its size, table and theme stay: the
    table's background is drawn once, not every frame. A table equal to the last one (a new
    match on the same table, the next shot of a watched match) keeps it too."""

    def __init__(self) -> None:
        self._key: tuple | None = None
        self._table: Table | None = None
        self._table_dict: dict | None = None
        self._got: tuple[Layout | None, TableView | None] = (None, None)

    def get(self, cols: int, rows: int, table: Table,
            theme: str = "standard") -> tuple[Layout | None, TableView | None]:
        """The layout (None when the screen is too small) and the view of `table`."""
        if table is not self._table:
            as_dict = table_to_dict(table)
            if as_dict != self._table_dict:
                self._key = None
            self._table, self._table_dict = table, as_dict
        if self._key != (cols, rows, theme):
            lay = layout(cols, rows, table)
            self._got = (lay, TableView(table, lay, theme) if lay is not None else None)
            self._key = (cols, rows, theme)
        return self._got
