"""A batch's renewals at an instant where a pair meets now leave the pairs and cushions that
cannot meet at that instant for later (`Schedule._later`), and make them when the table's
clock is to move (`Schedule.complete`). The runs are the runs that make every prediction at
once, pass by pass and bit for bit, on the geometry a break is made of: straight breaks at
every power, frozen balls, lines of balls exactly 2R apart, rows frozen to a rail."""

from __future__ import annotations

import numpy as np
import pytest

from termpool.physics import schedule
from termpool.physics.engine import Engine, WorkLimit
from termpool.physics.params import BALL_RADIUS, Physics
from termpool.scene import MAX_SPEED, load_scene
from tests.test_predict_chunks import _tables
from tests.test_slow_many import _on_the_rails


def _breaks() -> tuple:
    """Straight breaks at 16 powers from a tap to the fastest shot a scene may give: the
    cue ball on the head spot aimed dead at the apex of a frozen rack."""
    sc = load_scene({"balls": "8ball", "shot": {"speed": 1.0}})
    speeds = np.linspace(0.25, MAX_SPEED, 16)
    pos = np.broadcast_to(sc.pos, (16,) + sc.pos.shape).copy()
    vel = sc.vel[None] * speeds[:, None, None]
    w = sc.w[None] * speeds[:, None, None]
    return sc.table, sc.physics, pos, vel, w


def _frozen() -> tuple:
    """The six tables of frozen racks, lines exactly 2R apart and pressed balls."""
    sc, pos, vel = _tables()
    return sc.table, sc.physics, pos, vel, None


def _rails() -> tuple:
    """Rows frozen to a rail and each other, met slowly, and on four more tables met by a
    ball rolling in at 1 to 4 m/s."""
    table, pos, vel, w = _on_the_rails(8)
    fast = np.linspace(1.0, 4.0, 4)
    vel[4:, 0, 0] = fast
    w[4:, 0, 1] = fast / BALL_RADIUS  # rolling
    return table, Physics(), pos, vel, w


def _run(make, later: bool) -> tuple[Engine, list]:
    """Run to rest, leaving pairs for later or not: the engine and each pass's events."""
    table, physics, pos, vel, w = make()
    eng = Engine(table, physics, pos, vel, w)
    eng.schedule.defer = later
    passes = []
    real = eng._handle

    def handle(tabs, code):
        passes.append((tabs.tobytes(), code.tobytes()))
        real(tabs, code)

    eng._handle = handle
    eng.run_events()
    return eng, passes


@pytest.mark.parametrize("make", [_breaks, _frozen, _rails], ids=["breaks", "frozen", "rails"])
def test_leaving_pairs_for_later_runs_as_making_every_prediction_at_once(make, monkeypatch):
    """Every pass handles the same events of the same tables, and the tables end the same,
    bit for bit; and pairs and cushions were left for later on the way."""
    waited = []
    real = schedule.Schedule._wait

    def wait(self, b, i):
        waited.append(b.size)
        real(self, b, i)

    monkeypatch.setattr(schedule.Schedule, "_wait", wait)
    later, later_passes = _run(make, True)
    assert sum(waited) > 0
    monkeypatch.undo()
    now, now_passes = _run(make, False)
    assert later_passes == now_passes
    assert later.at_rest().all() and not later.schedule.pending
    for name in ("pos", "vel", "w", "state"):
        assert getattr(later, name).tobytes() == getattr(now, name).tobytes()
    assert later.events == now.events


def test_what_waits_is_never_met_at_the_clock(monkeypatch):
    """Each prediction `complete` makes for a ball whose pairs waited is later than its
    table's clock: waiting could not have changed which event came next."""
    made = []
    real = schedule.Schedule.complete

    def complete(self, force=False):
        tables, late = self._late_tables.copy(), self._late.copy()
        before = self.times.copy()
        real(self, force)
        N = self.N
        for b in np.flatnonzero(tables & ~self._late_tables):
            pairs = np.zeros((N, N), dtype=bool)  # of a ball whose pairs waited
            pairs[late[b]] = pairs[:, late[b]] = True
            cushions = np.zeros(N, dtype=bool)
            cushions[late[b]] = True
            was, now = before[b], self.times[b]
            gained = np.isinf(was) & np.isfinite(now) & np.concatenate(
                [np.zeros(2 * N, dtype=bool), cushions, pairs.ravel()])
            made.append(int(gained.sum()))
            assert (now[gained] > self.tb[b]).all()

    monkeypatch.setattr(schedule.Schedule, "complete", complete)
    for make in (_breaks, _frozen, _rails):
        _run(make, True)
    assert sum(made) > 10


def test_a_work_limit_in_a_cascade_leaves_every_prediction_made(monkeypatch):
    """The work limit met among the breaks' contacts at the impact's instant, with pairs
    waiting: the engine stops with every prediction made, as if none had waited."""
    table, physics, pos, vel, w = _breaks()
    probe = Engine(table, physics, pos, vel, w)
    works = []
    real_handle = probe._handle

    def handle(tabs, code):
        works.append(probe.work)
        real_handle(tabs, code)

    probe._handle = handle
    probe.run_events()
    forced = []
    real = schedule.Schedule.complete

    def complete(self, force=False):
        if force:
            forced.append(self.pending)
        real(self, force)

    monkeypatch.setattr(schedule.Schedule, "complete", complete)
    stopped = []
    for later in (True, False):
        eng = Engine(table, physics, pos, vel, w, max_work=works[20])  # 20 passes in
        eng.schedule.defer = later
        with pytest.raises(WorkLimit):
            eng.run_events()
        stopped.append(eng)
    assert forced == [True]  # pairs were waiting when the limit was met
    a, b = stopped
    assert a.passes == b.passes and not a.schedule.pending
    assert a.schedule.times.tobytes() == b.schedule.times.tobytes()
    assert a.t_next.tobytes() == b.t_next.tobytes()
