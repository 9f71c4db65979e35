"""Slow contacts: touching balls and cushions settled together, without chatter.

Below `v_inelastic` a contact is perfectly inelastic. An isolated pair is settled at once;
a contact inside a cluster of touching balls and cushions is solved with the whole cluster as
one complementarity problem (cluster.py), on velocities and then on positions. A mixin of
Engine: it works on the engine's arrays.
"""

from __future__ import annotations

import numpy as np

from termpool.physics.cluster import solve_inelastic
from termpool.physics.joined import push
from termpool.physics.roots import V_MIN
from termpool.physics.state import CLUSTER_GAP, EPS_U, POCKETED
from termpool.physics.state import norm as _norm
from termpool.physics.state import perp as _perp


class SlowContacts:
    def _slow_bounce(self, b, i) -> np.ndarray:
        """True for balls (b, i) about to meet a cushion, jaw or tip (not a pocket's hole)
        slower than v_inelastic: they settle on it with their cluster instead of bouncing,
        and stay pressed to it while friction drives them there."""
        t = self.tb[b]
        f = self.f_cush[b, i]
        nseg = self._nseg
        out = f < nseg + self._npt
        p, v, _ = self._eval(b, i, t, spin=False)
        tab = self.table
        n = tab.seg_n[np.minimum(f, nseg - 1)]
        tip = (f >= nseg) & out
        if tip.any():
            d = p[tip] - tab.points[f[tip] - nseg]
            n[tip] = d / _norm(d)[:, None]
        return out & (-(v * n).sum(axis=1) < self.physics.v_inelastic)

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
        rkind = [np.zeros(a.size, dtype=np.int64)]  # 0 ball, 1 rail or jaw, 2 jaw tip
        pm, rcm = p[mem], self.rc[b, mem]

        def cushion_rows(x, normals, gaps, kind):
            ra.append(mem[x])
            rc_.append(np.full(x.size, -1))
            rn.append(normals)
            rg.append(gaps)
            rkind.append(np.full(x.size, kind))

        seg_gap, beside, tip_gap, tip_dir = self._cushion_gaps(pm, rcm)
        slow = v[mem] @ tab.seg_n.T >= -cap
        x, f = np.nonzero((np.abs(seg_gap) < CLUSTER_GAP) & beside & slow)
        cushion_rows(x, tab.seg_n[f], seg_gap[x, f], 1)
        slow = (v[mem][:, None] * tip_dir).sum(axis=2) >= -cap
        x, f = np.nonzero((tip_gap < CLUSTER_GAP) & slow)
        cushion_rows(x, tip_dir[x, f], tip_gap[x, f], 2)
        ra, rc_, rn, rg, rkind = (np.concatenate(z) for z in (ra, rc_, rn, rg, rkind))
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
        # Contacts that neither close nor part are resting: friction may press them together,
        # and then they carry a steady force (joined.py). Their curvature (balls rolling
        # round each other, a ball round a jaw tip) would part them of itself.
        u = J @ v.reshape(-1)
        rest = u <= V_MIN
        bend = np.zeros(nc)
        rel = v[ra] - np.where(ball[:, None], v[np.maximum(rc_, 0)], 0.0)
        tang = rel - (rel * rn).sum(axis=1)[:, None] * rn
        reach = np.where(ball, R[ra] + R[np.maximum(rc_, 0)], self.rc[b, ra])
        curved = ball | (rkind == 2)
        bend[curved] = (tang[curved] ** 2).sum(axis=1) / reach[curved]
        self._join(b, mem, t, p, v, w, ra[rest], rc_[rest], rn[rest], bend[rest])
        # What the solves changed: velocities as the balls now start (a resting contact's
        # last rounding of speed taken out, a ball set at rest), and positions.
        row = self._motion[b, mem]
        moved = (row[:, 3:5] != v_in[mem]).any(axis=1) | (row[:, 1:3] != p0[mem]).any(axis=1)
        return members, mem[moved].tolist()

    def _join(self, b: int, mem, t: float, p, v, w, ra, rc_, rn, bend) -> None:
        """Start the motion of balls `mem` of table b at time t from (p, v, w) (all N balls):
        balls in resting contacts (rows ra, rc_, rn, bend as in _cluster) move as a group
        held by the contacts' forces; the others move freely."""
        held = np.unique(np.concatenate([ra, rc_[rc_ >= 0]]))
        free = mem[~np.isin(mem, held)]
        self.group[b, mem] = -1
        if free.size:
            self._set(np.full(free.size, b), free, np.full(free.size, t), p[free], v[free],
                      w[free])
        if held.size:
            where = {int(x): n for n, x in enumerate(held.tolist())}
            rows = [(where[int(x)], where.get(int(y), -1), n, bb)
                    for x, y, n, bb in zip(ra, rc_, rn, bend, strict=True)]
            vj, acc, alpha, state, duration, wj = push(
                self.physics, v[held], w[held], self.radius[b, held],
                self.mass[b, held], self.spin_rate[b, held], rows)
            self.state[b, held] = state
            self.t_trans[b, held] = t + duration
            self._motion[b, held, :12] = np.concatenate(
                [np.full((held.size, 1), t), p[held], vj, acc, wj, alpha], axis=1)
            self.group[b, held] = int(held.min())
        self._ngroup[b] = int((self.group[b] >= 0).sum())
