"""Table geometry: cushion noses as line segments, jaw tips as points, pockets as holes.

Coordinates: x along the length from the head rail, y across, origin at the corner of the
playing area (the cushion noses). Left means larger y, as seen from the head end.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

PRESETS = {"7ft": (1.981, 0.991), "8ft": (2.235, 1.118), "9ft": (2.54, 1.27)}
POCKET_NAMES = ("head_right", "head_left", "side_right", "side_left", "foot_right", "foot_left")


@dataclass
class Table:
    length: float = 2.54
    width: float = 1.27
    pockets: str = "standard"  # or "none"
    corner_mouth: float = 0.116  # between the cushion noses (4.5-4.625 in)
    side_mouth: float = 0.129  # 5-5.125 in
    corner_jaw_angle: float = 142.0  # degrees between rail nose and jaw face
    side_jaw_angle: float = 104.0
    jaw_length: float = 0.05
    corner_hole_radius: float = 0.06
    side_hole_radius: float = 0.065
    hole_depth: float = 0.005  # how far behind the mouth line the hole's edge starts
    # Built geometry (filled by __post_init__).
    seg_a: np.ndarray = field(init=False, repr=False)
    seg_b: np.ndarray = field(init=False, repr=False)
    seg_n: np.ndarray = field(init=False, repr=False)
    seg_kind: list = field(init=False, repr=False)
    points: np.ndarray = field(init=False, repr=False)
    hole_c: np.ndarray = field(init=False, repr=False)
    hole_r: np.ndarray = field(init=False, repr=False)
    hole_names: tuple = field(init=False, repr=False)

    @classmethod
    def preset(cls, name: str, **over) -> Table:
        if name not in PRESETS:
            raise ValueError(f"table: unknown preset '{name}' (use 7ft, 8ft or 9ft)")
        length, width = PRESETS[name]
        return cls(length=length, width=width, **over)

    def __post_init__(self) -> None:
        if self.pockets not in ("standard", "none"):
            raise ValueError("table.pockets: must be 'standard' or 'none'")
        if self.pockets == "none":
            self._build_plain()
        else:
            self._build_pockets()

    @property
    def head_spot(self) -> tuple[float, float]:
        return (self.length / 4, self.width / 2)

    @property
    def foot_spot(self) -> tuple[float, float]:
        return (3 * self.length / 4, self.width / 2)

    def _finish(self, segs, kinds, points, holes, names) -> None:
        centre = np.array([self.length / 2, self.width / 2])
        a = np.array([s[0] for s in segs], float)
        b = np.array([s[1] for s in segs], float)
        d = b - a
        n = np.stack([-d[:, 1], d[:, 0]], axis=1)
        n /= np.linalg.norm(n, axis=1)[:, None]
        ref = np.array([s[2] if s[2] is not None else centre for s in segs], float)
        flip = np.einsum("ij,ij->i", ref - a, n) < 0
        n[flip] *= -1
        self.seg_a, self.seg_b, self.seg_n, self.seg_kind = a, b, n, kinds
        self.points = np.array(points, float).reshape(-1, 2)
        self.hole_c = np.array([h[0] for h in holes], float).reshape(-1, 2)
        self.hole_r = np.array([h[1] for h in holes], float)
        self.hole_names = tuple(names)

    def _build_plain(self) -> None:
        L, W = self.length, self.width
        corners = [(0, 0), (L, 0), (L, W), (0, W)]
        segs = [(corners[k], corners[(k + 1) % 4], None) for k in range(4)]
        self._finish(segs, ["rail"] * 4, [], [], [])

    def _build_pockets(self) -> None:
        L, W = self.length, self.width
        a = self.corner_mouth / math.sqrt(2)
        hs = self.side_mouth / 2
        turn_c = math.radians(180 - self.corner_jaw_angle)
        turn_s = math.radians(180 - self.side_jaw_angle)
        segs, kinds, points, holes, names = [], [], [], [], []

        def jaw(tip, along, out, turn, other):
            # The jaw leaves the rail nose at `tip`, turned away from the rail towards `out`.
            d = math.cos(turn) * np.asarray(along) + math.sin(turn) * np.asarray(out)
            segs.append((tip, tuple(np.asarray(tip) + self.jaw_length * d), other))
            kinds.append("jaw")
            points.append(tip)

        # Corner pockets: (corner, unit vectors along rail 1 and rail 2), in POCKET_NAMES order.
        corner_defs = {
            "head_right": ((0.0, 0.0), (1, 0), (0, 1)),
            "head_left": ((0.0, W), (1, 0), (0, -1)),
            "foot_right": ((L, 0.0), (-1, 0), (0, 1)),
            "foot_left": ((L, W), (-1, 0), (0, -1)),
        }
        side_defs = {"side_right": ((L / 2, 0.0), (0, -1)), "side_left": ((L / 2, W), (0, 1))}
        for name in POCKET_NAMES:
            if name in corner_defs:
                c, e1, e2 = (np.array(v, float) for v in corner_defs[name])
                t1, t2 = c + a * e1, c + a * e2
                jaw(tuple(t1), -e1, -e2, turn_c, tuple(t2))
                jaw(tuple(t2), -e2, -e1, turn_c, tuple(t1))
                inward = (e1 + e2) / math.sqrt(2)
                mid = (t1 + t2) / 2
                r = self.corner_hole_radius
            else:
                c, out = (np.array(v, float) for v in side_defs[name])
                e = np.array([1.0, 0.0])
                t1, t2 = c + hs * e, c - hs * e
                jaw(tuple(t1), -e, out, turn_s, tuple(t2))
                jaw(tuple(t2), e, out, turn_s, tuple(t1))
                inward = -out
                mid = c
                r = self.side_hole_radius
            holes.append((tuple(mid - (self.hole_depth + r) * inward), r))
            names.append(name)
        # Rail noses between the jaw tips.
        rails = [
            ((a, 0.0), (L / 2 - hs, 0.0)),
            ((L / 2 + hs, 0.0), (L - a, 0.0)),
            ((a, W), (L / 2 - hs, W)),
            ((L / 2 + hs, W), (L - a, W)),
            ((0.0, a), (0.0, W - a)),
            ((L, a), (L, W - a)),
        ]
        for p, q in rails:
            segs.append((p, q, None))
            kinds.append("rail")
        self._finish(segs, kinds, points, holes, names)

    def channels(self) -> list[np.ndarray]:
        """Each pocket's channel, the polygon between its jaws: from one jaw tip along its
        jaw to the jaw's end, across to the other jaw's end and back to its tip (where the
        jaws cross, only up to the crossing). Beyond the cushion noses a ball is on the table
        only here."""
        jaws = [k for k, kind in enumerate(self.seg_kind) if kind == "jaw"]
        out = []
        for a, b in zip(jaws[0::2], jaws[1::2], strict=True):
            t1, e1, t2, e2 = self.seg_a[a], self.seg_b[a], self.seg_a[b], self.seg_b[b]
            x = _crossing(t1, e1, t2, e2)
            out.append(np.array([t1, e1, e2, t2] if x is None else [t1, x, t2]))
        return out

    def inside(self, x: float, y: float, r: float) -> bool:
        """True when a ball of radius r at (x, y) lies within the cushion noses."""
        return r <= x <= self.length - r and r <= y <= self.width - r

    def on_bed(self, x: float, y: float, r: float, tol: float = 1e-6) -> bool:
        """True when a ball of radius r at (x, y) is in play: not over a hole, and within the
        cushion noses, or in a pocket's mouth or between its jaws (a ball can stop there, past
        the line of the rail noses) clear of the rails, jaws and jaw tips by `tol`."""
        if not (math.isfinite(x) and math.isfinite(y)):
            return False
        p = np.array([x, y], float)
        if (np.hypot(*(self.hole_c - p).T) <= self.hole_r).any():
            return False  # over a hole (a corner hole may reach past the rail lines): pocketed
        if self.inside(x, y, r):
            return True
        if not self.hole_r.size:
            return False
        if not (0 <= x <= self.length and 0 <= y <= self.width) and not any(
                _within(p, c) for c in self.channels()):
            return False  # past the rail lines but not between a pocket's jaws: off the slate
        d = self.seg_b - self.seg_a
        rel = p - self.seg_a
        t = (rel * d).sum(axis=1) / (d * d).sum(axis=1)
        beside = (t >= 0) & (t <= 1)
        if (beside & ((rel * self.seg_n).sum(axis=1) < r - tol)).any():
            return False  # behind or into a rail or jaw
        near = self.seg_a + np.clip(t, 0, 1)[:, None] * d
        gap = min(np.hypot(*(near - p).T).min(), np.hypot(*(self.points - p).T).min())
        return bool(gap >= r - tol)


def _crossing(p1: np.ndarray, p2: np.ndarray, q1: np.ndarray, q2: np.ndarray):
    """Where segments p1p2 and q1q2 cross, or None."""
    d, e, w = p2 - p1, q2 - q1, q1 - p1
    den = d[0] * e[1] - d[1] * e[0]
    if den == 0:
        return None
    s = (w[0] * e[1] - w[1] * e[0]) / den
    u = (w[0] * d[1] - w[1] * d[0]) / den
    return p1 + s * d if 0 <= s <= 1 and 0 <= u <= 1 else None


def _within(p: np.ndarray, poly: np.ndarray) -> bool:
    """Whether point p lies within the simple polygon poly (the even-odd rule)."""
    x, y = p
    inside = False
    for k in range(len(poly)):
        (x1, y1), (x2, y2) = poly[k], poly[k - 1]
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside
