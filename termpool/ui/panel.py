"""The panel beside or below the table, and the boxes drawn over it (help, pause, ...).

Everything here writes text into (chars, fg, bg) cells; the app decides what to say.
`PanelInfo` is plain data so the panel can be tested without a match. The game and a watched
match fill it (`draw_panel`); a scene on its own lists its balls (`draw_ball_list`); a screen
too small for the table says so (`message_cells`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from termpool.physics.state import POCKETED
from termpool.ui.canvas import put_text
from termpool.ui.palette import (
    BACKDROP_C,
    CUE,
    DIM_TEXT_C,
    EIGHT,
    STRIPE,
    STRIPE_WHITE_C,
    TEXT_C,
    ball_style,
    mono_glyph,
)
from termpool.ui.table_view import MIN_COLS, MIN_ROWS, Layout

BLACK = (0, 0, 0)
TURN_C = (250, 214, 90)
TEXT_MIN_COLS = 70  # a bottom panel keeps this much room for text before it shows widgets
WIDGET_GAP = 2  # blank columns between a bottom panel's text and its widgets
SIDE_WIDGET_ROWS = 24  # a side panel this tall has room for them below its text
FOUL_C = (240, 110, 90)
GOOD_C = (130, 220, 130)
BOX_BG = (28, 32, 40)
TONES = {"plain": TEXT_C.rgb, "dim": DIM_TEXT_C.rgb, "note": DIM_TEXT_C.rgb, "turn": TURN_C,
         "foul": FOUL_C, "warn": FOUL_C, "good": GOOD_C, "plan": TURN_C, "news": TURN_C}
# ("note": a key's answer, gone once the aim or a charge moves on (ui.state.say); "warn":
# what the aim would do, said while aiming; "plan": the computer's plan, a note; "news": of
# an online match, said once: a player back in it)


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
    most_widgets: list = field(default_factory=list)  # the blocks the match ever shows at
    # once (the players' line keeps clear of them all, so it does not move as they come and go)
    theme: str = "standard"
    legend: list[int] = field(default_factory=list)  # balls to show with their numbers in
    # a free row of a bottom panel (where the table is too small to number them)


def ball_tokens(ids: Sequence[str], which: list[int], mono: bool,
                theme: str = "standard") -> list[tuple]:
    """Panel labels (text, fg, bg) for balls: solids as the number on the ball's colour,
    stripes as the number in the colour on white, the cue ball as 'c'."""
    out = []
    for k in which:
        st = ball_style(ids[k], k, theme)
        if mono:
            out.append((mono_glyph(st) + st.number, None, None))
        elif st.tag == STRIPE:
            out.append((f"{st.number:>2}", st.colour.rgb, STRIPE_WHITE_C.rgb))
        elif st.tag == CUE:
            out.append((" c", BLACK, st.colour.rgb))
        else:
            r, g, b = st.colour.rgb
            light = 0.299 * r + 0.587 * g + 0.114 * b > 110 and st.tag != EIGHT
            out.append((f"{st.number:>2}", BLACK if light else TEXT_C.rgb, st.colour.rgb))
    return out


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


def _cut(lines: list[tuple[str, str]], room: int, width: int) -> list[tuple[str, str]]:
    """The first `room` of the wrapped lines; when some are left out, the last line kept ends
    in an ellipsis, so a cut sentence reads as cut."""
    if len(lines) <= room:
        return lines
    if room <= 0:
        return []
    text, tone = lines[room - 1]
    text = text if len(text) < width else text[:width - 1].rsplit(" ", 1)[0]
    return [*lines[:room - 1], (text + "…", tone)]


KEPT_TONES = ("plain", "good", "foul", "warn", "news")  # verdicts, warnings, news: kept
# longest


def fit_status(status: Sequence[tuple[str, str]], room: int,
               width: int) -> list[tuple[str, str]]:
    """The status lines (text, tone) for `room` rows `width` wide, wrapped. Where they do not
    all fit whole, rows go in turn to: the lines before the first verdict or warning that
    are not notes (what to do now, news), the verdicts and warnings ("plain", "good",
    "foul", "warn") a row each, then each of them whole in order, the other lines a row
    each (a key's answer, "note", first; then the computer's plan, "plan", and dim lines
    such as the power or "Computer is aiming", which the key bar and the players' row say
    too), then whole. A line given fewer rows than it needs is cut at a word with "…"; one
    given none is left out. So what a rule said reads whole, the power and the plan giving
    way first."""
    wrapped = [[(s, tone) for s in _wrap(text, width)] for text, tone in status]
    if sum(len(w) for w in wrapped) <= room:
        return [line for w in wrapped for line in w]
    rows = [0] * len(wrapped)
    left = max(room, 0)
    kept = [k for k, (_, tone) in enumerate(status) if tone in KEPT_TONES]
    # Of the rest, a key's answer ("note") first: it answers what was just pressed, where the
    # power line and the plan are on show all the time.
    rest = sorted((k for k in range(len(status)) if k not in kept),
                  key=lambda k: status[k][1] != "note")
    whole = [len(w) for w in wrapped]
    order = [(k, 1) for k in _leading(status, kept)] + [(k, 1) for k in kept] \
        + [(k, whole[k]) for k in kept] \
        + [(k, 1) for k in rest] + [(k, whole[k]) for k in rest]
    for k, want in order:
        more = min(max(want - rows[k], 0), left)
        rows[k] += more
        left -= more
    return [line for k, w in enumerate(wrapped) for line in _cut(w, rows[k], width)]


def _leading(status: Sequence[tuple[str, str]], kept: list[int]) -> list[int]:
    """The lines before the first verdict or warning (the first line, if none) that are not
    notes ("dim", "note", "plan")."""
    end = kept[0] if kept else min(len(status), 1)
    return [k for k in range(end) if status[k][1] not in ("dim", "note", "plan")]


def status_rows_needed(status: Sequence[tuple[str, str]], width: int) -> int:
    """The rows a bottom panel's status takes before the keys' line does: a row for each
    leading line (`_leading`) and for each verdict or warning; the first of these whole
    where it is a verdict, or where two or more compete (a warning of the shot aimed and
    the last verdict). A warning alone, which changes as the aim moves, keeps the keys."""
    kept = [k for k, (_, tone) in enumerate(status) if tone in KEPT_TONES]
    rows = len(_leading(status, kept)) + len(kept)
    if len(kept) > 1 or kept and status[kept[0]][1] != "warn":
        rows += len(_wrap(status[kept[0]][0], width)) - 1
    return rows


def _clear(cells, col: int, row: int, ncols: int, nrows: int) -> None:
    chars, fg, bg = cells
    chars[row:row + nrows, col:col + ncols] = " "
    if bg is not None:
        bg[row:row + nrows, col:col + ncols] = BACKDROP_C.rgb
        fg[row:row + nrows, col:col + ncols] = TEXT_C.rgb


def player_line(p: PlayerLine, info: PanelInfo, mono: bool, width: int,
                keep_score: bool = False, start: int = 0) -> list[tuple] | None:
    """One player's line as (text, fg, bg) pieces within `width` cells: marker and name, then
    group, frames and fouls, then the group's balls in order, those down dim in their
    places. Where that is too long it is said more shortly, in turn (`_forms`): without the
    balls down, without the group's word (the balls show it; in mono they lose their
    glyphs), with the frames and fouls as "1/3" and "F2", without them; only a line that
    still does not fit is cut, at a piece (a name too long, within itself), with "…". With
    `keep_score`, a line that cannot keep the frames and fouls is None instead. `start`: the
    first of those forms to try."""
    return _line(_forms(p, info, mono), width, keep_score, start)


def _line(forms: list[list[tuple]], width: int, keep_score: bool,
          start: int = 0) -> list[tuple] | None:
    """`player_line` from its forms (`_forms`)."""
    k = _first_fit(forms, width, keep_score, start)
    if k is not None:
        return forms[k]
    if keep_score:
        return None
    out, used = [], 0
    for t, fg, bg in forms[-1]:
        if used + len(t) > width - 1:
            if not out:  # a name too long for the line: as much of it as fits
                out.append((t[:max(width - 1, 0)], fg, bg))
            out.append(("…", DIM_TEXT_C.rgb, BACKDROP_C.rgb))
            break
        out.append((t, fg, bg))
        used += len(t)
    return out


def _first_fit(forms: list[list[tuple]], width: int, keep_score: bool,
               start: int = 0) -> int | None:
    """The first of `forms` from `start` on that fits `width` (with `keep_score`, of the
    three that keep the frames and fouls), or None."""
    for k in range(start, 3 if keep_score else len(forms)):
        if sum(len(t) for t, _, _ in forms[k]) <= width:
            return k
    return None


def _forms(p: PlayerLine, info: PanelInfo, mono: bool) -> list[list[tuple]]:
    """`player_line`'s forms of a player's line, the longest first."""
    name = [(("▶ " if p.turn else "  ") + p.name, TURN_C if p.turn else TEXT_C.rgb,
             BACKDROP_C.rgb)]
    todo = ball_tokens(info.ids, p.balls, mono, info.theme)
    # Every ball of the group in its place, those down dim: a ball pocketed does not move
    # the others along.
    mine = dict(zip(p.balls, todo, strict=True))
    every = [mine.get(k) or (f"{info.ids[k]:>2}", DIM_TEXT_C.rgb, BACKDROP_C.rgb)
             for k in sorted(p.balls + p.down)]
    long = [x for x in (p.group, p.score and f"frames {p.score}", p.fouls and f"fouls {p.fouls}")
            if x]
    short = [x for x in (p.score, p.fouls and f"F{p.fouls}") if x]

    def build(extra, toks, gap):
        out = list(name)
        if extra:
            out.append((gap + " · ".join(extra), DIM_TEXT_C.rgb, BACKDROP_C.rgb))
        for t in toks:
            out += [(" ", TEXT_C.rgb, BACKDROP_C.rgb), t]
        return out

    # In mono the short forms give plain numbers: 1-7 and 9-15 tell the groups apart too.
    plain = todo if not mono else [(f"{info.ids[k]:>2}", None, None) for k in p.balls]
    return [build(long, every, "  "), build(long, todo, " "), build(short, plain, " "),
            build([], plain, " ")]


def _put_line(cells, r: int, c: int, pieces: list[tuple]) -> int:
    for text, fg, bg in pieces:
        put_text(cells, r, c, text, fg, bg)
        c += len(text)
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


def widget_fits(lay: Layout, block) -> bool:
    """Whether a bottom panel shows a widget of these cells (else its words go in the
    status): it must leave the text TEXT_MIN_COLS columns and fit the panel's height. A side
    panel shows it below the status."""
    _, _, ncols, nrows = lay.panel_rect
    h, w = block[0].shape
    if lay.panel == "side":
        return w <= ncols - 2 and nrows >= SIDE_WIDGET_ROWS
    return _room(ncols - 2, nrows, block)


def _room(width: int, nrows: int, block) -> bool:
    h, w = block[0].shape
    return width - w - 1 >= TEXT_MIN_COLS and h <= nrows


def _placed(width: int, nrows: int, blocks) -> tuple[list[tuple[object, int]], int]:
    """The widgets that take the right end of a bottom panel `width` wide (those that fit),
    each with its column from the panel's left, and the columns left to text, less the
    blank columns before them."""
    right, placed = width, []
    for block, _where in blocks:
        if _room(right, nrows, block):
            right -= block[0].shape[1] + 1
            placed.append((block, right))
    # Two blank columns before a widget: with one, a line cut to fit reads on into the
    # spin face's words ("... hit no top 0.0").
    return placed, right - (WIDGET_GAP if placed else 1)


def _bottom(cells, c0: int, r0: int, width: int, nrows: int, info: PanelInfo, mono) -> None:
    # Widgets (spin face, power meter) take the right end; text gets the rest.
    placed, w = _placed(width, nrows, info.widgets)
    for block, col in placed:
        _paste(cells, block, r0, c0 + col)
    r = r0
    players = info.players[:2]
    # The players share the width left by the most widgets the match shows, whichever are
    # up now: the second player's name stays put from ball in hand to aim to charge.
    half = min(w, _placed(width, nrows, info.most_widgets or info.widgets)[1]) // 2
    keep = nrows >= 5
    forms = [_forms(p, info, mono) for p in players]
    # Where one line has no room for its balls down, the other leaves them out too (the
    # rest of each line is said as shortly as it needs).
    start = 0 if all(_first_fit(f, half - 1, keep) == 0 for f in forms) else 1
    shared = [_line(f, half - 1, keep, start) for f in forms]
    if len(players) > 1 and all(x is not None for x in shared):
        # Both players on one row when they fit whole (in short panels always: the status
        # keeps its rows).
        _put_line(cells, r, c0, shared[0])
        _put_line(cells, r, c0 + half, shared[1])
        r += 1
    else:
        for p in players:
            _put_line(cells, r, c0, player_line(p, info, mono, w))
            r += 1
    room = r0 + nrows - 1 - r
    # What to do now and a row for each verdict and warning (the first whole, where several
    # compete) are never lost for the keys' line: where they do not fit, that row is theirs
    # too (H still opens the help).
    hint = status_rows_needed(info.status, w) <= room
    for s, tone in fit_status(info.status, room if hint else room + 1, w):
        put_text(cells, r, c0, s, _tone(tone), BACKDROP_C.rgb)
        r += 1
    if info.legend and r < r0 + nrows - 1:  # a row to spare: which colour is which number
        pieces = [("balls", DIM_TEXT_C.rgb, BACKDROP_C.rgb)]
        for t in ball_tokens(info.ids, info.legend, mono, info.theme):
            pieces += [(" ", TEXT_C.rgb, BACKDROP_C.rgb), t]
        if sum(len(t) for t, _, _ in pieces) <= w:
            _put_line(cells, r, c0, pieces)
    if hint:  # the whole width where no widget takes the right end
        put_text(cells, r0 + nrows - 1, c0, _fit_help(info, w if placed else width),
                 DIM_TEXT_C.rgb, BACKDROP_C.rgb)


def _side(cells, c0: int, r0: int, width: int, nrows: int, info: PanelInfo, mono) -> None:
    r = r0
    end = r0 + nrows
    put_text(cells, r, c0, info.title[:width], TEXT_C.rgb, BACKDROP_C.rgb)
    r += 2
    for p in info.players:
        bare = PlayerLine(p.name, p.group, [], [], p.score, p.turn, p.fouls)
        _put_line(cells, r, c0, player_line(bare, info, mono, width))
        r += 1
        if p.balls or p.down:
            balls = PlayerLine("", "", p.balls, p.down)
            _put_line(cells, r, c0, player_line(balls, info, mono, width)[1:])
            r += 1
        r += 1
    for s, tone in fit_status(info.status, end - 1 - r, width):
        put_text(cells, r, c0, s, _tone(tone), BACKDROP_C.rgb)
        r += 1
    r += 1
    for block, _where in info.widgets:
        if r + block[0].shape[0] < end - 1 and block[0].shape[1] <= width:
            _paste(cells, block, r, c0)
            r += block[0].shape[0] + 1
    for s in _wrap(fit_hint(info.help, 3 * width - 6), width)[::-1]:
        end -= 1
        if end <= r:
            break
        put_text(cells, end, c0, s, DIM_TEXT_C.rgb, BACKDROP_C.rgb)


SPARE = 9  # a key help part of this rank shows only where every part fits in its long form


def fit_hint(parts: Sequence[tuple], width: int) -> str:
    """The key help for a line of `width` cells: every part in its long form if they fit
    (two spaces apart, else one), then in each shorter form in turn (a part gives one to
    three: long, short, tight), then without the highest ranks, one rank at a time. Parts
    are never cut; only the rank-0 parts' tightest forms, should even they not fit, are cut
    at the end. Parts of rank SPARE are the first to go: they never shorten the others."""
    everything = [((t,) if isinstance(t, str) else tuple(t), r) for t, r in parts]
    if any(r >= SPARE for _, r in everything):
        for sep in ("  ", " "):
            line = sep.join(f[0] for f, _ in everything)
            if len(line) <= width:
                return line
    forms = [(f, r) for f, r in everything if r < SPARE]
    limits = [math.inf, *sorted({r for _, r in forms if r > 0}, reverse=True)]
    depth = max((len(f) for f, _ in forms), default=1)
    for limit in limits:
        for v in range(depth):
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


def _box_body(cols: int, lines: Sequence[str], title: str, wrap: bool) -> tuple[int, list]:
    width = min(cols - 2, max([len(s) for s in lines] + [len(title) + 4]) + 4)
    room = width - 4
    body = []
    for s in lines:
        if len(s) <= room:
            body.append(s)
        else:
            body += _wrap(s, room) if wrap else [s[:room - 1] + "…"]
    return width, body


def box_clear_of(cells, lines: Sequence[str], keep: tuple[int, int, int, int],
                 title: str = "", wrap: bool = True,
                 within: tuple[int, int] | None = None) -> tuple[int, int] | None:
    """Where (top row, left column) a box of these lines goes so that it leaves the cells
    `keep` (col, row, cols, rows: the cue ball and the balls about it) in view: in the
    middle if it does, else the nearest place to the middle that does, inside the first
    `within` (cols, rows) of the screen if given; None where no place does (then it goes
    in the middle)."""
    rows, cols = cells[0].shape
    width, body = _box_body(cols, lines, title, wrap)
    height = min(rows, len(body) + 2)
    kc, kr, kw, kh = keep
    mid_top, mid_left = max(0, (rows - height) // 2), max(0, (cols - width) // 2)
    best = None
    most_cols, most_rows = within or (cols, rows)
    for top in range(0, min(rows, most_rows) - height + 1):
        for left in range(0, min(cols, most_cols) - width + 1):
            clear = (top + height <= kr or kr + kh <= top or left + width <= kc
                     or kc + kw <= left)
            far = abs(top - mid_top) + abs(left - mid_left) / 2  # cells are tall
            if clear and (best is None or far < best[0]):
                best = (far, top, left)
    return None if best is None else best[1:]


def draw_box(cells, lines: Sequence[str], title: str = "", tone: str = "plain",
             wrap: bool = True, at: tuple[int, int] | None = None) -> None:
    """A framed box of text in the middle of the screen (help, pause, questions), or with
    its top left corner `at` (row, column). Lines too long for the screen are wrapped, or
    (wrap=False, for columns) cut with an ellipsis."""
    chars, fg, bg = cells
    rows, cols = chars.shape
    width, body = _box_body(cols, lines, title, wrap)
    height = min(rows, len(body) + 2)
    top, left = max(0, (rows - height) // 2), max(0, (cols - width) // 2)
    if at is not None:
        top, left = at
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


def draw_ball_list(cells, lay: Layout, ids: Sequence[str], state=None, title: str = "termpool",
                   mono: bool = False) -> None:
    """The panel of a scene on its own: a title, then the balls on the table and the balls
    pocketed (state: the engine's codes, or None for all on the table)."""
    col, row, ncols, nrows = lay.panel_rect
    if ncols <= 2 or nrows <= 0:
        return
    c0, width = col + 1, ncols - 2
    st = None if state is None else np.asarray(state).reshape(-1)
    on = [k for k in range(len(ids)) if st is None or st[k] != POCKETED]
    on_set = set(on)
    gone = [k for k in range(len(ids)) if k not in on_set]
    r = row
    put_text(cells, r, c0, title[:width], TEXT_C.rgb, BACKDROP_C.rgb)
    r += 1
    for label, which in (("on the table", on), ("pocketed", gone)):
        if not which or r >= row + nrows:
            continue
        put_text(cells, r, c0, label[:width], DIM_TEXT_C.rgb, BACKDROP_C.rgb)
        r += 1
        c = c0
        for text, fg, bg in ball_tokens(ids, which, mono):
            if c + len(text) > c0 + width:
                r, c = r + 1, c0
            if r >= row + nrows:
                break
            put_text(cells, r, c, text, fg, bg)
            c += len(text) + 1
        r += 1


def message_cells(cols: int, rows: int, lines: Sequence[str], mono: bool = False):
    """Blank cells with lines of text centred: the 'window too small' screen."""
    chars = np.full((rows, cols), " ", dtype="<U1")
    fg = bg = None
    if not mono:
        fg = np.zeros((rows, cols, 3), dtype=np.uint8)
        bg = np.zeros((rows, cols, 3), dtype=np.uint8)
        bg[...] = BACKDROP_C.rgb
    cells = (chars, fg, bg)
    top = max(0, (rows - len(lines)) // 2)
    for k, line in enumerate(lines):
        put_text(cells, top + k, max(0, (cols - len(line)) // 2), line, TEXT_C.rgb,
                 BACKDROP_C.rgb)
    return cells


def too_small_lines(cols: int, rows: int) -> list[str]:
    """What a window too small for the game says, in the longest words that fit it (whole
    down to 10x2)."""
    need, now = f"{MIN_COLS}x{MIN_ROWS}", f"{cols}x{rows}"
    forms = [["make the window at least", f"{need} (now {now})"],
             ["window too small:", f"need {need}, now {now}"],
             ["too small:", f"need {need}", f"now {now}"],
             [f"need {need}", f"now {now}"]]
    for lines in forms:
        if len(lines) <= rows and max(len(s) for s in lines) <= cols:
            return lines
    return [s[:cols] for s in forms[-1][:max(rows, 1)]]
