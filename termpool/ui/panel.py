"""The match panel beside or below the table, and the boxes drawn over it (help, pause, ...).

Everything here writes text into (chars, fg, bg) cells; the app decides what to say.
`PanelInfo` is plain data so the panel can be tested without a match.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from termpool.ui.canvas import put_text
from termpool.ui.frame import _ball_tokens
from termpool.ui.palette import BACKDROP_C, DIM_TEXT_C, TEXT_C
from termpool.ui.table_view import Layout

TURN_C = (250, 214, 90)
FOUL_C = (240, 110, 90)
GOOD_C = (130, 220, 130)
BOX_BG = (28, 32, 40)
TONES = {"plain": TEXT_C.rgb, "dim": DIM_TEXT_C.rgb, "turn": TURN_C, "foul": FOUL_C,
         "good": GOOD_C}


@dataclass
class PlayerLine:
    name: str
    group: str = ""  # "solids", "reds", "" while open
    balls: list[int] = field(default_factory=list)  # indices of the balls still to pot
    down: list[int] = field(default_factory=list)  # indices of the group's balls pocketed
    score: str | None = None  # frames won of those needed ("1/3"), in a race of several
    turn: bool = False
    fouls: int = 0


@dataclass
class PanelInfo:
    title: str
    players: list[PlayerLine]
    status: list[tuple[str, str]]  # (text, tone) lines, most important first
    help: Sequence[tuple]  # key help: (text, rank) in screen order, text a string or
    # (long, short) forms; rank 0 must show, higher ranks are left out first where the line
    # is too narrow (see fit_hint)
    ids: Sequence[str] = ()
    widgets: list = field(default_factory=list)  # (cells, name) blocks: spin face, power meter
    theme: str = "standard"


def _tone(t: str):
    return TONES.get(t, TEXT_C.rgb)


def _wrap(text: str, width: int) -> list[str]:
    out, line = [], ""
    for word in text.split():
        if line and len(line) + 1 + len(word) > width:
            out.append(line)
            line = word
        else:
            line = f"{line} {word}" if line else word
    if line:
        out.append(line)
    return [s[:width] for s in out] or [""]


def _clear(cells, col: int, row: int, ncols: int, nrows: int) -> None:
    chars, fg, bg = cells
    chars[row:row + nrows, col:col + ncols] = " "
    if bg is not None:
        bg[row:row + nrows, col:col + ncols] = BACKDROP_C.rgb
        fg[row:row + nrows, col:col + ncols] = TEXT_C.rgb


def _player(cells, r: int, c0: int, width: int, p: PlayerLine) -> int:
    """One player's line: marker, name, and group, frames and fouls. Returns the column after
    the text, where the balls to pot go."""
    mark = "▶ " if p.turn else "  "
    text = f"{mark}{p.name}"
    put_text(cells, r, c0, text[:width], TURN_C if p.turn else TEXT_C.rgb, BACKDROP_C.rgb)
    c = c0 + len(text) + 1
    extra = []
    if p.group:
        extra.append(p.group)
    if p.score is not None:
        extra.append(f"frames {p.score}")
    if p.fouls:
        extra.append(f"fouls {p.fouls}")
    if extra:
        s = " " + " · ".join(extra)
        put_text(cells, r, c, s[: max(0, c0 + width - c)], DIM_TEXT_C.rgb, BACKDROP_C.rgb)
        c += len(s) + 1
    return c


def draw_panel(cells, lay: Layout, info: PanelInfo, mono: bool = False) -> None:
    """Fill the layout's panel rectangle from `info`."""
    col, row, ncols, nrows = lay.panel_rect
    if ncols <= 2 or nrows <= 0:
        return
    _clear(cells, col, row, ncols, nrows)
    if lay.panel == "side":
        _side(cells, col + 1, row, ncols - 2, nrows, info, mono)
    else:
        _bottom(cells, col + 1, row, ncols - 2, nrows, info, mono)


def _tokens(cells, r: int, c: int, end: int, p: PlayerLine, info: PanelInfo, mono: bool) -> None:
    """The balls a player still has to pot, in colour, then the ones already down, dim."""
    toks = _ball_tokens(info.ids, p.balls, mono, info.theme)
    toks += [(f"{info.ids[k]:>2}", DIM_TEXT_C.rgb, BACKDROP_C.rgb) for k in p.down]
    for text, fg, bg in toks:
        if c + len(text) > end:
            break
        put_text(cells, r, c, text, fg, bg)
        c += len(text) + 1


def _bottom(cells, c0: int, r0: int, width: int, nrows: int, info: PanelInfo, mono) -> None:
    # Widgets (spin face, power meter) take the right end; text gets the rest.
    right = c0 + width
    for block, _where in info.widgets:
        bw = block[0].shape[1]
        if right - bw - 1 < c0 + 30:
            continue
        right -= bw + 1
        _paste(cells, block, r0, right)
    w = right - c0 - 1
    r = r0
    if nrows < 6 and len(info.players) > 1:
        # Short panels: both players share a row so the status keeps two.
        c, half = c0, c0 + w // 2
        for k, p in enumerate(info.players[:2]):
            start = c0 if k == 0 else max(c + 1, half)
            c = _player(cells, r, start, w - (start - c0), p)
            _tokens(cells, r, c, (half - 1) if k == 0 else c0 + w, p, info, mono)
        r += 1
    else:
        for p in info.players[:2]:
            c = _player(cells, r, c0, w, p)
            _tokens(cells, r, c, c0 + w, p, info, mono)
            r += 1
    lines = []
    for text, tone in info.status:
        lines += [(s, tone) for s in _wrap(text, w)]
    room = r0 + nrows - 1 - r
    for s, tone in lines[:max(0, room)]:
        put_text(cells, r, c0, s, _tone(tone), BACKDROP_C.rgb)
        r += 1
    put_text(cells, r0 + nrows - 1, c0, _fit_help(info, w), DIM_TEXT_C.rgb, BACKDROP_C.rgb)


def _side(cells, c0: int, r0: int, width: int, nrows: int, info: PanelInfo, mono) -> None:
    r = r0
    end = r0 + nrows
    put_text(cells, r, c0, info.title[:width], TEXT_C.rgb, BACKDROP_C.rgb)
    r += 2
    for p in info.players:
        _player(cells, r, c0, width, p)
        r += 1
        if p.balls or p.down:
            _tokens(cells, r, c0 + 2, c0 + width, p, info, mono)
            r += 1
        r += 1
    for text, tone in info.status:
        for s in _wrap(text, width):
            if r >= end - 1:
                break
            put_text(cells, r, c0, s, _tone(tone), BACKDROP_C.rgb)
            r += 1
    r += 1
    for block, _where in info.widgets:
        if r + block[0].shape[0] < end - 1:
            _paste(cells, block, r, c0)
            r += block[0].shape[0] + 1
    for s in _wrap(fit_hint(info.help, 3 * width - 6), width)[::-1]:
        end -= 1
        if end <= r:
            break
        put_text(cells, end, c0, s, DIM_TEXT_C.rgb, BACKDROP_C.rgb)


def fit_hint(parts: Sequence[tuple], width: int) -> str:
    """The key help for a line of `width` cells: every part in its long form if they fit
    (two spaces apart, else one), then in their short forms, then without the highest ranks,
    one rank at a time. Parts are never cut; only the rank-0 parts' short forms, should even
    they not fit, are cut at the end."""
    forms = [((t,) if isinstance(t, str) else tuple(t), r) for t, r in parts]
    limits = [math.inf, *sorted({r for _, r in forms if r > 0}, reverse=True)]
    for limit in limits:
        for v in (0, 1):
            keep = [f[min(v, len(f) - 1)] for f, r in forms if r < limit]
            for sep in ("  ", " "):
                line = sep.join(keep)
                if len(line) <= width:
                    return line
    return " ".join(f[-1] for f, r in forms if r == 0)[:width]


def _fit_help(info: PanelInfo, width: int) -> str:
    return fit_hint(info.help, width)


def _paste(cells, block, r: int, c: int) -> None:
    chars, fg, bg = cells
    bc, bf, bb = block
    rows, cols = chars.shape
    h, w = bc.shape
    h, w = min(h, rows - r), min(w, cols - c)
    if h <= 0 or w <= 0:
        return
    chars[r:r + h, c:c + w] = bc[:h, :w]
    if fg is not None and bf is not None:
        fg[r:r + h, c:c + w] = bf[:h, :w]
        bg[r:r + h, c:c + w] = bb[:h, :w]


def draw_box(cells, lines: Sequence[str], title: str = "", tone: str = "plain",
             wrap: bool = True) -> None:
    """A framed box of text in the middle of the screen (help, pause, questions). Lines too
    long for the screen are wrapped, or (wrap=False, for columns) cut with an ellipsis."""
    chars, fg, bg = cells
    rows, cols = chars.shape
    width = min(cols - 2, max([len(s) for s in lines] + [len(title) + 4]) + 4)
    room = width - 4
    body = []
    for s in lines:
        if len(s) <= room:
            body.append(s)
        else:
            body += _wrap(s, room) if wrap else [s[:room - 1] + "…"]
    height = min(rows, len(body) + 2)
    top, left = max(0, (rows - height) // 2), max(0, (cols - width) // 2)
    chars[top:top + height, left:left + width] = " "
    if bg is not None:
        bg[top:top + height, left:left + width] = BOX_BG
        fg[top:top + height, left:left + width] = TEXT_C.rgb
    edge = "─" * (width - 2)
    put_text(cells, top, left, f"┌{edge}┐", DIM_TEXT_C.rgb, BOX_BG)
    put_text(cells, top + height - 1, left, f"└{edge}┘", DIM_TEXT_C.rgb, BOX_BG)
    for r in range(top + 1, top + height - 1):
        put_text(cells, r, left, "│", DIM_TEXT_C.rgb, BOX_BG)
        put_text(cells, r, left + width - 1, "│", DIM_TEXT_C.rgb, BOX_BG)
    if title:
        put_text(cells, top, left + 2, f" {title} ", TURN_C, BOX_BG)
    for k, s in enumerate(body[: height - 2]):
        put_text(cells, top + 1 + k, left + 2, s, _tone(tone) if k == 0 else TEXT_C.rgb, BOX_BG)


def blank_cells(cols: int, rows: int, mono: bool):
    chars = np.full((rows, cols), " ", dtype="<U1")
    if mono:
        return chars, None, None
    fg = np.empty((rows, cols, 3), dtype=np.uint8)
    bg = np.empty((rows, cols, 3), dtype=np.uint8)
    fg[...] = TEXT_C.rgb
    bg[...] = BACKDROP_C.rgb
    return chars, fg, bg
