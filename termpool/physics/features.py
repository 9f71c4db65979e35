"""A table's cushion features as the engine meets them: the rails and jaws (segments of the
cushion noses), the jaw tips (points) and the pocket holes, numbered in that order; a ball's
next feature is an index into them (`Engine.f_cush`).
"""

from __future__ import annotations

import math

import numpy as np

from termpool.physics.roots import first_line_contact, first_line_contact_one
from termpool.physics.table import Table
from termpool.physics.vec import dots, norm


class Features:
    """The features of `table`, with the geometry contact predictions and responses use."""

    def __init__(self, table: Table) -> None:
        self.table = table
        self.nseg, self.npt = len(table.seg_a), len(table.points)
        self.first_hole = self.nseg + self.npt  # features from here on are pocket holes
        seg_d = table.seg_b - table.seg_a
        self.seg_len = norm(seg_d)
        self.seg_dir = seg_d / self.seg_len[:, None]
        self.seg_off = (table.seg_a * table.seg_n).sum(axis=1)  # each line's offset along n
        self.seg_start = (table.seg_a * self.seg_dir).sum(axis=1)
        self.seg_lo = np.minimum(table.seg_a, table.seg_b)  # each segment's box
        self.seg_hi = np.maximum(table.seg_a, table.seg_b)
        # The segments' numbers `lines` reads, a row each (one gather a call): normal, direction,
        # offset, start, length, start point.
        self.seg_rows = np.concatenate([table.seg_n.T, self.seg_dir.T, self.seg_off[None],
                                        self.seg_start[None], self.seg_len[None], table.seg_a.T])
        # Jaw tips, then holes: met as circles (a ball's centre at reach rc of a tip, within
        # a hole's radius of its centre).
        self.circles = np.concatenate([table.points.reshape(-1, 2), table.hole_c.reshape(-1, 2)])
        self.circle_rows = self.circles.T.copy()  # (2, C): x, then y
        # Every feature's box (2, S + C), x then y: the segments', then the points themselves.
        self.box_lo = np.concatenate([self.seg_lo, self.circles]).T.copy()
        self.box_hi = np.concatenate([self.seg_hi, self.circles]).T.copy()
        # Plain-float forms for a few balls (lines_one, Schedule.predict_few).
        self.circle_list = self.circles.tolist()
        self.hole_c, self.hole_r = table.hole_c.tolist(), table.hole_r.tolist()
        self.lines1 = list(zip(table.seg_a.tolist(), self.seg_dir.tolist(),
                               self.seg_len.tolist(), table.seg_n.tolist(),
                               self.seg_off.tolist(), self.seg_start.tolist(), strict=True))

    def lines(self, q, rc, horizon, near=None, out=None) -> np.ndarray:
        """(M, S) first contact times of M balls, whose positions, velocities and
        accelerations are the planes q (6, M) (x, y, vx, vy, ax, ay), with the cushion
        segments; with `near` (M, S), only of the (ball, segment) pairs it marks (inf
        elsewhere: the caller knows those cannot meet). With `out`, a C-contiguous (M, W)
        array whose first S columns are inf, the times are written there and it is
        returned."""
        M, S = q.shape[1], self.nseg
        m, k = (np.ones((M, S), dtype=bool) if near is None else near).nonzero()
        px, py, vx, vy, ax, ay = q.take(m, axis=1)
        nx, ny, dx, dy, off, start, length, _, _ = g = self.seg_rows.take(k, axis=1)
        # (each dot product the two products added in the order `dots` adds them)
        s0 = (px * nx + py * ny) - off
        along0 = (px * dx + py * dy) - start
        beside = (along0 >= 0) & (along0 <= length)
        tl = first_line_contact(s0, vx * nx + vy * ny, ax * nx + ay * ny, rc.take(m),
                                horizon.take(m), beside)
        # The contact must fall on the segment itself; its ends are the jaw-tip points.
        # Worked out only where a time was found (few of the pairs), as `lines_one` does.
        f = (tl < np.inf).nonzero()[0]  # (never a nan)
        if out is None:
            out = np.full((M, S), np.inf)
        if f.size:
            t = tl.take(f)
            tt = t * t
            px, py, vx, vy, ax, ay = q.take(m.take(f), axis=1)
            _, _, dx, dy, _, _, length, ex, ey = g.take(f, axis=1)
            qx = (px + vx * t + 0.5 * ax * tt) - ex
            qy = (py + vy * t + 0.5 * ay * tt) - ey
            along = qx * dx + qy * dy
            on = ((along >= 0) & (along <= length)).nonzero()[0]
            out.ravel()[(m * out.shape[1] + k).take(f.take(on))] = t.take(on)
        return out

    def lines_few(self, p, v, a, rc, horizon, reach) -> np.ndarray:
        """`lines` for a few balls in plain floats (`lines_one`), bit-identical."""
        return np.array([self.lines_one(*args) for args in zip(
            p.tolist(), v.tolist(), a.tolist(), rc.tolist(), horizon.tolist(), reach.tolist(),
            strict=True)]).reshape(len(p), self.nseg)

    def lines_one(self, p: list, v: list, a: list, rc: float, horizon: float,
                  reach: float) -> list:
        """`lines` for one ball in plain floats, operation for operation (`dots` adds the
        two products in the same order), so the times are bit-identical. A ball whose centre
        is further from a cushion segment than its reach (travel in the window plus the nose
        distance, with a micrometre to spare) cannot meet it and skips it: the array path
        finds no contact there either."""
        out = [math.inf] * self.nseg
        far = reach + 1e-6
        p0, p1 = p
        for k, (ak, dk, length, nk, off, start) in enumerate(self.lines1):
            # The ball's distance from the segment is at least each of these.
            s0 = p0 * nk[0] + p1 * nk[1] - off
            along0 = p0 * dk[0] + p1 * dk[1] - start
            if s0 > far or -s0 > far or -along0 > far or along0 - length > far:
                continue
            beside = along0 >= 0 and along0 <= length
            tl = first_line_contact_one(s0, v[0] * nk[0] + v[1] * nk[1],
                                        a[0] * nk[0] + a[1] * nk[1], rc, horizon, beside)
            if tl < math.inf:
                # The contact must fall on the segment itself (as in `lines`).
                tt = tl * tl
                qx = (p0 + v[0] * tl + 0.5 * a[0] * tt) - ak[0]
                qy = (p1 + v[1] * tl + 0.5 * a[1] * tt) - ak[1]
                along = qx * dk[0] + qy * dk[1]
                if along >= 0 and along <= length:
                    out[k] = tl
        return out

    def names(self, f) -> list[str]:
        """Names of features by index (an array or a list): rail, jaw, tip, or the pocket's
        name."""
        tab, nseg, npt = self.table, self.nseg, self.npt
        names = []
        for fi in (f.tolist() if isinstance(f, np.ndarray) else f):
            if fi < nseg:
                names.append(tab.seg_kind[fi])
            elif fi < nseg + npt:
                names.append("tip")
            else:
                names.append(tab.hole_names[fi - nseg - npt])
        return names

    def normals(self, f, p) -> np.ndarray:
        """Unit normals (into the table) of rails, jaws or jaw tips f for balls at p: a rail's
        or jaw's, or from a jaw tip to the ball (not for pocket holes)."""
        nseg = self.nseg
        n = self.table.seg_n[np.minimum(f, nseg - 1)]
        tip = (f >= nseg) & (f < self.first_hole)
        if tip.any():
            d = p[tip] - self.table.points[f[tip] - nseg]
            n[tip] = d / norm(d)[:, None]
        return n

    def points(self, f) -> np.ndarray:
        """A point on each rail, jaw or jaw tip f: a segment's start, or the tip."""
        seg = (f < self.nseg)[:, None]
        tips = self.table.points
        return np.where(seg, self.table.seg_a[np.minimum(f, self.nseg - 1)],
                        tips[np.clip(f - self.nseg, 0, max(self.npt - 1, 0))]
                        if self.npt else 0.0)

    def contact_one(self, f: int, p: list) -> tuple[list, list]:
        """A point on rail, jaw or jaw tip f and its normal for a ball at p, in plain floats
        (`points` and `normals` bit for bit)."""
        if f < self.nseg:
            return self.table.seg_a[f].tolist(), self.table.seg_n[f].tolist()
        ref = self.table.points[f - self.nseg].tolist()
        d0, d1 = p[0] - ref[0], p[1] - ref[1]
        dist = float(np.hypot(d0, d1))
        return ref, [d0 / dist, d1 / dist]

    def gaps(self, p, rc):
        """Gaps of balls at p (M, 2) with contact reach rc (M,) to the cushion segments, with
        whether each ball is beside the segment, and to the jaw tips, with the direction from
        each tip: (seg_gap (M, S), beside (M, S), tip_gap (M, P), tip_dir (M, P, 2))."""
        tab = self.table
        seg_gap = dots(p, tab.seg_n) - self.seg_off - rc[:, None]
        along = dots(p, self.seg_dir) - self.seg_start
        beside = (along >= 0) & (along <= self.seg_len)
        dp = p[:, None] - tab.points[None]
        dd = norm(dp)
        return seg_gap, beside, dd - rc[:, None], dp / dd[..., None]
