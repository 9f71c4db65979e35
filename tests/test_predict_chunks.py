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
from termpool.physics.params import BALL_RADIUS
from termpool.physics.state import POCKETED
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
    alone meets it from its own side: both sides give the same bits."""
    scene, pos, vel = _tables()
    many, one = (_engine(scene, pos, vel, schedule.CHUNK, monkeypatch) for _ in range(2))
    B, n = many.B, many.N
    b, i = np.divmod(np.arange(B * n), n)
    twice = np.array([0, 5, 17, 40, 95])
    for eng in (many, one):
        eng.tb[:] = 0.01 * np.arange(B)
    with np.errstate(all="ignore"):
        many.schedule.predict_many(np.concatenate([b, b[twice]]), np.concatenate([i, i[twice]]))
        for bb, ii in zip(b.tolist(), i.tolist(), strict=True):
            one.schedule.predict_few(np.array([bb]), np.array([ii]))
    assert many.schedule.times.tobytes() == one.schedule.times.tobytes()
    assert np.array_equal(many.f_cush, one.f_cush)
    assert np.isfinite(many.schedule.t_pair).sum() > 20
