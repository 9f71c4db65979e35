"""The exact geometry pool is made of: straight breaks at every power, paths that pass a ball
or a jaw tip at exactly the contact distance, frozen balls, balls on one line, balls on a rail.

Random floats almost never produce these, and they are what real play produces all the time.
Besides the laws checked here, every contact the engine applies in these tests is checked to be
between touching bodies (`contact_check.py`, installed for the whole suite by conftest.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from termpool.physics.cue import strike
from termpool.physics.engine import Engine
from termpool.physics.params import BALL_RADIUS, Physics, nose_reach
from termpool.physics.table import Table
from termpool.scene import RACK_ROWS, load_scene

R = BALL_RADIUS
OPEN = Table(length=20.0, width=10.0, pockets="none")  # no cushion in reach


def ball_events(events, kind="ball_ball"):
    return [ev for ev in events if ev["type"] == kind]


@pytest.mark.parametrize("mode", ["8ball", "9ball"])
def test_straight_break_at_every_power_first_hits_the_apex_when_it_reaches_it(mode):
    """The cue ball on the head spot, struck at the apex on the foot spot, runs exactly tangent
    to rack balls behind the apex: at every power from 2 to 14 m/s in steps of 0.1 the first
    contact is with the apex, when the cue ball is 2R short of the foot spot."""
    sc = load_scene({"balls": mode})
    speeds = np.round(np.arange(20, 141) / 10, 1)
    B = len(speeds)
    vel = np.zeros((B, len(sc.ids), 2))
    w = np.zeros((B, len(sc.ids), 3))
    for b, v in enumerate(speeds.tolist()):
        vel[b, 0], w[b, 0] = strike(v, 0.0)
    pos = np.broadcast_to(sc.pos, (B,) + sc.pos.shape)
    eng = Engine(sc.table, sc.physics, pos, vel, w, sc.radius, sc.mass)
    eng.run(1 / 60)
    apex = sc.ids.index(RACK_ROWS[mode][0][0])
    fx, fy = sc.table.foot_spot
    for b, v in enumerate(speeds.tolist()):
        first = ball_events(eng.events[b])[0]
        assert first["i"][:2] == [0, apex], (v, first)
        cue = first["balls"][0]
        # The event logs the balls after the contact; a cue ball left with a sub-mm/s slip
        # starts rolling at once on a path up to 20 nm from the slide (docs/physics.md).
        assert cue["x"] == pytest.approx(fx - 2 * R, abs=2e-8), v
        assert cue["y"] == fy, v  # a straight shot stays on its line, to the bit


def graze(angle: float, side: int, length: float = 0.4, start=(10.0, 5.0)):
    """An object ball placed so that the cue ball's straight path at `angle` passes it at
    exactly 2R, on the left (side = 1) or the right (side = -1)."""
    a = math.radians(angle)
    u = np.array([math.cos(a), math.sin(a)])
    n = np.array([-u[1], u[0]]) * side
    return np.array([start, np.array(start) + length * u + 2 * R * n])


@pytest.mark.parametrize("speed", [0.2, 1.0, 3.0, 8.0, 14.0])
@pytest.mark.parametrize("top", [-0.3, 0.0, 0.4])
def test_a_path_exactly_tangent_to_a_ball_is_no_contact(speed, top):
    """Passing a ball at exactly the contact distance is a tangency with no closing speed:
    no impulse, the object ball stays where it is."""
    for angle in range(0, 360, 15):
        for side in (1, -1):
            pos = graze(float(angle), side)
            v, w = strike(speed, float(angle), 0.0, top)
            eng = Engine(OPEN, Physics(), pos, [v, (0.0, 0.0)], [w, (0.0, 0.0, 0.0)])
            # Until the cue ball could reach a cushion: nothing comes back.
            eng.run_events(duration=min(2.0, 4.5 / speed))
            hits = ball_events(eng.events[0])
            moved = float(np.hypot(*(eng.pos[0, 1] - pos[1])))
            # Rounding can leave the path a hair inside 2R: then the contact is real but
            # negligible. Anything more than a nanometre of push would be a wrong contact.
            assert moved < 1e-9, (angle, side, hits[:1])


@pytest.mark.parametrize("gap_speed", [0.05, 0.5, 3.0])
def test_a_ball_overtaking_another_on_a_line_2r_beside_it_does_not_touch_it(gap_speed):
    """Two balls rolling the same way on parallel lines exactly 2R apart: the faster passes
    the slower, tangent at one instant, and neither is pushed sideways."""
    slow = 1.0
    y0 = 5.0
    pos = [(10.0, y0), (10.3, y0 + 2 * R)]
    (v0, w0), (v1, w1) = strike(slow + gap_speed, 0.0, 0, 0.4), strike(slow, 0.0, 0, 0.4)
    eng = Engine(OPEN, Physics(), pos, [v0, v1], [w0, w1])
    eng.run(1 / 60)
    assert ball_events(eng.events[0]) == []
    assert eng.pos[0, 0, 1] == y0 and eng.pos[0, 1, 1] == y0 + 2 * R


@pytest.mark.parametrize("speed", [0.5, 2.0, 6.0])
def test_a_row_of_balls_on_one_line_stays_on_it(speed):
    """Balls on one straight line, struck along it: every contact is on the line, so nobody
    moves off it by a single bit, and every ball-ball event is between touching balls."""
    y = 5.0
    xs = [2.0, 2.6, 2.6 + 2 * R, 3.3, 3.3 + 2 * R, 3.3 + 4 * R]  # gaps, then frozen groups
    v, w = strike(speed, 0.0, 0.0, 0.2)
    vel = [v] + [(0.0, 0.0)] * (len(xs) - 1)
    spin = [w] + [(0.0, 0.0, 0.0)] * (len(xs) - 1)
    eng = Engine(OPEN, Physics(), [(x, y) for x in xs], vel, spin)
    eng.run(1 / 60)
    assert ball_events(eng.events[0])
    assert (eng.pos[0, :, 1] == y).all()


def rail_runs():
    """A ball frozen to a rail (its centre exactly the nose reach off it) rolling along it
    past each pocket of that rail, both ways."""
    tab = Table()
    rc = float(nose_reach(R, Physics().cushion_height))
    for y, rail in ((rc, "near"), (tab.width - rc, "far")):
        for x, angle in ((0.4, 180.0), (1.0, 0.0), (1.0, 180.0), (2.1, 0.0)):
            yield tab, (x, y), angle, rail


@pytest.mark.parametrize("speed", [0.3, 0.5, 1.5])
def test_a_ball_frozen_to_a_rail_passes_the_jaw_tips_without_touching_them(speed):
    """The tips of a pocket's jaws are on the rail's nose line, so a ball frozen to the rail
    passes them at exactly the contact distance: no cushion event, only the pocket (corner
    pockets) or nothing at all (it rolls on past a side pocket)."""
    for tab, p, angle, _ in rail_runs():
        v, w = strike(speed, angle, 0.0, 0.4)
        eng = Engine(tab, Physics(), [p], [v], [w])
        eng.run(1 / 60)
        kinds = [ev["type"] for ev in eng.events[0]]
        assert "cushion" not in kinds, (p, angle, [e for e in eng.events[0] if "feature" in e])
        # (sin 180 degrees is 1.2e-16 in floats: the path is straight to that.)
        assert eng.pos[0, 0, 1] == pytest.approx(p[1], abs=1e-9) or kinds[-1] == "pocket"


def hex_cluster(n_rows: int, origin: tuple[float, float]) -> list[tuple[float, float]]:
    """Frozen balls on a triangular lattice, every neighbour exactly 2R apart (as racked)."""
    dx = math.sqrt(3.0) * R
    return [(origin[0] + k * dx, origin[1] + (2 * j - k) * R)
            for k in range(n_rows) for j in range(k + 1)]


@settings(max_examples=40, deadline=None)
@given(
    rows=st.integers(2, 4),
    speed=st.sampled_from([0.3, 1.0, 2.5, 5.0, 9.0]),
    aim=st.sampled_from([-2 * R, -R, 0.0, R, 2 * R]),  # straight at a ball, or at a seam
    top=st.sampled_from([-0.3, 0.0, 0.4]),
)
def test_frozen_clusters_hit_on_exact_lines(rows, speed, aim, top):
    """A racked cluster struck on lines through its balls' centres and through the seams
    between them: contacts only between touching balls, no energy gained."""
    tab = Table(length=4.0, width=2.0, pockets="none")
    cluster = hex_cluster(rows, (2.5, 1.0))
    pos = [(2.42, 1.0 + aim)] + cluster  # close enough for the softest shot to arrive
    v, w = strike(speed, 0.0, 0.0, top)
    n = len(pos)
    eng = Engine(tab, Physics(), pos, [v] + [(0.0, 0.0)] * (n - 1),
                 [w] + [(0.0, 0.0, 0.0)] * (n - 1))
    energy0 = kinetic(eng)
    eng.run(1 / 60)
    assert kinetic(eng) <= energy0
    assert ball_events(eng.events[0])


def kinetic(eng) -> float:
    v, w = eng.vel[0], eng.w[0]
    m, r = eng.mass[0], eng.radius[0]
    return float((0.5 * m * (v * v).sum(axis=1) + 0.2 * m * r * r * (w * w).sum(axis=1)).sum())
