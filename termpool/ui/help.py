"""The help box: the keys, then the rules of the game in play (`rules.words.rules_page`, the
words the referees' verdicts share), in pages that fit the screen.

`pretty(spec)` is a key as the screen names it; `help_pages(keys, mode, cols, rows)` gives the
pages as (title, lines); `page_key` turns a key into the page to show (← → and PgUp PgDn turn
pages, any other key closes the box).
"""

from __future__ import annotations

import textwrap
from collections.abc import Sequence

from termpool.rules.words import MODE_NAMES, rules_page
from termpool.ui.controls import ACTIONS
from termpool.ui.keys import Key

NEXT_KEYS = ("right", "pagedown", "down")
BACK_KEYS = ("left", "pageup", "up")
BOX_EDGE = 6  # a box's frame and margins take this many columns of the screen ...
BOX_ROWS = 4  # ... and this many rows: its frame, a blank line and the footer
ARROWS = {"left": "←", "right": "→", "up": "↑", "down": "↓"}
DIGITS = "1234567890"  # the power keys: 10% to 90%, and 100%
TWO_COLUMNS = 30  # keys go in two columns (when one is too tall) if each has this much room


def pretty(spec: str) -> str:
    """A key spec as the screen shows it: "left" -> "←", "shift+up" -> "⇧↑", "space" ->
    "Space", "w" -> "W"."""
    *mods, name = spec.split("+") if spec != "+" else ["+"]
    base = ARROWS.get(name) or (name.capitalize() if len(name) > 1 else name.upper())
    return "".join({"shift": "⇧", "ctrl": "^", "alt": "M-"}.get(m, m) for m in mods) + base


def keymap_rows(keymap) -> list[tuple[str, str]]:
    """(keys, what they do) for every bound action of the game, and the mouse."""
    rows = []
    for a, desc in ACTIONS.items():
        if keymap.keys_for(a):
            rows.append((", ".join(pretty(k) for k in keymap.keys_for(a)), desc))
        if a == "shoot" and not any(keymap.action(Key(d)) for d in DIGITS):
            # The digits set the power where no action has them (ui.phases.aim); shoot is
            # always bound (controls.REQUIRED).
            strike = pretty(keymap.keys_for(a)[0])
            rows.append(("1-9, 0", f"power 10-90 %, 0: 100 %; then {strike} strikes"))
    rows.append(("mouse", "click or drag on the table: aim there"))
    return rows


def _wrapped(rows: Sequence[tuple[str, str]], width: int) -> list[list[str]]:
    """Each (keys, what they do) as lines at most `width` wide: what a key does wrapped
    under itself, never cut."""
    kw = max(len(k) for k, _ in rows)
    out = []
    for k, d in rows:
        parts = textwrap.wrap(d, max(8, width - kw - 2), break_on_hyphens=False) or [""]
        out.append([f"{k if j == 0 else '':<{kw}}  {p}".rstrip() for j, p in enumerate(parts)])
    return out


def key_lines(rows: Sequence[tuple[str, str]], cols: int, height: int) -> list[str]:
    """The keys as lines for a box on a screen `cols` wide: one column, or, when that is
    taller than `height` and the screen is wide enough, two (split where they come out most
    even). What a key does is wrapped under itself where it is too long (the pages then take
    the rest), never cut."""
    width = max(20, cols - BOX_EDGE)
    one = [line for entry in _wrapped(rows, width) for line in entry]
    half = (cols - 10) // 2
    if len(one) <= height or half < TWO_COLUMNS:
        return one
    best = None
    for n in range(1, len(rows)):
        left = [line for e in _wrapped(rows[:n], half) for line in e]
        right = [line for e in _wrapped(rows[n:], half) for line in e]
        if best is None or max(len(left), len(right)) < max(len(best[0]), len(best[1])):
            best = (left, right)
    left, right = best
    tall = max(len(left), len(right))
    left += [""] * (tall - len(left))
    right += [""] * (tall - len(right))
    return [f"{a:<{half}}  {b}".rstrip() for a, b in zip(left, right, strict=True)]


def rules_lines(mode: str, width: int, **how) -> list[str]:
    """The rules page of `mode` wrapped to `width`: paragraphs "Heading: text", a blank line
    between them."""
    out: list[str] = []
    for head, text in rules_page(mode, **how):
        if out:
            out.append("")
        out += textwrap.wrap(f"{head}: {text}", width, break_on_hyphens=False)
    return out


def paginate(lines: list[str], height: int) -> list[list[str]]:
    """Lines in pages of at most `height`, broken at a blank line where one is near the end
    of the page (a paragraph is not split if it fits a page), never starting with a blank."""
    pages, rest = [], list(lines)
    while rest:
        while rest and not rest[0]:
            rest.pop(0)
        if not rest:
            break
        cut = min(height, len(rest))
        if cut < len(rest):
            blanks = [k for k in range(1, cut + 1) if k < len(rest) and not rest[k]]
            if blanks and blanks[-1] >= cut // 2:
                cut = blanks[-1]
        pages.append(rest[:cut])
        rest = rest[cut:]
    return pages or [[]]


def help_pages(keys: Sequence[tuple[str, str]], mode: str | None, cols: int, rows: int,
               **how) -> list[tuple[str, list[str]]]:
    """The help box's pages for a cols x rows screen: the keys, then the rules of `mode` (of
    every mode when None), each page with a footer that says how to turn pages and close the
    box. `how` goes to `rules_page` (three_foul, eight_break, theme)."""
    width = max(20, cols - BOX_EDGE)
    height = max(3, rows - BOX_ROWS)
    pages = [("keys", p) for p in paginate(key_lines(keys, cols, height), height)]
    for m in [mode] if mode is not None else list(MODE_NAMES):
        title = f"{MODE_NAMES[m]} rules"
        pages += [(title, p) for p in paginate(rules_lines(m, width, **how), height)]
    n = len(pages)
    out = []
    for k, (title, lines) in enumerate(pages):
        footer = ("← → pages · any other key closes" if n > 1 else "any key closes this")
        out.append((f"{title} · {k + 1}/{n}" if n > 1 else title, [*lines, "", footer]))
    return out


def page_key(name: str, page: int, pages: int) -> tuple[int, bool]:
    """The page to show after key `name` on `page` of `pages`, and whether the box closes."""
    if pages > 1 and name in NEXT_KEYS:
        return min(page + 1, pages - 1), False
    if pages > 1 and name in BACK_KEYS:
        return max(page - 1, 0), False
    return page, True
