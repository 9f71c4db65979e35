"""The closed-form references of `termpool bench accuracy`: that the answers themselves are
right (against numbers computed another way), and that the engine meets them within the
tolerance each case documents."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

from bench import closed as bench_closed
from bench import closed_cases as cc
from bench import closed_form as cf
from termpool.physics.params import BALL_RADIUS, Physics
from termpool.scene import load_scene

R = BALL_RADIUS
CASES = {c.name: c for c in cc.cases()}
DEFAULT = Physics()
ELASTIC = Physics.from_dict(cc.ELASTIC)


def fact(case: cc.Case, label: str) -> float:
    ans = case.model
    f = next(f for f in case.facts if f.label == label)
    return f.measure(ans.events, ans.start, ans.final)


def contact_state(ans: cf.Answer, ball: int = 0) -> dict:
    """The ball's state in the answer just before its first contact."""
    t = ans.contacts[0][0]
    pc = [p for p in ans.tracks[ball].pieces if p.t0 < t][-1]
    p, v, w = pc.state(t)
    return {"v": v, "w": w}


# ------------------------------------------------------------------ the answers are right


def test_slide_to_roll_is_twelve_forty_ninths_and_two_sevenths() -> None:
    case = CASES["slide_roll"]
    v0 = case.scene["balls"][0]["vx"]
    mu_s, mu_r, g = (Fraction(x) for x in (DEFAULT.mu_slide, DEFAULT.mu_roll, DEFAULT.g))
    v = Fraction(v0)
    slide = Fraction(12, 49) * v * v / (mu_s * g)
    rolling = Fraction(5, 7) * v
    assert fact(case, "slide distance") == pytest.approx(float(slide), rel=1e-13)
    assert fact(case, "slide time") == pytest.approx(float(2 * v / (7 * mu_s * g)), rel=1e-13)
    assert fact(case, "rolling speed / v") == pytest.approx(5 / 7, rel=1e-14)
    stop = slide + rolling * rolling / (2 * mu_r * g)
    assert fact(case, "stop distance") == pytest.approx(float(stop), rel=1e-13)
    t_stop = 2 * v / (7 * mu_s * g) + rolling / (mu_r * g)
    assert fact(case, "stop time") == pytest.approx(float(t_stop), rel=1e-13)
    # The seed model has no slide: the full speed decays at mu_r g.
    assert case.seed.final[0, 0] - case.seed.start[0, 0] == pytest.approx(
        float(v * v / (2 * mu_r * g)), rel=1e-13)


def test_rolling_stop_is_the_same_law_in_both_models() -> None:
    case = CASES["roll_stop"]
    v0 = case.scene["balls"][0]["vx"]
    law = v0 * v0 / (2 * DEFAULT.mu_roll * DEFAULT.g)
    assert fact(case, "stop distance") == pytest.approx(law, rel=1e-13)
    assert fact(case, "stop time") == pytest.approx(v0 / (DEFAULT.mu_roll * DEFAULT.g),
                                                    rel=1e-13)
    ts = np.linspace(0.0, 12.0, 97)
    assert np.abs(case.model.positions(ts) - case.seed.positions(ts)).max() < 1e-12


def test_stun_spin_is_gone_at_contact_and_the_cue_ball_stays() -> None:
    case = CASES["stun"]
    at = contact_state(case.model)
    assert abs(R * at["w"][1]) < 1e-12 and at["v"][0] > 1.0
    assert fact(case, "cue ball's travel after contact") == 0.0
    # e = 1: the object ball takes the cue ball's whole speed.
    assert fact(case, "object ball's speed after contact") == pytest.approx(at["v"][0],
                                                                             rel=1e-14)


def deflection(cut: float) -> float:
    c = math.radians(cut)
    return math.degrees(math.atan(math.sin(c) * math.cos(c) / (math.sin(c) ** 2 + 0.4)))


@pytest.mark.parametrize("cut", [10.0, 30.0, 45.0, 60.0, 80.0])
def test_thirty_degree_rule_two_derivations(cut: float) -> None:
    # The answer follows a rolling ball through the contact law and the slide; the rule is
    # the same physics solved on paper for the final direction.
    case = cc.thirty(cut_deg=cut)
    assert fact(case, "cue ball's final deflection") == pytest.approx(deflection(cut),
                                                                       abs=1e-11)
    assert fact(case, "object ball's direction") == pytest.approx(cut, abs=1e-11)


def test_half_ball_hit_deflects_the_rolling_cue_ball_by_33_7_degrees() -> None:
    assert fact(CASES["thirty"], "cue ball's final deflection") == pytest.approx(33.67,
                                                                                  abs=0.005)


@pytest.mark.parametrize("cut", [15.0, 30.0, 70.0])
def test_ninety_degree_rule(cut: float) -> None:
    case = cc.ninety(cut_deg=cut)
    assert fact(case, "angle between the paths after contact") == pytest.approx(90.0,
                                                                                 abs=1e-11)
    assert fact(case, "cue ball's final direction") == pytest.approx(cut - 90.0, abs=1e-11)


@pytest.mark.parametrize("name", ["follow", "draw"])
def test_follow_and_draw_end_at_two_sevenths(name: str) -> None:
    assert fact(CASES[name], "final speed / R w at contact") == pytest.approx(
        float(Fraction(2, 7)), rel=1e-14)


def test_draw_with_e_below_one_keeps_part_of_the_speed() -> None:
    case = CASES["draw_e95"]
    e = case.scene["physics"]["e_ball"]
    at = contact_state(case.model)
    v, rw = at["v"][0], R * at["w"][1]
    # The cue ball keeps (1 - e)/2 v with all its back spin, then slides to rolling:
    # v - u/3.5 with u = v - R w.
    kept = (1 - e) / 2 * v
    final = kept - (kept - rw) / 3.5
    assert final == pytest.approx(5 / 7 * kept + 2 / 7 * rw, rel=1e-12)
    assert fact(case, "final speed / R w at contact") == pytest.approx(final / rw, rel=1e-12)


def test_cradle_push_matches_the_quoted_figures() -> None:
    # The figures derived independently when the cradle was first measured: 4.42 mm, 0.481 s.
    case = CASES["cradle"]
    assert fact(case, "pushed balls' travel") == pytest.approx(4.42, abs=0.005)
    assert fact(case, "pushed balls stop at") == pytest.approx(0.481, abs=0.0005)


def test_cradle_push_is_the_limit_of_many_small_inelastic_pushes() -> None:
    """Integrate the push another way: a lone sliding cue ball gains mu_s g h each small
    step h, the rolling row loses mu_r g h, and a perfectly inelastic push merges them (each
    rolling ball answering a push with 7/5 of its mass). The travel and stop converge to the
    closed form's as h shrinks."""
    case = CASES["cradle"]
    ph = ELASTIC
    g, mu_s, mu_r = ph.g, ph.mu_slide, ph.mu_roll
    t_contact = case.model.contacts[0][0]
    rw = R * contact_state(case.model)["w"][1]
    heavy = 4 * 7 / 5

    def integrate(h: float) -> tuple[float, float]:
        vc = vg = x = 0.0
        t = 0.0
        while rw - 2.5 * mu_s * g * t > vc:  # the cue ball still slips
            vc += mu_s * g * h
            vg = max(vg - mu_r * g * h, 0.0)
            if vc > vg:
                vc = vg = (vc + heavy * vg) / (1 + heavy)
            x += vg * h
            t += h
        return x + vg * vg / (2 * mu_r * g), t_contact + t + vg / (mu_r * g)

    travel = 1e-3 * fact(case, "pushed balls' travel")
    stop = fact(case, "pushed balls stop at")
    coarse, fine = integrate(1e-4), integrate(1e-5)
    for k, exact in enumerate((travel, stop)):
        assert abs(fine[k] - exact) < abs(coarse[k] - exact) / 5
    assert fine[0] == pytest.approx(travel, rel=1e-3)
    assert fine[1] == pytest.approx(stop, abs=1e-4)


def test_group_push_acceleration_by_momentum() -> None:
    # Momentum of the body counting 7/5 for each rolling ball: friction mu_s m g on the
    # pusher, rolling resistance 7/5 m mu_r g on each pushed ball.
    for n in (1, 4):
        a = cf.group_push(DEFAULT, n)
        heavy = Fraction(7, 5) * n
        mu_s, mu_r, g = (Fraction(x) for x in (DEFAULT.mu_slide, DEFAULT.mu_roll, DEFAULT.g))
        assert a == pytest.approx(float(g * (mu_s - heavy * mu_r) / (1 + heavy)), rel=1e-14)


@pytest.mark.parametrize("name", cc.NAMES)
def test_answers_are_continuous_and_meet_nothing_else(name: str) -> None:
    """Every path joins up, ends at rest, stays clear of the cushions and of the other balls
    except at the contacts the answer names: the scene's answer needs nothing else."""
    case = CASES[name]
    table = case.scene["table"]
    for ans in (case.model, case.seed):
        for tr in ans.tracks:
            for a, b in zip(tr.pieces, tr.pieces[1:], strict=False):
                assert np.abs(a.state(b.t0)[0] - b.p0).max() < 1e-12
            assert tr.pieces[-1].kind == "rest"
            assert not tr.pieces[-1].v0.any() and not tr.pieces[-1].a.any()
        end = max(pc.t0 for tr in ans.tracks for pc in tr.pieces)
        ts = np.linspace(0.0, end, 4001)
        p = ans.positions(ts)
        assert (p[..., 0] > R).all() and (p[..., 0] < table["length"] - R).all()
        assert (p[..., 1] > R).all() and (p[..., 1] < table["width"] - R).all()
        gaps = np.linalg.norm(p[:, :, None] - p[:, None], axis=-1) - 2 * R
        gaps += 1.0 * np.eye(len(ans.tracks))
        assert gaps.min() > -1e-9


def test_names_list_every_case_once() -> None:
    assert tuple(CASES) == cc.NAMES


def test_scene_and_answer_agree_on_the_start() -> None:
    for case in CASES.values():
        scene = load_scene(case.scene)
        for ans in (case.model, case.seed):
            assert np.abs(ans.start - scene.pos).max() < 1e-12


# ------------------------------------------------------------------ the engine against them


@pytest.mark.parametrize("name", cc.NAMES)
def test_engine_within_the_documented_tolerance(name: str) -> None:
    case = CASES[name]
    ref = bench_closed.reference(case, load_scene(case.scene), timed=False)
    assert ref["matched"] == ref["expected"] > 0
    assert ref["path_mm"] <= case.tol_mm and ref["rest_mm"] <= case.tol_mm
    assert ref["event_ms"] <= case.tol_ms
    assert ref["within"]
    if case.tol_why == cc.EXACT_WHY:
        assert ref["extra"] == 0  # nothing the closed form does not have
    for f in ref["facts"]:
        assert math.isfinite(f["error"])


@pytest.mark.parametrize("name", ["cradle", "cradle_roll"])
def test_a_pushed_row_moves_as_one_body_in_a_handful_of_events(name: str) -> None:
    # The cue ball's spin pushes the four balls it stopped against as one body: no chatter
    # (nothing but the closed form's own events), and its travel and stop time are exact.
    case = CASES[name]
    ref = bench_closed.reference(case, load_scene(case.scene), timed=False)
    assert ref["matched"] == ref["expected"] <= 20
    assert ref["extra"] == 0
    assert ref["rest_mm"] <= cc.EXACT_MM


def test_seed_scheme_converges_on_its_own_model_only() -> None:
    case = CASES["slide_roll"]
    scene = load_scene(case.scene)
    rows = [bench_closed.run_scheme(case, scene, "naive", dt) for dt in (1 / 60, 1 / 600)]
    own = [r["own"]["err_mm"] for r in rows]
    assert 5 < own[0] / own[1] < 20  # first order in dt
    # Against the engine's model it stays metres off: no slide, so it rolls on at full speed.
    assert min(r["model"]["err_mm"] for r in rows) > 1000
