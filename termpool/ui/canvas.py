"""A pixel canvas drawn with half blocks: each terminal cell shows two vertical pixels.

A `Canvas` is an RGB image (uint8, H x W x 3, H even) plus a tag per pixel saying what it shows
(see `palette`), which the monochrome mode turns into glyphs. `to_cells` turns the image into
terminal cells: '▀' with the top pixel as foreground and the bottom one as background, or ' '
on the background colour when both pixels are equal (fewer bytes, and no colour fringes).
"""

from __future__ import annotations

import functools

import numpy as np

from termpool.text import one_column
from termpool.ui.palette import BACKDROP, BACKDROP_C, MONO_GLYPH, MONO_PRIORITY

UPPER_HALF = "▀"

_PRIO = np.zeros(256, dtype=np.int16)
_GLYPH = np.full(256, " ", dtype="<U1")
for _tag, _p in MONO_PRIORITY.items():
    _PRIO[_tag] = _p
for _tag, _g in MONO_GLYPH.items():
    _GLYPH[_tag] = _g


class Canvas:
    """Square-ish pixels: a terminal cell is about 1:2, and holds two pixels one above the other."""

    __slots__ = ("rgb", "tag")

    def __init__(self, width: int, height: int, colour=BACKDROP_C.rgb, tag: int = BACKDROP):
        if height % 2 or height <= 0 or width <= 0:
            raise ValueError(f"canvas: height must be even and positive, not {width}x{height}")
        self.rgb = np.empty((height, width, 3), dtype=np.uint8)
        self.rgb[...] = colour
        self.tag = np.full((height, width), tag, dtype=np.uint8)

    @property
    def width(self) -> int:
        return self.rgb.shape[1]

    @property
    def height(self) -> int:
        return self.rgb.shape[0]

    def copy(self) -> Canvas:
        out = Canvas.__new__(Canvas)
        out.rgb = self.rgb.copy()
        out.tag = self.tag.copy()
        return out

    def copy_from(self, other: Canvas) -> None:
        """Overwrite this canvas with another of the same size (no allocation)."""
        np.copyto(self.rgb, other.rgb)
        np.copyto(self.tag, other.tag)

    def fill(self, where, colour, tag: int) -> None:
        """Paint the pixels selected by `where` (a boolean mask or an index/slice tuple)."""
        self.rgb[where] = colour
        self.tag[where] = tag


def to_cells(canvas) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(chars, fg, bg) for a Canvas or an (H, W, 3) uint8 array: chars is (H/2, W) of '▀' or
    ' ', fg the top pixels and bg the bottom ones, both (H/2, W, 3) uint8."""
    rgb = canvas.rgb if isinstance(canvas, Canvas) else np.asarray(canvas, dtype=np.uint8)
    if rgb.ndim != 3 or rgb.shape[2] != 3 or rgb.shape[0] % 2:
        raise ValueError(f"to_cells: need an (H, W, 3) array with H even, not {rgb.shape}")
    top = rgb[0::2]
    bot = rgb[1::2]
    same = (top == bot).all(axis=2)
    chars = np.where(same, " ", UPPER_HALF)
    return chars, np.ascontiguousarray(top), np.ascontiguousarray(bot)


def mono_tags(canvas) -> np.ndarray:
    """(H/2, W) tags for the monochrome mode: each cell's more important pixel's tag (a ball
    beats a pocket beats a rail beats felt)."""
    tag = canvas.tag if isinstance(canvas, Canvas) else np.asarray(canvas, dtype=np.uint8)
    top = tag[0::2]
    bot = tag[1::2]
    return np.where(_PRIO[top] >= _PRIO[bot], top, bot)


def mono_cells(canvas) -> np.ndarray:
    """(H/2, W) glyphs for the monochrome mode: each cell the glyph of its tag (`mono_tags`)."""
    return _GLYPH[mono_tags(canvas)]


@functools.lru_cache(maxsize=1024)
def _fits_cell(c: str) -> bool:
    return one_column(c)


def put_text(cells, row: int, col: int, text: str, fg=None, bg=None) -> None:
    """Write text into (chars, fg, bg) cells in place, clipped to the grid (one cell a char).
    fg and bg are RGB triples; they are ignored when the cells carry no colour (mono)."""
    chars, fga, bga = cells
    rows, cols = chars.shape
    if not 0 <= row < rows or col >= cols or not text:
        return
    if col < 0:
        text, col = text[-col:], 0
    text = text[: cols - col]
    if not text:
        return
    if not text.isascii():  # a wide or zero-width character would shift the rest of the row
        text = "".join(c if _fits_cell(c) else "?" for c in text)
    n = len(text)
    chars[row, col : col + n] = list(text)
    if fga is not None and fg is not None:
        fga[row, col : col + n] = fg
    if bga is not None and bg is not None:
        bga[row, col : col + n] = bg
