"""Screen tests of the half-block renderer: frames decoded with pyte, asserted on cells/pixels."""

from __future__ import annotations

import re

import numpy as np
import pyte
import pytest

from termpool.physics.engine import POCKETED, Engine
from termpool.physics.table import Table
from termpool.scene import load_scene
from termpool.ui.canvas import Canvas, mono_cells, put_text, to_cells
from termpool.ui.frame import Renderer, render_scene_text
from termpool.ui.output import (
    SYNC_BEGIN,
    SYNC_END,
    XTERM256,
    Screen,
    detect_depth,
    nearest16,
    nearest256,
    resolve_depth,
)
from termpool.ui.palette import (
    BALL_C,
    CUE_C,
    CUSHION_C,
    FELT_C,
    HAND16,
    POCKET_C,
    RAIL_C,
    STRIPE_WHITE_C,
    mono_glyph,
    mono_mark,
    mono_numbers,
    pack,
)
from termpool.ui.table_view import MIN_COLS, MIN_ROWS, layout

SIZES = [(80, 24), (120, 40), (200, 60)]
DEPTHS = ["truecolor", "256", "16", "mono"]
ANSI_NAMES = ["black", "red", "green", "brown", "blue", "magenta", "cyan", "white"]


# ----------------------------------------------------------------------------- decoding


def decode(text: str, cols: int, rows: int, screen: pyte.Screen | None = None) -> pyte.Screen:
    scr = screen if screen is not None else pyte.Screen(cols, rows)
    pyte.Stream(scr).feed(text)
    return scr


def colour_of(c: str) -> tuple[int, int, int] | str:
    """pyte colour: a hex string for 256/truecolor becomes RGB; names stay names."""
    if re.fullmatch(r"[0-9a-fA-F]{6}", c):
        return (int(c[0:2], 16), int(c[2:4], 16), int(c[4:6], 16))
    return c


def pixels(scr: pyte.Screen) -> np.ndarray:
    """(2*rows, cols) array of pixel colours (RGB tuples or names) from half-block cells."""
    out = np.empty((2 * scr.lines, scr.columns), dtype=object)
    for r in range(scr.lines):
        line = scr.buffer[r]
        for c in range(scr.columns):
            cell = line[c]
            fg, bg = colour_of(cell.fg), colour_of(cell.bg)
            if cell.data == "▀":
                out[2 * r, c], out[2 * r + 1, c] = fg, bg
            elif cell.data == "▄":
                out[2 * r, c], out[2 * r + 1, c] = bg, fg
            elif cell.data == "█":
                out[2 * r, c] = out[2 * r + 1, c] = fg
            else:
                out[2 * r, c] = out[2 * r + 1, c] = bg
    return out


def cells_of(scr: pyte.Screen) -> list[list[tuple]]:
    """What each cell shows: its character and colours (a blank cell shows no foreground)."""
    out = []
    for r in range(scr.lines):
        line = scr.buffer[r]
        row = []
        for c in range(scr.columns):
            cell = line[c]
            row.append((cell.data, None if cell.data == " " else cell.fg, cell.bg))
        out.append(row)
    return out


def text_of(scr: pyte.Screen) -> str:
    return "\n".join(scr.display)


# ------------------------------------------------------------------------------ fixtures


@pytest.fixture(scope="module")
def brk():
    return load_scene({"table": "9ft", "balls": "8ball", "shot": {"speed": 8.0}})


@pytest.fixture(scope="module")
def break_samples(brk):
    eng = Engine(brk.table, brk.physics, brk.pos, brk.vel, brk.w, brk.radius, brk.mass,
                 record=False)
    return eng.run(1 / 60, sample_hz=60)


TABLE = Table()
# A few balls at known places, well apart: (id, x, y).
PLACED = [("cue", 0.6, 0.64), ("3", 1.0, 0.3), ("11", 1.6, 0.3), ("8", 1.9, 0.9),
          ("2", 0.9, 1.0), ("10", 2.2, 0.5)]


def placed():
    ids = [p[0] for p in PLACED]
    pos = np.array([[p[1], p[2]] for p in PLACED])
    return ids, pos


def pixel_at(lay, x, y):
    X, Y = lay.to_pixels(x, y)
    return int(np.floor(Y)), int(np.floor(X))


def ball_box(lay, x, y, r=0.028575):
    """Canvas pixel rows/cols covering a ball (a pixel of slack each way)."""
    X, Y = lay.to_pixels(x, y)
    rr = max(1.0, r * lay.scale) + 1
    return (slice(int(np.floor(Y - rr)), int(np.ceil(Y + rr)) + 1),
            slice(int(np.floor(X - rr)), int(np.ceil(X + rr)) + 1))


# ------------------------------------------------------------------------------ the table


@pytest.mark.parametrize("cols,rows", SIZES)
def test_felt_in_the_centre_and_cushions_and_rails(cols, rows):
    ids, pos = placed()
    scr = decode(render_scene_text(TABLE, ids, pos, None, cols, rows, "truecolor"), cols, rows)
    px = pixels(scr)
    lay = layout(cols, rows, TABLE)
    j, i = pixel_at(lay, TABLE.length / 2, TABLE.width / 2)
    assert px[j, i] == FELT_C.rgb
    # Just outside the nose at mid-length of the head rail: cushion, then wood further out.
    jj = lay.py + lay.ph // 2
    assert px[jj, lay.px - 1] == CUSHION_C.rgb
    assert px[jj, lay.px - lay.cushion - 1] in (RAIL_C.rgb, (236, 228, 196))  # wood or diamond


@pytest.mark.parametrize("cols,rows", SIZES)
def test_table_keeps_its_two_to_one_proportions(cols, rows):
    ids, pos = placed()
    scr = decode(render_scene_text(TABLE, ids, pos, None, cols, rows, "truecolor"), cols, rows)
    px = pixels(scr)
    felt = np.vectorize(lambda p: p == FELT_C.rgb, otypes=[bool])(px)
    js, is_ = np.nonzero(felt)
    w = is_.max() - is_.min() + 1
    h = js.max() - js.min() + 1
    assert abs(w / h - 2.0) < 0.05, (w, h)
    # The table is as big as the terminal allows: it spans most of one dimension.
    lay = layout(cols, rows, TABLE)
    assert lay.outer[2] >= 0.85 * cols or lay.outer[3] >= 0.85 * 2 * rows


@pytest.mark.parametrize("cols,rows", SIZES)
def test_pockets_are_dark_holes(cols, rows):
    scr = decode(render_scene_text(TABLE, ["cue"], [[0.6, 0.6]], None, cols, rows,
                                   "truecolor"), cols, rows)
    px = pixels(scr)
    lay = layout(cols, rows, TABLE)
    for (hx, hy) in TABLE.hole_c:
        j, i = pixel_at(lay, hx, hy)
        assert px[j, i] == POCKET_C.rgb
    # The four corners of the playing area lie in the corner pockets.
    for (x, y) in [(0.0, 0.0), (TABLE.length, 0.0), (0.0, TABLE.width),
                   (TABLE.length, TABLE.width)]:
        j, i = pixel_at(lay, min(max(x, 0.004), TABLE.length - 0.004),
                        min(max(y, 0.004), TABLE.width - 0.004))
        assert px[j, i] == POCKET_C.rgb, (x, y)


def test_diamonds_on_the_rails():
    lay = layout(200, 60, TABLE)
    scr = decode(render_scene_text(TABLE, ["cue"], [[0.6, 0.6]], None, 200, 60, "truecolor"),
                 200, 60)
    px = pixels(scr)
    ox, oy, ow, oh = lay.outer
    is_d = np.vectorize(lambda p: p == (236, 228, 196), otypes=[bool])(px)
    # Count separate diamonds per rail: top rail rows, left rail columns.
    top = is_d[oy:lay.py - lay.cushion, lay.px:lay.px + lay.pw].any(axis=0)
    left = is_d[lay.py:lay.py + lay.ph, ox:lay.px - lay.cushion].any(axis=1)

    def runs(v):
        return int(np.sum(v[1:] & ~v[:-1]) + v[0])

    assert runs(top) == 6 and runs(left) == 3


# ------------------------------------------------------------------------------ the balls


@pytest.mark.parametrize("cols,rows", SIZES)
def test_balls_have_their_colours_at_their_positions(cols, rows):
    ids, pos = placed()
    scr = decode(render_scene_text(TABLE, ids, pos, None, cols, rows, "truecolor"), cols, rows)
    px = pixels(scr)
    lay = layout(cols, rows, TABLE)
    expect = {"cue": CUE_C.rgb, "3": BALL_C[3].rgb, "8": BALL_C[8].rgb, "2": BALL_C[2].rgb}
    for bid, x, y in PLACED:
        if bid in expect:
            j, i = pixel_at(lay, x, y)
            assert px[j, i] == expect[bid], bid


def test_each_ball_theme_has_its_colours_here() -> None:
    # The themes are named by the rules (their words for the groups); their colours are the
    # UI's, written once in the palette.
    from termpool.rules.common import SOLIDS, STRIPES
    from termpool.rules.words import THEMES
    from termpool.ui.palette import (
        CLASSIC_RED_C,
        CLASSIC_YELLOW_C,
        CUE,
        EIGHT,
        SOLID,
        STRIPE,
        ball_style,
    )

    looks = {t: {b: ball_style(b, 0, t) for b in ("cue", *SOLIDS, "8", *STRIPES)}
             for t in THEMES}
    assert looks["standard"] != looks["classic"]
    for look in looks.values():
        assert (look["cue"].tag, look["8"].tag) == (CUE, EIGHT)
        assert len({(s.tag, s.colour) for s in look.values()}) >= 3
    std = looks["standard"]
    assert all(std[b].tag == SOLID for b in SOLIDS) and all(std[b].tag == STRIPE for b in STRIPES)
    assert all(std[s].colour == std[str(int(s) + 8)].colour for s in SOLIDS)
    assert len({std[b].colour for b in SOLIDS}) == 7
    classic = looks["classic"]
    assert {classic[b].colour for b in SOLIDS} == {CLASSIC_RED_C}
    assert {classic[b].colour for b in STRIPES} == {CLASSIC_YELLOW_C}
    assert not any(s.tag == STRIPE for s in classic.values())


@pytest.mark.parametrize("cols,rows", SIZES)
def test_stripes_differ_from_solids(cols, rows):
    ids, pos = placed()
    scr = decode(render_scene_text(TABLE, ids, pos, None, cols, rows, "truecolor"), cols, rows)
    px = pixels(scr)
    lay = layout(cols, rows, TABLE)
    got = {}
    for bid, x, y in PLACED:
        got[bid] = set(px[ball_box(lay, x, y)].ravel().tolist())
    red = BALL_C[3].rgb
    assert red in got["3"] and red in got["11"]  # 11 is the red stripe
    assert STRIPE_WHITE_C.rgb in got["11"] and STRIPE_WHITE_C.rgb not in got["3"]
    assert STRIPE_WHITE_C.rgb in got["10"] and BALL_C[2].rgb in got["10"]


def test_pocketed_balls_are_not_drawn():
    ids, pos = placed()
    state = np.zeros(len(ids), dtype=np.int8)
    state[1] = POCKETED  # ball 3
    scr = decode(render_scene_text(TABLE, ids, pos, state, 120, 40, "truecolor"), 120, 40)
    px = pixels(scr)
    lay = layout(120, 40, TABLE)
    j, i = pixel_at(lay, 1.0, 0.3)
    assert px[j, i] == FELT_C.rgb
    assert BALL_C[3].rgb not in set(px[ball_box(lay, 1.0, 0.3)].ravel().tolist())


def test_break_rack_shows_every_colour(brk):
    scr = decode(render_scene_text(brk.table, brk.ids, brk.pos, None, 120, 40, "truecolor"),
                 120, 40)
    seen = set(pixels(scr).ravel().tolist())
    for n in range(1, 9):
        assert BALL_C[n].rgb in seen, n
    assert CUE_C.rgb in seen and STRIPE_WHITE_C.rgb in seen
    # The panel lists the balls.
    assert "termpool" in text_of(scr)


# ------------------------------------------------------------------------- diffed frames


@pytest.mark.parametrize("depth", DEPTHS)
@pytest.mark.parametrize("cols,rows", [(80, 24), (120, 40)])
def test_diffed_frames_decode_like_full_frames(brk, break_samples, depth, cols, rows):
    r = Renderer(brk.table, cols, rows, depth)
    scr = decode(r.frame(brk.ids, brk.pos), cols, rows)
    picks = [5, 20, 40, len(break_samples) - 1]
    for k in picks:
        _, pos, state = break_samples[k]
        diff = r.frame(brk.ids, pos[0], state[0])
        decode(diff, cols, rows, scr)
        full = render_scene_text(brk.table, brk.ids, pos[0], state[0], cols, rows, depth)
        assert len(diff) < len(full)
        assert cells_of(scr) == cells_of(decode(full, cols, rows)), k


def test_identical_frame_is_zero_bytes(brk):
    for depth in DEPTHS:
        r = Renderer(brk.table, 80, 24, depth)
        assert len(r.frame(brk.ids, brk.pos)) > 1000
        assert r.frame(brk.ids, brk.pos) == ""
        assert r.frame(brk.ids, brk.pos.copy()) == ""


def test_diff_skips_moves_and_colours_it_does_not_need():
    scr = Screen(10, 2, "truecolor")
    chars = np.full((2, 10), " ")
    fg = np.zeros((2, 10, 3), np.uint8)
    bg = np.zeros((2, 10, 3), np.uint8)
    bg[...] = (0, 100, 0)
    scr.render(chars, fg, bg)
    bg[0, 3:6] = (200, 0, 0)
    bg[0, 8] = (200, 0, 0)
    out = scr.render(chars, fg, bg)
    # One move to (1,4), one colour for the run, a relative skip to column 9, no second colour.
    assert out == "\x1b[1;4H\x1b[48;2;200;0;0m   \x1b[2C \x1b[0m"
    assert scr.render(chars, fg, bg) == ""


def test_sync_wrapping_and_reset(brk):
    r = Renderer(brk.table, 80, 24, "truecolor", sync=True)
    out = r.frame(brk.ids, brk.pos)
    assert out.startswith(SYNC_BEGIN) and out.endswith("\x1b[0m" + SYNC_END)
    assert r.frame(brk.ids, brk.pos) == ""  # nothing changed: not even the sync marks


# --------------------------------------------------------------------------- colour depths


def sgr_params(text: str) -> list[str]:
    return re.findall(r"\x1b\[([0-9;]*)m", text)


@pytest.mark.parametrize("depth", DEPTHS)
def test_each_depth_decodes(brk, depth):
    out = render_scene_text(brk.table, brk.ids, brk.pos, None, 120, 40, depth)
    scr = decode(out, 120, 40)
    lay = layout(120, 40, brk.table)
    j, i = pixel_at(lay, brk.table.length / 2, brk.table.width / 2)
    cell = scr.buffer[j // 2][i]
    params = sgr_params(out)
    if depth == "truecolor":
        assert colour_of(cell.bg) == FELT_C.rgb
        assert any(p.startswith("48;2;") for p in params)
    elif depth == "256":
        assert colour_of(cell.bg) == tuple(int(v) for v in XTERM256[28])
        assert all("38;2" not in p and "48;2" not in p for p in params)
        assert any("48;5;28" in p for p in params)
    elif depth == "16":
        assert cell.bg == "green"  # the felt stays green
        codes = {int(c) for p in params for c in p.split(";") if c}
        assert codes <= {0} | set(range(30, 38)) | set(range(40, 48)) | set(range(90, 98)) | set(
            range(100, 108))
    else:
        assert all(p in ("", "0") for p in params)  # no colour at all
        text = text_of(scr)
        for glyph in "○●◐◉█▒◆":
            assert glyph in text, glyph
        assert cell.data == " "
        # One glyph per ball: 16 balls in the rack and the cue ball, none merged.
        table_rows = text.splitlines()[: lay.panel_rect[1]]
        assert sum(line.count(g) for line in table_rows for g in "○●◐◉") == 16


def test_16_colour_palette_is_hand_picked():
    assert nearest16(pack(FELT_C.rgb)) == 2
    assert len({HAND16[pack(BALL_C[n].rgb)] for n in range(1, 9)}) == 8
    assert nearest16(pack((250, 250, 250))) == 15
    assert nearest256(pack((255, 0, 0))) == 196
    assert nearest256(pack(FELT_C.rgb)) == 28


def test_detect_depth():
    assert detect_depth({"COLORTERM": "truecolor", "TERM": "xterm-256color"}) == "truecolor"
    assert detect_depth({"COLORTERM": "24bit"}) == "truecolor"
    assert detect_depth({"TERM": "xterm-kitty"}) == "truecolor"
    assert detect_depth({"TERM": "xterm-256color"}) == "256"
    assert detect_depth({"TERM": "screen-256color"}) == "256"
    assert detect_depth({"TERM": "xterm"}) == "16"
    assert detect_depth({"TERM": "linux"}) == "16"
    assert detect_depth({"TERM": "dumb"}) == "mono"
    assert detect_depth({}) == "mono"
    assert detect_depth({}, "xterm-256color") == "256"
    assert detect_depth({"NO_COLOR": "1", "COLORTERM": "truecolor"}) == "mono"
    assert detect_depth({"NO_COLOR": "", "TERM": "xterm"}) == "16"  # empty NO_COLOR is unset
    assert resolve_depth("auto", {"NO_COLOR": "1", "TERM": "xterm-256color"}) == "mono"
    assert resolve_depth("256", {"NO_COLOR": "1"}) == "256"  # a forced depth wins
    with pytest.raises(ValueError):
        resolve_depth("8")


# -------------------------------------------------------------------------- layout, canvas


def test_layout_too_small_is_none():
    assert layout(MIN_COLS - 1, 40) is None
    assert layout(120, MIN_ROWS - 1) is None
    assert layout(MIN_COLS, MIN_ROWS) is not None
    out = render_scene_text(TABLE, ["cue"], [[0.6, 0.6]], None, 30, 10, "truecolor")
    text = text_of(decode(out, 30, 10))
    assert "make the window at least" in text and f"{MIN_COLS}x{MIN_ROWS}" in text


@pytest.mark.parametrize("cols,rows", [(40, 12), (80, 24), (120, 40), (200, 60), (300, 50),
                                       (60, 60)])
def test_layout_fits_and_leaves_a_panel(cols, rows):
    lay = layout(cols, rows, TABLE)
    ox, oy, ow, oh = lay.outer
    assert ox >= 0 and oy >= 0 and ox + ow <= cols and oy + oh <= 2 * rows
    pc, pr, pcols, prows = lay.panel_rect
    if lay.panel == "side":
        assert pc >= ox + ow and pcols >= 20
    else:
        assert 2 * pr >= oy + oh and prows >= 4
    assert abs(lay.pw / lay.ph - 2.0) < 0.05


def test_canvas_and_cells():
    with pytest.raises(ValueError):
        Canvas(10, 5)
    cv = Canvas(4, 2, (0, 0, 0))
    cv.rgb[0, 1] = (255, 0, 0)
    chars, fg, bg = to_cells(cv)
    assert chars.tolist() == [[" ", "▀", " ", " "]]
    assert tuple(fg[0, 1]) == (255, 0, 0) and tuple(bg[0, 1]) == (0, 0, 0)
    assert mono_cells(cv).shape == (1, 4)
    cells = (chars, fg, bg)
    put_text(cells, 0, 2, "abc", (1, 2, 3), (4, 5, 6))
    assert chars.tolist() == [[" ", "▀", "a", "b"]]
    assert tuple(fg[0, 3]) == (1, 2, 3)


def test_half_block_of_equal_quantised_colours_becomes_blank():
    # Two truecolor shades that map to one 16-colour index give a blank cell, not '▀'.
    scr = Screen(1, 1, "16")
    out = scr.render(np.array([["▀"]]), np.array([[FELT_C.rgb]], np.uint8),
                     np.array([[(30, 140, 40)]], np.uint8))
    assert "▀" not in out and out.count(" ") == 1


# The two 16-colour palettes most terminals start from: xterm's defaults and the VGA colours
# of the Linux console (ui.output.ANSI16).
XTERM16 = [(0, 0, 0), (205, 0, 0), (0, 205, 0), (205, 205, 0), (0, 0, 238), (205, 0, 205),
           (0, 205, 205), (229, 229, 229), (127, 127, 127), (255, 0, 0), (0, 255, 0),
           (255, 255, 0), (92, 92, 255), (255, 0, 255), (0, 255, 255), (255, 255, 255)]


def _lab(rgb) -> np.ndarray:
    """sRGB (0..255) to CIE L*a*b* (D65), for colour differences as the eye sees them."""
    c = np.asarray(rgb, float) / 255
    c = np.where(c > 0.04045, ((c + 0.055) / 1.055) ** 2.4, c / 12.92)
    xyz = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722],
                    [0.0193, 0.1192, 0.9505]]) @ c / np.array([0.95047, 1.0, 1.08883])
    f = np.where(xyz > 0.008856, np.cbrt(xyz), 7.787 * xyz + 16 / 116)
    return np.array([116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])])


@pytest.mark.parametrize("palette", ["xterm", "vga"])
def test_every_ball_stands_out_from_the_felt_cushions_and_rails_in_16_colours(palette):
    from termpool.ui.output import ANSI16
    from termpool.ui.palette import CLASSIC_RED_C, CLASSIC_YELLOW_C, CUE_C, CUSHION_C, RAIL_C

    rgb = XTERM16 if palette == "xterm" else ANSI16
    # A colour difference (CIE76) of 35: far apart; the green 6 drawn bright green on the
    # green felt was 24 in xterm's palette and 31 in the VGA one, the 5 on the rails 0.
    for ball in [*BALL_C.values(), CUE_C, CLASSIC_RED_C, CLASSIC_YELLOW_C]:
        for ground in (FELT_C, CUSHION_C, RAIL_C):
            d = np.linalg.norm(_lab(rgb[HAND16[pack(ball.rgb)]])
                               - _lab(rgb[HAND16[pack(ground.rgb)]]))
            assert d >= 35, (ball, ground, d)
    assert HAND16[pack(FELT_C.rgb)] == 2  # and the felt is green


def _contrast(a, b) -> float:
    """WCAG contrast ratio of two sRGB colours (1 to 21)."""
    def lum(rgb) -> float:
        c = np.asarray(rgb, float) / 255
        c = np.where(c > 0.04045, ((c + 0.055) / 1.055) ** 2.4, c / 12.92)
        return float(c @ [0.2126, 0.7152, 0.0722])
    hi, lo = sorted((lum(a), lum(b)), reverse=True)
    return (hi + 0.05) / (lo + 0.05)


def test_ball_numbers_take_the_ink_that_reads_best_on_their_ball():
    from termpool.ui.palette import NUMBER_DARK_C, NUMBER_LIGHT_C, number_colour

    # Light ink on the mid-green 6 read at 2.2:1; dark ink reads at 8:1.
    for ball in BALL_C.values():
        ink = number_colour(ball)
        other = NUMBER_LIGHT_C if ink == NUMBER_DARK_C else NUMBER_DARK_C
        assert _contrast(ball.rgb, ink.rgb) >= max(4.5, _contrast(ball.rgb, other.rgb)), ball


# ------------------------------------------------------------ mono: every ball drawn

MONO_BALLS = "●◐◉○123456789"


def _mono_table(ids, pos, cols, rows):
    from termpool.ui.table_view import TableView

    table = Table.preset("9ft")
    lay = layout(cols, rows, table)
    view = TableView(table, lay)
    return view, view.mono(ids, pos)


@pytest.mark.parametrize("mode", ["8ball", "9ball"])
@pytest.mark.parametrize(("cols", "rows"), [(50, 16), (80, 24), (120, 40)])
def test_mono_draws_every_ball_of_a_rack(mode, cols, rows) -> None:
    # A rack's balls are closer than a cell: each still gets a glyph of its own, as the
    # colour modes draw every ball, and the cue ball keeps its own cell.
    sc = load_scene({"table": "9ft", "balls": mode})
    view, chars = _mono_table(sc.ids, sc.pos, cols, rows)
    glyphs = [g for g in chars.ravel() if g in MONO_BALLS]
    styles = [view.style(b, k) for k, b in enumerate(sc.ids)]
    want = sorted(mono_mark(st, mono_numbers(styles)) for st in styles)
    assert sorted(glyphs) == want
    x, y = view.layout.to_pixels(*sc.pos[sc.ids.index("cue")])
    assert chars[int(y) // 2, int(x)] == "○"


@pytest.mark.parametrize("ids", [["cue", "1", "9", "8"], ["cue", "1", "9", "8", "12"]])
def test_mono_moves_no_ball_that_has_a_cell_of_its_own(ids) -> None:
    pos = np.array([[0.5, 0.5], [1.0, 0.3], [1.6, 0.9], [2.2, 0.6], [0.5, 1.0]])[:len(ids)]
    view, chars = _mono_table(ids, pos, 80, 24)
    numbers = len(ids) == 4  # the 12's number takes two characters: the groups' glyphs
    for k, b in enumerate(ids):
        x, y = view.layout.to_pixels(*pos[k])
        st = view.style(b, k)
        want = st.number if numbers and b != "cue" else mono_glyph(st)
        assert chars[int(y) // 2, int(x)] == want
    assert sum(g in MONO_BALLS for g in chars.ravel()) == len(ids)


@pytest.mark.parametrize(("mode", "numbers"), [("9ball", True), ("8ball", False)])
def test_mono_draws_9_ball_by_number_and_15_balls_by_group(mode, numbers) -> None:
    # 9-ball asks for the lowest ball: each is its digit. With 15 balls a ball is its
    # group's glyph, and it stays so as balls go down (the game's balls decide, not the
    # table's).
    sc = load_scene({"table": "9ft", "balls": mode})
    state = np.zeros(len(sc.ids), dtype=int)
    state[[k for k, b in enumerate(sc.ids) if b not in ("cue", "1", "2", "3")]] = POCKETED
    for st in (None, state):
        view, chars = _mono_table(sc.ids, sc.pos, 120, 40)
        chars = view.mono(sc.ids, sc.pos, st)
        shown = "".join(g for g in chars.ravel() if g in MONO_BALLS)
        if numbers:
            assert "●" not in shown and "◐" not in shown and "◉" not in shown
            assert sorted(shown.replace("○", "")) == sorted(
                b for k, b in enumerate(sc.ids) if b != "cue" and (st is None or not st[k]))
        else:
            assert not any(c.isdigit() for c in shown)
            assert shown.count("○") == 1


def test_mono_puts_a_hidden_ball_on_the_nearest_free_cloth() -> None:
    # Two balls frozen along the table's length at 80x24 (4 cm a cell): the second goes to
    # the free cell of cloth nearest its centre, on its side of the first.
    from termpool.physics.params import BALL_RADIUS

    table = Table.preset("9ft")
    lay = layout(80, 24, table)
    c, r = 40, 8
    x0, y0 = lay.to_table(c, r)  # the centre of a cell of cloth
    for ids, marks in ((["1", "12"], "●◐"), (["1", "9"], "19")):  # by group, by number
        pos = np.array([[x0, y0], [x0 + 0.2 * BALL_RADIUS, y0]])  # the same cell, the 2nd right
        _, chars = _mono_table(ids, pos, 80, 24)
        assert chars[r, c] == marks[0] and chars[r, c + 1] == marks[1]
        assert sum(g in MONO_BALLS for g in chars.ravel()) == 2


def test_put_text_keeps_one_character_a_cell_whatever_the_text():
    """A wide character (an emoji, CJK) takes two columns and a combining mark none: either
    would shift the rest of the row on the terminal, so each is drawn as "?"; the game's
    own symbols (arrows, balls, blocks) are kept."""
    chars = np.full((1, 12), " ", dtype="<U1")
    put_text((chars, None, None), 0, 0, "Zoë🎱王b\u0301 ●←▀")
    assert "".join(chars[0]) == "Zoë??b? ●←▀ "
