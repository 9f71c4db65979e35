"""Aiming aids: the straight-line cast against hand-worked cases and the engine, and the pixels
of the overlays (aim line, ghost ball, stick, placement ring, spin face, power bar)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from termpool.physics.engine import Engine
from termpool.physics.params import BALL_RADIUS, Physics
from termpool.physics.table import Table
from termpool.ui.aim import Aim, aim_direction, aim_trace
from termpool.ui.canvas import Canvas
from termpool.ui.overlay import (
    PULL_M,
    STICK_GAP_M,
    blit_cells,
    draw_cue_stick,
    draw_placement,
    draw_prediction,
    mono_prediction,
    power_meter_cells,
    spin_face_cells,
)
from termpool.ui.palette import (
    AIM,
    AIM_C,
    BUTT_C,
    CUE,
    EIGHT,
    GUIDE_C,
    PLACE_BAD_C,
    PLACE_OK_C,
    POWER_C,
    SOLID,
    SPIN_DOT_C,
    SPIN_LIMIT_C,
    STICK_C,
    STRIPE,
    TIP_C,
)
from termpool.ui.predict import Leg, Prediction
from termpool.ui.table_view import TableView, layout

R = BALL_RADIUS
TABLE = Table()  # 9 ft, standard pockets
L, W = TABLE.length, TABLE.width


def trace(pos, angle, on_table=None, radius=R, cue=0, **kw) -> Aim:
    return aim_trace(TABLE, np.array(pos, dtype=float), radius, on_table, cue, angle, **kw)


# ------------------------------------------------------------------ geometry, worked by hand


def test_straight_shot_stops_2r_short_of_the_object_ball():
    a = trace([[0.6, 0.635], [1.4, 0.635]], 0.0)
    assert a.hit == "ball" and a.ball == 1
    assert a.ghost == pytest.approx((1.4 - 2 * R, 0.635), abs=1e-12)
    assert a.cut == pytest.approx(0.0, abs=1e-9)
    assert a.object_dir == pytest.approx((1.0, 0.0), abs=1e-12)
    assert a.cue_dir is None  # full ball: a stunned cue ball stops dead


def test_thirty_degree_cut():
    # The object ball sits R off the line of aim: at contact the centres are 2R apart and R
    # apart across the line, so the line of centres is 30 degrees off the aim.
    a = trace([[0.5, 0.6], [1.3, 0.6 + R]], 0.0)
    assert a.hit == "ball" and a.ball == 1
    assert a.ghost == pytest.approx((1.3 - math.sqrt(3) * R, 0.6), abs=1e-12)
    assert a.cut == pytest.approx(30.0, abs=1e-9)
    assert a.object_dir == pytest.approx((math.sqrt(3) / 2, 0.5), abs=1e-12)
    # The stunned cue ball leaves square to the line of centres, on the far side.
    assert a.cue_dir == pytest.approx((0.5, -math.sqrt(3) / 2), abs=1e-12)


def test_cut_on_the_other_side_mirrors():
    a = trace([[0.5, 0.6], [1.3, 0.6 - R]], 0.0)
    assert a.object_dir == pytest.approx((math.sqrt(3) / 2, -0.5), abs=1e-12)
    assert a.cue_dir == pytest.approx((0.5, math.sqrt(3) / 2), abs=1e-12)


def test_first_of_two_balls_in_line_is_hit_whatever_their_order():
    a = trace([[0.5, 0.6], [1.8, 0.6], [1.2, 0.6]], 0.0)
    assert a.ball == 2 and a.ghost[0] == pytest.approx(1.2 - 2 * R, abs=1e-12)
    b = trace([[0.5, 0.6], [1.2, 0.6], [1.8, 0.6]], 0.0)
    assert b.ball == 1 and b.ghost[0] == pytest.approx(1.2 - 2 * R, abs=1e-12)


def test_cue_ball_need_not_be_first():
    a = trace([[1.2, 0.6], [0.5, 0.6]], 0.0, cue=1)
    assert a.ball == 0 and a.ghost[0] == pytest.approx(1.2 - 2 * R, abs=1e-12)


def test_pocketed_balls_are_ignored():
    a = trace([[0.5, 0.6], [1.2, 0.6], [1.8, 0.6]], 0.0, on_table=[True, False, True])
    assert a.ball == 2 and a.ghost[0] == pytest.approx(1.8 - 2 * R, abs=1e-12)
    # With no ball left in the way, the ray goes on to the foot cushion.
    b = trace([[0.5, 0.6], [1.2, 0.6]], 0.0, on_table=[True, False])
    assert b.hit == "cushion" and b.ghost == pytest.approx((L - R, 0.6), abs=1e-12)


def test_different_radii_meet_at_the_sum():
    a = trace([[0.5, 0.6], [1.2, 0.6]], 0.0, radius=[0.03, 0.02])
    assert a.ghost[0] == pytest.approx(1.2 - 0.05, abs=1e-12)
    assert trace([[0.5, 0.6], [1.2, 0.6]], 0.0, radius=None).ghost[0] == pytest.approx(
        1.2 - 2 * R, abs=1e-12)


@pytest.mark.parametrize("angle, ghost", [
    (90.0, (0.7, W - R)), (-90.0, (0.7, R)), (270.0, (0.7, R)), (180.0, (R, 0.4)),
    (0.0, (L - R, 0.4)), (360.0, (L - R, 0.4)), (-0.0, (L - R, 0.4)),
])
def test_ray_to_a_rail_stops_r_from_the_cushion_line(angle, ghost):
    a = trace([[0.7, 0.4]], angle)
    assert a.hit == "cushion" and a.ball is None and a.object_dir is None and a.cut is None
    assert a.ghost == pytest.approx(ghost, abs=1e-12)


def test_oblique_ray_to_a_rail():
    a = trace([[0.7, 0.4]], 30.0)
    assert a.hit == "cushion"
    assert a.ghost == pytest.approx((0.7 + (W - R - 0.4) / math.tan(math.radians(30)), W - R),
                                    abs=1e-12)


def test_rail_gap_moves_the_cushion_contact():
    a = trace([[0.7, 0.4]], 90.0, rail_gap=0.02)
    assert a.ghost == pytest.approx((0.7, W - 0.02), abs=1e-12)


def test_aim_into_a_corner_pocket_is_reported_as_pocket():
    # Down the diagonal into the head-right corner: clear of both jaws, into the hole.
    a = trace([[0.4, 0.4]], 225.0)
    assert a.hit == "pocket" and a.ball is None
    k = int(np.argmin(np.hypot(*(TABLE.hole_c - np.array(a.ghost)).T)))
    assert TABLE.hole_names[k] == "head_right"
    assert math.dist(a.ghost, TABLE.hole_c[k]) == pytest.approx(TABLE.hole_r[k], abs=1e-12)
    assert a.ghost[0] == pytest.approx(a.ghost[1], abs=1e-12)  # still on the diagonal


def test_aim_into_a_side_pocket_is_reported_as_pocket():
    a = trace([[L / 2, 0.6]], 90.0)
    k = TABLE.hole_names.index("side_left")
    assert a.hit == "pocket"
    assert a.ghost == pytest.approx((L / 2, TABLE.hole_c[k][1] - TABLE.hole_r[k]), abs=1e-12)


def test_aim_at_a_pocket_jaw_stops_on_the_jaw():
    # Along the long rail, 6 cm out, into the head-right corner: the ball meets the jaw face
    # that leaves the short rail's nose at (0, a), turned 38 degrees (180 - 142) from it.
    y = 0.06
    a_tip = TABLE.corner_mouth / math.sqrt(2)
    turn = math.radians(180 - TABLE.corner_jaw_angle)
    # The jaw runs from (0, a_tip) along (-sin turn, -cos turn); the centre is R from it.
    x = (R - (a_tip - y) * math.sin(turn)) / math.cos(turn)
    a = trace([[0.6, y]], 180.0)
    assert a.hit == "cushion"
    assert a.ghost == pytest.approx((x, y), abs=1e-12)
    assert 0 < x < R  # past the rail's end: it is the jaw, not the short rail, that stops it


def test_aim_just_inside_the_jaw_tip_stops_on_the_tip():
    # The short rail's tip at (0, a) lies 0.6 R off the line of aim: the centres meet R apart,
    # 0.8 R short of it (a 3-4-5 triangle).
    a_tip = TABLE.corner_mouth / math.sqrt(2)
    a = trace([[0.5, a_tip - 0.6 * R]], 180.0)
    assert a.hit == "cushion"
    assert a.ghost == pytest.approx((0.8 * R, a_tip - 0.6 * R), abs=1e-12)


def test_balls_touching_the_cue_ball():
    pos = [[1.0, 0.6], [1.0 + 2 * R, 0.6]]
    full = trace(pos, 0.0)
    assert full.hit == "ball" and full.ball == 1
    assert full.ghost == pytest.approx((1.0, 0.6), abs=1e-15) and full.cut == pytest.approx(0)
    thin = trace(pos, 60.0)
    assert thin.hit == "ball" and thin.ghost == pytest.approx((1.0, 0.6), abs=1e-15)
    assert thin.cut == pytest.approx(60.0, abs=1e-9)
    # Aiming away from it, or along the tangent, leaves it alone.
    assert trace(pos, 180.0).hit == "cushion"
    assert trace(pos, 90.0).hit == "cushion"
    assert trace(pos, -90.0).hit == "cushion"


def test_cue_ball_frozen_to_the_rail():
    a = trace([[0.7, R]], -90.0)
    assert a.hit == "cushion" and a.ghost == pytest.approx((0.7, R), abs=1e-15)
    assert trace([[0.7, R]], 90.0).ghost == pytest.approx((0.7, W - R), abs=1e-12)


def test_no_cushion_on_a_table_without_pockets_is_missed():
    plain = Table(pockets="none")
    for angle in (0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0):
        a = aim_trace(plain, np.array([[0.7, 0.4]]), R, None, 0, angle)
        assert a.hit == "cushion"


def test_outside_the_table_nothing_is_hit():
    a = trace([[-1.0, -1.0]], 180.0)
    assert a.hit == "none" and a.ball is None
    assert all(math.isfinite(v) for v in a.ghost)


@pytest.mark.parametrize("angle", [0.0, 90.0, 180.0, 270.0, -180.0, 45.0, 1e-300, 89.99999999,
                                   1e6, -720.0])
def test_no_nan_at_any_angle(angle):
    pos = [[0.7, 0.4], [1.5, 0.4], [0.7, 1.0], [0.3, 0.4], [0.7, 0.1]]
    a = trace(pos, angle)
    vals = list(a.ghost) + list(a.object_dir or ()) + list(a.cue_dir or ())
    vals += [a.cut] if a.cut is not None else []
    assert all(math.isfinite(v) for v in vals)
    assert a.hit in ("ball", "cushion", "pocket")


def test_exact_axis_directions():
    assert aim_direction(0) == (1.0, 0.0) and aim_direction(90) == (0.0, 1.0)
    assert aim_direction(180) == (-1.0, 0.0) and aim_direction(-90) == (0.0, -1.0)
    assert aim_direction(450) == (0.0, 1.0)
    assert aim_direction(30) == pytest.approx((math.sqrt(3) / 2, 0.5), abs=1e-15)


@pytest.mark.parametrize("kw, field", [
    ({"angle": float("nan")}, "aim.angle"),
    ({"angle": float("inf")}, "aim.angle"),
    ({"cue": 3}, "aim.cue"),
    ({"cue": -1}, "aim.cue"),
    ({"on_table": [True]}, "aim.on_table"),
    ({"on_table": [0, 0]}, "aim.on_table"),  # engine state codes, not a mask
])
def test_bad_input_names_the_field(kw, field):
    args = {"angle": 0.0, "cue": 0, "on_table": None} | kw
    with pytest.raises(ValueError, match=field):
        trace([[0.5, 0.6], [1.0, 0.6]], args["angle"], on_table=args["on_table"],
              cue=args["cue"])


# ------------------------------------------------------------------ geometry, as properties


def _seg_dist(p, a, b) -> float:
    """Distance from point p to segment a-b."""
    p, a, b = (np.asarray(v, float) for v in (p, a, b))
    u = b - a
    s = min(1.0, max(0.0, float((p - a) @ u / (u @ u)))) if u @ u > 0 else 0.0
    return float(np.linalg.norm(p - a - s * u))


def _segs_dist(a, b, c, d) -> float:
    """Distance between segments a-b and c-d (0 when they cross)."""
    def orient(p, q, r):
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
    if (orient(a, b, c) * orient(a, b, d) < 0) and (orient(c, d, a) * orient(c, d, b) < 0):
        return 0.0
    return min(_seg_dist(a, c, d), _seg_dist(b, c, d), _seg_dist(c, a, b), _seg_dist(d, a, b))


coord = st.tuples(st.floats(2 * R, L - 2 * R), st.floats(2 * R, W - 2 * R))


@given(cue=coord, others=st.lists(coord, min_size=0, max_size=4),
       angle=st.floats(-360.0, 360.0, allow_nan=False))
def test_the_ghost_is_the_first_contact_along_the_ray(cue, others, angle):
    pos = np.array([cue] + others)
    n = len(pos)
    for i in range(n):
        for j in range(i):
            assume(np.linalg.norm(pos[i] - pos[j]) > 2 * R + 1e-6)
    a = trace(pos, angle)
    c, g = pos[0], np.array(a.ghost)
    d = np.array(aim_direction(angle))
    # On the ray, forwards.
    assert abs((g - c)[0] * d[1] - (g - c)[1] * d[0]) < 1e-9 and (g - c) @ d >= -1e-12
    # Nothing is met before the ghost ...
    for k in range(1, n):
        assert _seg_dist(pos[k], c, g) >= 2 * R - 1e-9
    for sa, sb in zip(TABLE.seg_a, TABLE.seg_b, strict=True):
        assert _segs_dist(c, g, sa, sb) >= R - 1e-9
    for hc, hr in zip(TABLE.hole_c, TABLE.hole_r, strict=True):
        assert _seg_dist(hc, c, g) >= hr - 1e-9
    # ... and the ghost touches what was hit.
    if a.hit == "ball":
        assert np.linalg.norm(pos[a.ball] - g) == pytest.approx(2 * R, abs=1e-9)
        n_obj = (pos[a.ball] - g) / (2 * R)
        assert a.object_dir == pytest.approx(tuple(n_obj), abs=1e-9)
        assert math.cos(math.radians(a.cut)) == pytest.approx(n_obj @ d, abs=1e-9)
    elif a.hit == "cushion":
        near = min(_seg_dist(g, sa, sb) for sa, sb in zip(TABLE.seg_a, TABLE.seg_b, strict=True))
        assert near == pytest.approx(R, abs=1e-9)
    else:
        assert a.hit == "pocket"
        assert min(np.hypot(*(TABLE.hole_c - g).T) - TABLE.hole_r) == pytest.approx(0, abs=1e-9)


# ------------------------------------------------------------------ agreement with the engine


def _first_event(pos, angle, physics, kinds=("ball_ball", "cushion", "pocket"), speed=2.5):
    pos = np.array(pos, dtype=float)
    vel = np.zeros_like(pos)
    vel[0] = speed * np.array(aim_direction(angle))  # a stun shot: no spin at the strike
    eng = Engine(TABLE, physics, pos, vel, None, R, record=True)
    eng.run(1 / 60, duration=3.0)
    return eng, next(e for e in eng.events[0] if e["type"] in kinds)


STUN_SHOTS = [
    ([[0.6, 0.5], [1.5, 0.62]], 7.0),
    ([[0.6, 0.5], [1.5, 0.62]], 5.0),
    ([[0.6, 0.5], [1.5, 0.62], [1.9, 0.4]], -3.0),
    ([[0.6, 0.5], [1.5, 0.62], [1.9, 0.4]], -4.5),
    ([[1.9, 0.9], [1.1, 0.45], [0.7, 0.3]], 209.0),
    ([[1.0, 0.3], [1.2, 1.0]], 75.0),
]


@pytest.mark.parametrize("pos, angle", STUN_SHOTS)
def test_ghost_and_object_line_match_the_engine(pos, angle):
    a = trace(pos, angle)
    assert a.hit == "ball"
    _eng, ev = _first_event(pos, angle, Physics(ball_ball="frictionless"))
    assert ev["type"] == "ball_ball" and ev["i"][:2] == [0, a.ball]
    cue, obj = ev["balls"][0], ev["balls"][1]
    assert math.dist((cue["x"], cue["y"]), a.ghost) < 1e-6
    v = np.array([obj["vx"], obj["vy"]])
    assert np.abs(v / np.linalg.norm(v) - np.array(a.object_dir)).max() < 1e-6


@pytest.mark.parametrize("pos, angle", STUN_SHOTS)
def test_tangent_line_matches_an_elastic_engine(pos, angle):
    a = trace(pos, angle)
    _eng, ev = _first_event(pos, angle, Physics(ball_ball="frictionless", e_ball=1.0))
    cue = ev["balls"][0]
    v = np.array([cue["vx"], cue["vy"]])
    assert np.abs(v / np.linalg.norm(v) - np.array(a.cue_dir)).max() < 1e-6


@pytest.mark.parametrize("pos, angle, feature", [
    ([[0.7, 0.4]], 30.0, "rail"),
    ([[0.6, 0.06]], 180.0, "jaw"),
    ([[0.5, TABLE.corner_mouth / math.sqrt(2) - 0.3 * R]], 180.0, "tip"),
])
def test_cushion_contact_matches_the_engine_with_its_gap(pos, angle, feature):
    eng, ev = _first_event(pos, angle, Physics())
    a = trace(pos, angle, rail_gap=float(eng.rc[0, 0]))
    assert a.hit == "cushion" and ev["type"] == "cushion" and ev["feature"] == feature
    assert math.dist((ev["balls"][0]["x"], ev["balls"][0]["y"]), a.ghost) < 1e-6


def test_pocket_matches_the_engine():
    _eng, ev = _first_event([[0.4, 0.4]], 225.0, Physics())
    assert ev["type"] == "pocket" and ev["pocket"] == "head_right"
    assert trace([[0.4, 0.4]], 225.0).hit == "pocket"


# ------------------------------------------------------------------ overlay pixels


@pytest.fixture(scope="module")
def view():
    lay = layout(200, 60, TABLE)
    return TableView(TABLE, lay)


def _px(lay, p):
    x, y = lay.to_pixels(p[0], p[1])
    return np.array([float(x), float(y)])


def _coloured(cv, colour):
    jj, ii = np.nonzero((cv.rgb == np.array(colour.rgb, np.uint8)).all(axis=2) & (cv.tag == AIM))
    return np.stack([ii + 0.5, jj + 0.5], axis=1)  # pixel centres


def straight(a: Aim, cue) -> Prediction:
    """A prediction along a straight cast (the cue ball to the ghost; the first ball along
    the line of centres and the cue ball along the tangent, 0.3 and 0.2 m): the drawing
    tests' paths, known exactly."""
    g = np.array(a.ghost)
    if a.ball is None:
        return Prediction(Leg(np.array([cue, g]), a.hit))
    o = g + 2 * R * np.array(a.object_dir)
    obj = Leg(np.array([o, o + 0.3 * np.array(a.object_dir)]), "rest")
    after = Leg(np.array([g, g + 0.2 * np.array(a.cue_dir)]), "rest")
    return Prediction(Leg(np.array([cue, g]), "ball"), a.ball, a.ghost, obj, after)


def on_path(pts, path, lay) -> np.ndarray:
    """Each pixel centre's distance (pixels) from a polyline given in table metres."""
    P = np.array([_px(lay, p) for p in path])
    best = np.full(len(pts), np.inf)
    for a, b in zip(P, P[1:], strict=False):
        ab = b - a
        t = np.clip(((pts - a) @ ab) / (ab @ ab), 0.0, 1.0)
        best = np.minimum(best, np.linalg.norm(pts - (a + t[:, None] * ab), axis=1))
    return best


def test_aim_line_pixels_lie_on_the_ray(view):
    lay = view.layout
    pos = [[0.5, 0.3], [2.0, 1.0]]
    a = trace(pos, math.degrees(math.atan2(0.7, 1.5)) + 1.0)
    assert a.hit == "ball"
    cv = view.background.copy()
    draw_prediction(cv, lay, straight(a, pos[0]), R, "ghost")
    c, g = _px(lay, pos[0]), _px(lay, a.ghost)
    u = (g - c) / np.linalg.norm(g - c)
    pts = _coloured(cv, AIM_C)
    r_px = R * lay.scale
    line = pts[np.linalg.norm(pts - g, axis=1) > r_px + 1.0]
    rel = line - c
    across = np.abs(rel[:, 0] * u[1] - rel[:, 1] * u[0])
    along = rel @ u
    assert across.max() <= math.sqrt(0.5) + 1e-9
    assert along.min() > 0 and along.max() < np.linalg.norm(g - c)
    # Dotted: about half of the pixels it crosses, spread over the whole length.
    length = np.linalg.norm(g - c) - 2 * r_px
    assert 0.3 * length < len(line) < 0.8 * length
    assert along.max() - along.min() > 0.9 * length


def test_ghost_outline_is_centred_on_the_ghost(view):
    lay = view.layout
    pos = [[0.7, 0.4]]
    a = trace(pos, 30.0)
    cv = view.background.copy()
    draw_prediction(cv, lay, straight(a, pos[0]), R)
    g = _px(lay, a.ghost)
    r_px = R * lay.scale
    pts = _coloured(cv, AIM_C)
    ring = pts[np.linalg.norm(pts - g, axis=1) <= r_px + 0.5 + 1e-9]
    assert len(ring) >= 8
    assert np.abs(np.linalg.norm(ring - g, axis=1) - r_px).max() <= 0.5 + 1e-9
    assert np.linalg.norm(ring.mean(axis=0) - g) < 0.5


def test_the_paths_follow_the_prediction_even_where_they_bend(view):
    lay = view.layout
    ghost = np.array([1.2, 0.6])
    obj = Leg(np.array([ghost + [2 * R, 0.0], [1.8, 0.6], [2.1, 0.9]]), "cushion")
    bend = [ghost + [0.3 * (1 - math.cos(t)), 0.3 * math.sin(t)] for t in np.linspace(0, 1, 12)]
    pred = Prediction(Leg(np.array([[0.4, 0.6], ghost]), "ball"), 1, tuple(ghost), obj,
                      Leg(np.array(bend), "rest"))
    cv = view.background.copy()
    draw_prediction(cv, lay, pred, R)
    r_px = R * lay.scale
    from termpool.ui.palette import OBJECT_C

    # The cue ball's path and the ghost in white, the first ball's path and its end in pink.
    solid = np.concatenate([_coloured(cv, AIM_C), _coloured(cv, OBJECT_C)])
    assert on_path(_coloured(cv, OBJECT_C), obj.points, lay).max() <= r_px + 0.5 + 1e-9
    rings = np.zeros(len(solid), bool)
    for p in (ghost, obj.points[-1]):
        rings |= np.abs(np.linalg.norm(solid - _px(lay, p), axis=1) - r_px) <= 0.5 + 1e-9
    lines = solid[~rings]
    d = np.minimum(on_path(lines, obj.points, lay), on_path(lines, pred.cue.points, lay))
    assert d.max() <= math.sqrt(0.5) + 1e-9
    # The first ball's path is solid: nearly every pixel of its length is drawn.
    length = sum(np.linalg.norm(_px(lay, q) - _px(lay, p))
                 for p, q in zip(obj.points, obj.points[1:], strict=False)) - 2 * r_px
    assert (on_path(lines, obj.points, lay) <= 0.75).sum() >= 0.8 * length
    guide = _coloured(cv, GUIDE_C)
    ring = np.abs(np.linalg.norm(guide - _px(lay, bend[-1]), axis=1) - r_px) <= 0.5 + 1e-9
    assert len(guide[~ring]) > 5 and on_path(guide[~ring], bend, lay).max() <= math.sqrt(0.5) + 1e-9
    assert not _coloured(view.background.copy(), GUIDE_C).size


def test_ghost_level_draws_the_cue_path_and_the_ghost_only(view):
    lay = view.layout
    pos = [[0.5, 0.6], [1.3, 0.6 + R]]
    a = trace(pos, 0.0)
    pred = straight(a, pos[0])
    cv = view.background.copy()
    draw_prediction(cv, lay, pred, R, "ghost")
    assert not len(_coloured(cv, GUIDE_C))
    u = np.array([a.object_dir[0], -a.object_dir[1]])
    pts = _coloured(cv, AIM_C) - _px(lay, a.ghost)
    assert not ((pts @ u) > 4 * R * lay.scale).any()
    off = view.background.copy()
    draw_prediction(off, lay, pred, R, "off")
    assert (off.rgb == view.background.rgb).all()


def test_a_path_into_a_pocket_has_no_ring(view):
    lay = view.layout
    hole = TABLE.hole_c.reshape(-1, 2)[0]
    pred = Prediction(Leg(np.array([[0.6, 0.6], hole]), "pocket", "head_right"))
    cv = view.background.copy()
    draw_prediction(cv, lay, pred, R)
    pts = _coloured(cv, AIM_C)
    assert len(pts) and on_path(pts, pred.cue.points, lay).max() <= math.sqrt(0.5) + 1e-9


def test_overlays_leave_the_balls_alone(view):
    lay = view.layout
    ids = ["cue", "3", "9"]
    pos = np.array([[0.5, 0.6], [1.3, 0.6 + R], [1.35 + 3 * R, 0.6 + 3 * R]])
    cv = view.draw(ids, pos, None, R, canvas=view.background.copy())
    before = cv.copy()
    balls = np.isin(before.tag, [SOLID, STRIPE, EIGHT, CUE])
    a = trace(pos, 0.0)
    draw_prediction(cv, lay, straight(a, pos[0]), R)
    draw_cue_stick(cv, lay, pos[0], R, 0.0, 0.5)
    draw_placement(cv, lay, pos[0], R, False)
    assert (cv.rgb[balls] == before.rgb[balls]).all()
    assert (cv.tag != before.tag).any()


@pytest.mark.parametrize("angle", [0.0, 37.0, 90.0, 200.0, -45.0])
def test_stick_lies_opposite_the_aim(view, angle):
    lay = view.layout
    cue = (1.3, 0.6)
    cv = view.background.copy()
    draw_cue_stick(cv, lay, cue, R, angle)
    c = _px(lay, cue)
    dx, dy = aim_direction(angle)
    back = np.array([-dx, dy])  # opposite the aim, in pixels
    pts = np.concatenate([_coloured(cv, k) for k in (TIP_C, STICK_C, BUTT_C)])
    rel = pts - c
    along = rel @ back
    across = np.abs(rel[:, 0] * back[1] - rel[:, 1] * back[0])
    assert len(pts) > 20
    assert along.min() >= (R + STICK_GAP_M) * lay.scale - 1.0
    assert across.max() <= 0.015 * lay.scale + 1e-9
    # The tip is nearest the ball, the butt farthest.
    tip = _coloured(cv, TIP_C) - c
    butt = _coloured(cv, BUTT_C) - c
    assert (tip @ back).max() < (butt @ back).min()


def test_stick_draws_back_with_pull(view):
    lay = view.layout
    cue = (1.3, 0.6)
    near = []
    for pull in (0.0, 0.5, 1.0):
        cv = view.background.copy()
        draw_cue_stick(cv, lay, cue, R, 0.0, pull)
        tip = _coloured(cv, TIP_C)
        near.append(np.linalg.norm(tip - _px(lay, cue), axis=1).min())
    assert near[0] < near[1] < near[2]
    assert near[2] - near[0] == pytest.approx(PULL_M * lay.scale, abs=1.5)
    cv = view.background.copy()
    draw_cue_stick(cv, lay, cue, R, 0.0, 5.0)  # beyond full power: held at full pull
    tip = _coloured(cv, TIP_C)
    assert np.linalg.norm(tip - _px(lay, cue), axis=1).min() == pytest.approx(near[2])


def test_placement_ring_red_where_illegal(view):
    lay = view.layout
    p = (1.0, 0.5)
    for ok, colour, other in ((True, PLACE_OK_C, PLACE_BAD_C), (False, PLACE_BAD_C, PLACE_OK_C)):
        cv = view.background.copy()
        draw_placement(cv, lay, p, R, ok)
        ring = _coloured(cv, colour)
        assert len(ring) >= 8 and not len(_coloured(cv, other))
        dist = np.linalg.norm(ring - _px(lay, p), axis=1)
        assert dist.min() > R * lay.scale - 1e-9 and dist.max() <= R * lay.scale + 1.0 + 1e-9


def test_overlays_clip_at_the_canvas_edge():
    small = layout(40, 12, TABLE)
    cv = TableView(TABLE, small).background.copy()
    draw_cue_stick(cv, small, (0.05, 0.05), R, 45.0, 1.0)  # the stick runs off the canvas
    draw_prediction(cv, small, Prediction(Leg(np.array([[0.05, 0.05], [50.0, 50.0]]), "open")),
                    R)
    draw_placement(cv, small, (-5.0, -5.0), R, True)
    assert (cv.tag == AIM).any()


def test_mono_aim_off_the_grid_is_clipped(view):
    chars = view.mono(["cue"], np.array([[0.7, 0.4]]), None, R)
    before = chars.copy()
    mono_prediction(chars, view.layout,
                    Prediction(Leg(np.array([[0.7, 0.4], [60.0, -40.0]]), "cushion")))
    assert (chars != before).any() and (before[chars != before] == " ").all()


def test_mono_aim_marks_the_paths_and_the_ghost(view):
    lay = view.layout
    pos = [[0.5, 0.6], [1.3, 0.6 + R]]
    a = trace(pos, 0.0)
    chars = view.mono(["cue", "1"], np.array(pos), None, R)
    before = chars.copy()
    mono_prediction(chars, lay, straight(a, pos[0]))
    gx, gy = _px(lay, a.ghost)
    cx, cy = _px(lay, pos[0])
    assert chars[int(gy) // 2, int(gx)] == "◌"
    dots = np.argwhere(chars == ".")
    assert len(dots) > 0.8 * (gx - cx) - 3
    assert (dots[:, 0] == int(cy) // 2).all()  # a flat shot: one row of dots
    # the first ball leaves at 30 degrees up-right: on screen, cells twice as tall as wide
    assert set(chars[chars != before]) == {".", "◌", "-", ":"} | ({"/"} & set(chars.ravel()))
    ghost_only = before.copy()
    mono_prediction(ghost_only, lay, straight(a, pos[0]), "ghost")
    assert set(ghost_only[ghost_only != before]) == {".", "◌"}


# ------------------------------------------------------------------ panel widgets


def _face_pixels(cells):
    chars, fg, bg = cells
    rows, cols = chars.shape
    px = np.empty((2 * rows, cols, 3), np.uint8)
    px[0::2], px[1::2] = fg, bg
    return px


def _where(px, colour):
    jj, ii = np.nonzero((px == np.array(colour.rgb, np.uint8)).all(axis=2))
    return ii, jj


def test_spin_dot_moves_right_for_side_and_up_for_top():
    def dot(side, top):
        ii, jj = _where(_face_pixels(spin_face_cells(side, top)), SPIN_DOT_C)
        assert len(ii) == 1
        return ii[0], jj[0]

    x0, y0 = dot(0.0, 0.0)
    xr, yr = dot(0.4, 0.0)
    xl, _ = dot(-0.4, 0.0)
    xu, yu = dot(0.0, 0.4)
    _, yd = dot(0.0, -0.4)
    assert xl < x0 < xr and yr == y0
    assert yu < y0 < yd and xu == x0


def test_spin_face_draws_the_miscue_limit():
    px = _face_pixels(spin_face_cells(0.0, 0.0, (13, 7)))
    ii, jj = _where(px, SPIN_LIMIT_C)
    rp = min(13, 14) / 2
    dist = np.hypot(ii + 0.5 - 13 / 2, jj + 0.5 - 7)
    assert len(ii) >= 8 and np.abs(dist - 0.5 * rp).max() <= 0.5
    # The dot at the limit sits on that circle.
    ii, jj = _where(_face_pixels(spin_face_cells(0.5, 0.0, (13, 7))), SPIN_DOT_C)
    assert abs(math.hypot(ii[0] + 0.5 - 6.5, jj[0] + 0.5 - 7) - 0.5 * rp) <= 0.75


def test_spin_face_mono_glyphs():
    chars, fg, bg = spin_face_cells(0.0, 0.3, mono=True)
    assert fg is None and bg is None
    assert (chars == "●").sum() == 1 and (chars == "░").any() and (chars == "·").any()


def test_power_bar_fills_in_proportion():
    width, label = 30, "power"
    bar = width - len(label) - 1

    def filled(level):
        chars, fg, _bg = power_meter_cells(level, width, label)
        assert "".join(chars[0, : len(label)]) == label
        part = chars[0, len(label) + 1:]
        n8 = 8 * int((part == "█").sum())
        for k, ch in enumerate("▏▎▍▌▋▊▉"):
            n8 += (k + 1) * int((part == ch).sum())
        coloured = (fg[0, len(label) + 1:] == np.array(POWER_C.rgb, np.uint8)).all(axis=1)
        assert coloured.sum() == math.ceil(n8 / 8)
        return n8

    for level in (0.0, 0.1, 0.25, 0.5, 0.77, 1.0):
        assert filled(level) == round(level * bar * 8)
    assert filled(2.0) == bar * 8 and filled(-1.0) == 0


def test_power_bar_keeps_room_for_the_bar():
    chars, _fg, _bg = power_meter_cells(1.0, 9, "a very long label")
    assert chars.shape == (1, 9)
    assert (chars[0] == "█").sum() >= 3


@pytest.mark.parametrize("call, field", [
    (lambda: power_meter_cells(float("nan"), 10, "p"), "power.level"),
    (lambda: power_meter_cells(0.5, 0, "p"), "power.width"),
    (lambda: spin_face_cells(float("nan"), 0.0), "spin.side"),
    (lambda: spin_face_cells(0.0, float("inf")), "spin.top"),
    (lambda: spin_face_cells(0.0, 0.0, (2, 1)), "spin.size"),
])
def test_widget_bad_input_names_the_field(call, field):
    with pytest.raises(ValueError, match=field):
        call()


def test_stick_bad_input_names_the_field(view):
    cv = view.background.copy()
    with pytest.raises(ValueError, match="stick.pull"):
        draw_cue_stick(cv, view.layout, (1.0, 0.5), R, 0.0, float("nan"))
    with pytest.raises(ValueError, match="stick.angle"):
        draw_cue_stick(cv, view.layout, (1.0, 0.5), R, float("nan"), 0.0)
    with pytest.raises(ValueError, match="stick.cue_pos"):
        draw_cue_stick(cv, view.layout, (float("nan"), 0.5), R, 0.0, 0.0)


def test_blit_cells_copies_and_clips():
    dst = (np.full((3, 5), " ", "<U1"), np.zeros((3, 5, 3), np.uint8),
           np.zeros((3, 5, 3), np.uint8))
    src = power_meter_cells(1.0, 4, "")
    blit_cells(dst, src, 1, 3)  # two of its four cells fit
    assert "".join(dst[0][1]) == "   ██"
    assert (dst[1][1, 3:] == POWER_C.rgb).all() and (dst[1][1, :3] == 0).all()
    blit_cells(dst, src, 5, 0)  # entirely outside: nothing
    mono = (np.full((2, 4), " ", "<U1"), None, None)
    blit_cells(mono, src, 0, -2)
    assert "".join(mono[0][0]) == "██  "


def test_same_inputs_give_the_same_pixels(view):
    pos = [[0.5, 0.6], [1.3, 0.6 + R]]
    out = []
    for _ in range(2):
        cv = Canvas(*view.layout.canvas_size)
        cv.copy_from(view.background)
        a = trace(pos, 3.3)
        draw_prediction(cv, view.layout, straight(a, pos[0]), R)
        draw_cue_stick(cv, view.layout, pos[0], R, 3.3, 0.4)
        out.append(cv.rgb.tobytes())
    assert out[0] == out[1]


def test_at_80x24_the_two_paths_differ_and_no_line_shares_a_balls_cell():
    from termpool.ui.palette import OBJECT_C

    lay = layout(80, 24, TABLE)
    small = TableView(TABLE, lay)
    for k in range(12):  # the object ball on even and odd pixel rows and columns
        obj = np.array([1.3 + 0.013 * k, 0.6 + 0.011 * k])
        cue = obj - np.array([0.6, 0.05 * (k % 3 - 1)])
        pos = np.array([cue, obj])
        cv = small.draw(["cue", "3"], pos, None, R, canvas=small.background.copy())
        balls = np.isin(cv.tag, [SOLID, STRIPE, EIGHT, CUE])
        cell_has_ball = balls[0::2] | balls[1::2]
        aim_at = obj + np.array([0.0, 1.6 * R * (k % 4 - 1.5) / 1.5])  # cuts either way
        a = trace(pos, math.degrees(math.atan2(*(aim_at - cue)[::-1])))
        assert a.ball == 1
        draw_prediction(cv, lay, straight(a, pos[0]), R)
        aid = cv.tag == AIM
        assert not (cell_has_ball & (aid[0::2] | aid[1::2])).any()
        cue_px, obj_px = _coloured(cv, AIM_C), _coloured(cv, OBJECT_C)
        assert len(cue_px) and len(obj_px)
        ring = max(1.0, R * lay.scale) + 0.5  # the ring where the first ball stops
        assert on_path(obj_px, straight(a, pos[0]).object.points, lay).max() <= ring + 0.71
    assert np.linalg.norm(np.subtract(OBJECT_C.rgb, AIM_C.rgb)) > 100
    assert OBJECT_C.c16 != AIM_C.c16 and OBJECT_C.c256 != AIM_C.c256
