"""Slow contacts: touching balls and cushions settled together, without chatter.

Below `v_inelastic` a contact is perfectly inelastic. An isolated pair is settled at once;
a contact inside a cluster of touching balls and cushions is solved with the whole cluster as
one complementarity problem (cluster.py), on velocities and then on positions, and contacts
left resting join their balls into a group (joined.py). `SlowContacts` decides, for the
cushion and ball-ball events of a pass, which are fast (`respond.Responses`) and which slow.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from termpool.physics import motion
from termpool.physics.balls import Balls
from termpool.physics.cluster import Rows, solve_inelastic
from termpool.physics.events import ENDS
from termpool.physics.features import Features
from termpool.physics.joined import Groups
from termpool.physics.motion import Col, snap
from termpool.physics.params import Physics
from termpool.physics.respond import Responses
from termpool.physics.roots import A_MIN, V_MIN
from termpool.physics.schedule import Due, Schedule
from termpool.physics.slow_many import solve_clusters
from termpool.physics.state import CLUSTER_GAP, EPS_U, POCKETED
from termpool.physics.vec import dots
from termpool.physics.vec import norm as _norm


class Cluster(NamedTuple):
    """A contact to solve with its cluster: the event (its place in the pass), the balls it
    starts from, whether every contact is inelastic (over the work bound), and whether the
    contact is the event's own (else the event renews a group's motion)."""

    event: int
    seeds: list[int]
    every: bool
    own: bool


@dataclass
class Solved:
    """What solving a pass's clusters did: the balls it set moving, (tables, balls) arrays for
    their predictions; each cluster's size; events that changed nothing; per event, the other
    balls its cluster set moving (`extra`) and other balls' state changes (`also`: ball,
    state before, state after)."""

    tables: list = field(default_factory=list)
    balls: list = field(default_factory=list)
    sizes: list[int] = field(default_factory=list)
    quiet: set[int] = field(default_factory=set)
    extra: dict[int, list[int]] = field(default_factory=dict)
    also: dict[int, list[tuple[int, int, int]]] = field(default_factory=dict)


_NOTHING = Solved()  # what solving no cluster does (only ever read)
# Clusters of a pass solved together from this many on (slow_many; one alone is solved here),
# and at most MANY_CLUSTERS at a time.
MANY = 2
MANY_CLUSTERS = 256


class SlowContacts:
    """Slow contacts of B tables at their clocks `tb`: the balls, their groups and the table's
    features; fast contacts go to `respond`."""

    def __init__(self, physics: Physics, balls: Balls, features: Features, schedule: Schedule,
                 groups: Groups, respond: Responses, tb: np.ndarray) -> None:
        self.physics, self.balls, self.features, self.schedule = physics, balls, features, schedule
        self.groups, self.respond, self.tb = groups, respond, tb
        self.many = MANY  # clusters solved together from this many (tests vary it)

    def cushions(self, tabs, i, cu, busy, any_busy: bool) -> tuple[list[Cluster], set[int]]:
        """Balls i[cu] of tables tabs[cu] meeting a cushion feature or a hole (busy: over the
        work bound, over the whole pass). A slow bounce (or any bounce over the work bound)
        is solved with its cluster: the ball settles on the cushion, and stays pressed to it
        while friction drives it there; the others bounce or drop. Returns (clusters to
        solve: (event, seed balls, every contact inelastic, the event's own slow contact),
        events that changed nothing: a resting contact that began, no impulse)."""
        clusters: list = []
        quiet: set[int] = set()
        approach = self._approach(tabs[cu], i[cu])
        slow = approach < self.physics.v_inelastic
        # Slowly, touching a ball (pressed into the rail by it) or grouped: with the
        # cluster; over the work bound: with the cluster, inelastically.
        crowd = np.zeros(cu.size, dtype=bool)
        if slow.any():
            crowd[slow] = self._crowded(tabs[cu[slow]], i[cu[slow]])
        if any_busy:
            crowd |= busy[cu] & (self.schedule.f_cush[tabs[cu], i[cu]] < self.features.first_hole)
        if crowd.any():
            # A cluster's solve leaves out a contact sunk deeper than CLUSTER_GAP, and the
            # ball would meet it again at once, for ever: it bounces (and is lifted).
            k = crowd.nonzero()[0]
            crowd[k] = ~self._sunk(tabs[cu[k]], i[cu[k]])
        for n in cu[crowd].tolist():
            clusters.append(Cluster(n, [int(i[n])], bool(busy[n]), True))
        alone = ~crowd
        if alone.any():
            self.respond.cushion(tabs[cu[alone]], i[cu[alone]])
            # A slow ball left pressed to the cushion by its friction stays on it, held by
            # the cushion's force (a group); one that met it with no speed at all was no
            # impact.
            calm = alone & slow
            if calm.any():
                pressed = np.zeros(cu.size, dtype=bool)
                pressed[calm] = self._pressed_on(tabs[cu[calm]], i[cu[calm]])
                for n in cu[pressed].tolist():
                    clusters.append(Cluster(n, [int(i[n])], False, True))
                quiet.update(cu[calm & ~pressed & (approach <= V_MIN)].tolist())
        return clusters, quiet

    def pairs(self, b, i, j, pr, busy) -> tuple[list[Cluster], set[int]]:
        """Ball-ball contacts (b, i, j), events pr of the pass (busy: over the work bound, or
        None for none): fast ones collide; slow ones of a pair that touches nothing else
        settle here. Returns (clusters to solve, events that changed nothing, as `cushions`)."""
        n = b.size
        if n == 1 and busy is None and self.respond.pair_one(int(b[0]), int(i[0]), int(j[0])):
            return [], set()
        clusters: list[Cluster] = []
        quiet: set[int] = set()
        # Both balls' states, once, for the closing speed and for whichever response.
        tb = self.tb[b]
        p, v, w = self.balls.eval(np.concatenate([b, b]), np.concatenate([i, j]),
                                  np.concatenate([tb, tb]))
        states = (p[:n], v[:n], w[:n], p[n:], v[n:], w[n:])
        d = states[3] - states[0]
        closing = ((states[1] - states[4]) * d).sum(axis=1) / _norm(d)
        slow = closing < self.physics.v_inelastic
        if busy is not None:
            slow |= busy
        if not slow.any():
            self.respond.collide(b, i, j, *states)
            return clusters, quiet
        fast = ~slow
        if fast.any():
            self.respond.collide(b[fast], i[fast], j[fast], *(x[fast] for x in states))
        calm = slow if busy is None else slow & ~busy
        sl = calm.nonzero()[0]
        if sl.size:
            # A pair alone, neither ball grouped: settled here, unless it stays pressed
            # together, which the cluster's solve makes a group.
            bs, is_, js = b[sl], i[sl], j[sl]
            group = self.groups.label
            alone = self._alone(bs, is_, js) & (group[bs, is_] < 0) & (group[bs, js] < 0)
            if alone.any():
                a = sl[alone]
                changed = self._settle(b[a], i[a], j[a], *(x[a] for x in states))
                pressed = self._pressed(b[a], i[a], j[a])
                quiet.update(int(pr[k]) for k in a[~changed & ~pressed].tolist())
                alone[alone] = ~pressed
            sl = sl[~alone]
        late = sl.tolist() + (busy.nonzero()[0].tolist() if busy is not None else [])
        for k in late:
            every = busy is not None and bool(busy[k])
            clusters.append(Cluster(int(pr[k]), [int(i[k]), int(j[k])], every, True))
        return clusters, quiet

    def solve(self, tabs, i, j, due, clusters: list[Cluster], record: bool) -> Solved:
        """Solve the pass's clusters (as `cushions` and `pairs` return them; events by their
        place in the pass, whose tables, balls and what was due are tabs, i, j, due)."""
        if not clusters:  # the usual pass
            return _NOTHING
        out = Solved()
        tables = [int(tabs[n]) for n, _, _, _ in clusters]
        # Each table has one event a pass, so its cluster is its own: the clusters are solved
        # together (slow_many), MANY_CLUSTERS at a time to bound the temporaries, or one
        # alone as here.
        assert len(set(tables)) == len(tables)
        solved: list = []
        for s in range(0, len(clusters), MANY_CLUSTERS):
            part = tables[s:s + MANY_CLUSTERS]
            near = self._touching(part)
            chunk = clusters[s:s + MANY_CLUSTERS]
            before = self.balls.state[part].copy()
            if len(part) >= self.many:
                found = solve_clusters(self.physics, self.balls, self.features, self.groups,
                                       self.tb, part, [c.seeds for c in chunk],
                                       [c.every for c in chunk], near)
            else:
                p, v, w, q, *pairs = near
                ends = np.searchsorted(q, np.arange(len(part) + 1))
                found = [self._cluster(b, c.seeds, c.every, p[n], v[n], w[n],
                                       *(x[ends[n]:ends[n + 1]] for x in pairs))
                         for n, (b, c) in enumerate(zip(part, chunk, strict=True))]
            solved += [(f, st) for f, st in zip(found, before, strict=True)]
        flat: list[int] = []
        for c, (n, _, _, own) in enumerate(clusters):
            b = tables[c]
            (members, moved), before = solved[c]
            out.sizes.append(len(members))
            if own and not moved:
                out.quiet.add(n)
            flat += members
            ends = []
            if record:
                # A group renewed when one of its balls stops may stop the others with it:
                # each such end is an event of its own.
                self_ = int(i[n]) if due[n] == Due.TRANSITION else -1  # a transition's ball
                was, now = before.tolist(), self.balls.state[b].tolist()
                ends = [(k, was[k], now[k]) for k in members
                        if k != self_ and (was[k], now[k]) in ENDS]
                out.also.setdefault(n, []).extend(ends)
            if due[n] != Due.TRANSITION:  # a transition renews a group: others move by rounding
                skip = {int(i[n]), int(j[n])} | {k for k, _, _ in ends} | set(out.extra.get(n, ()))
                out.extra.setdefault(n, []).extend(k for k in moved if k not in skip)
        # The balls set moving, all clusters' in one pair of arrays.
        out.tables.append(np.repeat(np.array(tables, dtype=np.int64), out.sizes))
        out.balls.append(np.array(flat, dtype=np.int64))
        return out

    def _approach(self, b, i) -> np.ndarray:
        """Speeds into the cushion, jaw or tip that balls (b, i) are about to meet (inf for
        a pocket's hole: never a slow contact)."""
        feat = self.features
        if b.size == 1:  # one ball (the usual case), in plain floats
            bb, ib = int(b[0]), int(i[0])
            f = int(self.schedule.f_cush[bb, ib])
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
        out = -(v * feat.normals(self.schedule.f_cush[b, i], p)).sum(axis=1)
        return np.where(self.schedule.f_cush[b, i] < feat.first_hole, out, np.inf)

    def _crowded(self, b, i) -> np.ndarray:
        """True for balls (b, i) that touch another ball or belong to a group."""
        k = np.arange(self.balls.N)[None, :]
        p, _, _ = self.balls.eval(b[:, None], k, self.tb[b][:, None], spin=False)
        own = p[np.arange(len(b)), i]
        gap = _norm(p - own[:, None]) - self.balls.radius[b] - self.balls.radius[b, i][:, None]
        other = (self.balls.state[b] != POCKETED) & (k != i[:, None])
        return (other & (gap < CLUSTER_GAP)).any(axis=1) | (self.groups.label[b, i] >= 0)

    def _pressed_on(self, b, i) -> np.ndarray:
        """True for balls (b, i), just bounced slowly off a cushion feature, that do not
        leave it: still moving into it (a tiny slide completed into it), or neither moving
        off nor into it but accelerating into it."""
        p, v, _ = self.balls.eval(b, i, self.tb[b], spin=False)
        n = self.features.normals(self.schedule.f_cush[b, i], p)
        vn = (v * n).sum(axis=1)
        an = (self.balls.acc[b, i] * n).sum(axis=1)
        tip = self.schedule.f_cush[b, i] >= self.features.nseg
        bend = np.where(tip, ((v - vn[:, None] * n) ** 2).sum(axis=1) / self.balls.rc[b, i], 0.0)
        return (vn < 0) | ((vn <= V_MIN) & (an + bend < -A_MIN))

    def _alone(self, b, i, j) -> np.ndarray:
        """True for pairs (b, i, j) that touch no third ball and no cushion."""
        N = self.balls.N
        t = self.tb[b]
        k = np.arange(N)[None, :]
        p, _, _ = self.balls.eval(b[:, None], k, t[:, None], spin=False)  # (M, N, 2)
        R = self.balls.radius[b]
        live = (self.balls.state[b] != POCKETED) & (k != i[:, None]) & (k != j[:, None])
        crowded = np.zeros(len(b), dtype=bool)
        for x in (i, j):
            px = p[np.arange(len(b)), x]
            gap = _norm(p - px[:, None]) - R - R[np.arange(len(b)), x][:, None]
            crowded |= (live & (gap < CLUSTER_GAP)).any(axis=1)
            seg_gap, beside, tip_gap, _ = self.features.gaps(px, self.balls.rc[b, x])
            crowded |= ((seg_gap < CLUSTER_GAP) & beside).any(axis=1)
            crowded |= (tip_gap < CLUSTER_GAP).any(axis=1)
        return ~crowded

    def _settle(self, b, i, j, pi, vi, wi, pj, vj, wj) -> np.ndarray:
        """Slow contact of an isolated pair, balls now at (pi, vi, wi) and (pj, vj, wj):
        perfectly inelastic along the normal, repeated with the slip completion of motion.snap
        until the pair no longer closes. Returns which pairs it changed."""
        t = self.tb[b]
        ri, rj = self.balls.radius[b, i], self.balls.radius[b, j]
        mi, mj = self.balls.mass[b, i], self.balls.mass[b, j]
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
        self.respond.part(b, i, j, t, pi, pj, vi, vj, wi, wj)
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

    def _touching(self, tables: list[int]) -> tuple:
        """For each of `tables` (distinct) at its clock: its balls' (N, 2) positions and
        velocities and (N, 3) spins (with a leading axis over the tables), and its touching
        pairs (within CLUSTER_GAP, neither pocketed), each way round: (table's place q, ball
        a, ball c, offset c - a (K, 2), distance, how fast they close), ordered by q, a, c."""
        N = self.balls.N
        tarr = np.array(tables, dtype=np.int64)
        p, v, w = motion.at_many(self.balls.motion.take(tarr, axis=0), self.tb[tarr][:, None])
        R = self.balls.radius[tarr]
        live = self.balls.state[tarr] != POCKETED
        dx = p[:, None, :, 0] - p[:, :, None, 0]
        dy = p[:, None, :, 1] - p[:, :, None, 1]
        # The distances (np.hypot, the costly part) only of pairs that may touch: squared,
        # against the largest reach with a margin far above their rounding; then exactly.
        top = (2.0 * float(self.balls.radius.max()) + CLUSTER_GAP) * (1.0 + 1e-6)
        near = dx * dx + dy * dy < top * top
        near &= live[:, :, None] & live[:, None, :]
        k = np.arange(N)
        near[:, k, k] = False
        f = near.reshape(-1).nonzero()[0]
        ga, c = np.divmod(f, N)  # ga = q N + a
        q, a = np.divmod(ga, N)
        gc = ga - a + c
        R = R.reshape(-1)
        dist = np.hypot(dx.take(f), dy.take(f))
        keep = (dist - (R.take(ga) + R.take(gc)) < CLUSTER_GAP).nonzero()[0]
        q, a, c, ga, gc, dist = (x.take(keep) for x in (q, a, c, ga, gc, dist))
        P, V = p.reshape(-1, 2), v.reshape(-1, 2)
        d = P.take(gc, axis=0) - P.take(ga, axis=0)
        closing = -((V.take(gc, axis=0) - V.take(ga, axis=0)) * d).sum(axis=1) / np.where(
            dist > 0, dist, 1)
        return p, v, w, q, a, c, d, dist, closing

    def _cluster(self, b: int, seeds: list[int], every: bool, p, v, w, a_, c_, d_, dist_,
                 closing):
        """Resolve a slow contact together with every ball and cushion touching its cluster
        (with `every`, fast contacts too: the work bound's inelastic fallback); the table's
        balls and touching pairs (a_, c_, offsets, distances, closing speeds) as `_touching`
        gives them."""
        N, tab = self.balls.N, self.features.table
        t = self.tb[b]
        p0, v_in = p.copy(), v.copy()
        R, m = self.balls.radius[b], self.balls.mass[b]
        # A contact that closes fast is a collision of its own, handled pair by pair (this is
        # what carries a cradle's wave down the row); only slow contacts join the cluster.
        cap = np.inf if every else self.physics.v_inelastic
        slow = closing <= cap
        a_, c_, d_, dist_ = a_[slow], c_[slow], d_[slow], dist_[slow]
        near: list[list[int]] = [[] for _ in range(N)]
        for a, c in zip(a_.tolist(), c_.tolist(), strict=True):
            near[a].append(c)
        members = list(dict.fromkeys(seeds))
        seen = set(members)
        for a in members:  # grows while we walk it
            for c in near[a]:
                if c not in seen:
                    seen.add(c)
                    members.append(c)
        mem = np.array(members)
        # Contact rows: ball a, ball c (or -1: a cushion), normal pushing a away, gap; the
        # pairs of members in the order of their places among the members.
        place = np.full(N, -1)
        place[mem] = np.arange(mem.size)
        pa, pc = place[a_], place[c_]
        k = ((pa >= 0) & (pa < pc)).nonzero()[0]
        k = k[np.lexsort((pc[k], pa[k]))]
        a, c = a_[k], c_[k]
        ra, rc_, rn, rg = [a], [c], [-d_[k] / dist_[k][:, None]], [np.zeros(a.size)]
        rkind = [np.zeros(a.size, dtype=np.int64)]  # 0 ball, 1 rail or jaw, 2 jaw tip
        pm, rcm = p[mem], self.balls.rc[b, mem]

        def cushion_rows(x, normals, gaps, kind):
            ra.append(mem[x])
            rc_.append(np.full(x.size, -1))
            rn.append(normals)
            rg.append(gaps)
            rkind.append(np.full(x.size, kind))

        seg_gap, beside, tip_gap, tip_dir = self.features.gaps(pm, rcm)
        slow = dots(v[mem], tab.seg_n) >= -cap
        x, f = ((np.abs(seg_gap) < CLUSTER_GAP) & beside & slow).nonzero()
        cushion_rows(x, tab.seg_n[f], seg_gap[x, f], 1)
        slow = (v[mem][:, None] * tip_dir).sum(axis=2) >= -cap
        x, f = ((tip_gap < CLUSTER_GAP) & slow).nonzero()
        cushion_rows(x, tip_dir[x, f], tip_gap[x, f], 2)
        ra, rc_, rn, rg, rkind = (np.concatenate(z) for z in (ra, rc_, rn, rg, rkind))
        nc = len(ra)
        J = Rows(ra, rc_, rn, N)  # u = J v: separating speed along each contact normal
        # A rolling ball given a small push slides for an instant and then rolls on with 5/7
        # of the push (the slip completion, motion.snap): it answers as if 7/5 as heavy.
        slip = motion.slip(v, w, R)[2]
        snaps = (slip <= EPS_U) & (self.physics.mu_slide > 0)
        k_snap = np.where(snaps, 5.0 / 7.0, 1.0) / m
        inv_m = 1.0 / m
        for _ in range(20):
            u0 = J.speeds(v)
            if not (u0 < -V_MIN).any():
                break
            lam = solve_inelastic(J.matrix(k_snap), u0)  # (built once, when first needed)
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
        reach = np.where(ball, R[ra] + R[np.maximum(rc_, 0)], self.balls.rc[b, ra])
        curved = ball | (rkind == 2)
        bend[curved] = (tang[curved] ** 2).sum(axis=1) / reach[curved]
        self.groups.join(b, mem, t, p, v, w, ra[rest], rc_[rest], rn[rest], bend[rest])
        # What the solves changed: velocities as the balls now start (a resting contact's
        # last rounding of speed taken out, a ball set at rest), and positions.
        row = self.balls.motion[b, mem]
        moved = (row[:, Col.V] != v_in[mem]).any(axis=1) | (row[:, Col.P] != p0[mem]).any(axis=1)
        return members, mem[moved].tolist()

    def _sunk(self, b, i) -> np.ndarray:
        """True for balls (b, i) sunk deeper than CLUSTER_GAP into the rail, jaw or jaw tip
        they are about to meet."""
        p, _, _ = self.balls.eval(b, i, self.tb[b], spin=False)
        f = self.schedule.f_cush[b, i]
        n = self.features.normals(f, p)
        depth = self.balls.rc[b, i] - ((p - self.features.points(f)) * n).sum(axis=1)
        return depth > CLUSTER_GAP
