"""Regenerate the README's screen captures: python docs/screenshots.py (needs pyte).

Plays the same key script headless at 80x24 and 160x50 and writes, per size, the text capture
(monochrome glyphs, as `termpool play --headless --colors mono` prints it) and a PNG of the
truecolor frames decoded by pyte (each cell drawn as its two half-block pixels).
"""

from __future__ import annotations

import struct
import sys
import zlib
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from termpool.files import write_atomic  # noqa: E402
from termpool.ui.app import App, Options  # noqa: E402
from termpool.ui.headless import play  # noqa: E402
from termpool.ui.keys import parse_script  # noqa: E402

SCRIPT = "enter right*6 space-hold 1.1 wait 20 left*3 d w"
SIZES = ((80, 24), (160, 50))
OUT = ROOT / "docs" / "screens"
CELL_W, CELL_H = 8, 16


def _png(rgb: np.ndarray, path: Path) -> None:
    h, w, _ = rgb.shape
    raw = b"".join(b"\x00" + rgb[r].tobytes() for r in range(h))

    def chunk(tag: bytes, data: bytes) -> bytes:
        crc = zlib.crc32(tag + data) & 0xFFFFFFFF
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", crc)

    head = struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)
    write_atomic(path, b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", head)
                 + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def _colour(c: str, default: tuple[int, int, int]) -> tuple[int, int, int]:
    if isinstance(c, str) and len(c) == 6:
        try:
            return tuple(int(c[k:k + 2], 16) for k in (0, 2, 4))
        except ValueError:
            pass
    return default


def _image(frames: list[str], cols: int, rows: int) -> np.ndarray:
    import pyte

    screen = pyte.Screen(cols, rows)
    pyte.Stream(screen).feed("".join(frames))
    img = np.zeros((rows * CELL_H, cols * CELL_W, 3), np.uint8)
    for y in range(rows):
        for x in range(cols):
            ch = screen.buffer[y][x]
            fg, bg = _colour(ch.fg, (210, 210, 210)), _colour(ch.bg, (0, 0, 0))
            block = img[y * CELL_H:(y + 1) * CELL_H, x * CELL_W:(x + 1) * CELL_W]
            block[:] = bg
            if ch.data == "▀":
                block[:CELL_H // 2] = fg
            elif ch.data not in (" ", ""):  # text: a solid mark where the glyph is
                block[CELL_H // 4:3 * CELL_H // 4, 1:CELL_W - 1] = fg
    return img


def main() -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    for cols, rows in SIZES:
        opts = dict(mode="8ball", opponent="human", seed=0)  # the same rack every time
        text = play(App(Options(colors="mono", **opts)), parse_script(SCRIPT), cols, rows)
        write_atomic(OUT / f"{cols}x{rows}.txt", text + "\n")
        frames: list[str] = []
        play(App(Options(colors="truecolor", **opts)), parse_script(SCRIPT), cols, rows, frames)
        _png(_image(frames, cols, rows), OUT / f"{cols}x{rows}.png")
        print(f"wrote {OUT / f'{cols}x{rows}'}.txt and .png")


if __name__ == "__main__":
    main()
