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


# What the aim aid draws (its colours, and in mono its marks): a page after the keys.
AID_LEGEND = [
    ("Dots (. in mono)", "the cue ball's path to the first ball it meets, through up to three "
     "cushions; a ring (o) is the cue ball where they touch."),
    ("Pink (- / | \\)", "that ball's path, on to its first cushion, ball or pocket, and "
     "through a pocket's jaws to the pocket or out: throw and a pocket missed show."),
    ("Green dots (:)", "the cue ball after the hit, through one cushion to its next contact "
     "or rest (through a pocket's jaws too), curving with follow or draw."),
    ("Below the table", "the power the aid shows the shot at, the first ball it sees hit and, "
     "when it sees a pot, the pocket; a red line when the referee would call it a foul."),
    ("G", "every path, then the ghost ball only, then off."),
]


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
    """The keys as lines for a box on a screen `cols` wide (see `key_entries`)."""
    return [line for entry in key_entries(rows, cols, height) for line in entry]


def key_entries(rows: Sequence[tuple[str, str]], cols: int, height: int) -> list[list[str]]:
    """The keys as lines for a box on a screen `cols` wide, in entries that a page must not
    split: one column (an entry a key), or, when that is taller than `height` and the screen
    is wide enough, two (split where they come out most even; an entry then runs from a row
    where both columns start a key to the next). What a key does is wrapped under itself
    where it is too long (the pages then take the rest), never cut."""
    width = max(20, cols - BOX_EDGE)
    one = _wrapped(rows, width)
    half = (cols - 10) // 2
    if sum(len(e) for e in one) <= height or half < TWO_COLUMNS:
        return one
    best = None
    for n in range(1, len(rows)):
        left, right = _wrapped(rows[:n], half), _wrapped(rows[n:], half)
        tall = max(sum(len(e) for e in left), sum(len(e) for e in right))
        if best is None or tall < best[0]:
            best = (tall, left, right)
    tall, left, right = best

    def column(entries):  # its lines, padded, and the rows where it may break
        lines = [line for e in entries for line in e]
        starts, at = set(), 0
        for e in entries:
            starts.add(at)
            at += len(e)
        return lines + [""] * (tall - len(lines)), starts | set(range(len(lines), tall))

    (a, sa), (b, sb) = column(left), column(right)
    lines = [f"{x:<{half}}  {y}".rstrip() for x, y in zip(a, b, strict=True)]
    cuts = [k for k in range(tall) if k in sa and k in sb] + [tall]
    return [lines[i:j] for i, j in zip(cuts, cuts[1:], strict=False) if j > i]


def paragraph_lines(paragraphs: Sequence[tuple[str, str]], width: int) -> list[str]:
    """(heading, text) paragraphs wrapped to `width` as "Heading: text", a blank line
    between them."""
    out: list[str] = []
    for head, text in paragraphs:
        if out:
            out.append("")
        out += textwrap.wrap(f"{head}: {text}", width, break_on_hyphens=False)
    return out


def rules_lines(mode: str, width: int, **how) -> list[str]:
    """The rules page of `mode` wrapped to `width` (`paragraph_lines`)."""
    return paragraph_lines(rules_page(mode, **how), width)


def paginate(lines: list[str], height: int) -> list[list[str]]:
    """Lines in pages of at most `height`, the paragraphs (between blank lines) kept whole on
    a page where they fit one (see `paginate_entries`)."""
    entries, entry = [], []
    for line in [*lines, ""]:
        if line:
            entry.append(line)
        elif entry:
            entries.append(entry)
            entry = []
    return paginate_entries(entries, height, gap=True)


def paginate_entries(entries: list[list[str]], height: int,
                     gap: bool = False) -> list[list[str]]:
    """Entries (lists of lines) in pages of at most `height` lines, a blank line between two
    entries with `gap`: an entry goes whole to the next page rather than be split, unless it
    is taller than a page on its own. No line is lost; no page starts with a blank."""
    pages: list[list[str]] = []
    page: list[str] = []
    for entry in entries:
        sep = [""] if gap and page else []
        if page and len(page) + len(sep) + len(entry) > height:
            pages.append(page)
            page, sep = [], []
        page += sep
        rest = list(entry)
        while len(page) + len(rest) > height:  # taller than a page: it must be split
            room = height - len(page)
            pages.append(page + rest[:room])
            page, rest = [], rest[room:]
        page += rest
    if page:
        pages.append(page)
    return pages or [[]]


def help_pages(keys: Sequence[tuple[str, str]], mode: str | None, cols: int, rows: int,
               aid: bool = True, **how) -> list[tuple[str, list[str]]]:
    """The help box's pages for a cols x rows screen: the keys, what the aim aid draws (with
    `aid`), then the rules of `mode` (of every mode when None), each page with a footer that
    says how to turn pages and close the box. `how` goes to `rules_page` (three_foul,
    eight_break, theme)."""
    width = max(20, cols - BOX_EDGE)
    height = max(3, rows - BOX_ROWS)
    pages = [("keys", p) for p in paginate_entries(key_entries(keys, cols, height), height)]
    if aid:  # a player's help (a watched match shows no aid)
        pages += [("the aim aid", p) for p in paginate(paragraph_lines(AID_LEGEND, width),
                                                        height)]
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
