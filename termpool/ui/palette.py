"""Colours of the table and the balls, with hand-picked 256- and 16-colour equivalents.

Every pixel of a canvas carries an RGB colour and a semantic tag (felt, cushion, ball...). The
colour depths "truecolor" and "256" use the RGB (256 through `HAND256`, else the nearest xterm
colour); "16" uses `HAND16`, picked so the felt stays green, every ball stands out from the
felt, the cushions and the rails in the common 16-colour palettes (xterm's and the VGA one of
the Linux console), and the balls stay apart as far as 16 colours allow: there the rails are
dark grey and the cushions a lighter green band, so that the orange 5 can have the brown-yellow
3, and the green 6 is cyan; "mono" ignores colour and draws each cell's most important tag as
a glyph.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

# Tags: what a pixel shows. Mono mode draws a cell as the glyph of its higher-priority pixel.
BACKDROP, FELT, CUSHION, RAIL, DIAMOND, POCKET, SOLID, STRIPE, EIGHT, CUE, TEXT = range(11)
AIM = 11  # overlays: aim line, ghost ball, cue stick, placement ring (ui/overlay.py)
MONO_GLYPH = {
    BACKDROP: " ",
    FELT: " ",
    CUSHION: "▒",
    RAIL: "░",
    DIAMOND: "◆",
    POCKET: "█",
    SOLID: "●",
    STRIPE: "◐",
    EIGHT: "◉",
    CUE: "○",
    TEXT: " ",
    AIM: "·",
}
MONO_PRIORITY = {
    BACKDROP: 0, FELT: 1, TEXT: 1, CUSHION: 2, RAIL: 3, POCKET: 4, DIAMOND: 5,
    SOLID: 6, STRIPE: 7, EIGHT: 8, CUE: 9, AIM: 2,
}


class Colour(NamedTuple):
    rgb: tuple[int, int, int]
    c256: int  # xterm-256 index (16..255: the cube and the greys, not the themable 0..15)
    c16: int  # 0..7 normal, 8..15 bright


BACKDROP_C = Colour((0, 0, 0), 16, 0)
FELT_C = Colour((22, 110, 54), 28, 2)
CUSHION_C = Colour((13, 74, 36), 22, 10)
RAIL_C = Colour((108, 58, 26), 94, 8)
DIAMOND_C = Colour((236, 228, 196), 230, 15)
POCKET_C = Colour((6, 6, 6), 232, 0)
CUE_C = Colour((246, 246, 238), 231, 15)
STRIPE_WHITE_C = Colour((240, 238, 226), 255, 15)
TEXT_C = Colour((210, 210, 210), 252, 7)
DIM_TEXT_C = Colour((130, 130, 130), 244, 8)
# Overlays (ui/overlay.py). The stick is yellow in 16 colours so it stands out on the rail.
AIM_C = Colour((238, 238, 228), 255, 15)  # the cue ball's path (dotted) and the ghost ball
OBJECT_C = Colour((255, 135, 215), 212, 13)  # the first ball's path (solid): pink, unlike
# the cue ball's white and every ball's colour (the purple 4 is magenta 5 in 16 colours)
GUIDE_C = Colour((150, 200, 160), 115, 7)  # faint: the cue ball's tangent line
STICK_C = Colour((224, 190, 132), 180, 11)  # maple shaft
BUTT_C = Colour((84, 44, 22), 52, 1)
TIP_C = Colour((70, 120, 210), 68, 12)  # chalked tip
PLACE_OK_C = Colour((120, 220, 240), 117, 14)  # ball-in-hand ring
PLACE_BAD_C = Colour((235, 40, 40), 196, 9)  # ... where the ball may not go
POWER_C = Colour((240, 170, 40), 214, 11)
SPIN_DOT_C = Colour((220, 30, 40), 160, 9)
SPIN_LIMIT_C = Colour((150, 150, 150), 246, 8)  # the miscue limit on the spin face
CALL_C = Colour((255, 200, 40), 220, 11)  # the ring round the pocket called for the 8
NUMBER_DARK_C = Colour((16, 16, 16), 233, 0)  # a ball's number on a light ball ...
NUMBER_LIGHT_C = Colour((250, 250, 250), 231, 15)  # ... and on a dark one

# Standard ball colours, 1..8; 9..15 are striped 1..7.
BALL_C = {
    1: Colour((246, 196, 0), 220, 11),  # yellow
    2: Colour((28, 72, 204), 26, 12),  # blue
    3: Colour((214, 28, 36), 160, 9),  # red
    4: Colour((106, 38, 156), 91, 5),  # purple
    5: Colour((246, 114, 18), 208, 3),  # orange
    6: Colour((40, 196, 92), 41, 14),  # green, brighter than the felt (cyan in 16 colours)
    7: Colour((122, 22, 58), 89, 1),  # maroon, toward wine: apart from the 3's red at a glance
    8: Colour((30, 30, 34), 234, 0),  # black
}

# The "classic" theme (UK pub pool, the seed game): reds and yellows, no stripes.
CLASSIC_RED_C = Colour((200, 25, 25), 160, 9)
CLASSIC_YELLOW_C = Colour((245, 205, 30), 220, 11)

ALL_COLOURS = (
    BACKDROP_C, FELT_C, CUSHION_C, RAIL_C, DIAMOND_C, POCKET_C, CUE_C, STRIPE_WHITE_C,
    TEXT_C, DIM_TEXT_C, *BALL_C.values(), CLASSIC_RED_C, CLASSIC_YELLOW_C,
    AIM_C, OBJECT_C, GUIDE_C, STICK_C, BUTT_C, TIP_C, PLACE_OK_C, PLACE_BAD_C, POWER_C, SPIN_DOT_C,
    SPIN_LIMIT_C, CALL_C, NUMBER_DARK_C, NUMBER_LIGHT_C,
)


def pack(rgb: tuple[int, int, int]) -> int:
    r, g, b = rgb
    return (r << 16) | (g << 8) | b


HAND256 = {pack(c.rgb): c.c256 for c in ALL_COLOURS}
HAND16 = {pack(c.rgb): c.c16 for c in ALL_COLOURS}

CUE_IDS = ("cue", "0", "white", "c")


class BallStyle(NamedTuple):
    tag: int  # SOLID, STRIPE, EIGHT or CUE
    colour: Colour
    number: str  # the label shown in panels


def ball_style(ball_id: str, index: int = 0, theme: str = "standard") -> BallStyle:
    """Standard colours for ids 'cue' and '1'..'15'; other ids cycle through the solids.
    theme "classic": 1-7 red, 9-15 yellow, all plain (`mono_glyph` keeps the stripes' glyph
    for the yellows, so mono still tells the groups apart)."""
    bid = str(ball_id)
    if bid.lower() in CUE_IDS:
        return BallStyle(CUE, CUE_C, "c")
    try:
        n = int(bid)
    except ValueError:
        n = -1
    if 1 <= n <= 15:
        if n == 8:
            return BallStyle(EIGHT, BALL_C[8], "8")
        if theme == "classic":
            return BallStyle(SOLID, CLASSIC_RED_C if n < 8 else CLASSIC_YELLOW_C, str(n))
        if n > 8:
            return BallStyle(STRIPE, BALL_C[n - 8], str(n))
        return BallStyle(SOLID, BALL_C[n], str(n))
    return BallStyle(SOLID, BALL_C[1 + index % 7], bid[:2])


def number_colour(ball: Colour) -> Colour:
    """The colour a number is written in on a ball of colour `ball`: dark on light balls,
    light on dark ones (by the colour's luma at the depth it is shown in)."""
    r, g, b = ball.rgb
    return NUMBER_DARK_C if 0.299 * r + 0.587 * g + 0.114 * b > 130 else NUMBER_LIGHT_C


def mono_glyph(style: BallStyle) -> str:
    """The glyph of a ball in mono: by its tag, with classic yellows drawn as the stripes."""
    if style.colour is CLASSIC_YELLOW_C:
        return MONO_GLYPH[STRIPE]
    return MONO_GLYPH[style.tag]


def mono_numbers(styles: Sequence[BallStyle]) -> bool:
    """Whether a game of these balls is drawn in mono by the balls' numbers: where every
    object ball's is one character (9-ball), whose rules ask for the lowest, which a glyph
    by group cannot tell. With 15 balls a ball is the glyph of its group, which 8-ball is
    about. (Decided by the game's balls, not those left, so that it never changes in play.)"""
    return all(len(st.number) == 1 for st in styles if st.tag != CUE)


def mono_mark(style: BallStyle, numbers: bool) -> str:
    """A ball's one character on the table in mono: its number (with `numbers`, see
    `mono_numbers`) or its glyph; the cue ball's glyph either way."""
    return style.number if numbers and style.tag != CUE else mono_glyph(style)
