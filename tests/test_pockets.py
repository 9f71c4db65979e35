"""Pocket geometry over the whole allowed range: whatever mouths, jaws and holes a scene may
give, a ball shot into a pocket falls in or stays on the table; it never passes through the
jaws, or between them past the hole, and rolls off. (Geometries that could let a ball through
are refused by the scene: tests/test_scene.py.)"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from termpool.physics.engine import POCKETED, Engine
from termpool.physics.params import Physics
from termpool.physics.table import Table
from termpool.scene import RADIUS_RANGE, TABLE_RANGES, SceneError, load_scene

POCKET_KEYS = [k for k in TABLE_RANGES if k not in ("length", "width")]


def _cross(p1, p2, q1, q2):
    """Where segments p1p2 and q1q2 cross, or None."""
    d, e, w = p2 - p1, q2 - q1, q1 - p1
    den = d[0] * e[1] - d[1] * e[0]
    if den == 0:
        return None
    s = (w[0] * e[1] - w[1] * e[0]) / den
    u = (w[0] * d[1] - w[1] * d[0]) / den
    return p1 + s * d if 0 <= s <= 1 and 0 <= u <= 1 else None


def _inside(pt, poly) -> bool:
    """Even-odd rule: pt within the simple polygon poly."""
    x, y = pt
    inside = False
    for k in range(len(poly)):
        (x1, y1), (x2, y2) = poly[k], poly[k - 1]
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside


def channels(tab: Table) -> list[list[np.ndarray]]:
    """Each pocket's channel: the region between its two jaws, from the tips on the rail
    noses to the jaws' ends (to where the jaws cross, if they do)."""
    jaws = [k for k, kind in enumerate(tab.seg_kind) if kind == "jaw"]
    out = []
    for k in range(len(tab.hole_names)):
        a, b = jaws[2 * k], jaws[2 * k + 1]
        t1, e1, t2, e2 = tab.seg_a[a], tab.seg_b[a], tab.seg_a[b], tab.seg_b[b]
        x = _cross(t1, e1, t2, e2)
        out.append([t1, x, t2] if x is not None else [t1, e1, e2, t2])
    return out


def in_play(tab: Table, chans, x: float, y: float, tol: float = 1e-6) -> bool:
    """A ball's centre on the table: within the cushion noses, in a pocket's channel or
    over a hole."""
    if -tol <= x <= tab.length + tol and -tol <= y <= tab.width + tol:
        return True
    if (np.hypot(*(tab.hole_c - np.array([x, y])).T) <= tab.hole_r + tol).any():
        return True
    return any(_inside((x, y), c) for c in chans)


def test_the_oracle_tells_the_table_from_the_floor() -> None:
    tab = Table()
    chans = channels(tab)
    assert in_play(tab, chans, 1.0, 0.5) and in_play(tab, chans, 0.0, 0.0)
    assert in_play(tab, chans, tab.length / 2, -0.01)  # between the side pocket's jaws
    assert not in_play(tab, chans, 1.0, -0.01)  # behind a rail
    assert not in_play(tab, chans, -1.24, 0.06)  # where a ball once came to rest
    assert not in_play(tab, chans, tab.length / 2 + 0.2, -0.03)


def test_a_ball_reaching_a_corner_hole_inside_the_rail_lines_falls_in_there() -> None:
    """A corner hole reaches into the bed past the rail lines: a small ball rolling slowly
    into the corner meets the hole's edge far from any rail, and falls in as its centre
    crosses it (it used to roll on over the hole and stop there, never pocketed)."""
    tab = Table()
    r, k = 0.005, tab.hole_names.index("head_right")
    u = -np.array([1.0, 1.0]) / math.sqrt(2)  # into the corner
    start = np.array([0.045, 0.045])
    speed = 0.05
    eng = Engine(tab, Physics(), [start], [speed * u], [[*(np.array([-u[1], u[0]]) * speed / r),
                                                         0.0]], radius=r)
    eng.run(1 / 60)
    assert eng.state[0, 0] == POCKETED and eng.pocket[0, 0] == k
    ev = next(e for e in eng.events[0] if e["type"] == "pocket")
    # When the centre crosses the edge, at the rolling law's time.
    gap = math.hypot(*(start - tab.hole_c[k])) - tab.hole_r[k]
    a = Physics().mu_roll * Physics().g
    assert ev["t"] == pytest.approx((speed - math.sqrt(speed * speed - 2 * a * gap)) / a,
                                    rel=1e-9)


geometry = st.dictionaries(
    st.sampled_from(POCKET_KEYS),
    st.one_of(*(st.sampled_from(TABLE_RANGES[k]) for k in POCKET_KEYS),
              st.floats(0.0, 1.0), st.floats(0.0, 0.15), st.floats(1.0, 180.0)),
    max_size=4)
size = st.one_of(st.just({}), st.sampled_from([{"preset": "7ft"}, {"preset": "8ft"}]),
                 st.fixed_dictionaries({"length": st.floats(0.5, 4.0),
                                        "width": st.floats(0.3, 2.0)}))


@settings(max_examples=80, deadline=None,
          suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])
@given(size=size, pockets=geometry, pocket=st.integers(0, 5), data=st.data())
def test_a_ball_shot_into_any_allowed_pocket_falls_in_or_stays_on_the_table(size, pockets,
                                                                            pocket, data):
    """An object ball in front of a pocket, struck into it (straight or cut, at any speed and
    spin) by a cue ball of any allowed size: at every step and every event both balls are on
    the table or in a hole, and when all is still each is pocketed or on the table."""
    table = {**size, **pockets}
    r = data.draw(st.sampled_from([RADIUS_RANGE[0], 0.01, 0.028575, 0.05]), label="radius")
    try:
        tab = load_scene({"table": table, "balls": [{"x": 0.05, "y": 0.05,
                                                     "radius": 0.001}]}).table
    except SceneError:
        assume(False)
    mid = (tab.points[2 * pocket] + tab.points[2 * pocket + 1]) / 2  # the mouth's middle
    inward = np.array([tab.length / 2, tab.width / 2]) - mid
    inward /= np.hypot(*inward)
    back = data.draw(st.floats(2.0, 6.0), label="object ball, radii from the mouth")
    obj = mid + back * r * inward
    cut = math.radians(data.draw(st.floats(-40.0, 40.0), label="cut"))
    c, s = math.cos(cut), math.sin(cut)
    to_obj = np.array([c * -inward[0] - s * -inward[1], s * -inward[0] + c * -inward[1]])
    cue = obj - to_obj * (2 * r + data.draw(st.floats(0.01, 0.5), label="cue distance"))
    aim = math.degrees(math.atan2(*(obj - cue)[::-1]))
    shot = {"speed": data.draw(st.floats(0.05, 25.0), label="speed"),
            "angle": aim + data.draw(st.floats(-3.0, 3.0), label="aim error"),
            "side": data.draw(st.floats(-0.35, 0.35), label="side"),
            "top": data.draw(st.floats(-0.35, 0.35), label="top")}
    balls = [{"id": "cue", "x": float(cue[0]), "y": float(cue[1]), "radius": r},
             {"id": "1", "x": float(obj[0]), "y": float(obj[1]), "radius": r}]
    try:
        sc = load_scene({"table": table, "balls": balls, "shot": shot})
    except SceneError:
        assume(False)  # a ball that does not fit there
    eng = Engine(sc.table, sc.physics, sc.pos, sc.vel, sc.w, sc.radius, sc.mass)
    chans = channels(sc.table)
    seen = 0
    while not eng.at_rest().all() and eng.time < 120.0:  # side spin may last 70 s
        eng.step(1 / 60)
        states = [(eng.time, i, float(x), float(y))
                  for i, (x, y) in enumerate(eng.pos[0]) if eng.state[0, i] != POCKETED]
        states += [(ev["t"], i, b["x"], b["y"]) for ev in eng.events[0][seen:]
                   for i, b in zip(ev["i"], ev["balls"], strict=False)
                   if b["state"] != "pocketed"]
        seen = len(eng.events[0])
        for t, i, x, y in states:
            assert in_play(sc.table, chans, x, y), f"ball {i} off the table at ({x}, {y}), t={t}"
    assert eng.at_rest().all()
