"""Ball colour themes: ball id -> (name, rgb, striped).

- "standard": the numbered American set. 1-7 solids (yellow, blue, red, purple, orange,
  green, maroon), the black 8, 9-15 stripes of the same colours (9 yellow ... 15 maroon).
- "classic": two coloured groups of seven, like the seed game and UK pub pool: 1-7 red
  ("reds", the solids group), 9-15 yellow ("yellows", the stripes group), the black 8 and the
  white cue ball. No stripes.

The rules always speak of "solids" and "stripes"; `group_label` gives the theme's word.
"""

from __future__ import annotations

from typing import NamedTuple


class BallLook(NamedTuple):
    name: str
    rgb: tuple[int, int, int]
    striped: bool


WHITE = ("white", (245, 245, 240))
BLACK = ("black", (20, 20, 20))
COLOURS = [
    ("yellow", (250, 200, 20)),
    ("blue", (20, 60, 200)),
    ("red", (210, 30, 30)),
    ("purple", (100, 40, 150)),
    ("orange", (245, 120, 20)),
    ("green", (20, 130, 60)),
    ("maroon", (130, 20, 30)),
]
CLASSIC_RED = ("red", (200, 25, 25))
CLASSIC_YELLOW = ("yellow", (245, 205, 30))


def _standard() -> dict[str, BallLook]:
    out = {"cue": BallLook(*WHITE, False), "8": BallLook(*BLACK, False)}
    for k, (name, rgb) in enumerate(COLOURS):
        out[str(k + 1)] = BallLook(name, rgb, False)
        out[str(k + 9)] = BallLook(name, rgb, True)
    return out


def _classic() -> dict[str, BallLook]:
    out = {"cue": BallLook(*WHITE, False), "8": BallLook(*BLACK, False)}
    for k in range(7):
        out[str(k + 1)] = BallLook(*CLASSIC_RED, False)
        out[str(k + 9)] = BallLook(*CLASSIC_YELLOW, False)
    return out


THEMES: dict[str, dict[str, BallLook]] = {"standard": _standard(), "classic": _classic()}
GROUP_LABELS = {
    "standard": {"solids": "solids", "stripes": "stripes"},
    "classic": {"solids": "reds", "stripes": "yellows"},
}


def ball_look(ball_id: str, theme: str = "standard") -> BallLook:
    """How ball `ball_id` looks in `theme` (KeyError for an unknown theme or ball)."""
    return THEMES[theme][str(ball_id)]


def group_label(group: str, theme: str = "standard") -> str:
    """The theme's word for a rules group: "solids" is "reds" in the classic theme."""
    return GROUP_LABELS[theme][group]
