"""Known billiards results, checked against closed-form laws (not against the code's output)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from termpool.physics.cue import strike
from termpool.physics.cushion import MODELS
from termpool.physics.engine import Engine
from termpool.physics.params import BALL_MASS, BALL_RADIUS, Physics, nose_reach
from termpool.physics.table import Table

R = BALL_RADIUS
G = 9.81
BIG = Table(length=20.0, width=10.0, pockets="none")  # no cushion gets in the way


def single(v, w, physics=None, table=BIG, start=(2.0, 5.0)):
    return Engine(table, physics or Physics(), [start], [v], [w])


def first(events, kind):
    return next(ev for ev in events if ev["type"] == kind)


@pytest.mark.parametrize("v0", [0.5, 2.0, 6.0])
@pytest.mark.parametrize("mu", [0.1, 0.2, 0.4])
def test_centre_ball_rolls_at_five_sevenths_after_sliding_distance(v0, mu):
    ph = Physics(mu_slide=mu)
    v, w = strike(v0, 30.0, 0, 0)
    eng = single(v, w, ph)
    eng.run(1 / 60)
    ev = first(eng.events[0], "slide_to_roll")
    speed = math.hypot(ev["balls"][0]["vx"], ev["balls"][0]["vy"])
    assert speed == pytest.approx(5 / 7 * v0, rel=1e-12)
    assert ev["t"] == pytest.approx(2 * v0 / (7 * mu * G), rel=1e-12)
    dist = math.hypot(ev["balls"][0]["x"] - 2.0, ev["balls"][0]["y"] - 5.0)
    assert dist == pytest.approx(12 * v0**2 / (49 * mu * G), rel=1e-12)


@pytest.mark.parametrize("v0", [0.3, 1.0, 2.5])
def test_rolling_ball_stops_after_v2_over_2_mu_roll_g(v0):
    ph = Physics(mu_roll=0.01)
    v, w = strike(v0, 0.0, 0, 0.4)  # top 0.4 R: natural roll from the start
    long = Table(length=40.0, width=10.0, pockets="none")
    eng = single(v, w, ph, table=long, start=(1.0, 5.0))
    eng.run(1 / 60)
    types = [ev["type"] for ev in eng.events[0]]
    assert types == ["roll_to_stop"]
    x = eng.pos[0, 0, 0]
    assert x - 1.0 == pytest.approx(v0**2 / (2 * 0.01 * G), rel=1e-12)
    assert eng.events[0][0]["t"] == pytest.approx(v0 / (0.01 * G), rel=1e-12)


def test_side_spin_decays_then_stops():
    ph = Physics(mu_spin=0.0127)
    eng = single((0.0, 0.0), (0.0, 0.0, 30.0), ph)
    eng.run(1 / 60)
    ev = first(eng.events[0], "spin_to_stop")
    assert ev["t"] == pytest.approx(30.0 * 2 * R / (5 * 0.0127 * G), rel=1e-12)
    assert eng.pos[0, 0] == pytest.approx([2.0, 5.0], abs=0)


def two_ball_cut(cut_deg, cue_v, cue_w, physics, gap=0.5):
    """Cue ball travelling +x, object ball placed for a cut of `cut_deg` at contact."""
    c = math.radians(cut_deg)
    obj = np.array([6.0, 5.0])
    contact = obj - 2 * R * np.array([math.cos(c), math.sin(c)])
    cue = contact - np.array([gap, 0.0])
    vel = np.array([cue_v, [0.0, 0.0]])
    w = np.array([cue_w, [0.0, 0.0, 0.0]])
    return Engine(BIG, physics, np.array([cue, obj]), vel, w)


@pytest.mark.parametrize("cut", [5.0, 20.0, 30.0, 45.0, 60.0, 80.0])
def test_frictionless_elastic_stun_splits_at_ninety_degrees(cut):
    ph = Physics(ball_ball="frictionless", e_ball=1.0)
    eng = two_ball_cut(cut, (2.0, 0.0), (0.0, 0.0, 0.0), ph, gap=1e-4)
    eng.run(1 / 60)
    ev = first(eng.events[0], "ball_ball")
    a, b = ev["balls"]
    va = np.array([a["vx"], a["vy"]])
    vb = np.array([b["vx"], b["vy"]])
    cosang = va @ vb / (np.linalg.norm(va) * np.linalg.norm(vb))
    assert abs(cosang) < 1e-9
    # Object ball leaves along the line of centres, at the cut angle.
    assert math.degrees(math.atan2(vb[1], vb[0])) == pytest.approx(cut, abs=1e-6)


@pytest.mark.parametrize("cut", [10.0, 30.0, 45.0, 60.0])
def test_rolling_cue_ball_final_deflection_matches_thirty_degree_rule(cut):
    # A naturally rolling cue ball, frictionless elastic contact: once friction has restored
    # rolling, its path is deflected from the original line by atan(sin c cos c/(sin^2 c+2/5)).
    ph = Physics(ball_ball="frictionless", e_ball=1.0, mu_roll=0.0)
    v, w = strike(1.5, 0.0, 0, 0.4)
    eng = two_ball_cut(cut, v, w, ph, gap=0.3)
    eng.run(1 / 60, duration=5.0)
    evs = eng.events[0]
    k = next(n for n, ev in enumerate(evs) if ev["type"] == "ball_ball")
    roll = next(ev for ev in evs[k:] if ev["type"] == "slide_to_roll" and ev["i"] == [0])
    vx, vy = roll["balls"][0]["vx"], roll["balls"][0]["vy"]
    c = math.radians(cut)
    expected = math.degrees(math.atan(math.sin(c) * math.cos(c) / (math.sin(c) ** 2 + 0.4)))
    assert abs(math.degrees(math.atan2(vy, vx))) == pytest.approx(expected, abs=1e-6)


@pytest.mark.parametrize("spin", [1.0, -1.0, 0.5, -0.3])
def test_straight_follow_and_draw_end_at_two_sevenths(spin):
    # Cue ball arrives with top (spin > 0) or back spin R w = spin * v; after a full hit it
    # stops, then friction turns the spin into 2/7 of R w (forward for follow, back for draw).
    ph = Physics(ball_ball="frictionless", e_ball=1.0, mu_roll=0.0)
    v0 = 2.0
    eng = two_ball_cut(0.0, (v0, 0.0), (0.0, spin * v0 / R, 0.0), ph, gap=1e-9)
    eng.run(1 / 60, duration=3.0)
    evs = eng.events[0]
    hit = first(evs, "ball_ball")
    cue_after = hit["balls"][0]
    assert cue_after["vx"] == pytest.approx(0.0, abs=1e-6)
    rw = R * cue_after["w"][1]
    roll = next(ev for ev in evs if ev["type"] == "slide_to_roll" and ev["i"] == [0])
    assert roll["balls"][0]["vx"] == pytest.approx(2 / 7 * rw, rel=1e-9)
    assert rw == pytest.approx(spin * v0, rel=1e-3)  # barely any spin lost on the way


def test_ball_ball_momentum_kept_and_energy_not_gained_with_friction():
    ph = Physics(ball_ball="frictional")
    v, w = strike(3.0, 0.0, 0.3, 0.2)
    eng = two_ball_cut(35.0, v, w, ph, gap=1e-9)
    p_before = BALL_MASS * np.array(v)
    eng.run(1 / 60, duration=0.01)
    ev = first(eng.events[0], "ball_ball")
    a, b = ev["balls"]
    p_after = BALL_MASS * np.array([a["vx"] + b["vx"], a["vy"] + b["vy"]])
    assert p_after == pytest.approx(p_before, abs=1e-9)
    inertia = 0.4 * BALL_MASS * R * R

    def energy(vx, vy, w):
        return 0.5 * BALL_MASS * (vx * vx + vy * vy) + 0.5 * inertia * float(np.dot(w, w))

    e_before = energy(*v, np.array(w))
    e_after = energy(a["vx"], a["vy"], a["w"]) + energy(b["vx"], b["vy"], b["w"])
    assert e_after <= e_before * (1 + 1e-12)


@pytest.mark.parametrize("e", [0.95, 0.5])
def test_sliding_ball_contact_throws_by_coulombs_law(e):
    # While the contact slides, the tangential impulse is mu_b times the normal one (Coulomb,
    # as Alciatore's throw analysis has it), whatever the restitution: the object ball leaves
    # at tan(throw) = mu_b(slip) from the line of centres. (A cap of mu_b e times the closing
    # speed instead would give 2 e mu_b / (1 + e).)
    ph = Physics(ball_ball="frictional", e_ball=e)
    cut, speed = 30.0, 2.0
    eng = two_ball_cut(cut, (speed, 0.0), (0.0, 0.0, 0.0), ph, gap=1e-9)
    eng.run(1 / 60, duration=0.01)
    b = first(eng.events[0], "ball_ball")["balls"][1]
    c = math.radians(cut)
    n = np.array([math.cos(c), math.sin(c)])
    vb = np.array([b["vx"], b["vy"]])
    tangential = vb - (vb @ n) * n
    slip = speed * math.sin(c)  # no spin yet: the surfaces slide at the tangential speed
    mu = 0.00995 + 0.108 * math.exp(-1.088 * slip)
    assert np.linalg.norm(tangential) / (vb @ n) == pytest.approx(mu, rel=1e-6)


def test_cut_induced_throw_is_a_few_degrees_and_larger_when_slow():
    def throw(speed):
        ph = Physics(ball_ball="frictional")
        eng = two_ball_cut(30.0, (speed, 0.0), (0.0, 0.0, 0.0), ph, gap=1e-9)
        eng.run(1 / 60, duration=0.01)
        b = first(eng.events[0], "ball_ball")["balls"][1]
        return 30.0 - math.degrees(math.atan2(b["vy"], b["vx"]))

    slow, fast = throw(0.5), throw(5.0)
    assert 0.5 < fast < slow < 6.0


def rail_bounce(side, physics, angle=45.0):
    """A rolling ball hits the far rail (y = W) at `angle` to it, travelling +x."""
    tab = Table(length=4.0, width=1.27, pockets="none")
    v, w = strike(1.0, angle, side, 0.0)
    eng = Engine(tab, physics, [[1.0, 0.5]], [v], [w])
    eng.run(1 / 60, duration=5.0)
    ev = first(eng.events[0], "cushion")
    return ev["balls"][0], np.array(v)


def test_simple_cushion_without_friction_reflects_normal_speed_times_e():
    # Each model's own closed forms, straight on the model: tests/test_cushion.py.
    ph = Physics(cushion="simple", mu_cushion=0.0, e_cushion=0.85)
    after, before_dir = rail_bounce(0.0, ph)
    # The ball slides a little on the way: compare with its velocity just before the rail.
    vx, vy = after["vx"], after["vy"]
    assert vy < 0
    # Horizontal tangential speed unchanged; normal speed reversed times e (|vy| / vx is
    # e * tan of the incoming angle, since the incoming ball keeps its direction on the way).
    assert -vy / vx == pytest.approx(0.85 * before_dir[1] / before_dir[0], rel=1e-9)


@pytest.mark.parametrize("model", sorted(MODELS))
def test_running_english_widens_and_reverse_narrows_the_rebound(model):
    ph = Physics(cushion=model)

    def out_angle(side):
        after, _ = rail_bounce(side, ph)
        return math.degrees(math.atan2(-after["vy"], after["vx"]))  # angle from the rail

    plain, right, left = out_angle(0.0), out_angle(0.4), out_angle(-0.4)
    # Travelling +x into the far rail, right english (wz > 0) is running: the ball leaves
    # flatter along the rail; left english is reverse and sends it back more steeply.
    assert right < plain < left


@pytest.mark.parametrize("model", sorted(MODELS))
def test_cushion_never_adds_energy_whatever_the_spin(model):
    rng = np.random.default_rng(7)
    for _ in range(40):
        ph = Physics(mu_cushion=float(rng.uniform(0, 1)), e_cushion=float(rng.uniform(0, 1)),
                     cushion=model)
        w = rng.normal(0, 200, 3)
        v = np.array([rng.uniform(-1, 1), rng.uniform(0.1, 3.0)])
        tab = Table(length=4.0, width=1.27, pockets="none")
        eng = Engine(tab, ph, [[2.0, 1.27 - R - 1e-4]], [v], [w])
        inertia = 0.4 * BALL_MASS * R * R
        e0 = 0.5 * BALL_MASS * v @ v + 0.5 * inertia * w @ w
        eng.run(1 / 60, duration=0.02)
        ev = first(eng.events[0], "cushion")["balls"][0]
        e1 = 0.5 * BALL_MASS * (ev["vx"] ** 2 + ev["vy"] ** 2) + 0.5 * inertia * np.dot(
            ev["w"], ev["w"])
        assert e1 <= e0 * (1 + 1e-12)


def test_fast_ball_does_not_tunnel_with_a_long_step():
    # 20 m/s with dt = 1/30: 0.67 m per step, the object ball is 0.3 m away.
    ph = Physics()
    eng = Engine(BIG, ph, [[2.0, 5.0], [2.3, 5.0]], [[20.0, 0.0], [0.0, 0.0]])
    eng.step(1 / 30)
    assert [ev["type"] for ev in eng.events[0]][:1] == ["ball_ball"]
    assert eng.pos[0, 1, 0] > 2.3
    tab = Table(length=2.54, width=1.27, pockets="none")
    eng = Engine(tab, ph, [[2.3, 0.6]], [[20.0, 0.0]])
    eng.step(1 / 30)
    assert eng.events[0][0]["type"] == "cushion"
    assert eng.pos[0, 0, 0] < 2.54 - R * 0.9


def test_pocketing_rattling_in_and_staying_out():
    tab = Table.preset("9ft")
    ph = Physics()
    # Straight down the diagonal into the foot-right corner (x = L, y = 0).
    start = np.array([2.0, 0.54])
    target = np.array([2.54, 0.0])
    d = target - start
    ang = math.degrees(math.atan2(d[1], d[0]))
    v, w = strike(2.0, ang, 0, 0.4)
    eng = Engine(tab, ph, [start], [v], [w])
    eng.run(1 / 60)
    assert eng.state[0, 0] == 4
    assert tab.hole_names[eng.pocket[0, 0]] == "foot_right"
    # Rolling along the long rail into the corner: close to the rail it meets the far jaw
    # and rattles in; a little further out it strikes the jaw's tip and stays out.
    def along_rail(y):
        v, w = strike(1.5, 0.0, 0, 0.4)
        eng = Engine(tab, ph, [[2.0, y]], [v], [w])
        eng.run(1 / 60)
        feats = [ev.get("feature") for ev in eng.events[0] if ev["type"] == "cushion"]
        k = int(eng.pocket[0, 0])
        return feats, eng.state[0, 0], tab.hole_names[k] if k >= 0 else None

    feats, state, pocket = along_rail(0.06)
    assert feats[0] == "jaw" and state == 4 and pocket == "foot_right"
    feats, state, pocket = along_rail(0.075)  # (it may roll into another pocket later)
    assert feats[0] == "tip" and pocket != "foot_right"


def test_a_ball_out_of_a_pocket_mouth_meets_the_rail_beside_it():
    # Found by a 5000 rad/s spin into a rack: a ball just inside the side pocket's mouth, its
    # centre a little behind the rail line, leaves into the table and its spin curves it back
    # onto the rail beside the pocket. Being behind the rail's line at the start (off the
    # rail's end) must not hide that contact, or the ball goes through the rail.
    tab = Table.preset("9ft")
    eng = Engine(tab, Physics(), [[1.2344, -0.0024]], [[1.336, 1.053]],
                 [[4011.0, -4014.0, 4710.0]])
    eng.run(1 / 60, duration=1.6)
    hit = first(eng.events[0], "cushion")
    ball = hit["balls"][0]
    assert hit["feature"] == "rail" and ball["x"] > 1.3345  # the rail past the far jaw
    assert ball["y"] == pytest.approx(float(eng.rc[0, 0]), abs=1e-6)  # touching, in front
    assert ball["vy"] > 0


def test_fixed_step_is_exact_whatever_the_step():
    tab = Table.preset("9ft")
    ph = Physics()
    v, w = strike(3.0, 10.0, 0.2, -0.3)
    pos = [[0.6, 0.6], [1.4, 0.75], [1.8, 0.4], [2.0, 0.9]]
    vel = [v, [0, 0], [0, 0], [0, 0]]
    spin = [w, [0, 0, 0], [0, 0, 0], [0, 0, 0]]
    ref = Engine(tab, ph, pos, vel, spin)
    ref.run_events()
    for dt in (1 / 15, 1 / 60, 1 / 1000):
        eng = Engine(tab, ph, pos, vel, spin)
        eng.run(dt)
        assert np.array_equal(eng.pos, ref.pos)
        assert [e["t"] for e in eng.events[0]] == [e["t"] for e in ref.events[0]]


def test_newtons_cradle_takes_a_handful_of_contacts():
    # A stun ball into a row of five frozen balls, elastic and frictionless between balls:
    # the wave passes in one contact per ball and the last ball leaves with the speed.
    ph = Physics(ball_ball="frictionless", e_ball=1.0, mu_slide=0.0, mu_roll=0.0)
    row = [[3.0 + 2 * R * k, 5.0] for k in range(5)]
    pos = [[2.9, 5.0]] + row
    vel = [[2.0, 0.0]] + [[0.0, 0.0]] * 5
    eng = Engine(BIG, ph, pos, vel)
    eng.run(1 / 60, duration=0.5)
    hits = [ev for ev in eng.events[0] if ev["type"] == "ball_ball"]
    assert len(hits) == 5
    v = eng.vel[0]
    assert v[5] == pytest.approx([2.0, 0.0], abs=1e-12)
    assert np.abs(v[:5]).max() < 1e-12


@pytest.mark.parametrize("e", [0.95, 0.8])
def test_newtons_cradle_on_cloth_settles_in_bounded_work(e):
    # With cloth friction the cue ball follows into the row and pushes it: the row and the
    # cue ball move as one body held by resting contacts, not as thousands of pair contacts.
    ph = Physics(e_ball=e)
    row = [[3.0 + 2 * R * k, 5.0] for k in range(5)]
    eng = Engine(BIG, ph, [[2.9, 5.0]] + row, [[2.0, 0.0]] + [[0.0, 0.0]] * 5)
    eng.run(1 / 60)
    hits = [ev for ev in eng.events[0] if ev["type"] == "ball_ball"]
    assert len(hits) <= 20
    assert eng.passes < 60
    p = eng.pos[0]
    gaps = np.linalg.norm(p[:, None] - p[None], axis=2) + np.eye(6) - 2 * R
    assert gaps.min() > -1e-6


def test_balls_at_rest_cost_nothing():
    tab = Table.preset("9ft")
    eng = Engine(tab, Physics(), [[0.5, 0.5], [1.0, 0.5]])
    for _ in range(100):
        eng.step(1 / 60)
    assert eng.passes == 0
    assert eng.at_rest().all()


def test_batch_matches_tables_run_alone():
    tab = Table.preset("9ft")
    ph = Physics()
    rng = np.random.default_rng(3)
    B = 5
    pos = np.array([[[0.6, 0.6], [1.4, 0.75], [1.8, 0.4]]] * B)
    vel = np.zeros((B, 3, 2))
    spin = np.zeros((B, 3, 3))
    for b in range(B):
        v, w = strike(float(rng.uniform(1, 5)), float(rng.uniform(-20, 20)), 0.1, 0.1)
        vel[b, 0], spin[b, 0] = v, w
    batch = Engine(tab, ph, pos, vel, spin)
    batch.run(1 / 60)
    for b in range(B):
        one = Engine(tab, ph, pos[b], vel[b], spin[b])
        one.run(1 / 60)
        assert np.array_equal(one.pos[0], batch.pos[b])
        assert one.events[0] == batch.events[b]


def test_heavier_cue_ball_follows_through_on_a_full_hit():
    ph = Physics(ball_ball="frictionless", e_ball=1.0, mu_slide=0.0)
    m1, m2 = 0.2, 0.17
    eng = Engine(BIG, ph, [[2.0, 5.0], [2.0 + 2 * R + 1e-9, 5.0]], [[1.0, 0.0], [0, 0]],
                 mass=[m1, m2])
    eng.run(1 / 60, duration=1e-3)
    a, b = first(eng.events[0], "ball_ball")["balls"]
    assert a["vx"] == pytest.approx((m1 - m2) / (m1 + m2), rel=1e-9)
    assert b["vx"] == pytest.approx(2 * m1 / (m1 + m2), rel=1e-9)


def test_batch_of_breaks_is_step_independent_and_matches_single_tables():
    # Racked breaks are full of slow contacts and touching clusters; a table's result must
    # depend neither on the step nor on which other tables share its batch.
    from bench.speed import batch_breaks, break_scene

    scene = break_scene()
    pos, vel, w = batch_breaks(scene, 64)
    args = (scene.table, scene.physics)
    kw = {"radius": scene.radius, "mass": scene.mass}
    events = Engine(*args, pos, vel, w, **kw)
    events.run_events()
    stepped = Engine(*args, pos, vel, w, **kw)
    stepped.run(1 / 60)
    assert np.array_equal(events.pos, stepped.pos)
    for b in (0, 7):
        alone = Engine(*args, pos[b], vel[b], w[b], **kw)
        alone.run(1 / 30)
        assert np.array_equal(alone.pos[0], events.pos[b])
        assert alone.events[0] == events.events[b]


def test_stopped_tables_keep_their_clock_and_the_others_run_on_unchanged():
    # A batch's user may stop tables it has seen enough of (the computer's throw check): the
    # others run on bit for bit as in the batch without the stop, and a stopped table's
    # balls stay as they were when it stopped, with no events after.
    from bench.speed import batch_breaks, break_scene

    scene = break_scene()
    pos, vel, w = batch_breaks(scene, 4)
    args = (scene.table, scene.physics, pos, vel, w)
    kw = {"radius": scene.radius, "mass": scene.mass}
    full = Engine(*args, **kw)
    full.run_events(duration=30.0)
    part = Engine(*args, **kw)
    part.run_events(duration=0.25)
    held, n_events = part.pos[1].copy(), len(part.log[1])
    part.stop([1])
    part.run_events(duration=30.0)  # every other clock moves on to 30 s
    assert np.array_equal(part.pos[1], held) and len(part.log[1]) == n_events
    assert part.at_rest()[1]  # a stopped table counts as done for the run
    assert len(full.log[1]) > n_events  # it had more to do
    for b in (0, 2, 3):
        assert np.array_equal(part.pos[b], full.pos[b])
        assert part.events[b] == full.events[b]


def test_reference_driver_on_a_table_already_at_rest():
    eng = Engine(BIG, Physics(), [[1.0, 1.0], [2.0, 2.0]])
    eng.run_events()
    assert eng.time == 0.0
    assert np.array_equal(eng.pos[0], [[1.0, 1.0], [2.0, 2.0]])


def test_duration_takes_whole_steps_despite_rounding():
    eng = Engine(BIG, Physics(), [[1.0, 1.0]], [[1.0, 0.0]])
    eng.run(0.001, duration=2.0)
    assert eng.steps == 2000
    assert eng.time == 2.0


def pinned_reference(x0, ut, un, ph, h=2e-6):
    """A ball on the rail y = 0 whose slip (ut along it, un away from it) drives it into the
    rail: the rail cancels the normal acceleration, so v stays along the rail while the slip's
    parts fall at 3.5 and 2.5 mu_s g in the slip's direction. Integrated by RK4 (plain
    floats) until the slip is spent, then rolled to rest; returns the final x."""
    k = ph.mu_slide * ph.g

    def f(vx, a, b):
        n = math.hypot(a, b)
        return vx, -k * a / n, -3.5 * k * a / n, -2.5 * k * b / n

    x, vx, a, b = x0, 0.0, ut, un
    while math.hypot(a, b) > 3.5 * k * h:
        k1 = f(vx, a, b)
        k2 = f(vx + h / 2 * k1[1], a + h / 2 * k1[2], b + h / 2 * k1[3])
        k3 = f(vx + h / 2 * k2[1], a + h / 2 * k2[2], b + h / 2 * k2[3])
        k4 = f(vx + h * k3[1], a + h * k3[2], b + h * k3[3])
        x, vx, a, b = (y + h / 6 * (p + 2 * q + 2 * r + s) for y, p, q, r, s in
                       zip((x, vx, a, b), k1, k2, k3, k4, strict=True))
    return x + vx * abs(vx) / (2 * ph.mu_roll * ph.g)


@pytest.mark.parametrize("ut, un", [(1.0, 2.0), (-0.5, 1.0), (2.0, 0.3)])
def test_ball_pressed_into_a_rail_by_its_spin_slides_along_it(ut, un):
    # Spin whose slip points away from the rail: friction drives the ball into it. Pressed
    # there, it moves along the rail as one constrained motion, never leaving it and without
    # a train of bounces, and ends where the constrained motion integrated finely ends.
    ph = Physics(mu_cushion=0.0)  # the constrained motion has no rail friction
    tab = Table(length=4.0, width=2.0, pockets="none")
    rc = float(nose_reach(R, ph.cushion_height))
    x0 = 2.0
    w = (un / R, -ut / R, 0.0)  # slip u = v + R z x w = (ut, un)
    eng = Engine(tab, ph, [(x0, rc)], [(0.0, 0.0)], [w])
    for _t, p, _state in eng.run(1 / 60, sample_hz=200):
        assert abs(p[0, 0, 1] - rc) < 1e-9  # on the rail (within roots.TOUCH)
    assert [e["type"] for e in eng.events[0]] == ["slide_to_roll", "roll_to_stop"]
    assert eng.passes < 200
    x_ref = pinned_reference(x0, ut, un, ph)
    assert abs(eng.pos[0, 0, 0] - x_ref) < 5e-5  # 0.05 mm: the friction's direction is
    # renewed every joined.TURN of its turn


def _pressed_pair(slip: tuple) -> tuple:
    """Ball 0 rolling at 0.3 m/s along +y with the given small slip, frozen against ball 1
    on its +x side (the contact's normal pushes ball 0 along -x): `joined.push`'s inputs."""
    v = np.array([[0.0, 0.3], [0.0, 0.0]])
    d = np.array(slip) - v[0]  # u = v + R z x w = v + R (-wy, wx)
    w = np.zeros((2, 3))
    w[0, 0], w[0, 1] = d[1] / R, -d[0] / R
    return v, w, np.full(2, R), np.full(2, BALL_MASS), np.ones(2)


@pytest.mark.parametrize("slip, ends", [((-2e-5, 1e-5), True), ((-2e-5, 0.0), False),
                                        ((-2e-4, 1e-4), False)])
def test_a_grouped_slip_the_contact_turns_ends_at_once_when_tiny(slip, ends):
    # A slip that friction drives into the contact, partly across it: the contact's force
    # turns it. Under joined.EPS_TURNED it ends now (the ball rolls on with v - u / 3.5, its
    # speed into the contact taken out); along the normal (not turned) or larger, it slides
    # to its exact end. push_many gives push's bits either way.
    from termpool.physics import joined
    from termpool.physics.cluster import Rows
    from termpool.physics.state import ROLLING, SLIDING

    ph = Physics()
    v, w, radius, m, rate = _pressed_pair(slip)
    out = joined.push(ph, v, w, radius, m, rate, [(0, 1, np.array([-1.0, 0.0]), 0.0)])
    assert out[3][0] == (ROLLING if ends else SLIDING)
    if ends:
        assert out[0][0].tolist() == [0.0, 0.3 - slip[1] / 3.5]
    sets = joined.Sets(Rows(np.array([0]), np.array([1]), np.array([[-1.0, 0.0]]), 2),
                       np.array([0, 0]), np.array([0]), 1)
    many = joined.push_many(ph, v, w, radius, m, rate, sets, np.zeros(1))
    assert [np.asarray(x).tobytes() for x in many] == [np.asarray(x).tobytes() for x in out]


def test_a_turned_slip_in_a_group_ends_without_a_geometric_tail(monkeypatch):
    # A ball spun against a frozen neighbour, its slip partly across the contact: the pair
    # moves as a group whose contact force turns the slip, renewed each joined.TURN of its
    # turn, in ever shorter pieces as the slip runs out. Ending it under EPS_TURNED cuts that
    # tail, and the balls end where they end without the cut, to a hundredth of a millimetre.
    from termpool.physics import joined

    def run() -> Engine:
        eng = Engine(BIG, Physics(), [(2.0, 5.0), (2.0 + 2 * R, 5.0)], [(0.0, 0.0)] * 2,
                     [(20.0, 20.0, 0.0), (0.0, 0.0, 0.0)])
        eng.run_events()
        return eng

    cut = run()
    monkeypatch.setattr(joined, "EPS_TURNED", 0.0)
    whole = run()
    assert cut.passes < whole.passes
    assert np.abs(cut.pos - whole.pos).max() < 1e-5


@pytest.mark.parametrize("speed", [0.0, 0.3, 5.0])
def test_a_completed_slip_stays_on_its_slide_at_the_lowest_allowed_friction(speed):
    """A slip under state.EPS_U is completed at once: the ball starts rolling where the slide
    ends, and before then its path stands for the slide. That path strays from the slide by
    |u|^2 / (24.5 mu_slide g), so the lowest mu_slide and g a scene may give must keep it under
    roots.SINK, the overlap the engine resolves at once (at the old limits, 1e-4 and 0.1, it
    was millimetres and more: a ball was set 2 mm into a rail, and its run never ended)."""
    from termpool.physics.params import PHYSICS_RANGES
    from termpool.physics.roots import SINK
    from termpool.physics.state import EPS_U

    mu, g = PHYSICS_RANGES["mu_slide"][0], PHYSICS_RANGES["g"][0]
    ph = Physics(mu_slide=mu, g=g)
    u = 0.999 * EPS_U  # slip along +x: v - R wy
    eng = single([speed + u, 0.0], [0.0, speed / R, 0.0], ph)
    a = mu * g
    ts = u / (3.5 * a)
    for tau in np.linspace(0.0, ts, 9):
        p, _, _ = eng.balls.eval(np.array([0]), np.array([0]), np.array([tau]), spin=False)
        slide = 2.0 + (speed + u) * tau - 0.5 * a * tau * tau  # the exact slide
        assert abs(float(p[0, 0]) - slide) < SINK, f"strays {float(p[0, 0]) - slide:.3g} m"
