"""Slow contacts: touching balls and cushions settled together, without chatter.

Below `v_inelastic` a contact is perfectly inelastic. An isolated pair is settled at once;
a contact inside a cluster of touching balls and cushions is solved with the whole cluster as
one complementarity problem (cluster.py), on velocities and then on positions. A mixin of
Engine: it works on the engine's arrays.
"""

from __future__ import annotations

import math

import numpy as np

from termpool.physics.cluster import Rows, solve_inelastic
from termpool.physics.joined import push
from termpool.physics.motion import Col, snap
from termpool.physics.roots import A_MIN, V_MIN
from termpool.physics.state import CLUSTER_GAP, EPS_U, POCKETED
from termpool.physics.vec import dots
from termpool.physics.vec import norm as _norm
from termpool.physics.vec import perp as _perp


class SlowContacts:
    def _approach(self, b, i) -> np.ndarray:
        """Speeds into the cushion, jaw or tip that balls (b, i) are about to meet (inf for
        a pocket's hole: never a slow contact)."""
        feat = self.features
        if b.size == 1:  # one ball (the usual case), in plain floats
            bb, ib = int(b[0]), int(i[0])
            f = int(self.f_cush[bb, ib])
            if f >= feat.first_hole:
                return np.array([math.inf])
            row = self.balls.motion[bb, ib].tolist()
            d = float(self.tb[bb]) - row[Col.T0]
            vx, vy = row[Col.VX] + row[Col.AX] * d, row[Col.VY] + row[Col.AY] * d
            px = row[Col.PX] + (row[Col.VX] + 0.5 * row[Col.AX] * d) * d
            py = row[Col.PY] + (row[Col.VY] + 0.5 * row[Col.AY] * d) * d
            _, (nx, ny) = feat.contact_one(f, [px, py])
            return np.array([-(vx * nx + vy * ny)])
        p, v, _ = self.balls.eval(b, i, self.tb[b], spin=False)
        out = -(v * feat.normals(self.f_cush[b, i], p)).sum(axis=1)
        return np.where(self.f_cush[b, i] < feat.first_hole, out, np.inf)

    def _crowded(self, b, i) -> np.ndarray:
        """True for balls (b, i) that touch another ball or belong to a group."""
        k = np.arange(self.N)[None, :]
        p, _, _ = self.balls.eval(b[:, None], k, self.tb[b][:, None], spin=False)
        own = p[np.arange(len(b)), i]
        gap = _norm(p - own[:, None]) - self.radius[b] - self.radius[b, i][:, None]
        other = (self.state[b] != POCKETED) & (k != i[:, None])
        return (other & (gap < CLUSTER_GAP)).any(axis=1) | (self.group[b, i] >= 0)

    def _pressed_on(self, b, i) -> np.ndarray:
        """True for balls (b, i), just bounced slowly off a cushion feature, that do not
        leave it: still moving into it (a tiny slide completed into it), or neither moving
        off nor into it but accelerating into it."""
        p, v, _ = self.balls.eval(b, i, self.tb[b], spin=False)
        n = self.features.normals(self.f_cush[b, i], p)
        vn = (v * n).sum(axis=1)
        an = (self.balls.acc[b, i] * n).sum(axis=1)
        tip = self.f_cush[b, i] >= self.features.nseg
        bend = np.where(tip, ((v - vn[:, None] * n) ** 2).sum(axis=1) / self.rc[b, i], 0.0)
        return (vn < 0) | ((vn <= V_MIN) & (an + bend < -A_MIN))

    def _alone(self, b, i, j) -> np.ndarray:
        """True for pairs (b, i, j) that touch no third ball and no cushion."""
        N = self.N
        t = self.tb[b]
        k = np.arange(N)[None, :]
        p, _, _ = self.balls.eval(b[:, None], k, t[:, None], spin=False)  # (M, N, 2)
        R = self.radius[b]
        live = (self.state[b] != POCKETED) & (k != i[:, None]) & (k != j[:, None])
        crowded = np.zeros(len(b), dtype=bool)
        for x in (i, j):
            px = p[np.arange(len(b)), x]
            gap = _norm(p - px[:, None]) - R - R[np.arange(len(b)), x][:, None]
            crowded |= (live & (gap < CLUSTER_GAP)).any(axis=1)
            seg_gap, beside, tip_gap, _ = self.features.gaps(px, self.rc[b, x])
            crowded |= ((seg_gap < CLUSTER_GAP) & beside).any(axis=1)
            crowded |= (tip_gap < CLUSTER_GAP).any(axis=1)
        return ~crowded

    def _settle(self, b, i, j, pi, vi, wi, pj, vj, wj) -> np.ndarray:
        """Slow contact of an isolated pair, balls now at (pi, vi, wi) and (pj, vj, wj):
        perfectly inelastic along the normal, repeated with the slip completion of _set
        until the pair no longer closes. Returns which pairs it changed."""
        t = self.tb[b]
        ri, rj = self.radius[b, i], self.radius[b, j]
        mi, mj = self.mass[b, i], self.mass[b, j]
        d = pj - pi
        dist = _norm(d)
        n = d / dist[:, None]
        changed = ri + rj - dist > 0  # a sink to undo
        for _ in range(20):
            # Each pair stops as soon as it no longer closes, whatever the other tables do.
            closing = ((vi - vj) * n).sum(axis=1)
            live = closing > V_MIN
            if not live.any():
                break
            changed |= live
            jn = np.where(live, closing, 0.0) / (1.0 / mi + 1.0 / mj)
            vi = vi - (jn / mi)[:, None] * n
            vj = vj + (jn / mj)[:, None] * n
            _, vi, wi, _ = snap(self.physics, pi, vi, wi, ri, None, live, move=False)
            _, vj, wj, _ = snap(self.physics, pj, vj, wj, rj, None, live, move=False)
        self._part(b, i, j, t, pi, pj, vi, vj, wi, wj)
        return changed

    def _pressed(self, b, i, j) -> np.ndarray:
        """True for touching pairs (b, i, j) that, moving as now set, neither close nor part
        but accelerate into each other (as roots.first_contact finds them)."""
        t = np.concatenate([self.tb[b], self.tb[b]])
        p, v, _ = self.balls.eval(np.concatenate([b, b]), np.concatenate([i, j]), t, spin=False)
        n = len(b)
        a = self.balls.acc[b, j] - self.balls.acc[b, i]
        d, dv = p[n:] - p[:n], v[n:] - v[:n]
        r = _norm(d)
        pv = (d * dv).sum(axis=1)
        acc = ((dv * dv).sum(axis=1) + (d * a).sum(axis=1)) / r - pv * pv / r ** 3
        return (np.abs(pv) <= V_MIN * r) & (acc < -A_MIN)

    def _cluster(self, b: int, seeds: list[int], every: bool = False):
        """Resolve a slow contact together with every ball and cushion touching its cluster
        (with `every`, fast contacts too: the work bound's inelastic fallback)."""
        N, tab = self.N, self.table
        t = self.tb[b]
        k = np.arange(N)
        p, v, w = self.balls.eval(np.full(N, b), k, np.full(N, t))
        p0, v_in = p.copy(), v.copy()
        R, m = self.radius[b], self.mass[b]
        live = self.state[b] != POCKETED
        d = p[None, :, :] - p[:, None, :]
        dist = _norm(d)
        touch = (dist - (R[:, None] + R[None, :]) < CLUSTER_GAP) & live[:, None] & live[None, :]
        np.fill_diagonal(touch, False)
        # A contact that closes fast is a collision of its own, handled pair by pair (this is
        # what carries a cradle's wave down the row); only slow contacts join the cluster.
        closing = -((v[None, :, :] - v[:, None, :]) * d).sum(axis=2) / np.where(dist > 0, dist, 1)
        cap = np.inf if every else self.physics.v_inelastic
        touch &= closing <= cap
        near = touch.tolist()
        members = list(dict.fromkeys(seeds))
        seen = set(members)
        for a in members:  # grows while we walk it
            for c in range(N):
                if near[a][c] and c not in seen:
                    seen.add(c)
                    members.append(c)
        mem = np.array(members)
        # Contact rows: ball a, ball c (or -1: a cushion), normal pushing a away, gap.
        ia, ic = np.nonzero(np.triu(touch[np.ix_(mem, mem)]))
        a, c = mem[ia], mem[ic]
        ra, rc_, rn, rg = [a], [c], [-d[a, c] / dist[a, c][:, None]], [np.zeros(a.size)]
        rkind = [np.zeros(a.size, dtype=np.int64)]  # 0 ball, 1 rail or jaw, 2 jaw tip
        pm, rcm = p[mem], self.rc[b, mem]

        def cushion_rows(x, normals, gaps, kind):
            ra.append(mem[x])
            rc_.append(np.full(x.size, -1))
            rn.append(normals)
            rg.append(gaps)
            rkind.append(np.full(x.size, kind))

        seg_gap, beside, tip_gap, tip_dir = self.features.gaps(pm, rcm)
        slow = dots(v[mem], tab.seg_n) >= -cap
        x, f = np.nonzero((np.abs(seg_gap) < CLUSTER_GAP) & beside & slow)
        cushion_rows(x, tab.seg_n[f], seg_gap[x, f], 1)
        slow = (v[mem][:, None] * tip_dir).sum(axis=2) >= -cap
        x, f = np.nonzero((tip_gap < CLUSTER_GAP) & slow)
        cushion_rows(x, tip_dir[x, f], tip_gap[x, f], 2)
        ra, rc_, rn, rg, rkind = (np.concatenate(z) for z in (ra, rc_, rn, rg, rkind))
        nc = len(ra)
        J = Rows(ra, rc_, rn, N)  # u = J v: separating speed along each contact normal
        # A rolling ball given a small push slides for an instant and then rolls on with 5/7
        # of the push (the slip completion in _set): it answers as if 7/5 as heavy.
        slip = _norm(v + R[:, None] * _perp(w[:, :2]))
        snaps = (slip <= EPS_U) & (self.physics.mu_slide > 0)
        A = J.matrix(np.where(snaps, 5.0 / 7.0, 1.0) / m)
        inv_m = 1.0 / m
        for _ in range(20):
            u0 = J.speeds(v)
            if not (u0 < -V_MIN).any():
                break
            lam = solve_inelastic(A, u0)
            v = v + J.spread(lam, inv_m)
            # A push leaves a rolling ball with a tiny slip that is completed at once; do it
            # here so that the solve sees the velocities that result.
            _, v[mem], w[mem], _ = snap(self.physics, p[mem], v[mem], w[mem], R[mem], None,
                                                move=False)
        # Undo sub-micrometre sinks: the smallest mass-weighted moves that leave no contact
        # overlapping (the same complementarity problem, on positions), so a light ball
        # squeezed against a rail by a heavy one moves the heavy one back.
        ball = J.ball
        for _ in range(3):
            gaps = np.empty(nc)
            gaps[ball] = _norm(p[rc_[ball]] - p[ra[ball]]) - R[ra[ball]] - R[rc_[ball]]
            cush = ~ball
            gaps[cush] = rg[cush] + ((p[ra[cush]] - p0[ra[cush]]) * rn[cush]).sum(axis=1)
            if not (gaps < -1e-12).any():  # rounding is not an overlap
                break
            lam = solve_inelastic(J.matrix(inv_m), np.minimum(gaps, 0.0))
            p = p + J.spread(lam, inv_m)
        # Contacts that neither close nor part are resting: friction may press them together,
        # and then they carry a steady force (joined.py). Their curvature (balls rolling
        # round each other, a ball round a jaw tip) would part them of itself.
        rest = J.speeds(v) <= V_MIN
        bend = np.zeros(nc)
        rel = v[ra] - np.where(ball[:, None], v[np.maximum(rc_, 0)], 0.0)
        tang = rel - (rel * rn).sum(axis=1)[:, None] * rn
        reach = np.where(ball, R[ra] + R[np.maximum(rc_, 0)], self.rc[b, ra])
        curved = ball | (rkind == 2)
        bend[curved] = (tang[curved] ** 2).sum(axis=1) / reach[curved]
        self._join(b, mem, t, p, v, w, ra[rest], rc_[rest], rn[rest], bend[rest])
        # What the solves changed: velocities as the balls now start (a resting contact's
        # last rounding of speed taken out, a ball set at rest), and positions.
        row = self.balls.motion[b, mem]
        moved = (row[:, Col.V] != v_in[mem]).any(axis=1) | (row[:, Col.P] != p0[mem]).any(axis=1)
        return members, mem[moved].tolist()

    def _join(self, b: int, mem, t: float, p, v, w, ra, rc_, rn, bend) -> None:
        """Start the motion of balls `mem` of table b at time t from (p, v, w) (all N balls):
        balls in resting contacts (rows ra, rc_, rn, bend as in _cluster) move as a group
        held by the contacts' forces; the others move freely."""
        held = np.unique(np.concatenate([ra, rc_[rc_ >= 0]]))
        free = mem[~np.isin(mem, held)]
        self.group[b, mem] = -1
        if free.size:
            self.balls.set(np.full(free.size, b), free, np.full(free.size, t), p[free], v[free],
                      w[free])
        if held.size:
            where = {int(x): n for n, x in enumerate(held.tolist())}
            rows = [(where[int(x)], where.get(int(y), -1), n, bb)
                    for x, y, n, bb in zip(ra, rc_, rn, bend, strict=True)]
            vj, acc, alpha, state, duration, wj = push(
                self.physics, v[held], w[held], self.radius[b, held],
                self.mass[b, held], self.balls.spin_rate[b, held], rows)
            self.state[b, held] = state
            self.t_trans[b, held] = t + duration
            self.balls.motion[b, held, :Col.RATE] = np.concatenate(
                [np.full((held.size, 1), t), p[held], vj, acc, wj, alpha], axis=1)
            self.group[b, held] = int(held.min())
        self._ngroup[b] = int((self.group[b] >= 0).sum())
