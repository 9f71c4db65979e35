"""The renewals' cheap culls (a ball's path boxed over its window, `motion.swept`; pairs,
cushion points and segments its box stays apart from skipped) change no prediction: with
them and without them the times and features are the same bits, on the geometry games are
made of (racks of frozen balls, balls exactly two radii apart closing, parting and at rest,
straight lines, balls exactly on a rail and in a pocket's mouth), and they do skip most pairs
of a break."""

from __future__ import annotations

import numpy as np
import pytest

from termpool.physics import schedule
from termpool.physics.engine import Engine
from termpool.physics.motion import swept
from termpool.physics.params import BALL_RADIUS
from termpool.physics.state import POCKETED
from termpool.scene import load_scene

R = BALL_RADIUS


def _sampled(p, v, a, T, n=4001):
    s = np.linspace(0.0, 1.0, n) * T
    return p + v * s + 0.5 * a * s * s


@pytest.mark.parametrize("p, v, a, T", [
    (0.5, 2.0, -1.0, 3.0),  # turns inside the window: the vertex is the top
    (0.5, 2.0, -1.0, 1.0),  # turns after it: the end is
    (0.5, -2.0, 1.0, 3.0),  # turns at the bottom
    (0.5, 0.0, 0.0, 5.0),  # at rest
    (0.5, 1.5, 0.0, 2.0),  # straight
    (0.5, 0.0, -3.0, 2.0),  # from rest
    (0.5, 2.0, -1.0, 0.0),  # an empty window
])
def test_swept_box_is_the_range_of_the_path(p, v, a, T):
    """The box is the path's range over the window: every point of the path is in it, and
    its ends are points of the path (closed form: ends and vertex)."""
    with np.errstate(all="ignore"):  # (as the engine runs it: no vertex is a nan)
        lo, hi = swept(np.array(p), np.array(v), np.array(a), np.array(T))
    x = _sampled(p, v, a, T)
    assert lo <= x.min() + 1e-12 and hi >= x.max() - 1e-12
    assert x.min() - lo < 1e-6 and hi - x.max() < 1e-6


def test_swept_boxes_of_random_paths_hold_them():
    rng = np.random.default_rng(3)
    p, v, a = rng.normal(0, 1, (3, 500))
    T = rng.uniform(0.0, 4.0, 500)
    with np.errstate(all="ignore"):
        lo, hi = swept(p, v, a, T)
    x = _sampled(p[:, None], v[:, None], a[:, None], T[:, None], n=2001)
    # (to rounding: the samples are worked out another way)
    assert (lo <= x.min(axis=1) + 1e-12).all() and (hi >= x.max(axis=1) - 1e-12).all()
    assert (x.min(axis=1) - lo < 1e-5).all() and (hi - x.max(axis=1) < 1e-5).all()


def _tables():
    """(scene, pos, vel) of tables of the 8-ball rack: the break; a ball frozen to the apex
    closing on it; a straight line of balls exactly 2R apart hit end on; two pairs exactly 2R
    apart, one parting, one closing; balls frozen to a rail, one rolling along it and one
    into it; a ball in a pocket's mouth, one heading into a corner and one into a jaw tip;
    a rack with nothing moving."""
    scene = load_scene({"balls": "8ball", "shot": {"speed": 8.0}})
    tab = scene.table
    n = len(scene.ids)
    cue, apex = scene.index("cue"), scene.index("1")
    B = 7
    pos = np.broadcast_to(scene.pos, (B, n, 2)).copy()
    vel = np.zeros((B, n, 2))
    vel[0] = scene.vel
    pos[1, cue] = pos[1, apex] - [2 * R, 0.0]
    vel[1, cue] = [0.3, 0.0]
    line = [k for k in range(n) if k != cue][:6]
    for m, k in enumerate(line):
        pos[2, k] = [1.0 + 2 * R * m, 0.635]
    pos[2, cue] = [1.0 - 2 * R, 0.635]
    vel[2, cue] = [2.0, 0.0]
    pos[3, cue], pos[3, apex] = [0.6, 0.3], [0.6 + 2 * R, 0.3]
    vel[3, cue] = [-0.5, 0.0]
    k2, k3 = line[4], line[5]
    pos[3, k2], pos[3, k3] = [0.6, 0.9], [0.6, 0.9 + 2 * R]
    vel[3, k2] = [0.0, 0.05]
    # Frozen to the bottom rail: centres exactly a nose reach from its line (found from the
    # engine's own rail line, y = 0 side), one at rest, one rolling along, one into it.
    eng = Engine(tab, scene.physics, scene.pos, None, None, scene.radius, scene.mass)
    rc = float(eng.rc[0, 0])
    y0 = float(eng.features.seg_off[np.argmax(eng.features.table.seg_n[:, 1])]) + rc
    pos[4, line[:3]] = [[0.9, y0], [0.9 + 2 * R, y0], [1.5, y0]]
    vel[4, line[2]] = [-0.6, 0.0]
    pos[4, line[3]] = [2.0, y0]  # on the rail, pressed into it as it rolls along: met now
    vel[4, line[3]] = [0.3, -0.01]
    pos[4, cue] = [0.9 + R, y0 + 0.3]
    vel[4, cue] = [0.0, -1.0]
    corner = tab.hole_c[0]
    pos[5, cue] = corner + [0.05, 0.05]
    vel[5, cue] = [-0.4, -0.4]
    pos[5, apex] = corner + [0.3, 0.3]
    vel[5, apex] = [-1.0, -1.0]
    pos[5, line[0]] = tab.points[4] + [-0.01, 0.1]  # into a side pocket's jaw tip
    vel[5, line[0]] = [0.0, -1.0]
    return scene, pos, vel


def _renew_all(eng: Engine, t: float) -> tuple:
    """Every ball of every table renewed at clock t: the times and features (with the
    pairs and cushions that could wait for a later pass made too)."""
    eng.tb[:] = t
    b, i = np.divmod(np.arange(eng.B * eng.N), eng.N)
    with np.errstate(all="ignore"):
        eng.schedule.predict_many(b, i)
        eng.schedule.complete(force=True)
    return eng.schedule.times.tobytes(), eng.f_cush.tobytes()


def _counted(monkeypatch, name: str, cols: slice = slice(None)) -> list:
    """(kept, all) of each later call of Schedule's cull `name`, in its columns `cols`."""
    kept = []
    real = getattr(schedule.Schedule, name)

    def counted(self, *args):
        out = real(self, *args)
        kept.append((int(out[..., cols].sum()), out[..., cols].size))
        return out

    monkeypatch.setattr(schedule.Schedule, name, counted)
    return kept


@pytest.mark.parametrize("t", [0.0, 0.013, 0.05])
def test_culled_renewals_are_the_renewals_without_the_cull_bit_for_bit(t, monkeypatch):
    """Every ball of every table renewed, some pocketed: with the boxes' cull and with every
    pair and cushion point kept, the same times and features, bit for bit; the cull skipped
    most pairs and points, and contacts (frozen ones at once) were found."""
    scene, pos, vel = _tables()
    engines = [Engine(scene.table, scene.physics, pos, vel, None, scene.radius, scene.mass)
               for _ in range(2)]
    for eng in engines:
        eng.state[6, 3] = POCKETED
    nseg = engines[0].features.nseg  # (the features' cull: the segments, then the points)
    pairs = _counted(monkeypatch, "_overlap")
    segments = _counted(monkeypatch, "_near_features", slice(None, nseg))
    points = _counted(monkeypatch, "_near_features", slice(nseg, None))
    culled = _renew_all(engines[0], t)
    monkeypatch.setattr(schedule, "CULL", False)
    whole = _renew_all(engines[1], t)
    assert culled == whole
    assert sum(k for k, _ in pairs) * 2 < sum(n for _, n in pairs)
    assert sum(k for k, _ in points) * 2 < sum(n for _, n in points)
    if t == 0.0:  # (later, a few balls: lines_one's own cull)
        assert sum(k for k, _ in segments) * 2 < sum(n for _, n in segments)
    tp = engines[0].schedule.t_pair
    assert (tp == t).sum() >= 2 and np.isfinite(tp).sum() > 20
    eng = engines[0]
    f = eng.f_cush[np.isfinite(eng.t_cush)]
    assert ((f >= eng.features.nseg) & (f < eng.features.first_hole)).any()  # a tip met
    assert (f < eng.features.nseg).any()  # and a rail or jaw


def test_a_batch_run_with_the_cull_is_the_run_without_it(monkeypatch):
    """The tables run to rest in one batch: with the cull and without it the same events,
    passes and final tables, bit for bit."""
    scene, pos, vel = _tables()
    runs = []
    for cull in (True, False):
        monkeypatch.setattr(schedule, "CULL", cull)
        eng = Engine(scene.table, scene.physics, pos, vel, None, scene.radius, scene.mass)
        eng.run_events()
        runs.append(eng)
    a, b = runs
    assert a.at_rest().all() and a.passes == b.passes
    assert a.pos.tobytes() == b.pos.tobytes() and a.state.tobytes() == b.state.tobytes()
    assert a.events == b.events
