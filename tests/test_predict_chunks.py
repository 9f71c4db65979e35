"""Predictions renewed in chunks of rows (schedule.CHUNK) are those renewed in one piece, bit for
bit, on the geometry games are made of: racks of frozen balls, balls exactly two radii apart
closing, parting and at rest, straight lines of balls, pocketed balls; and chunking bounds the
memory a renewal of many balls takes."""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest

from termpool.physics import schedule
from termpool.physics.engine import Engine
from termpool.physics.params import BALL_RADIUS, Physics
from termpool.physics.state import POCKETED
from termpool.physics.table import Table
from termpool.scene import load_scene

R = BALL_RADIUS


def _tables():
    """(scene, pos, vel) of six tables of the 8-ball rack: the break; a ball frozen to the
    rack's apex closing on it; a straight line of balls exactly 2R apart hit end on; two balls
    exactly 2R apart parting and two closing; slow balls pressed into the rack; a rack with
    nothing moving."""
    scene = load_scene({"balls": "8ball", "shot": {"speed": 8.0}})
    n = len(scene.ids)
    cue, apex = scene.index("cue"), scene.index("1")
    B = 6
    pos = np.broadcast_to(scene.pos, (B, n, 2)).copy()
    vel = np.zeros((B, n, 2))
    vel[0] = scene.vel
    pos[1, cue] = pos[1, apex] - [2 * R, 0.0]  # frozen to the apex, pushing into it
    vel[1, cue] = [0.3, 0.0]
    line = [k for k in range(n) if k != cue][:6]  # a straight line down the table's middle
    for m, k in enumerate(line):
        pos[2, k] = [1.0 + 2 * R * m, 0.635]
    pos[2, cue] = [1.0 - 2 * R, 0.635]
    vel[2, cue] = [2.0, 0.0]
    pos[3, cue], pos[3, apex] = [0.6, 0.3], [0.6 + 2 * R, 0.3]
    vel[3, cue] = [-0.5, 0.0]  # parting
    k2, k3 = line[4], line[5]
    pos[3, k2], pos[3, k3] = [0.6, 0.9], [0.6, 0.9 + 2 * R]
    vel[3, k2] = [0.0, 0.05]  # closing, slowly
    vel[4, line[:4]] = [[-0.01, 0.0], [0.0, 0.004], [0.0, -0.004], [-0.02, 0.001]]
    vel[4, cue] = [0.0, 0.0]
    return scene, pos, vel


def _engine(scene, pos, vel, chunk, monkeypatch) -> Engine:
    monkeypatch.setattr(schedule, "CHUNK", chunk)
    eng = Engine(scene.table, scene.physics, pos, vel, None, scene.radius, scene.mass)
    monkeypatch.undo()
    return eng


@pytest.mark.parametrize("chunk", [1, 5 * 16, 7 * 16 + 3])
def test_predictions_in_chunks_match_one_piece_bit_for_bit(chunk, monkeypatch):
    """Construction renews every ball's predictions (96 rows): in chunks of one, five and
    seven rows the times and features are the same bits as in one piece, and so is every
    renewal after it, up to rest."""
    scene, pos, vel = _tables()
    calls = []
    real = schedule.Schedule._predict_rows

    def counted(self, b, *args):
        calls.append(b.size)
        return real(self, b, *args)

    monkeypatch.setattr(schedule.Schedule, "_predict_rows", counted)
    small = _engine(scene, pos, vel, chunk, monkeypatch)
    monkeypatch.setattr(schedule.Schedule, "_predict_rows", counted)
    assert max(calls) == max(1, chunk // 16) and len(calls) > 1  # it did cut
    calls.clear()
    whole = _engine(scene, pos, vel, 10 ** 9, monkeypatch)
    assert calls == [96]
    s, w = small.schedule, whole.schedule
    assert s.times.tobytes() == w.times.tobytes()
    assert np.array_equal(s.f_cush, w.f_cush)
    assert (w.t_pair == 0).sum() >= 2  # the frozen, closing pairs meet now
    assert np.isfinite(w.t_pair[2]).any()  # the line's contacts ahead
    # Renewing every ball again at a later clock, some pocketed, all tables at once.
    for eng in (small, whole):
        eng.tb[:] = 0.05
        eng.state[5, 3] = POCKETED
        b, i = np.divmod(np.arange(eng.B * eng.N), eng.N)
        with np.errstate(all="ignore"):
            eng.schedule.predict_many(b, i)
    assert s.times.tobytes() == w.times.tobytes()
    assert np.array_equal(s.f_cush, w.f_cush)


def test_a_batch_run_with_small_chunks_is_the_run_in_one_piece(monkeypatch):
    """Every pass renews predictions in chunks of one row: the same events, passes and final
    tables as with the default chunk, bit for bit."""
    scene, pos, vel = _tables()
    runs = []
    for chunk in (1, schedule.CHUNK):
        eng = _engine(scene, pos, vel, chunk, monkeypatch)
        eng.run_events()
        runs.append(eng)
    a, b = runs
    assert a.at_rest().all() and a.passes == b.passes
    assert a.pos.tobytes() == b.pos.tobytes() and a.state.tobytes() == b.state.tobytes()
    assert a.events == b.events


def test_chunks_bound_the_memory_of_a_big_renewal(monkeypatch):
    """Renewing 512 tables' balls at once: the chunked renewal's peak allocation is a small
    part of the one-piece renewal's, which grows with the batch."""
    scene = load_scene({"balls": "8ball", "shot": {"speed": 8.0}})
    B, n = 512, len(scene.ids)
    rng = np.random.default_rng(7)
    pos = np.broadcast_to(scene.pos, (B, n, 2)).copy()
    vel = rng.normal(0.0, 0.5, (B, n, 2))  # every ball moving: every pair a candidate
    peaks = []
    for chunk in (schedule.CHUNK, 10 ** 9):
        eng = _engine(scene, pos, vel, chunk, monkeypatch)
        b, i = np.divmod(np.arange(B * n), n)
        tracemalloc.start()
        with np.errstate(all="ignore"):
            eng.schedule.predict_many(b, i)
        peaks.append(tracemalloc.get_traced_memory()[1])
        tracemalloc.stop()
    chunked, whole = peaks
    assert chunked * 3 < whole


def test_renewing_many_balls_at_once_is_renewing_them_one_by_one(monkeypatch):
    """All balls of the six tables renewed in one call, some listed twice (an event's ball is
    also its cluster's): the same times and features, bit for bit, as renewing each ball alone
    in plain floats, in turn. A pair of renewed balls is met once in the call, and each
    alone meets it from its own side: both sides give the same bits. (Where a pair meets
    now, pairs that cannot meet at the clock wait, `Schedule._later`: made, they are the
    same too.)"""
    scene, pos, vel = _tables()
    many, one = (_engine(scene, pos, vel, schedule.CHUNK, monkeypatch) for _ in range(2))
    B, n = many.B, many.N
    b, i = np.divmod(np.arange(B * n), n)
    twice = np.array([0, 5, 17, 40, 95])
    for eng in (many, one):
        eng.tb[:] = 0.01 * np.arange(B)
    with np.errstate(all="ignore"):
        many.schedule.predict_many(np.concatenate([b, b[twice]]), np.concatenate([i, i[twice]]))
        assert many.schedule.pending  # the frozen pairs meet now: some pairs wait
        many.schedule.complete(force=True)
        for bb, ii in zip(b.tolist(), i.tolist(), strict=True):
            one.schedule.predict_few(np.array([bb]), np.array([ii]))
    assert many.schedule.times.tobytes() == one.schedule.times.tobytes()
    assert np.array_equal(many.f_cush, one.f_cush)
    assert np.isfinite(many.schedule.t_pair).sum() > 20


def _alone(scene, pos, vel) -> Engine:
    return Engine(scene.table, scene.physics, pos, vel, None, scene.radius, scene.mass)


def test_one_table_renewing_all_its_balls_in_floats_matches_the_arrays_bit_for_bit(monkeypatch):
    """Each of the six tables alone (one table renews a cluster's balls in plain floats):
    every ball renewed in one call, some listed twice, at a clock past the start, gives the
    same times and features, bit for bit, in plain floats (`predict_few`, and `predict`'s
    choice for one table) as in arrays (`predict_many`), pairs of renewed balls included."""
    scene, pos, vel = _tables()
    n = len(scene.ids)
    i = np.concatenate([np.arange(n), [0, 5, 11]])
    b = np.zeros(i.size, dtype=np.int64)
    finite = 0
    for k in range(len(pos)):
        engines = [_alone(scene, pos[k], vel[k]) for _ in range(3)]
        for eng, way in zip(engines, ("predict_few", "predict", "predict_many"), strict=True):
            eng.tb[0] = 0.01 * (k + 1)
            with np.errstate(all="ignore"):
                getattr(eng.schedule, way)(b, i)
        few, chosen, many = engines
        assert few.schedule.times.tobytes() == many.schedule.times.tobytes()
        assert chosen.schedule.times.tobytes() == many.schedule.times.tobytes()
        assert np.array_equal(few.f_cush, many.f_cush)
        finite += int(np.isfinite(many.schedule.t_pair).sum())
    assert finite > 20


def _outcome(eng: Engine, samples) -> tuple:
    return (eng.pos.tobytes(), eng.vel.tobytes(), eng.w.tobytes(), eng.state.tobytes(),
            eng.events, eng.passes, [(t, p.tobytes(), s.tobytes()) for t, p, s in samples])


@pytest.mark.parametrize("dt", [None, 1 / 60])
def test_one_table_runs_the_same_with_its_clusters_renewed_in_arrays(dt, monkeypatch):
    """The six tables and the break, each alone, run to rest with the one-table paths
    (plain-float renewals of clusters, the event loop in plain numbers) and with every
    renewal of more than a few balls in arrays: the same positions, velocities, spins,
    states, events and samples, bit for bit."""
    scene, pos, vel = _tables()
    runs = []
    for plain in (schedule.PLAIN_MAX, 0):
        monkeypatch.setattr(schedule, "PLAIN_MAX", plain)
        out = []
        for k in range(len(pos)):
            eng = _alone(scene, pos[k], vel[k])
            samples = eng.run_events(sample_hz=30) if dt is None else eng.run(dt, sample_hz=30)
            out.append(_outcome(eng, samples))
        runs.append(out)
    monkeypatch.undo()
    assert runs[0] == runs[1]
    assert sum(len(o[4][0]) for o in runs[0]) > 100  # events were run


@pytest.mark.parametrize("dt", [None, 1 / 60])
def test_one_table_alone_runs_as_it_does_in_a_batch_bit_for_bit(dt):
    """The six tables run alone (the one-table event loop: plain numbers, its event's arrays
    made once, clusters renewed in plain floats) and together in one batch (the array
    paths): each table ends with the same positions, velocities, spins and states, and the
    same events, bit for bit."""
    scene, pos, vel = _tables()
    batch = Engine(scene.table, scene.physics, pos, vel, None, scene.radius, scene.mass)
    batch.run_events() if dt is None else batch.run(dt)
    for k in range(len(pos)):
        eng = _alone(scene, pos[k], vel[k])
        eng.run_events() if dt is None else eng.run(dt)
        for name in ("pos", "vel", "w", "state"):
            assert getattr(eng, name)[0].tobytes() == getattr(batch, name)[k].tobytes(), name
        assert eng.events[0] == batch.events[k]


def test_a_renewals_balls_and_tables_are_numbered_as_np_unique_numbers_them():
    """A renewal names a ball at most once, the first time it is named, and numbers its
    tables in order, as np.unique would (a ball named twice: an event's, and its cluster's)."""
    rng = np.random.default_rng(30)
    eng = Engine(Table(), Physics(), np.zeros((40, 3, 2)) + [[0.5, 0.5], [1.0, 0.5], [1.5, 0.5]])
    for size in (2, 3, 50, 400):
        key = rng.integers(0, 120, size)  # repeats, in any order
        key[rng.random(size) < 0.3] = key[0]
        want = np.unique(key, return_index=True)[1]
        want.sort()
        assert schedule._firsts(key).tolist() == want.tolist()
        b = key // 3
        tabs, u = eng.schedule._tables(b)
        want_tabs, want_u = np.unique(b, return_inverse=True)
        assert tabs.tolist() == want_tabs.tolist() and u.tolist() == want_u.tolist()
    assert not eng.schedule._place.any()  # (its marks cleared for the next renewal)
