"""The cluster solves of many tables at once (slow_many, joined.push_many, joined.blocks) give
the bits of the one-table solves: contact matrices of several sets of rows against each set's
own, and whole runs with every pass's clusters solved together against one at a time, on
racks, touching triangles, rows of frozen balls and the example and bench scenes."""

from __future__ import annotations

import copy
import glob
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from termpool.physics import joined, slow_many
from termpool.physics.cluster import Rows
from termpool.physics.engine import Engine
from termpool.physics.features import Features
from termpool.physics.params import BALL_RADIUS, Physics
from termpool.physics.schedule import Due
from termpool.physics.state import CLUSTER_GAP, POCKETED
from termpool.physics.table import Table
from termpool.scene import load_scene
from tests.test_cluster import CASES, _masses

ROOT = Path(__file__).resolve().parent.parent
SCENES = sorted(glob.glob(str(ROOT / "bench" / "scenes" / "*.json"))
                + glob.glob(str(ROOT / "examples" / "*.json")))


def test_contact_matrices_of_several_sets_are_each_sets_own_bit_for_bit():
    """Every case of test_cluster (a pair, a row, a corner against two rails, a wedged ball,
    racks, hexagonal packs on a rail) in one set of rows, balls numbered apart: each block is
    `Rows.matrix` of the case alone, for equal, mixed and held (0) inverse masses."""
    # A ball in a corner whose rails' normals carry signed zeros: n . n' sums two -0.0s,
    # which numpy's row sum gives as 0.0.
    corner = Rows(np.array([0, 0, 1]), np.array([-1, -1, 0]),
                  np.array([[0.0, 1.0], [-1.0, -0.0], [-0.0, -1.0]]), 2)
    for seed in (0, 1, 2):
        cases = [*CASES.values(), corner]
        a, c, n, k, starts, counts = [], [], [], [], [], []
        first = rows = 0
        for case in cases:
            a.append(case.a + first)
            c.append(np.where(case.c >= 0, case.c + first, -1))
            n.append(case.n)
            k.append(_masses(case, seed))
            starts.append(rows)
            counts.append(len(case))
            first += case.balls
            rows += len(case)
        J = Rows(np.concatenate(a), np.concatenate(c), np.concatenate(n), first)
        got = joined.blocks(J, np.array(starts), np.array(counts), np.concatenate(k))
        for case, kq, A in zip(cases, k, got, strict=True):
            assert A.tobytes() == np.ascontiguousarray(case.matrix(kq)).tobytes()


def _same_run(make) -> tuple[Engine, Engine]:
    """Run an engine to rest with every pass's clusters solved together (even one alone), and
    one with each solved alone; both must agree bit for bit."""
    runs = []
    for many in (1, 10 ** 9):
        eng = make()
        eng.slow.many = many
        eng.run_events()
        runs.append(eng)
    a, b = runs
    assert a.passes == b.passes
    assert a.pos.tobytes() == b.pos.tobytes() and a.vel.tobytes() == b.vel.tobytes()
    assert a.w.tobytes() == b.w.tobytes() and a.state.tobytes() == b.state.tobytes()
    assert a.events == b.events
    return a, b


@pytest.mark.parametrize("path", SCENES, ids=[Path(p).stem for p in SCENES])
def test_each_scene_with_clusters_solved_together_is_the_same(path):
    sc = load_scene(path)
    _same_run(lambda: Engine(sc.table, sc.physics, sc.pos, sc.vel, sc.w, sc.radius, sc.mass))


@pytest.mark.parametrize("name", ["bench/scenes/cluster.json", "bench/scenes/break.json",
                                  "examples/nineball.json"])
def test_a_batch_with_clusters_solved_together_is_the_same(name):
    """24 tables of one scene, the shot's speed scaled from 5 % to 120 %: clusters of every
    size come in the same pass (the touching triangle, the 8-ball and 9-ball racks), some
    groups needing a second round of forces, some only turning, some none."""
    sc = load_scene(ROOT / name)
    B = 24
    rng = np.random.default_rng(5)
    vel = sc.vel[None] * rng.uniform(0.05, 1.2, (B, 1, 1))
    pos = np.broadcast_to(sc.pos, (B,) + sc.pos.shape).copy()
    w = np.broadcast_to(sc.w, (B,) + sc.w.shape)
    seen = []
    real = joined.Sets.solve

    def counted(self, free, k, bend, chosen):
        seen.append((self.count, int(chosen.sum())))
        return real(self, free, k, bend, chosen)

    joined.Sets.solve = counted
    try:
        batched, _ = _same_run(lambda: Engine(sc.table, sc.physics, pos, vel, w, sc.radius,
                                              sc.mass))
    finally:
        joined.Sets.solve = real
    assert any(count > 1 for count, _ in seen)  # several groups pushed together
    assert any(0 < chosen < count for count, chosen in seen)  # some of them only
    # And each table as it would run alone.
    for b in (0, 7, 23):
        one = Engine(sc.table, sc.physics, pos[b], vel[b], w[b], sc.radius, sc.mass)
        one.run_events()
        assert one.pos.tobytes() == batched.pos[b:b + 1].tobytes()
        assert one.events[0] == batched.events[b]


def _on_the_rails(B: int) -> tuple:
    """B tables of frozen balls exactly touching a rail (centres at their reach) and each
    other (2R apart): a row along a side rail and a pair on the foot rail, each met by a
    ball a hair away rolling at a few mm/s (some below the inelastic speed, some above), and
    a pair in the middle of the table met so."""
    table = Table.preset("9ft")
    R = BALL_RADIUS
    rc = Engine(table, Physics(), np.array([[0.5, 0.5]])).balls.rc[0, 0]
    L = table.length
    pos = np.array([[0.6 - 2 * R - 1e-4, rc], [0.6, rc], [0.6 + 2 * R, rc], [0.6 + 4 * R, rc],
                    [L - rc, 0.5 - 2 * R - 1e-4], [L - rc, 0.5], [L - rc, 0.5 + 2 * R],
                    [1.2 - 2 * R - 1e-4, 0.6], [1.2, 0.6]])
    pos = np.broadcast_to(pos, (B,) + pos.shape).copy()
    speed = np.linspace(0.001, 0.012, B)[:, None]
    vel = np.zeros_like(pos)
    vel[:, 0, 0] = speed[:, 0]
    vel[:, 4, 1] = speed[:, 0]
    vel[:, 7, 0] = speed[:, 0]
    w = np.zeros(pos.shape[:2] + (3,))
    w[:, [0, 7], 1] = speed / R  # rolling: w = z x v / R
    w[:, 4, 0] = -speed[:, 0] / R
    return table, pos, vel, w


def test_clusters_against_the_rails_solved_together_are_the_same(monkeypatch):
    """Rows of frozen balls on the rails nudged slowly, 16 tables at once: the batched solve,
    which looks for rail, jaw and tip contacts only among balls by the table's edges
    (by_rails), gives the bits of one cluster at a time, which looks at every ball."""
    table, pos, vel, w = _on_the_rails(16)
    seen = []
    real = slow_many.by_rails

    def counted(features, p, rc):
        out = real(features, p, rc)
        seen.append(out)
        return out

    monkeypatch.setattr(slow_many, "by_rails", counted)
    _same_run(lambda: Engine(table, Physics(), pos, vel, w))
    flags = np.concatenate(seen)
    assert flags.any() and not flags.all()  # balls by the rails, and balls away from them


@pytest.mark.parametrize("preset", ["7ft", "8ft", "9ft"])
def test_balls_by_the_rails_are_all_those_near_a_rail_jaw_or_tip(preset):
    """by_rails keeps every ball within CLUSTER_GAP of a rail, jaw or jaw tip by the
    features' own gaps: balls exactly on a rail, sunk a little into one, in the pocket
    mouths against the jaws and their tips, exactly 2R from a ball on a rail, and random
    balls over the whole bed and beyond; and it leaves out a rack in the middle."""
    table = Table.preset(preset)
    feat = Features(table)
    rc = Engine(table, Physics(), np.array([[0.5, 0.5]])).balls.rc[0, 0]
    L, W, R = table.length, table.width, BALL_RADIUS
    rng = np.random.default_rng(3)
    exact = [(rc, 0.5), (L - rc, 0.5), (0.7, rc), (0.7, W - rc), (rc - 1e-7, 0.6),
             (0.7, W - rc + 5e-7), (0.7 + 2 * R, rc), (rc + 2 * R, 0.5)]
    # Points by each jaw and tip, at the reach along each feature's normal, with a jitter.
    tips = table.points + rng.normal(0.0, 1e-3, table.points.shape)
    p = np.concatenate([np.array(exact), tips,
                        rng.uniform([-0.05, -0.05], [L + 0.05, W + 0.05], (4000, 2)),
                        rng.uniform([0.0, 0.0], [0.06, W], (2000, 2))])
    for f in range(feat.nseg):  # on each rail and jaw's line, beside it
        t = rng.uniform(0.0, 1.0, 50)[:, None]
        on = table.seg_a[f] + t * (table.seg_b[f] - table.seg_a[f]) + rc * table.seg_n[f]
        p = np.concatenate([p, on])
    r = np.full(len(p), rc)
    seg_gap, beside, tip_gap, _ = feat.gaps(p, r)
    near = (((np.abs(seg_gap) < CLUSTER_GAP) & beside).any(axis=1)
            | (tip_gap < CLUSTER_GAP).any(axis=1))
    kept = slow_many.by_rails(feat, p, r)
    assert near.sum() > 100  # the points do test it
    assert not (near & ~kept).any()
    rack = np.array([(0.75 * L + 3 ** 0.5 * R * i, W / 2 + (j - i / 2) * 2 * R)
                     for i in range(5) for j in range(i + 1)])
    assert not slow_many.by_rails(feat, rack, np.full(15, rc)).any()


def test_a_table_with_features_inside_its_bed_keeps_every_ball():
    """Where a rail or tip does not lie beyond the bed's edges (a bed longer than its rails
    here), the bound does not hold: every ball is looked at."""
    table = copy.copy(Table.preset("9ft"))
    table.length += 0.1
    p = np.array([[1.2, 0.6], [0.5, 0.5]])
    assert slow_many.by_rails(SimpleNamespace(table=table), p, np.full(2, 0.03)).all()


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_groups_solved_together_are_each_groups_own_solve_bit_for_bit(seed):
    """Sets.solve of every case of test_cluster at once (balls numbered apart), with equal,
    mixed and held (0) inverse masses, asked twice with the same masses (the matrices kept)
    and once with others: each group's accelerations are `joined._solve` of the group alone,
    rows with nothing that can move included."""
    rng = np.random.default_rng(seed)
    cases = list(CASES.values())
    a, c, n, ks, first, groups, rowg = [], [], [], [], 0, [], []
    for q, case in enumerate(cases):
        a.append(case.a + first)
        c.append(np.where(case.c >= 0, case.c + first, -1))
        n.append(case.n)
        ks.append(_masses(case, seed))
        groups.append(np.full(case.balls, q))
        rowg.append(np.full(len(case), q))
        first += case.balls
    J = Rows(np.concatenate(a), np.concatenate(c), np.concatenate(n), first)
    sets = joined.Sets(J, np.concatenate(groups), np.concatenate(rowg), len(cases))
    bend = rng.uniform(0.0, 0.1, len(J)) * (rng.uniform(size=len(J)) < 0.3)
    k = np.concatenate(ks)
    every = np.ones(len(cases), dtype=bool)
    for kk in (k, k, np.where(rng.uniform(size=k.size) < 0.2, 0.0, k)):
        free = rng.normal(0.0, 1.0, (first, 2))
        got = sets.solve(free, kk, bend, every)
        start = rows = 0
        for case in cases:
            s = slice(start, start + case.balls)
            r = slice(rows, rows + len(case))
            own = Rows(case.a, case.c, case.n, case.balls)
            assert got[s].tobytes() == joined._solve(free[s], kk[s], own, bend[r]).tobytes()
            start += case.balls
            rows += len(case)


def _grouped(B: int, seed: int) -> Engine:
    """B racks at rest with their balls in groups of every size (labels as `Groups` keeps
    them: a group's first ball), some balls in none."""
    sc = load_scene(ROOT / "bench/scenes/break.json")
    pos = np.broadcast_to(sc.pos, (B,) + sc.pos.shape).copy()
    eng = Engine(sc.table, sc.physics, pos, np.zeros_like(pos), None, sc.radius, sc.mass)
    rng = np.random.default_rng(seed)
    N = eng.balls.N
    for b in range(B):
        cut = np.sort(rng.choice(np.arange(1, N), 4, replace=False))
        for part in np.split(rng.permutation(N), cut):
            if part.size > 1 or rng.uniform() < 0.5:
                eng.groups.label[b, part] = part.min() if part.size > 1 else -1
        eng.groups.count[b] = int((eng.groups.label[b] >= 0).sum())
    return eng


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_groups_broken_at_once_are_broken_as_event_by_event(seed):
    """break_up frees the groups of every table's event at once: the labels, counts, freed
    balls and their motions are those of breaking them one event at a time, for bounces,
    fast pairs of grouped and ungrouped balls and events that break nothing (a transition,
    a check), each table once."""
    B = 40
    rng = np.random.default_rng(seed)
    tabs = rng.permutation(B)[:30]
    i = rng.integers(0, 16, 30)
    j = np.where(rng.uniform(size=30) < 0.5, (i + rng.integers(1, 16, 30)) % 16, -1)
    due = np.where(j >= 0, Due.PAIR, rng.choice([Due.TRANSITION, Due.CHECK, Due.CUSHION], 30))
    runs = []
    for form in ("at once", "each"):
        eng = _grouped(B, seed)
        involved = eng.groups.involved(tabs, i, j, due)
        assert involved.any() and not involved.all()
        with np.errstate(all="ignore"):  # (as the engine starts balls at rest)
            if form == "at once":
                out = eng.groups.break_up(tabs, i, j, due, involved)
            else:
                sel = np.flatnonzero(involved & (due >= Due.CUSHION))
                out = eng.groups._break_each(tabs, i, j, sel)
        runs.append((eng, [np.concatenate(x) if x else np.zeros(0, int) for x in out]))
    (a, (ab, ai)), (b, (bb, bi)) = runs
    assert ab.size > 0
    assert np.array_equal(ab, bb) and np.array_equal(ai, bi)
    assert np.array_equal(a.groups.label, b.groups.label)
    assert np.array_equal(a.groups.count, b.groups.count)
    assert a.balls.motion.tobytes() == b.balls.motion.tobytes()


def test_touching_pairs_are_those_within_the_gap_by_their_distance():
    """`SlowContacts._touching` of several tables (it measures only the pairs whose squared
    distance is near the largest reach): every pair of balls whose np.hypot distance less
    the two radii is below CLUSTER_GAP, each way round, in order, and no other; on exact
    racks, pairs a hair either side of the gap, balls of mixed radii, a sunk pair and a
    pocketed ball; with the offsets, distances and closing speeds the definitions give."""
    R = BALL_RADIUS
    sizes = (R, 0.8 * R, 1.3 * R)  # the pairs' balls, a table each (the last the largest)
    rows = []
    for r2 in sizes:
        rack = [(1.5 + 3 ** 0.5 * R * i, 0.6 + (j - i / 2) * 2 * R)
                for i in range(5) for j in range(i + 1)]
        gaps = [2 * r2 + CLUSTER_GAP * f for f in (1 - 1e-9, 1 + 1e-9, 0.5, 1.0)]
        left = [(0.3, 0.3 + 0.2 * k) for k in range(4)]
        right = [(0.3 + g, 0.3 + 0.2 * k) for k, g in enumerate(gaps)]
        rows.append(rack + left + right + [(1.0, 1.0), (1.0 + R + r2 - 1e-7, 1.0)])
    pos = np.array(rows)
    B, N = pos.shape[:2]
    radius = np.full((B, N), R)
    radius[:, 15:23] = np.array(sizes)[:, None]
    radius[:, 24] = sizes
    vel = np.random.default_rng(2).normal(0.0, 0.01, pos.shape)
    eng = Engine(Table.preset("9ft"), Physics(), pos, vel, None, radius, np.full((B, N), 0.17))
    eng.balls.state[1, 3] = POCKETED
    order = [2, 0, 1]
    p, v, _, q, a, c, d, dist, closing = eng.slow._touching(order)
    want = []
    for k, b in enumerate(order):
        live = eng.balls.state[b] != POCKETED
        for i in range(N):
            for j in range(N):
                h = np.hypot(*(p[k, j] - p[k, i]))
                reach = radius[b, i] + radius[b, j]
                if i != j and live[i] and live[j] and h - reach < CLUSTER_GAP:
                    want.append((k, i, j, h))
    got = list(zip(q.tolist(), a.tolist(), c.tolist(), dist.tolist(), strict=True))
    assert got == want
    pairs = {(x, y, z) for x, y, z, _ in got}
    assert all((k, 15, 19) in pairs and (k, 16, 20) not in pairs for k in range(3))
    assert (0, 23, 24) in pairs and not any(x == 2 and 3 in (y, z) for x, y, z in pairs)
    assert d.tobytes() == (p[q, c] - p[q, a]).tobytes()
    assert closing.tobytes() == (-((v[q, c] - v[q, a]) * d).sum(axis=1) / dist).tobytes()
