"""Where balls go between shots: racks, re-spots and ball-in-hand placement (pure functions).

Positions are (x, y) in metres in the table's frame (x from the head rail, y across). Nothing
here simulates: these are the table-side chores of a referee.
"""

from __future__ import annotations

import math

import numpy as np

from termpool.physics.params import BALL_RADIUS
from termpool.physics.table import Table
from termpool.rules.common import SOLIDS, STRIPES
from termpool.rules.words import KITCHEN, RECORD, Voice
from termpool.scene import RACK_ROWS, rack

# Balls closer than this overlap; a little slack so balls set exactly touching (a rack, a
# re-spot against a ball) are not refused for a rounding error.
TOUCH_TOL = 1e-9
MODE_RACK = {"8ball": "8ball", "9ball": "9ball", "practice": "8ball"}


def rack_slots(kind: str, table: Table, radius: float = BALL_RADIUS) -> list[list[tuple]]:
    """The rack's ball positions by row (apex on the foot spot first), as in `scene.rack`."""
    placed = {b["id"]: (b["x"], b["y"]) for b in rack(kind, table, radius)}
    return [[placed[bid] for bid in row] for row in RACK_ROWS[kind]]


def rack_balls(mode: str, table: Table, rng: np.random.Generator,
               radius: float = BALL_RADIUS) -> dict[str, tuple[float, float]]:
    """A fresh rack for `mode`: ball id -> position, the cue ball on the head spot.

    8-ball (and practice, a full 15-ball rack), WPA: the 8 in the centre of the third row, one
    solid and one stripe in the two back corners (which corner gets which is random too), the
    other twelve at random. 9-ball: the 1 at the apex on the foot spot, the 9 in the centre,
    the others at random. Every random choice comes from `rng`, so a seed gives one rack.
    """
    kind = MODE_RACK[mode]
    rows = rack_slots(kind, table, radius)
    out: dict[str, tuple[float, float]] = {"cue": table.head_spot}
    if kind == "8ball":
        solids, stripes = list(SOLIDS), list(STRIPES)
        solid = solids.pop(int(rng.integers(len(solids))))
        stripe = stripes.pop(int(rng.integers(len(stripes))))
        back = (solid, stripe) if rng.integers(2) == 0 else (stripe, solid)
        fixed = {(2, 1): "8", (4, 0): back[0], (4, 4): back[1]}
        rest = solids + stripes
    else:
        fixed = {(0, 0): "1", (2, 1): "9"}
        rest = [str(n) for n in range(2, 9)]
    free = [(k, j) for k, row in enumerate(rows) for j in range(len(row)) if (k, j) not in fixed]
    order = rng.permutation(len(rest))
    for slot, n in zip(free, order, strict=True):
        fixed[slot] = rest[int(n)]
    for (k, j), bid in fixed.items():
        out[bid] = rows[k][j]
    return out


def free_on_string(table: Table, x0: float, r: float, others: np.ndarray,
                   others_r: np.ndarray, forward: bool = True) -> tuple[float, float] | None:
    """The free point on the long string (y = W/2) nearest to x0 in one direction, for a ball
    of radius r among balls at `others` (M, 2) of radii `others_r` (M,).

    Searched first from x0 towards the foot rail (`forward`, larger x) or the head rail, then
    the other way; touching a ball is allowed. None when the string is full.
    """
    yc = table.width / 2
    lo, hi = r, table.length - r
    blocked = []
    for (bx, by), br in zip(np.asarray(others, float).reshape(-1, 2), np.ravel(others_r),
                            strict=True):
        s, dy = r + br, abs(by - yc)
        if dy < s:
            h = math.sqrt(s * s - dy * dy)
            blocked.append((bx - h, bx + h))

    def free(x: float) -> bool:
        return lo <= x <= hi and all(not (a < x < b) for a, b in blocked)

    ends = [x0, lo, hi, *(a for a, _ in blocked), *(b for _, b in blocked)]
    ahead = sorted(x for x in ends if (x >= x0 if forward else x <= x0))
    behind = sorted(x for x in ends if (x <= x0 if forward else x >= x0))
    if forward:
        behind.reverse()
    else:
        ahead.reverse()
    for x in ahead + behind:
        if free(x):
            return (x, yc)
    return None


def respot_point(table: Table, r: float, others: np.ndarray,
                 others_r: np.ndarray) -> tuple[float, float]:
    """Where a re-spotted object ball goes: the foot spot, or if it is taken the nearest free
    point behind it on the long string (towards the foot rail), else in front of it."""
    p = free_on_string(table, table.foot_spot[0], r, others, others_r, forward=True)
    if p is None:
        raise ValueError("respot: no free point on the long string")
    return p


def cue_return_point(table: Table, r: float, others: np.ndarray,
                     others_r: np.ndarray) -> tuple[float, float]:
    """Where the cue ball waits after a scratch, for the incoming player to place: the head
    spot, or if it is taken the nearest free point behind it (towards the head rail)."""
    p = free_on_string(table, table.head_spot[0], r, others, others_r, forward=False)
    if p is None:
        raise ValueError("cue ball: no free point on the long string")
    return p


def mouth_lines(table: Table) -> list[tuple[str, np.ndarray, np.ndarray]]:
    """Per pocket: (name, a point of its mouth line, the line's unit normal into the table).

    The mouth joins the pocket's two jaw tips (the table stores two tips per pocket, in the
    order of `hole_names`)."""
    out = []
    centre = np.array([table.length / 2, table.width / 2])
    for k, name in enumerate(table.hole_names):
        p, q = table.points[2 * k], table.points[2 * k + 1]
        d = q - p
        n = np.array([-d[1], d[0]]) / math.hypot(d[0], d[1])
        if np.dot(centre - p, n) < 0:
            n = -n
        out.append((name, p, n))
    return out


def head_string(table: Table) -> float:
    """Where the head string crosses the table (x, m): through the head spot, a quarter of the
    length from the head rail. The kitchen, where a break is taken from, is behind it."""
    return table.head_spot[0]


def in_area(table: Table, x, area: str):
    """Whether centres at x (a number or an array) lie in `area`: anywhere, or in the kitchen
    (x at most the head string's). The area part of the placement rule."""
    return x <= head_string(table) if area == "kitchen" else np.full(np.shape(x), True)[()]


def placement_error(table: Table, x: float, y: float, r: float, area: str,
                    others: dict[str, tuple[float, float, float]],
                    v: Voice = RECORD) -> str | None:
    """Why a cue ball of radius r cannot be placed at (x, y) with ball in hand in `area`
    ("anywhere" or "kitchen"), in words (a pocket named in the voice `v`); None when it can.
    `others` maps the id of every other ball on the table to (x, y, radius)."""
    if isinstance(x, bool) or isinstance(y, bool):
        return "the position must be two numbers (x, y)"
    try:
        x, y = float(x), float(y)
    except (TypeError, ValueError):
        return "the position must be two numbers (x, y)"
    if not (math.isfinite(x) and math.isfinite(y)):
        return "the position must be finite"
    if not table.inside(x, y, r):
        return (f"off the table: the centre must lie within [{r:.3f}, {table.length - r:.3f}] x "
                f"[{r:.3f}, {table.width - r:.3f}] m")
    if not in_area(table, x, area):
        return (f"not in the kitchen: {KITCHEN} the centre must be at "
                f"x <= {head_string(table):.3f} m")
    for name, p, n in mouth_lines(table):
        if float(np.dot(np.array([x, y]) - p, n)) < r - TOUCH_TOL:
            return f"in the mouth of the {v.pocket(name)} pocket"
    for bid, (bx, by, br) in others.items():
        if math.hypot(x - bx, y - by) < r + br - TOUCH_TOL:
            return f"overlaps {v.ball(bid)}"
    return None


def spots_ok(table: Table, xy: np.ndarray, r: float, area: str, others: np.ndarray,
             others_r: np.ndarray, margin: float = 0.0) -> np.ndarray:
    """`placement_error`'s rule for many spots at once: which of xy (M, 2) a cue ball of radius
    r may be placed on with ball in hand in `area`, among balls at `others` (K, 2) of radii
    `others_r` (K,). With `margin` the spot must also stay that far inside the cushion noses
    and the pocket mouths, and twice that clear of every ball (0: the rule itself)."""
    xy = np.asarray(xy, float).reshape(-1, 2)
    x, y = xy[:, 0], xy[:, 1]
    ok = (x >= r + margin) & (x <= table.length - r - margin)
    ok &= (y >= r + margin) & (y <= table.width - r - margin)
    ok &= in_area(table, x, area)
    for _, p, n in mouth_lines(table):
        ok &= (xy - p) @ n >= r - TOUCH_TOL + margin
    others = np.asarray(others, float).reshape(-1, 2)
    if len(others):
        d = np.linalg.norm(xy[:, None] - others[None], axis=-1)
        ok &= (d >= r + np.ravel(others_r)[None] + 2 * margin - TOUCH_TOL).all(axis=1)
    return ok
