"""Laws every cushion model obeys, closed forms where a model has one, and the choice of model
in scenes and records. (Float and array forms agreeing bit for bit: tests/test_motion.py.)"""

from __future__ import annotations

import copy
import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from termpool.game import Match, Shot
from termpool.game.record import replay, run_to_rest, start_engine
from termpool.physics.cue import strike
from termpool.physics.cushion import MODELS, mathavan
from termpool.physics.cushion.rail import nose_one
from termpool.physics.params import (
    BALL_MASS,
    BALL_RADIUS,
    FRICTIONLESS_OK,
    PHYSICS_RANGES,
    Physics,
)
from termpool.scene import (
    MASS_RANGE,
    MAX_SPEED,
    MAX_SURFACE_SPEED,
    RADIUS_RANGE,
    SceneError,
    load_scene,
)

R, M = BALL_RADIUS, BALL_MASS
NAMES = sorted(MODELS)
UP = [0.0, -1.0]  # a cushion whose normal points down the table: rail frame = table frame


def energy(v, w, r: float = R, m: float = M) -> float:
    return 0.5 * m * (v[0] * v[0] + v[1] * v[1]) + 0.2 * m * r * r * sum(x * x for x in w)


def bounce(model: str, ph: Physics, n, v, w, r: float = R, m: float = M):
    return MODELS[model].bounce_one(list(n), list(v), list(w), r, m, ph)


def square(speed: float, roll: float):
    """Into the UP cushion at `speed`, square, with top spin R w = roll * speed (1: rolling,
    0: stun, < 0: draw)."""
    return [0.0, speed], [-roll * speed / R, 0.0, 0.0]


def random_cases(seed: int, k: int):
    """Random approaches: any normal, speed, spin, size and weight."""
    rng = np.random.default_rng(seed)
    for _ in range(k):
        a = rng.uniform(0, 2 * math.pi)
        n = [math.cos(a), math.sin(a)]
        v = rng.normal(0.0, 2.0, 2) - rng.uniform(0.0, 3.0) * np.array(n)
        w = rng.normal(0.0, 100.0, 3)
        yield n, v.tolist(), w.tolist(), float(rng.uniform(0.02, 0.04)), float(
            rng.uniform(0.1, 0.2))


def extreme_cases():
    """Zero and grazing speeds, huge spins and speeds, a ball barely touching."""
    n = [0.6, -0.8]
    t = [0.8, 0.6]  # along the cushion
    for vn in (0.0, 1e-300, 1e-12, 1e-4, 0.005, 1.0, 100.0):
        for vt in (0.0, 1e-9, 3.0):
            for w in ([0.0, 0.0, 0.0], [1e4, -1e4, 1e4], [0.0, 0.0, -5e3], [1e-200, 0.0, 0.0]):
                v = [vt * t[0] - vn * n[0], vt * t[1] - vn * n[1]]
                yield n, v, w


PHYSICS = [Physics(cushion=c, e_cushion=e, mu_cushion=mu, mu_slide=ms, cushion_height=h)
           for c in NAMES for e in (0.0, 0.85, 1.0) for mu in (0.0, 0.2, 5.0)
           for ms in (0.0, 0.2, 3.0) for h in (0.0366, 0.01, 0.2)]


# ------------------------------------------------------------------------------- the laws


@pytest.mark.parametrize("ph", PHYSICS, ids=lambda p: f"{p.cushion}-e{p.e_cushion}-mu"
                         f"{p.mu_cushion}-ms{p.mu_slide}-h{p.cushion_height}")
def test_no_cushion_adds_energy_or_gives_nan(ph):
    cases = [(n, v, w, R, M) for n, v, w in extreme_cases()] + list(random_cases(1, 60))
    for n, v, w, r, m in cases:
        vo, wo = bounce(ph.cushion, ph, n, v, w, r, m)
        assert all(math.isfinite(x) for x in vo + wo)
        assert energy(vo, wo, r, m) <= energy(v, w, r, m) * (1 + 1e-12)


# Any physics a scene may give a cushion, at its limits or between (docs/limits.md).
def _within(key: str) -> st.SearchStrategy[float]:
    lo, hi = PHYSICS_RANGES[key]
    ends = [lo, hi, 0.0] if key in FRICTIONLESS_OK else [lo, hi]
    return st.one_of(st.sampled_from(ends), st.floats(lo, hi))


allowed_physics = st.builds(
    Physics, cushion=st.sampled_from(NAMES), e_cushion=_within("e_cushion"),
    mu_cushion=_within("mu_cushion"), mu_slide=_within("mu_slide"),
    cushion_height=_within("cushion_height"), g=_within("g"))


@settings(max_examples=300, deadline=None)
@given(ph=allowed_physics, a=st.floats(0.0, 2 * math.pi), speed=st.floats(0.0, MAX_SPEED),
       into=st.floats(0.0, 1.0), spin=st.tuples(*[st.floats(-1.0, 1.0)] * 3),
       r=st.sampled_from([*RADIUS_RANGE, R]), m=st.sampled_from([*MASS_RANGE, M]))
def test_no_allowed_physics_lets_a_cushion_add_energy(ph, a, speed, into, spin, r, m):
    """Over the whole of the allowed ranges (once, mu_slide 1e15 turned 0.130 J into 0.165 J),
    any approach at up to the speed and spin limits: the bounce is finite and adds no energy,
    in both forms of every model."""
    n = [math.cos(a), math.sin(a)]
    t = [-n[1], n[0]]
    vn, vt = -into * speed, math.sqrt(1.0 - into * into) * speed  # into the cushion
    v = [vn * n[0] + vt * t[0], vn * n[1] + vt * t[1]]
    w = [x * MAX_SURFACE_SPEED / r / math.sqrt(3.0) for x in spin]
    e_in = energy(v, w, r, m)
    vo, wo = bounce(ph.cushion, ph, n, v, w, r, m)
    va, wa = MODELS[ph.cushion].bounce(np.array([n]), np.array([v]), np.array([w]),
                                       np.array([r]), np.array([m]), ph)
    for vv, ww in ((vo, wo), (va[0].tolist(), wa[0].tolist())):
        assert all(math.isfinite(x) for x in vv + ww)
        assert energy(vv, ww, r, m) <= e_in * (1 + 1e-12), (energy(vv, ww, r, m), e_in)


@settings(max_examples=40, deadline=None)
@given(ph=allowed_physics, speed=st.floats(0.05, MAX_SPEED), angle=st.floats(-180.0, 180.0),
       side=st.floats(-0.35, 0.35), top=st.floats(-0.35, 0.35))
def test_a_lone_ball_never_gains_energy_between_its_events(ph, speed, angle, side, top):
    """A ball alone on the table loses energy to the cloth and the cushions, and gains none
    anywhere: at every event (a bounce, the end of a slide) it has no more than before."""
    from termpool.physics.engine import Engine
    from termpool.physics.table import Table

    (vx, vy), w = strike(speed, angle, side, top, R)
    eng = Engine(Table(pockets="none"), ph, [[1.27, 0.635]], [[vx, vy]], [w])
    eng.run(1 / 60, duration=30.0)
    last = energy([vx, vy], w)
    for ev in eng.events[0]:
        b = ev["balls"][0]
        now = energy([b["vx"], b["vy"]], b["w"])
        assert now <= last * (1 + 1e-12) + 1e-15, (ev["type"], ev["t"], last, now)
        last = now


def leaves_simple(ph: Physics) -> bool:
    """The simple cushion reverses the normal speed times e, then its friction at the nose
    can push the ball back in by up to mu (1 + e) |tan t| of it: it always leaves when
    e >= mu |tan t| / (1 - mu |tan t|) (below, it can hold a ball to the rail)."""
    s, c = nose_one(R, ph.cushion_height)
    k = ph.mu_cushion * abs(s) / c
    return k < 1 and ph.e_cushion >= k / (1 - k)


@pytest.mark.parametrize("ph", [p for p in PHYSICS if p.cushion != "simple" or leaves_simple(p)],
                         ids=lambda p: f"{p.cushion}-e{p.e_cushion}-mu{p.mu_cushion}-ms"
                         f"{p.mu_slide}-h{p.cushion_height}")
def test_the_ball_leaves_the_cushion(ph):
    cases = [(n, v, w, R, M) for n, v, w in extreme_cases()] + list(random_cases(2, 60))
    for n, v, w, r, m in cases:
        if ph.cushion == "simple" and -(v[0] * n[0] + v[1] * n[1]) <= ph.v_inelastic:
            continue  # below v_inelastic it does not bounce (the engine lifts it off)
        vo, _ = bounce(ph.cushion, ph, n, v, w, r, m)
        # Not moving into the cushion, to rounding (a ball stopped at it has speed 0 along n,
        # to a few 1e-16 of the speed in).
        assert vo[0] * n[0] + vo[1] * n[1] >= -1e-14 * math.hypot(*v)


def test_the_simple_cushion_can_hold_a_ball_below_its_bound():
    """The bound above is sharp: with e = 0 and back spin the friction keeps pushing in."""
    ph = Physics(cushion="simple", e_cushion=0.0)
    assert not leaves_simple(ph)
    vo, _ = bounce("simple", ph, UP, *square(1.0, -1.0))
    assert vo[1] > 0


@pytest.mark.parametrize("model", NAMES)
def test_a_mirrored_shot_rebounds_mirrored(model):
    """Reflected in the plane of the normal and the vertical, a shot gives the reflected
    result: velocities reflect, angular velocity (an axial vector) reflects and changes sign."""
    ph = Physics(cushion=model)
    for n, v, w, r, m in random_cases(3, 300):
        n2 = np.array(n)
        refl = 2 * np.outer(n2, n2) - np.eye(2)  # keeps n, reverses the direction along it
        mv = (refl @ v).tolist()
        mw = [*(-(refl @ w[:2])).tolist(), -w[2]]
        vo, wo = bounce(model, ph, n, v, w, r, m)
        mvo, mwo = bounce(model, ph, n, mv, mw, r, m)
        assert np.allclose(mvo, refl @ vo, rtol=0, atol=1e-9)
        assert np.allclose(mwo, [*(-(refl @ wo[:2])), -wo[2]], rtol=0, atol=1e-7)


@pytest.mark.parametrize("model", NAMES)
def test_turning_the_table_turns_the_rebound(model):
    ph = Physics(cushion=model)
    for n, v, w, r, m in random_cases(4, 200):
        a = 0.7
        rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        vo, wo = bounce(model, ph, n, v, w, r, m)
        tn, tv, tw = rot @ n, rot @ v, [*(rot @ w[:2]), w[2]]
        to, two = bounce(model, ph, tn.tolist(), tv.tolist(), tw, r, m)
        assert np.allclose(to, rot @ vo, rtol=0, atol=1e-9)
        assert np.allclose(two, [*(rot @ wo[:2]), wo[2]], rtol=0, atol=1e-7)


@pytest.mark.parametrize("model", NAMES)
def test_a_cushion_leaves_a_ball_moving_away_alone(model):
    ph = Physics(cushion=model)
    for v in ([0.0, -1.0], [2.0, 0.0], [0.0, 0.0]):
        w = [3.0, -40.0, 7.0]
        vo, wo = bounce(model, ph, UP, v, w)
        if model == "simple":  # its friction still acts on a sliding contact point
            continue
        assert (vo, wo) == (v, w)


# ----------------------------------------------------------------------- closed forms


@pytest.mark.parametrize("roll", [1.0, 0.5, 0.0, -0.5, -1.0])
@pytest.mark.parametrize("e, mu", [(0.85, 0.2), (0.5, 0.05), (1.0, 0.6)])
def test_simple_square_rebound_matches_its_closed_form(roll, e, mu):
    """Square in with top spin R w = k v: the normal speed is reversed times e, then the
    nose's slip, v (k - e s) along (0, s, -c), is opposed by at most mu (1 + e) v / c, or by
    what stops it (slip / 3.5): out = e + s sign(k - e s) min(mu (1 + e) / c, |k - e s| / 3.5)."""
    ph = Physics(cushion="simple", e_cushion=e, mu_cushion=mu)
    s, c = nose_one(R, ph.cushion_height)
    v, w = square(1.3, roll)
    vo, wo = bounce("simple", ph, UP, v, w)
    slip = roll - e * s
    out = e + s * math.copysign(min(mu * (1 + e) / c, abs(slip) / 3.5), slip)
    assert vo[0] == 0.0 and -vo[1] == pytest.approx(1.3 * out, rel=1e-12)


@pytest.mark.parametrize("roll", [1.0, 0.5, 0.0, -0.5, -1.0])
@pytest.mark.parametrize("e, mu", [(0.85, 0.2), (0.5, 0.05), (1.0, 0.6)])
def test_han_square_rebound_matches_its_closed_form(roll, e, mu):
    """Han: the contact-normal speed v cos t is reversed times e (impulse (1 + e) v c along
    the tilted normal), the nose's slip v (s + k) is opposed by at most mu times that impulse
    or by what stops it (Han's 2/7): out = (1 + e) c^2 - 1 + s sign(s + k) min(mu (1 + e) c,
    |s + k| / 3.5), and the friction leaves top spin R w = 2.5 that min, plus the spin in."""
    ph = Physics(cushion="han", e_cushion=e, mu_cushion=mu)
    s, c = nose_one(R, ph.cushion_height)
    v, w = square(1.3, roll)
    vo, wo = bounce("han", ph, UP, v, w)
    slip = s + roll
    j = math.copysign(min(mu * (1 + e) * c, abs(slip) / 3.5), slip)
    assert vo[0] == 0.0 and -vo[1] == pytest.approx(1.3 * ((1 + e) * c * c - 1 + s * j),
                                                    rel=1e-12)
    # wx > 0 is follow on the way out (and draw on the way in, so roll enters negated).
    assert R * wo[0] == pytest.approx(1.3 * (2.5 * j - roll), rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("model", NAMES)
@pytest.mark.parametrize("e", [0.0, 0.3, 0.85, 1.0])
def test_without_friction_the_rebound_has_each_models_closed_form(model, e):
    """No friction at the nose (nor, for Mathavan, on the slate): the speed along the rail
    and every spin are kept; the normal speed comes back times e (simple, and Mathavan, whose
    slate takes the tilted push's vertical part without doing work), or times
    (1 + e) cos^2 t - 1 (Han's tilted impulse; a ball left moving in is stopped)."""
    ph = Physics(cushion=model, e_cushion=e, mu_cushion=0.0, mu_slide=0.0)
    s, c = nose_one(R, ph.cushion_height)
    for angle in (0.0, 30.0, 80.0):
        a = math.radians(angle)
        v = [2.0 * math.sin(a), 2.0 * math.cos(a)]
        w = [-20.0, 45.0, 33.0]
        vo, wo = bounce(model, ph, UP, v, w)
        out = max((1 + e) * c * c - 1, 0.0) if model == "han" else e
        assert vo[0] == v[0] and wo == w
        assert -vo[1] == pytest.approx(out * v[1], rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("ph, speed, degrees", [
    (Physics(cushion="mathavan"), 0.01, 0.25),
    (Physics(cushion="mathavan", e_cushion=0.85, mu_cushion=0.2), 0.01, 0.25),
    (Physics(cushion="mathavan", e_cushion=0.5, mu_cushion=0.6, mu_slide=0.4), 0.015, 1.0)])
def test_mathavan_is_within_its_stated_accuracy_of_the_converged_impact(ph, speed, degrees,
                                                                         monkeypatch):
    """The fixed step rule keeps the rebound within 1% of the speed in and 0.25 degrees of
    the impact integrated with 500 times smaller steps, for cushions like the game's (1.5%
    and 1 degree for rough ones): the module docstring's figures."""
    shots = []
    for angle in (0, 20, 45, 70, 85):
        for roll in (1.0, 0.0, -1.0):
            for side in (0.0, 1.0, -1.0):
                a = math.radians(angle)
                v = [math.sin(a), math.cos(a)]
                shots.append((v, [-roll * v[1] / R, roll * v[0] / R, side / R]))
    coarse = [bounce("mathavan", ph, UP, v, w) for v, w in shots]
    monkeypatch.setattr(mathavan, "STEPS", 500 * mathavan.STEPS)
    monkeypatch.setattr(mathavan, "MAX_STEPS", 500 * mathavan.MAX_STEPS)
    for (vo, _), (v, w) in zip(coarse, shots, strict=True):
        fo, _ = bounce("mathavan", ph, UP, v, w)
        assert math.dist(vo, fo) < speed
        turn = math.atan2(vo[0], -vo[1]) - math.atan2(fo[0], -fo[1])
        assert abs(turn) < math.radians(degrees)


def test_mathavan_takes_a_bounded_number_of_steps(monkeypatch):
    calls = []
    real = mathavan._step_one
    monkeypatch.setattr(mathavan, "_step_one", lambda *a: calls.append(1) or real(*a))
    ph = Physics(cushion="mathavan", mu_cushion=5.0, mu_slide=3.0)
    for n, v, w in extreme_cases():
        calls.clear()
        bounce("mathavan", ph, n, v, w)
        assert len(calls) <= 2 * mathavan.MAX_STEPS


# ----------------------------------------------------------------- on the table, by name


@pytest.mark.parametrize("model", NAMES)
def test_a_break_runs_to_rest_with_each_cushion(model):
    scene = load_scene({"balls": "8ball", "shot": {"speed": 8.0},
                        "physics": {"cushion": model}})
    eng = start_engine(scene)
    run_to_rest(eng, 1 / 60)
    assert eng.at_rest().all()
    assert any(ev["type"] == "cushion" for ev in eng.events[0])


def test_a_scene_names_its_cushion_or_gets_a_one_line_error():
    assert load_scene({"physics": {"cushion": "han"}}).physics.cushion == "han"
    for bad in ("stronge", 3, None, ["han"]):
        with pytest.raises(SceneError) as err:
            load_scene({"physics": {"cushion": bad}})
        assert str(err.value) == "physics.cushion: must be one of 'simple', 'han', 'mathavan'"


def test_each_model_brings_its_own_e_and_mu_unless_given():
    for name, mod in MODELS.items():
        ph = Physics(cushion=name)
        assert (ph.e_cushion, ph.mu_cushion) == (mod.E_CUSHION, mod.MU_CUSHION)
    ph = Physics.from_dict({"cushion": "mathavan", "e_cushion": 0.7})
    assert (ph.e_cushion, ph.mu_cushion) == (0.7, mathavan.MU_CUSHION)


def simple_match() -> dict:
    m = Match("9ball", seed=3, players=("Ann", "Bob"), physics=Physics(cushion="simple"))
    m.begin(Shot(8.0, 0.0)).finish()
    return json.loads(json.dumps(m.to_json()))


def test_records_from_before_the_choice_replay_with_the_simple_cushion():
    data = simple_match()
    old = copy.deepcopy(data)
    for rec in old["shots"]:
        del rec["scene"]["physics"]["cushion"]
    assert all(r["ok"] for r in replay(old))
    other = copy.deepcopy(data)
    for rec in other["shots"]:
        rec["scene"]["physics"]["cushion"] = "mathavan"
    assert not any(r["ok"] for r in replay(other))  # the key is read, not ignored


def test_a_saved_match_from_before_the_choice_keeps_the_simple_cushion():
    data = simple_match()
    del data["match"]["physics"]["cushion"]
    assert Match.from_json(data).physics.cushion == "simple"


@pytest.mark.parametrize("ph", [Physics(cushion="mathavan"),
                                Physics(cushion="mathavan", e_cushion=1.0, mu_cushion=0.0),
                                Physics(cushion="mathavan", mu_cushion=5.0, mu_slide=3.0,
                                        cushion_height=0.01)])
def test_mathavan_on_arrays_gives_the_float_forms_bits_signed_zeros_included(ph):
    """The array form steps the slips and impulses in pairs of rows: every ball's rebound
    is the float form's to the bit (zeros' signs too), for zero, grazing and huge speeds and
    spins, balls moving along or off the rail, and random approaches, all in one array."""
    cases = [(n, v, w, R, M) for n, v, w in extreme_cases()]
    cases += list(random_cases(7, 300))
    cases += [(UP, [0.0, 0.0], [0.0, 0.0, 0.0], R, M), (UP, [1.0, -0.0], [-0.0, 0.0, 0.0], R, M)]
    n, v, w, r, m = (np.array(x, dtype=float) for x in zip(*cases, strict=True))
    with np.errstate(all="ignore"):
        V, W = mathavan.bounce_many(n.reshape(-1, 2), v.reshape(-1, 2), w.reshape(-1, 3), r, m,
                                    ph)
    for x, (nx, vx, wx, rx, mx) in enumerate(cases):
        vo, wo = mathavan.bounce_one(list(nx), list(vx), list(wx), rx, mx, ph)
        assert np.array(vo).tobytes() == V[x].tobytes()
        assert np.array(wo).tobytes() == W[x].tobytes()


@pytest.mark.parametrize("ph", [Physics(cushion="mathavan"),
                                Physics(cushion="mathavan", e_cushion=1.0, mu_cushion=0.0)])
def test_mathavan_on_arrays_steps_all_balls_at_once_as_the_float_form(ph, monkeypatch):
    """Balls that all hit the cushion at the same speed (at different spins and speeds
    along the rail): the array form steps every ball at once, without a mask, until the
    first of them ends its phase; with one ball added that does not hit, every step is
    masked. Each ball's rebound is the float form's to the bit either way."""
    masks = []
    real = mathavan._step
    monkeypatch.setattr(mathavan, "_step", lambda *a: masks.append(a[4] is None) or real(*a))
    rng = np.random.default_rng(4)
    k = 40
    v = np.column_stack([rng.uniform(-0.5, 0.5, k), np.full(k, 1.5)])  # 1.5 m/s into it
    w = rng.normal(0.0, 30.0, (k, 3))
    for extra in ([], [([0.0, -0.4], [0.0, 0.0, 0.0])]):  # the extra one moves away
        vv = np.concatenate([v, [e[0] for e in extra]]) if extra else v
        ww = np.concatenate([w, [e[1] for e in extra]]) if extra else w
        n = np.tile(UP, (len(vv), 1))
        r, m = np.full(len(vv), R), np.full(len(vv), M)
        masks.clear()
        V, W = mathavan.bounce_many(n, vv, ww, r, m, ph)
        assert masks and any(masks) == (not extra)
        for x in range(len(vv)):
            vo, wo = mathavan.bounce_one(UP, vv[x].tolist(), ww[x].tolist(), R, M, ph)
            assert np.array(vo).tobytes() == V[x].tobytes()
            assert np.array(wo).tobytes() == W[x].tobytes()
