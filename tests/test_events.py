"""The engine's typed events (physics/events.py): the log, its JSON form, and the rules reading
either."""

from __future__ import annotations

import numpy as np
import pytest

from termpool.physics.engine import Engine
from termpool.physics.events import ENDS, Event, EventKind
from termpool.physics.state import POCKETED, STATE_NAMES
from termpool.rules.events import summarize
from termpool.scene import load_scene


def _breaks():
    """Breaks from several spots and speeds with spin, batched: pockets, rails, jaws, tips."""
    sc = load_scene({"table": "9ft", "balls": "8ball", "shot": {"speed": 8.0, "angle": 0}})
    rng = np.random.default_rng(21)
    B = 12
    pos = np.repeat(sc.pos[None], B, axis=0)
    pos[:, 0, 1] += rng.uniform(-0.2, 0.2, B)
    vel = np.zeros_like(pos)
    speed, ang = rng.uniform(4.0, 10.0, B), np.radians(rng.uniform(-3.0, 3.0, B))
    vel[:, 0] = np.stack([speed * np.cos(ang), speed * np.sin(ang)], axis=1)
    w = np.zeros(pos.shape[:2] + (3,))
    w[:, 0] = rng.normal(0.0, 80.0, (B, 3))
    eng = Engine(sc.table, sc.physics, pos, vel, w, sc.radius, sc.mass)
    eng.run(1 / 60)
    return sc, eng


@pytest.fixture(scope="module")
def broken():
    return _breaks()


def test_the_json_events_are_the_typed_log_written_out(broken):
    _, eng = broken
    assert eng.events == [[ev.to_json() for ev in log] for log in eng.log]
    kinds = {ev.kind for log in eng.log for ev in log}
    assert {EventKind.BALL_BALL, EventKind.CUSHION, EventKind.POCKET} <= kinds


def test_each_typed_event_says_what_happened_to_which_balls(broken):
    sc, eng = broken
    tab = sc.table
    nseg = len(tab.seg_a)
    for b, log in enumerate(eng.log):
        assert [ev.t for ev in log] == sorted(ev.t for ev in log)
        for ev in log:
            assert isinstance(ev, Event) and ev.table == b
            assert len(ev.states) == len(ev.balls) and len(set(ev.balls)) == len(ev.balls)
            if ev.kind is EventKind.CUSHION:
                assert len(ev.balls) == 1 and ev.pocket is None
                f = ev.cushion
                assert ev.feature == (tab.seg_kind[f] if f < nseg else "tip")
                assert f < nseg + len(tab.points)
            elif ev.kind is EventKind.POCKET:
                assert len(ev.balls) == 1 and ev.cushion is None
                assert ev.pocket in tab.hole_names
                assert ev.states[0].state == POCKETED
                assert int(eng.pocket[b, ev.balls[0]]) == tab.hole_names.index(ev.pocket)
            elif ev.kind is EventKind.BALL_BALL:
                assert len(ev.balls) >= 2
            else:  # a ball's own motion changed state
                assert len(ev.balls) == 1
                name = STATE_NAMES[ev.states[0].state]
                if ev.kind in ENDS.values():
                    ends = [new for (old, new), k in ENDS.items() if k is ev.kind]
                    assert name == STATE_NAMES[ends[0]]


def test_the_rules_read_the_typed_log_as_they_read_the_json(broken):
    sc, eng = broken
    pocketed = 0
    for log, js in zip(eng.log, eng.events, strict=True):
        typed = summarize(log, sc.ids, is_break=True)
        assert typed == summarize(js, sc.ids, is_break=True)
        pocketed += len(typed.pocketed)
    assert pocketed > 0


def test_an_event_with_a_pocket_written_out():
    ev = Event(EventKind.POCKET, 1.5, 0, (3,), (), pocket="foot_left")
    assert ev.to_json() == {"t": 1.5, "type": "pocket", "pocket": "foot_left", "i": [3],
                            "balls": []}
    assert list(ev.to_json()) == ["t", "type", "pocket", "i", "balls"]  # records' key order
