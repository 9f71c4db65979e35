"""Terminal output: one string per frame holding only the cells that changed.

`Screen.render(chars, fg, bg)` compares the cells with the previous frame's and returns the
escape string that updates the terminal: a cursor move only where the next changed cell is not
where the cursor already is (CSI n C within a row, CSI row;col H otherwise), colour escapes only
when the colour differs from the last one emitted (cached strings), a reset at the end, and
optionally the whole wrapped in synchronized-output marks (CSI ?2026h ... CSI ?2026l). A frame
identical to the previous one gives '' (nothing to write).

Colour depths: "truecolor" (38;2;r;g;b), "256" (hand-picked for the game's colours, else the
nearest xterm-256 colour, cached), "16" (a hand-picked palette: the felt stays green), "mono"
(no colour at all: the caller passes glyph cells, see `canvas.mono_cells`).
"""

from __future__ import annotations

import os
from collections.abc import Mapping

import numpy as np

from termpool.ui.palette import HAND16, HAND256

DEPTHS = ("truecolor", "256", "16", "mono")
CSI = "\x1b["
RESET = "\x1b[0m"
SYNC_BEGIN = "\x1b[?2026h"
SYNC_END = "\x1b[?2026l"
NONE = -1  # colour code of "don't care" (the foreground of a blank cell, any colour in mono)

_TRUECOLOR_TERMS = ("truecolor", "24bit", "direct", "kitty", "alacritty", "wezterm", "foot",
                    "contour", "ghostty", "iterm")
_TRUECOLOR_PROGRAMS = ("iTerm.app", "WezTerm", "vscode", "ghostty", "Hyper", "Tabby")


def detect_depth(env: Mapping[str, str] | None = None, term: str | None = None) -> str:
    """The colour depth to use, from the environment only (no terminal queries).

    NO_COLOR (set and not empty) gives "mono"; COLORTERM=truecolor|24bit, a TERM naming a
    direct-colour terminal or a known TERM_PROGRAM gives "truecolor"; a TERM with "256color"
    gives "256"; "dumb" or no TERM gives "mono"; any other TERM gives "16".
    """
    env = os.environ if env is None else env
    if env.get("NO_COLOR"):
        return "mono"
    term = (env.get("TERM", "") if term is None else term).lower()
    colorterm = env.get("COLORTERM", "").lower()
    if colorterm in ("truecolor", "24bit"):
        return "truecolor"
    if any(t in term for t in _TRUECOLOR_TERMS):
        return "truecolor"
    if env.get("TERM_PROGRAM", "") in _TRUECOLOR_PROGRAMS and term != "dumb":
        return "truecolor"
    if "256" in term:
        return "256"
    if not term or term == "dumb":
        return "mono"
    return "16"


def resolve_depth(depth: str = "auto", env: Mapping[str, str] | None = None,
                  term: str | None = None) -> str:
    """A forced depth as given; "auto" detected (NO_COLOR -> "mono")."""
    if depth == "auto":
        return detect_depth(env, term)
    if depth not in DEPTHS:
        raise ValueError(f"colors: unknown depth '{depth}' (use auto, {', '.join(DEPTHS)})")
    return depth


# ------------------------------------------------------------------------- colour conversion

_CUBE = np.array([0, 95, 135, 175, 215, 255])


def _xterm256_rgb() -> np.ndarray:
    out = np.zeros((256, 3))
    idx = np.arange(216)
    out[16:232, 0] = _CUBE[idx // 36]
    out[16:232, 1] = _CUBE[(idx // 6) % 6]
    out[16:232, 2] = _CUBE[idx % 6]
    grey = 8 + 10 * np.arange(24)
    out[232:256] = grey[:, None]
    return out


XTERM256 = _xterm256_rgb()
# A neutral reference for the 16 ANSI colours (VGA-like), for colours not hand-picked.
ANSI16 = np.array([
    (0, 0, 0), (170, 0, 0), (0, 170, 0), (170, 85, 0), (0, 0, 170), (170, 0, 170), (0, 170, 170),
    (170, 170, 170), (85, 85, 85), (255, 85, 85), (85, 255, 85), (255, 255, 85), (85, 85, 255),
    (255, 85, 255), (85, 255, 255), (255, 255, 255),
], dtype=float)


def _nearest(rgb: np.ndarray, table: np.ndarray, first: int = 0) -> int:
    """Index of the nearest colour by the 'redmean' weighted distance."""
    cand = table[first:]
    rmean = (cand[:, 0] + rgb[0]) / 2
    d = cand - rgb
    dist = ((2 + rmean / 256) * d[:, 0] ** 2 + 4 * d[:, 1] ** 2
            + (2 + (255 - rmean) / 256) * d[:, 2] ** 2)
    return first + int(np.argmin(dist))


def _unpack(code: int) -> np.ndarray:
    return np.array([(code >> 16) & 255, (code >> 8) & 255, code & 255], dtype=float)


def nearest256(code: int) -> int:
    """xterm-256 index for a packed RGB: hand-picked for the game's colours, else nearest."""
    if code in HAND256:
        return HAND256[code]
    return _nearest(_unpack(code), XTERM256, 16)


def nearest16(code: int) -> int:
    if code in HAND16:
        return HAND16[code]
    return _nearest(_unpack(code), ANSI16)


def _fg_param(depth: str, code: int) -> str:
    if depth == "truecolor":
        return f"38;2;{(code >> 16) & 255};{(code >> 8) & 255};{code & 255}"
    if depth == "256":
        return f"38;5;{code}"
    return str(30 + code if code < 8 else 90 + code - 8)


def _bg_param(depth: str, code: int) -> str:
    if depth == "truecolor":
        return f"48;2;{(code >> 16) & 255};{(code >> 8) & 255};{code & 255}"
    if depth == "256":
        return f"48;5;{code}"
    return str(40 + code if code < 8 else 100 + code - 8)


# ----------------------------------------------------------------------------------- screen


class Screen:
    """Keeps the cells last sent to a cols x rows terminal and emits only the changes."""

    def __init__(self, cols: int, rows: int, depth: str = "truecolor", sync: bool = False,
                 env: Mapping[str, str] | None = None):
        self.depth = resolve_depth(depth, env)
        self.sync = sync
        self._lut_keys = np.zeros(0, dtype=np.int64)  # sorted packed RGB -> colour code
        self._lut_vals = np.zeros(0, dtype=np.int64)
        self._sgr: dict[tuple[int, int], str] = {}
        self.resize(cols, rows)

    def resize(self, cols: int, rows: int) -> None:
        """New terminal size: the next frame is sent in full."""
        self.cols, self.rows = int(cols), int(rows)
        self.invalidate()

    def invalidate(self) -> None:
        """Forget what the terminal shows (after a clear, a resize, a resume): next frame full."""
        self._prev: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None

    # -- colours
    def _codes(self, rgb: np.ndarray) -> np.ndarray:
        """(..., 3) uint8 RGB -> int64 colour codes for this depth (cached per colour)."""
        packed = (rgb[..., 0].astype(np.int64) << 16) | (rgb[..., 1].astype(np.int64) << 8) | rgb[
            ..., 2
        ]
        if self.depth == "truecolor":
            return packed
        keys = self._lut_keys
        if keys.size:
            pos = np.searchsorted(keys, packed)
            np.minimum(pos, keys.size - 1, out=pos)
            miss = keys[pos] != packed
            if not miss.any():
                return self._lut_vals[pos]
            new = np.unique(packed[miss])
        else:
            new = np.unique(packed)
        conv = nearest256 if self.depth == "256" else nearest16
        vals = np.array([conv(int(c)) for c in new], dtype=np.int64)
        keys = np.concatenate([keys, new])
        order = np.argsort(keys)
        self._lut_keys = keys = keys[order]
        self._lut_vals = np.concatenate([self._lut_vals, vals])[order]
        pos = np.searchsorted(keys, packed)
        return self._lut_vals[pos]

    def _sgr_for(self, fg: int, bg: int) -> str:
        """The escape setting fg and/or bg (NONE: leave unchanged), cached."""
        key = (fg, bg)
        s = self._sgr.get(key)
        if s is None:
            parts = []
            if fg != NONE:
                parts.append(_fg_param(self.depth, fg))
            if bg != NONE:
                parts.append(_bg_param(self.depth, bg))
            s = self._sgr[key] = CSI + ";".join(parts) + "m"
        return s

    # -- frames
    def render(self, chars: np.ndarray, fg: np.ndarray | None = None,
               bg: np.ndarray | None = None) -> str:
        """The escape string turning the previous frame into this one ('' if identical).

        chars: (rows, cols) one-character strings; fg, bg: (rows, cols, 3) uint8 RGB (ignored,
        and may be None, in mono). The first frame after creation, resize or `invalidate` is
        sent in full.
        """
        rows, cols = self.rows, self.cols
        chars = np.asarray(chars, dtype="<U1")
        if chars.shape != (rows, cols):
            raise ValueError(f"render: cells are {chars.shape[::-1]}, screen is {cols}x{rows}")
        code = chars.view(np.uint32).reshape(-1).copy()
        blank = code == 32
        if self.depth == "mono" or fg is None or bg is None:
            fgc = np.full(code.shape, NONE, dtype=np.int64)
            bgc = fgc.copy()
        else:
            fgc = self._codes(fg).reshape(-1)
            bgc = self._codes(bg).reshape(-1)
            # A half block whose halves became one colour at this depth is a blank cell.
            flat = (code == 0x2580) & (fgc == bgc)
            code[flat] = 32
            blank |= flat
            fgc = np.where(blank, NONE, fgc)
        prev = self._prev
        self._prev = (code, fgc, bgc)
        if prev is None:
            idx = np.arange(code.size)
        else:
            pc, pf, pb = prev
            idx = np.flatnonzero((code != pc) | (fgc != pf) | (bgc != pb))
            if idx.size == 0:
                return ""
        return self._emit(idx, code, fgc, bgc, chars.reshape(-1), full=prev is None)

    def _emit(self, idx, code, fgc, bgc, chars, full: bool) -> str:
        cols = self.cols
        f = fgc[idx]
        b = bgc[idx]
        n = idx.size
        start = np.ones(n, dtype=bool)
        if n > 1:
            start[1:] = (idx[1:] != idx[:-1] + 1) | (idx[1:] % cols == 0) | (f[1:] != f[:-1]) | (
                b[1:] != b[:-1]
            )
        starts = np.flatnonzero(start)
        ends = np.append(starts[1:], n)
        # Text of each run: the chars of the cells it covers (runs are contiguous in memory).
        flat_chars = chars.copy()
        flat_chars[code == 32] = " "
        out: list[str] = [RESET] if full else []  # a full frame starts from known attributes
        cur_row = cur_col = -1
        cur_f = cur_b = None
        any_sgr = False
        p0s = idx[starts].tolist()
        fs = f[starts].tolist()
        bs = b[starts].tolist()
        lens = (ends - starts).tolist()
        for p0, fv, bv, m in zip(p0s, fs, bs, lens, strict=True):
            row, col = divmod(p0, cols)
            if row != cur_row or col != cur_col:
                if row == cur_row and col > cur_col:
                    gap = col - cur_col
                    out.append(f"{CSI}{gap}C" if gap > 1 else f"{CSI}C")
                else:
                    out.append(f"{CSI}{row + 1};{col + 1}H")
            sf = fv if (fv != NONE and fv != cur_f) else NONE
            sb = bv if (bv != NONE and bv != cur_b) else NONE
            if sf != NONE or sb != NONE:
                out.append(self._sgr_for(sf, sb))
                any_sgr = True
                if sf != NONE:
                    cur_f = sf
                if sb != NONE:
                    cur_b = sb
            out.append("".join(flat_chars[p0 : p0 + m].tolist()))
            cur_row, cur_col = row, col + m
        if any_sgr:
            out.append(RESET)
        s = "".join(out)
        if self.sync:
            s = SYNC_BEGIN + s + SYNC_END
        return s
