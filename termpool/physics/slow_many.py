"""The cluster solves of slow contacts (slow.SlowContacts) for many tables at once.

In a batch of similar tables the clusters come together: after a break every table's rack
settles in the same pass. Solved one table at a time, each solve is a few hundred numpy calls
on arrays of a few balls; here one pass's clusters (one a table) go through the same steps
together: every ball and contact row of all of them in one array, each cluster's
complementarity problems still solved on their own (in plain floats), and the groups their
resting contacts form pushed together (joined.push_many). Every operation is the one-table
solve's, element for element and row for row in the same order, so the results are the
same bits (tests/test_slow_many.py holds them to it).
"""

from __future__ import annotations

from itertools import compress

import numpy as np

from termpool.physics.balls import Balls
from termpool.physics.cluster import PLAIN, TOL, Columns, Rows, inelastic_plain, solve_inelastic
from termpool.physics.features import Features
from termpool.physics.joined import Groups, Sets, blocks, push_many
from termpool.physics.motion import Col, snap
from termpool.physics.motion import slip as motion_slip
from termpool.physics.params import Physics
from termpool.physics.roots import V_MIN
from termpool.physics.state import CLUSTER_GAP, EPS_U
from termpool.physics.vec import any_by, dots
from termpool.physics.vec import norm as _norm


def solve_clusters(ph: Physics, balls: Balls, features: Features, groups: Groups,
                   tb: np.ndarray, tables: list[int], seeds: list[list[int]],
                   every: list[bool], near: tuple) -> list[tuple[list[int], list[int]]]:
    """Resolve the slow contacts of clusters on distinct `tables`, each grown from its
    `seeds` (with `every`: fast contacts too), as `SlowContacts` does one at a time; `near`
    is `SlowContacts._touching` of the tables. Returns each cluster's (members, balls the
    solve moved)."""
    p, v, w, pq, pa, pc, pd, pdist, closing = near
    C, N = len(tables), balls.N
    tab = features.table
    tarr = np.array(tables, dtype=np.int64)
    cap = np.where(every, np.inf, ph.v_inelastic)
    # Each cluster grown from its seeds over its table's slow contacts.
    slow = closing <= cap[pq]
    pq, pa, pc, pd, pdist = pq[slow], pa[slow], pc[slow], pd[slow], pdist[slow]
    # (The pairs come ordered by table, a, c: ball a's of table q are one run of them.)
    bounds = np.searchsorted(pq * N + pa, np.arange(C * N + 1)).tolist()
    partner = pc.tolist()
    members: list[list[int]] = []
    for q in range(C):
        mem = list(dict.fromkeys(seeds[q]))
        seen = set(mem)
        base = q * N
        for a in mem:  # grows while we walk it
            for c in partner[bounds[base + a]:bounds[base + a + 1]]:
                if c not in seen:
                    seen.add(c)
                    mem.append(c)
        members.append(mem)
    sizes = np.array([len(x) for x in members])
    mq = np.repeat(np.arange(C), sizes)  # each member's cluster, ball and place among all
    mb = np.array([k for x in members for k in x], dtype=np.int64)
    gm = mq * N + mb
    P, V, W = p.reshape(C * N, 2), v.reshape(C * N, 2).copy(), w.reshape(C * N, 3)
    P0, V_in = P.copy(), V.copy()
    # Contact rows, cluster by cluster: its pairs of balls in the order of their places
    # among its members, then its rails and jaws, then its jaw tips.
    place = np.full((C, N), -1)
    place[mq, mb] = np.arange(mq.size) - np.repeat(np.cumsum(sizes) - sizes, sizes)
    ia, ic = place[pq, pa], place[pq, pc]
    k = ((ia >= 0) & (ia < ic)).nonzero()[0]
    k = k[np.lexsort((ic[k], ia[k], pq[k]))]
    bq, a, c = pq[k], pa[k], pc[k]
    rq, ra, rc_ = [bq], [a], [c]
    rn, rg = [-pd[k] / pdist[k][:, None]], [np.zeros(a.size)]
    rkind = [np.zeros(a.size, dtype=np.int64)]
    # Only members by the rails can touch a rail, jaw or tip (the rest of a rack pays nothing).
    pm, rcm = P[gm], balls.rc[tarr[mq], mb]
    by = by_rails(features, pm, rcm).nonzero()[0]
    if by.size:
        seg_gap, beside, tip_gap, tip_dir = features.gaps(pm[by], rcm[by])
        mq_, mb_, vm = mq[by], mb[by], V[gm[by]]
        capm = cap[mq_][:, None]
        slow = dots(vm, tab.seg_n) >= -capm
        x, f = ((np.abs(seg_gap) < CLUSTER_GAP) & beside & slow).nonzero()
        for z, val in ((rq, mq_[x]), (ra, mb_[x]), (rc_, np.full(x.size, -1)),
                       (rn, tab.seg_n[f]), (rg, seg_gap[x, f]), (rkind, np.full(x.size, 1))):
            z.append(val)
        slow = (vm[:, None] * tip_dir).sum(axis=2) >= -capm
        x, f = ((tip_gap < CLUSTER_GAP) & slow).nonzero()
        for z, val in ((rq, mq_[x]), (ra, mb_[x]), (rc_, np.full(x.size, -1)),
                       (rn, tip_dir[x, f]), (rg, tip_gap[x, f]), (rkind, np.full(x.size, 2))):
            z.append(val)
        rq_, ra_, rc0, rn_, rg_, rk_ = (np.concatenate(z) for z in (rq, ra, rc_, rn, rg, rkind))
        order = np.argsort(rq_ * 3 + rk_, kind="stable")
        rq_, ra_, rc0, rn_, rg_, rk_ = (z[order] for z in (rq_, ra_, rc0, rn_, rg_, rk_))
    else:  # no member by the rails: the pairs' rows alone, already in their order
        rq_, ra_, rc0, rn_, rg_, rk_ = bq, a, c, rn[0], rg[0], rkind[0]
    ga = rq_ * N + ra_
    gc = np.where(rc0 >= 0, rq_ * N + rc0, -1)
    J = Rows(ga, gc, rn_, C * N)
    counts = np.bincount(rq_, minlength=C)
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
    Rf, mf = balls.radius[tarr].ravel(), balls.mass[tarr].ravel()
    slip = motion_slip(V, W, Rf)[2]
    snaps = (slip <= EPS_U) & (ph.mu_slide > 0)
    inv_m = 1.0 / mf
    # Velocities: each cluster until none of its contacts closes.
    live = np.ones(C, dtype=bool)
    cols: dict = {}  # the live clusters' matrices (often none is: a settling rack at rest)
    first, ends = starts.tolist(), (starts + counts).tolist()
    for _ in range(20):
        u0 = J.speeds(V)
        live &= any_by(u0 < -V_MIN, rq_, C)
        if not live.any():
            break
        if not cols:  # the clusters live now are all that may be later
            qs = live.nonzero()[0]
            cols = {q: Columns(M) for q, M in zip(
                qs.tolist(), blocks(J, starts[qs], counts[qs],
                                    np.where(snaps, 5.0 / 7.0, 1.0) / mf), strict=True)}
        lam = _solved(cols, u0, live, first, ends)
        k = gm[live[mq]]
        V[k] = (V + J.spread(lam, inv_m))[k]
        _, V[k], W[k], _ = snap(ph, P[k], V[k], W[k], Rf[k], None, move=False)
    # Positions: undo sinks, each cluster until none of its contacts overlaps.
    ball = J.ball
    cush = ~ball
    live = np.ones(C, dtype=bool)
    for _ in range(3):
        gaps = np.empty(len(J))
        gaps[ball] = _norm(P[gc[ball]] - P[ga[ball]]) - Rf[ga[ball]] - Rf[gc[ball]]
        gaps[cush] = rg_[cush] + ((P[ga[cush]] - P0[ga[cush]]) * rn_[cush]).sum(axis=1)
        live &= any_by(gaps < -1e-12, rq_, C)
        if not live.any():
            break
        qs = live.nonzero()[0]
        mats = {q: Columns(M) for q, M in
                zip(qs.tolist(), blocks(J, starts[qs], counts[qs], inv_m), strict=True)}
        lam = _solved(mats, np.minimum(gaps, 0.0), live, first, ends)
        k = gm[live[mq]]
        P = P.copy()
        P[k] = (P + J.spread(lam, inv_m))[k]
    # Resting contacts and their bends, then the groups they form.
    rest = J.speeds(V) <= V_MIN
    bend = np.zeros(len(J))
    rel = V[ga] - np.where(ball[:, None], V[np.maximum(gc, 0)], 0.0)
    tang = rel - (rel * rn_).sum(axis=1)[:, None] * rn_
    reach = np.where(ball, Rf[ga] + Rf[np.maximum(gc, 0)], balls.rc[tarr[rq_], ra_])
    curved = ball | (rk_ == 2)
    bend[curved] = (tang[curved] ** 2).sum(axis=1) / reach[curved]
    _join(ph, balls, groups, tb, tarr, members, mq, gm, P, V, W, rq_[rest], ga[rest],
          gc[rest], rn_[rest], bend[rest])
    row = balls.motion[tarr[mq], mb]
    moved = (row[:, Col.V] != V_in[gm]).any(axis=1) | (row[:, Col.P] != P0[gm]).any(axis=1)
    out = []
    hits = moved.tolist()  # the members cluster by cluster
    s = 0
    for mem in members:
        e = s + len(mem)
        out.append((mem, list(compress(mem, hits[s:e]))))
        s = e
    return out


def by_rails(features: Features, p: np.ndarray, rc: np.ndarray) -> np.ndarray:
    """Which balls at p (M, 2) with contact reach rc may be within CLUSTER_GAP of a rail,
    jaw or jaw tip (`Features.gaps`): on a table whose every segment and tip lies beyond one
    of its bed's edges (x <= 0, x >= length, y <= 0 or y >= width, as every preset's do), a
    ball farther than its reach and twice the gap from all four edges is farther than that
    from every feature, whatever the rounding. On any other table, every ball."""
    t = features.table
    L, W = t.length, t.width
    ends = np.stack([t.seg_a, t.seg_b])
    beyond = (((ends[..., 0] <= 0.0).all(axis=0) | (ends[..., 0] >= L).all(axis=0)
               | (ends[..., 1] <= 0.0).all(axis=0) | (ends[..., 1] >= W).all(axis=0)).all()
              and ((t.points[:, 0] <= 0.0) | (t.points[:, 0] >= L) | (t.points[:, 1] <= 0.0)
                   | (t.points[:, 1] >= W)).all())
    if not beyond:
        return np.ones(len(p), dtype=bool)
    d = rc + 2.0 * CLUSTER_GAP
    x, y = p[:, 0], p[:, 1]
    return (x < d) | (x > L - d) | (y < d) | (y > W - d)


def _solved(mats, u0: np.ndarray, live: np.ndarray, starts: list, ends: list) -> np.ndarray:
    """`solve_inelastic` of each live cluster q (its rows starts[q] to ends[q]) with the
    `Columns` mats[q] of its matrix and u0's rows: the impulses of all rows (0 for the
    others), the small problems in plain floats from one list of u0."""
    lam = [0.0] * len(u0)
    u = u0.tolist()
    for q in live.nonzero()[0].tolist():
        s, e = starts[q], ends[q]
        if e - s > PLAIN:
            lam[s:e] = solve_inelastic(mats[q].A, u0[s:e]).tolist()
        else:
            lam[s:e] = inelastic_plain(mats[q], u[s:e], TOL)
    return np.array(lam, dtype=float).reshape(len(u0))


def _join(ph: Physics, balls: Balls, groups: Groups, tb: np.ndarray, tarr: np.ndarray,
          members: list[list[int]], mq, gm, P, V, W, rq, ga, gc, rn, bend) -> None:
    """`Groups.join` of every cluster: each cluster's balls in resting contacts (rows rq:
    cluster, ga and gc: balls as cluster * N + ball, normals rn, bends) move as a group, the
    others freely. Balls are numbered cluster * N + ball."""
    N = balls.N
    C = len(members)
    held = np.zeros(C * N + 1, dtype=bool)  # (the last: ball -1, a cushion's, never held)
    held[ga] = True
    held[gc] = True
    held[-1] = False
    free = gm[~held[gm]]
    groups.label[tarr[mq], gm % N] = -1
    if free.size:
        bt, bi = tarr[free // N], free % N
        balls.set(bt, bi, tb[bt], P[free], V[free], W[free])
    hb = held.nonzero()[0]  # global numbers: cluster by cluster, ball by ball
    if hb.size:
        where = np.full(C * N + 1, -1)
        where[hb] = np.arange(hb.size)
        hq = hb // N
        J = Rows(where[ga], where[gc], rn, hb.size)
        bt, bi = tarr[hq], hb % N
        vj, acc, alpha, state, duration, wj = push_many(
            ph, V[hb], W[hb], balls.radius[bt, bi], balls.mass[bt, bi], balls.spin_rate[bt, bi],
            Sets(J, hq, rq, C), bend)
        t = tb[bt]
        balls.state[bt, bi] = state
        balls.t_trans[bt, bi] = t + duration
        balls.motion[bt, bi, :Col.RATE] = np.concatenate(
            [t[:, None], P[hb], vj, acc, wj, alpha], axis=1)
        # Each group labelled by its first ball (the tables are distinct).
        first = np.diff(hq, prepend=-1).nonzero()[0]
        groups.label[bt, bi] = np.repeat(bi[first], np.diff(first, append=hb.size))
    groups.count[tarr] = (groups.label[tarr] >= 0).sum(axis=1)
