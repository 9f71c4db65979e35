"""The cluster solves of many tables at once (slow_many, joined.push_many, joined.blocks) give
the bits of the one-table solves: contact matrices of several sets of rows against each set's
own, and whole runs with every pass's clusters solved together against one at a time, on
racks, touching triangles, rows of frozen balls and the example and bench scenes."""

from __future__ import annotations

import glob
from pathlib import Path

import numpy as np
import pytest

from termpool.physics import joined
from termpool.physics.cluster import Rows
from termpool.physics.engine import Engine
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
