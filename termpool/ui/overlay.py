"""Shot overlays drawn over a table canvas: the aim aid (the engine's predicted paths and the
ghost ball), cue stick, ball-in-hand ring, and the small panel widgets (spin face, power
meter) as cells.

Everything paints pixels of the `Canvas` (tag AIM), so it goes through the same half-block
conversion and diffing as the table. Lines and rings never paint over a ball's pixels: a ball
stays readable under the aid. Costs are a few numpy operations on at most a few thousand
pixels, well inside the frame budget (see benchmarks/render.py).
"""

from __future__ import annotations

import math

import numpy as np

from termpool.physics.params import BALL_RADIUS
from termpool.ui.aim import aim_direction
from termpool.ui.canvas import Canvas, to_cells
from termpool.ui.palette import (
    AIM,
    AIM_C,
    BACKDROP_C,
    BUTT_C,
    CALL_C,
    CUE,
    CUE_C,
    DIM_TEXT_C,
    EIGHT,
    GUIDE_C,
    OBJECT_C,
    PLACE_BAD_C,
    PLACE_OK_C,
    POWER_C,
    SOLID,
    SPIN_DOT_C,
    SPIN_LIMIT_C,
    STICK_C,
    STRIPE,
    TEXT_C,
    TIP_C,
)
from termpool.ui.predict import Prediction
from termpool.ui.table_view import MIN_BALL_PX, Layout

DOT_ON, DOT_PERIOD = 2.0, 4.0  # aim line: 2 pixels drawn in every 4, counted from the cue ball
STEP = 0.5  # px between samples along a line: no pixel the line crosses is skipped
STICK_M = 1.2  # visible stick length
STICK_GAP_M = 0.012  # tip to ball at rest
PULL_M = 0.25  # how far the stick draws back at full power
TIP_M = 0.015  # chalked tip length
BUTT_M = 0.45  # dark butt length
TIP_HALF_M, BUTT_HALF_M = 0.0065, 0.015  # stick half widths at the tip and the butt
EIGHTHS = "▏▎▍▌▋▊▉"  # partial cells of the power bar, 1/8 .. 7/8

Cells = tuple[np.ndarray, np.ndarray | None, np.ndarray | None]  # chars, fg, bg (None: mono)

_IS_BALL = np.zeros(256, dtype=bool)
_IS_BALL[[SOLID, STRIPE, EIGHT, CUE]] = True


# ----------------------------------------------------------------------------- pixel helpers


def _ball_px(lay: Layout, radius: float) -> float:
    """A ball's radius in pixels, as TableView draws it."""
    return max(MIN_BALL_PX, float(radius) * lay.scale)


def _ring(lay: Layout, w: int, h: int, centre, r_px: float, half: float = 0.5):
    """Pixels whose centres lie within `half` of a circle of r_px pixels around `centre` (m)."""
    cx, cy = lay.to_pixels(centre[0], centre[1])
    cx, cy = float(cx), float(cy)
    reach = r_px + half + 1.0
    if not (math.isfinite(cx) and math.isfinite(cy)):
        return np.empty(0, np.int64), np.empty(0, np.int64)
    i0, i1 = max(0, math.floor(cx - reach)), min(w, math.ceil(cx + reach))
    j0, j1 = max(0, math.floor(cy - reach)), min(h, math.ceil(cy + reach))
    if i1 <= i0 or j1 <= j0:
        return np.empty(0, np.int64), np.empty(0, np.int64)
    X = np.arange(i0, i1) + 0.5 - cx
    Y = np.arange(j0, j1) + 0.5 - cy
    dist = np.hypot(X[None, :], Y[:, None])
    jj, ii = np.nonzero(np.abs(dist - r_px) <= half)
    return ii + i0, jj + j0


def _paint(cv: Canvas, ix, iy, colour, over_balls: bool = False) -> None:
    if not over_balls:
        # Nor the other half of a ball's cell: a cell shows two colours, and a ball a pixel
        # or two across (80x24) that shares its cell with a line reads as half a line.
        ball = _IS_BALL[cv.tag]
        free = ~ball[iy, ix] & ~ball[np.minimum(iy ^ 1, cv.height - 1), ix]
        ix, iy = ix[free], iy[free]
    cv.rgb[iy, ix] = colour.rgb
    cv.tag[iy, ix] = AIM


def _unit(v) -> np.ndarray | None:
    n = math.hypot(v[0], v[1])
    return None if not n > 1e-15 else np.asarray(v, dtype=float) / n


# ----------------------------------------------------------------------------- table overlays


def _polyline(lay: Layout, w: int, h: int, pts, skip0: float = 0.0, skip1: float = 0.0,
              dotted: bool = False):
    """Pixels (ix, iy) a polyline through `pts` (K, 2, table metres) crosses on a w x h
    canvas, leaving out `skip0` pixels of its length at the start and `skip1` at the end (a
    ball's radius); dotted keeps DOT_ON of every DOT_PERIOD pixels counted from its start."""
    p = np.asarray(pts, dtype=float).reshape(-1, 2)
    if len(p) < 2 or not np.isfinite(p).all():
        return np.empty(0, np.int64), np.empty(0, np.int64)
    X, Y = lay.to_pixels(p[:, 0], p[:, 1])
    seg = np.hypot(np.diff(X), np.diff(Y))
    s = np.concatenate([[0.0], np.cumsum(seg)])
    total = float(s[-1])
    # Nothing beyond the canvas's diagonal from the start can be seen.
    end = min(total - skip1, skip0 + math.hypot(w, h) + math.hypot(X[0] - w / 2, Y[0] - h / 2))
    if end <= skip0:
        return np.empty(0, np.int64), np.empty(0, np.int64)
    at = np.arange(skip0, end + 1e-9, STEP)
    if dotted:
        at = at[np.mod(at - skip0, DOT_PERIOD) < DOT_ON]
    ix = np.floor(np.interp(at, s, X)).astype(np.int64)
    iy = np.floor(np.interp(at, s, Y)).astype(np.int64)
    keep = (ix >= 0) & (ix < w) & (iy >= 0) & (iy < h)
    return ix[keep], iy[keep]


def draw_prediction(canvas: Canvas, lay: Layout, pred: Prediction, radius: float = BALL_RADIUS,
                    level: str = "full") -> None:
    """The aim aid from the engine's prediction (`ui.predict`): the cue ball's path (dotted,
    white) to the ghost ball, where it first meets a ball (or a pocket, a cushion, its rest),
    and at level "full" the first ball's path (solid, pink) to its next contact or rest and,
    faint and dotted, the cue ball's path from the hit to its next contact. A ring marks
    where each path ends, unless it ends in a pocket. Level "ghost" draws the first path and
    its ring only."""
    if level == "off":
        return
    w, h = canvas.width, canvas.height
    r_px = _ball_px(lay, radius)
    legs = [(pred.cue, AIM_C, True)]
    if level == "full":
        legs += [(leg, colour, dotted) for leg, colour, dotted in
                 ((pred.object, OBJECT_C, False), (pred.after, GUIDE_C, True))
                 if leg is not None]
    for k, (leg, colour, dotted) in enumerate(legs):
        ring = leg.end != "pocket"
        _paint(canvas, *_polyline(lay, w, h, leg.points, r_px, r_px if ring else 0.0,
                                  dotted), colour)
        if ring and (k == 0 or len(leg.points) > 1):
            _paint(canvas, *_ring(lay, w, h, leg.points[-1], r_px), colour)


def draw_called_pocket(canvas: Canvas, lay: Layout, centre, hole_r: float) -> None:
    """A ring round the pocket called for the 8 (centre, radius in table metres), over the
    rail and cushions about it."""
    r_px = float(hole_r) * lay.scale + 1.0
    _paint(canvas, *_ring(lay, canvas.width, canvas.height, centre, r_px, 0.75), CALL_C)


def mono_called_pocket(chars: np.ndarray, lay: Layout, centre) -> None:
    """The called pocket in the monochrome mode: a '*' in the cell of its centre."""
    x, y = lay.to_pixels(centre[0], centre[1])
    r, c = int(math.floor(float(y))) // 2, int(math.floor(float(x)))
    rows, cols = chars.shape
    chars[min(max(r, 0), rows - 1), min(max(c, 0), cols - 1)] = "*"


def draw_head_string(canvas: Canvas, lay: Layout, x: float) -> None:
    """The head string (the kitchen's edge, x metres from the head rail): a dotted line
    across the cloth, for a ball in hand that must stay behind it."""
    _paint(canvas, *_polyline(lay, canvas.width, canvas.height, [(x, 0.0), (x, lay.width)],
                              dotted=True), GUIDE_C)


def mono_head_string(chars: np.ndarray, lay: Layout, x: float) -> None:
    """The head string in the monochrome mode: ':' down the blank cells of its column."""
    rows, cols = chars.shape
    ix, iy = _polyline(lay, cols, 2 * rows, [(x, 0.0), (x, lay.width)])
    r = iy // 2
    blank = chars[r, ix] == " "
    chars[r[blank], ix[blank]] = ":"


def draw_cue_stick(canvas: Canvas, lay: Layout, cue_pos, radius: float, angle_deg: float,
                   pull: float = 0.0) -> None:
    """The stick behind the cue ball, opposite the aim, its tip drawn back by `pull` (0..1, the
    power while charging) times PULL_M. It tapers from tip to butt and passes under balls."""
    if not math.isfinite(pull):
        raise ValueError("stick.pull: must be finite")
    if not math.isfinite(angle_deg):
        raise ValueError("stick.angle: must be finite")
    if not all(math.isfinite(float(v)) for v in (cue_pos[0], cue_pos[1], radius)):
        raise ValueError("stick.cue_pos: position and radius must be finite")
    pull = min(1.0, max(0.0, float(pull)))
    w, h = canvas.width, canvas.height
    dx, dy = aim_direction(angle_deg)
    cx, cy = lay.to_pixels(cue_pos[0], cue_pos[1])
    cx, cy = float(cx), float(cy)
    # Backwards in pixels (pixel y runs down). Pixels are square: one scale for distances.
    bx, by = -dx, dy
    k = lay.scale
    s0 = (float(radius) + STICK_GAP_M + pull * PULL_M) * k
    s1 = s0 + STICK_M * k
    hw_tip = max(0.5, TIP_HALF_M * k)
    hw_butt = max(0.5, BUTT_HALF_M * k)
    ends_x = (cx + bx * s0, cx + bx * s1)
    ends_y = (cy + by * s0, cy + by * s1)
    i0 = max(0, math.floor(min(ends_x) - hw_butt))
    i1 = min(w, math.ceil(max(ends_x) + hw_butt))
    j0 = max(0, math.floor(min(ends_y) - hw_butt))
    j1 = min(h, math.ceil(max(ends_y) + hw_butt))
    if i1 <= i0 or j1 <= j0:
        return
    X = (np.arange(i0, i1) + 0.5 - cx)[None, :]
    Y = (np.arange(j0, j1) + 0.5 - cy)[:, None]
    along = X * bx + Y * by
    across = np.abs(X * by - Y * bx)
    frac = np.clip((along - s0) / (s1 - s0), 0.0, 1.0)
    inside = (along >= s0) & (along <= s1) & (across <= hw_tip + (hw_butt - hw_tip) * frac)
    jj, ii = np.nonzero(inside)
    a = along[jj, ii]
    ii, jj = ii + i0, jj + j0
    for part, colour in ((a < s0 + TIP_M * k, TIP_C),
                         ((a >= s0 + TIP_M * k) & (a <= s1 - BUTT_M * k), STICK_C),
                         (a > s1 - BUTT_M * k, BUTT_C)):
        _paint(canvas, ii[part], jj[part], colour)


def draw_placement(canvas: Canvas, lay: Layout, pos, radius: float, ok: bool) -> None:
    """Ball in hand: a ring just outside the ball at `pos` (draw the ball itself with the
    table), light where it may go and red where it may not."""
    r_px = _ball_px(lay, radius) + 0.5
    colour = PLACE_OK_C if ok else PLACE_BAD_C
    _paint(canvas, *_ring(lay, canvas.width, canvas.height, pos, r_px), colour)


def mono_prediction(chars: np.ndarray, lay: Layout, pred: Prediction, level: str = "full",
                    radius: float = BALL_RADIUS) -> None:
    """The aim aid for the monochrome mode, on TableView.mono's glyph grid (in place): '.'
    along the cue ball's path, '◌' where it ends (the ghost ball, dotted: the cue ball is
    '○'), and at level "full" the first ball's path drawn with '-', '/', '|' or '\\' by its
    slope on screen and the cue ball's path after the hit with ':'. Only blank cells are
    marked: balls and cushions keep their glyphs."""
    if level == "off":
        return
    rows, cols = chars.shape
    w, h = cols, 2 * rows
    r_px = _ball_px(lay, radius)

    def mark(ix, iy, glyph):
        r, col = iy // 2, ix
        ok = (r >= 0) & (r < rows) & (col >= 0) & (col < cols)
        r, col = r[ok], col[ok]
        blank = chars[r, col] == " "
        chars[r[blank], col[blank]] = glyph

    if level == "full":
        if pred.object is not None:
            pts = pred.object.points
            for k, (p, q) in enumerate(zip(pts, pts[1:], strict=False)):
                # Cells are twice as tall as wide: the glyph follows the slope on screen.
                slope = math.degrees(math.atan2((q[1] - p[1]) * lay.sy,
                                                (q[0] - p[0]) * lay.sx * 2)) % 180
                glyph = "-/|\\"[int(((slope + 22.5) % 180) // 45)]
                mark(*_polyline(lay, w, h, [p, q], r_px if k == 0 else 0.0), glyph)
        if pred.after is not None:
            mark(*_polyline(lay, w, h, pred.after.points, r_px), ":")
    cue = pred.cue
    if cue.end != "pocket" and len(cue.points):
        gx, gy = lay.to_pixels(cue.points[-1][0], cue.points[-1][1])
        if math.isfinite(gx) and math.isfinite(gy):
            mark(np.array([math.floor(gx)]), np.array([math.floor(gy)]), "◌")
    mark(*_polyline(lay, w, h, cue.points, 0.0), ".")


# ----------------------------------------------------------------------------- panel widgets


def spin_face_cells(side: float, top: float, size: tuple[int, int] = (7, 4), *,
                    mono: bool = False) -> Cells:
    """A small cue-ball face, size = (cols, rows) cells, with the tip's point on it: side > 0
    moves it right, top > 0 up (units of R); a grey circle marks the miscue limit, 0.5 R.

    Returns (chars, fg, bg) like canvas.to_cells; with mono, (chars, None, None) with glyphs:
    '░' the face, '·' the limit, '●' the tip."""
    for name, val in (("side", side), ("top", top)):
        if not math.isfinite(val):
            raise ValueError(f"spin.{name}: must be finite")
    cols, rows = size
    if cols < 3 or rows < 2:
        raise ValueError(f"spin.size: need at least 3x2 cells, not {cols}x{rows}")
    cx, cy = cols / 2, float(rows)
    rp = min(cols, 2 * rows) / 2
    X = np.arange(cols)[None, :] + 0.5 - cx
    Y = np.arange(2 * rows)[:, None] + 0.5 - cy
    dist = np.hypot(X, Y)
    # Layers, each pixel its topmost: 0 backdrop, 1 face, 2 limit circle, 3 tip.
    layer = np.zeros((2 * rows, cols), dtype=np.int8)
    face = dist * dist <= rp * rp - 0.3  # as disc_mask rounds balls: no lone pixel at the poles
    layer[face] = 1
    layer[face & (np.abs(dist - 0.5 * rp) <= 0.5)] = 2
    off = math.hypot(side, top)
    k = 1.0 if off <= 1.0 else 1.0 / off  # a point off the face is shown on its edge
    tx, ty = side * k * rp, -top * k * rp
    j, i = divmod(int(np.argmin(((X - tx) ** 2 + (Y - ty) ** 2).ravel())), cols)
    layer[j, i] = 3
    if mono:
        pick = np.maximum(layer[0::2], layer[1::2])
        return np.array([" ", "░", "·", "●"])[pick], None, None
    colours = np.array([BACKDROP_C.rgb, CUE_C.rgb, SPIN_LIMIT_C.rgb, SPIN_DOT_C.rgb], np.uint8)
    return to_cells(colours[layer])


def power_meter_cells(level: float, width: int, label: str = "") -> Cells:
    """One row of `width` cells: the label, then a bar filled in proportion to level (0..1)
    to an eighth of a cell, its empty part dotted. (chars, fg, bg) like canvas.to_cells."""
    if not math.isfinite(level):
        raise ValueError("power.level: must be finite")
    if width < 1:
        raise ValueError(f"power.width: must be at least 1, not {width}")
    level = min(1.0, max(0.0, float(level)))
    text = f"{label} " if label else ""
    text = text[: width - max(1, width // 3)]  # the bar keeps a third of the row at least
    bar = width - len(text)
    chars = np.full((1, width), " ", dtype="<U1")
    fg = np.empty((1, width, 3), dtype=np.uint8)
    bg = np.empty((1, width, 3), dtype=np.uint8)
    bg[...] = BACKDROP_C.rgb
    fg[...] = TEXT_C.rgb
    chars[0, : len(text)] = list(text)
    eighths = round(level * bar * 8)
    full, part = divmod(eighths, 8)
    b = slice(len(text), width)
    chars[0, b] = "·"
    fg[0, b] = DIM_TEXT_C.rgb
    s = len(text)
    chars[0, s : s + full] = "█"
    fg[0, s : s + full] = POWER_C.rgb
    if part:
        chars[0, s + full] = EIGHTHS[part - 1]
        fg[0, s + full] = POWER_C.rgb
    return chars, fg, bg


def blit_cells(dst: Cells, src: Cells, row: int, col: int) -> None:
    """Copy cells `src` into `dst` (both (chars, fg, bg)) at row, col, clipped; colours are
    skipped where either side has none (mono)."""
    dc, dfg, dbg = dst
    sc, sfg, sbg = src
    rows, cols = dc.shape
    h, w = sc.shape
    r0, c0 = max(row, 0), max(col, 0)
    r1, c1 = min(row + h, rows), min(col + w, cols)
    if r1 <= r0 or c1 <= c0:
        return
    d = (slice(r0, r1), slice(c0, c1))
    s = (slice(r0 - row, r1 - row), slice(c0 - col, c1 - col))
    dc[d] = sc[s]
    if dfg is not None and sfg is not None:
        dfg[d] = sfg[s]
    if dbg is not None and sbg is not None:
        dbg[d] = sbg[s]
