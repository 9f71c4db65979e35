"""Slow contacts: touching balls and cushions settled together, without chatter.

Below `v_inelastic` a contact is perfectly inelastic. An isolated pair is settled at once;
a contact inside a cluster of touching balls and cushions is solved with the whole cluster as
one complementarity problem (cluster.py), on velocities and then on positions. A mixin of
Engine: it works on the engine's arrays.
"""

from __future__ import annotations

import numpy as np

from termpool.physics.cluster import solve_inelastic
from termpool.physics.roots import V_MIN
from termpool.physics.state import CLUSTER_GAP, EPS_U, POCKETED
from termpool.physics.state import norm as _norm
from termpool.physics.state import perp as _perp


class SlowContacts:
    def _squeezed(self, b, i) -> np.ndarray:
        """True for balls (b, i) about to bounce slowly off a cushion while touching a ball.

        Slowly means what it means for the bounce itself: the speed into the cushion is below
        v_inelastic (the ball may run fast along the rail). Such a bounce lifts the ball off
        the cushion, which would push it into the ball it touches; the cluster solve moves
        both instead.
        """
        t = self.tb[b]
        f = self.f_cush[b, i]
        nseg = self._nseg
        out = f < nseg + self._npt  # a pocket is never a squeeze
        k = np.arange(self.N)[None, :]
        p, v, _ = self._eval(b[:, None], k, t[:, None], spin=False)
        rows = np.arange(len(b))
        own, vel = p[rows, i], v[rows, i]
        gap = _norm(p - own[:, None]) - self.radius[b] - self.radius[b, i][:, None]
        other = (self.state[b] != POCKETED) & (k != i[:, None])
        out &= (other & (gap < CLUSTER_GAP)).any(axis=1)
        tab = self.table
        n = tab.seg_n[np.minimum(f, nseg - 1)]
        tip = (f >= nseg) & out
        if tip.any():
            d = own[tip] - tab.points[f[tip] - nseg]
            n[tip] = d / _norm(d)[:, None]
        return out & (-(vel * n).sum(axis=1) < self.physics.v_inelastic)

    def _cushion_gaps(self, p, rc):
        """Gaps of balls at p (M, 2) with contact reach rc (M,) to the cushion segments, with
        whether each ball is beside the segment, and to the jaw tips, with the direction from
        each tip: (seg_gap (M, S), beside (M, S), tip_gap (M, P), tip_dir (M, P, 2))."""
        tab = self.table
        seg_gap = p @ tab.seg_n.T - self._seg_off - rc[:, None]
        along = p @ self._seg_dir.T - self._seg_start
        beside = (along >= 0) & (along <= self._seg_len)
        dp = p[:, None] - tab.points[None]
        dd = _norm(dp)
        return seg_gap, beside, dd - rc[:, None], dp / dd[..., None]

    def _alone(self, b, i, j) -> np.ndarray:
        """True for pairs (b, i, j) that touch no third ball and no cushion."""
        N = self.N
        t = self.tb[b]
        k = np.arange(N)[None, :]
        p, _, _ = self._eval(b[:, None], k, t[:, None], spin=False)  # (M, N, 2)
        R = self.radius[b]
        live = (self.state[b] != POCKETED) & (k != i[:, None]) & (k != j[:, None])
        crowded = np.zeros(len(b), dtype=bool)
        for x in (i, j):
            px = p[np.arange(len(b)), x]
            gap = _norm(p - px[:, None]) - R - R[np.arange(len(b)), x][:, None]
            crowded |= (live & (gap < CLUSTER_GAP)).any(axis=1)
            seg_gap, beside, tip_gap, _ = self._cushion_gaps(px, self.rc[b, x])
            crowded |= ((seg_gap < CLUSTER_GAP) & beside).any(axis=1)
            crowded |= (tip_gap < CLUSTER_GAP).any(axis=1)
        return ~crowded

    def _settle(self, b, i, j, pi, vi, wi, pj, vj, wj) -> None:
        """Slow contact of an isolated pair, balls now at (pi, vi, wi) and (pj, vj, wj):
        perfectly inelastic along the normal, repeated with the slip completion of _set
        until the pair no longer closes."""
        t = self.tb[b]
        ri, rj = self.radius[b, i], self.radius[b, j]
        mi, mj = self.mass[b, i], self.mass[b, j]
        d = pj - pi
        dist = _norm(d)
        n = d / dist[:, None]
        for _ in range(20):
            # Each pair stops as soon as it no longer closes, whatever the other tables do.
            closing = ((vi - vj) * n).sum(axis=1)
            live = closing > V_MIN
            if not live.any():
                break
            jn = np.where(live, closing, 0.0) / (1.0 / mi + 1.0 / mj)
            vi = vi - (jn / mi)[:, None] * n
            vj = vj + (jn / mj)[:, None] * n
            _, vi, wi, _ = self._snap(pi, vi, wi, ri, None, live, move=False)
            _, vj, wj, _ = self._snap(pj, vj, wj, rj, None, live, move=False)
        self._part(b, i, j, t, pi, pj, vi, vj, wi, wj)

    def _cluster(self, b: int, seeds: list[int], every: bool = False):
        """Resolve a slow contact together with every ball and cushion touching its cluster
        (with `every`, fast contacts too: the work bound's inelastic fallback)."""
        N, tab = self.N, self.table
        t = self.tb[b]
        k = np.arange(N)
        p, v, w = self._eval(np.full(N, b), k, np.full(N, t))
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
        pm, rcm = p[mem], self.rc[b, mem]

        def cushion_rows(x, normals, gaps):
            ra.append(mem[x])
            rc_.append(np.full(x.size, -1))
            rn.append(normals)
            rg.append(gaps)

        seg_gap, beside, tip_gap, tip_dir = self._cushion_gaps(pm, rcm)
        slow = v[mem] @ tab.seg_n.T >= -cap
        x, f = np.nonzero((np.abs(seg_gap) < CLUSTER_GAP) & beside & slow)
        cushion_rows(x, tab.seg_n[f], seg_gap[x, f])
        slow = (v[mem][:, None] * tip_dir).sum(axis=2) >= -cap
        x, f = np.nonzero((tip_gap < CLUSTER_GAP) & slow)
        cushion_rows(x, tip_dir[x, f], tip_gap[x, f])
        ra, rc_, rn, rg = (np.concatenate(z) for z in (ra, rc_, rn, rg))
        nc = len(ra)
        J = np.zeros((nc, N, 2))  # u = J v: separating speed along each contact normal
        rows = np.arange(nc)
        J[rows, ra] = rn
        ball = rc_ >= 0
        J[rows[ball], rc_[ball]] = -rn[ball]
        J = J.reshape(nc, 2 * N)
        # A rolling ball given a small push slides for an instant and then rolls on with 5/7
        # of the push (the slip completion in _set): it answers as if 7/5 as heavy.
        slip = _norm(v + R[:, None] * _perp(w[:, :2]))
        snaps = (slip <= EPS_U) & (self.physics.mu_slide > 0)
        inv_m = np.repeat(np.where(snaps, 5.0 / 7.0, 1.0) / m, 2)
        A = (J * inv_m) @ J.T
        inv_m = np.repeat(1.0 / m, 2)
        for _ in range(20):
            vflat = v.reshape(-1)
            u0 = J @ vflat
            if not (u0 < -V_MIN).any():
                break
            lam = solve_inelastic(A, u0)
            v = (vflat + inv_m * (J.T @ lam)).reshape(N, 2)
            # A push leaves a rolling ball with a tiny slip that is completed at once; do it
            # here so that the solve sees the velocities that result.
            _, v[mem], w[mem], _ = self._snap(p[mem], v[mem], w[mem], R[mem], None, move=False)
        # Undo sub-micrometre sinks: the smallest mass-weighted moves that leave no contact
        # overlapping (the same complementarity problem, on positions), so a light ball
        # squeezed against a rail by a heavy one moves the heavy one back.
        A_pos = (J * inv_m) @ J.T
        ball = rc_ >= 0
        for _ in range(3):
            gaps = np.empty(nc)
            gaps[ball] = _norm(p[rc_[ball]] - p[ra[ball]]) - R[ra[ball]] - R[rc_[ball]]
            cush = ~ball
            gaps[cush] = rg[cush] + ((p[ra[cush]] - p0[ra[cush]]) * rn[cush]).sum(axis=1)
            if not (gaps < -1e-12).any():  # rounding is not an overlap
                break
            lam = solve_inelastic(A_pos, np.minimum(gaps, 0.0))
            p = p + (inv_m * (J.T @ lam)).reshape(N, 2)
        moved = (v[mem] != v_in[mem]).any(axis=1) | (p[mem] != p0[mem]).any(axis=1)
        self._set(np.full(len(mem), b), mem, np.full(len(mem), t), p[mem], v[mem], w[mem])
        return members, mem[moved].tolist()
