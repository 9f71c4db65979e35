"""Scene loading: validation messages, rack geometry, defaults, shots, round trip."""

from __future__ import annotations

import itertools
import json
import math
from dataclasses import fields
from pathlib import Path

import numpy as np
import pytest

from termpool.physics.cue import strike
from termpool.physics.params import BALL_MASS, BALL_RADIUS, PHYSICS_RANGES, Physics
from termpool.physics.table import Table
from termpool.scene import SceneError, load_scene, loads_scene, scene_to_dict

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = sorted((ROOT / "examples").glob("*.json"))
R = BALL_RADIUS


def two_balls(**shot) -> dict:
    d = {"balls": [{"id": "cue", "x": 0.6, "y": 0.6}, {"id": "1", "x": 1.5, "y": 0.6}]}
    if shot:
        d["shot"] = shot
    return d


def error(src) -> str:
    with pytest.raises(SceneError) as info:
        load_scene(src)
    msg = str(info.value)
    assert "\n" not in msg and msg.strip() == msg and msg
    assert isinstance(info.value, ValueError)
    return msg


# ------------------------------------------------------------------------------ validation


@pytest.mark.parametrize(
    "scene, expected",
    [
        # top level
        ({"balls": "8ball", "tabel": "9ft"}, "scene: unknown key 'tabel'"),
        ({"description": 5}, "description: must be a string"),
        # table
        ({"table": "10ft"}, "table: unknown preset '10ft'"),
        ({"table": 9}, "table: must be a preset name"),
        ({"table": {"lenght": 2.0}}, "table: unknown key 'lenght'"),
        ({"table": {"preset": "6ft"}}, "table.preset: unknown preset '6ft'"),
        ({"table": {"length": -2.0}}, "table.length: must be positive"),
        ({"table": {"width": 0}}, "table.width: must be positive"),
        ({"table": {"length": "long"}}, "table.length: must be a number"),
        ({"table": {"length": True}}, "table.length: must be a number"),
        ({"table": {"width": float("inf")}}, "table.width: must be finite"),
        ({"table": {"pockets": "some"}}, "table.pockets: must be 'standard' or 'none'"),
        ({"table": {"hole_depth": -0.1}}, "table.hole_depth: must not be negative"),
        ({"table": {"corner_jaw_angle": 200}}, "table.corner_jaw_angle: must be at most 180"),
        ({"table": {"length": 0.25, "width": 0.3}}, "table: pocket mouths do not fit"),
        ({"table": {"length": 2.0, "width": 0.15}}, "table: corner pocket mouths do not fit"),
        # physics
        ({"physics": {"mu_slide": -0.1}}, "physics.mu_slide: must not be negative"),
        ({"physics": {"mu_sliide": 0.1}}, "physics: unknown key 'mu_sliide'"),
        ({"physics": {"e_ball": 1.5}}, "physics.e_ball: must be at most 1"),
        ({"physics": {"g": True}}, "physics.g: must be a number"),
        ({"physics": {"mu_roll": float("nan")}}, "physics.mu_roll: must be finite"),
        ({"physics": {"ball_ball": "sticky"}}, "physics.ball_ball: must be 'frictional'"),
        ({"physics": [1]}, "physics: must be an object"),
        # balls
        ({"balls": "snooker"}, "balls: unknown rack 'snooker'"),
        ({"balls": 3}, "balls: must be a list of balls or a rack name"),
        ({"balls": []}, "balls: must list at least one ball"),
        ({"balls": [[0.5, 0.5]]}, "balls[0]: must be an object"),
        ({"balls": [{"x": 0.5, "y": 0.5, "spin": 1}]}, "balls[0]: unknown key 'spin'"),
        ({"balls": [{"id": "cue", "x": 0.5}]}, "balls[0] (id 'cue'): missing key 'y'"),
        ({"balls": [{"x": 0.5, "y": 0.5}, {"x": True, "y": 0.5}]}, "balls[1].x: must be a number"),
        ({"balls": [{"x": 0.5, "y": "0.5"}]}, "balls[0].y: must be a number"),
        ({"balls": [{"x": 0.5, "y": 0.5, "vx": float("nan")}]}, "balls[0].vx: must be finite"),
        ({"balls": [{"x": 0.5, "y": 0.5, "w": [1, 2]}]}, "balls[0].w: must be a list of 3"),
        ({"balls": [{"x": 0.5, "y": 0.5, "w": [1, 2, "3"]}]}, "balls[0].w[2]: must be a number"),
        ({"balls": [{"x": 0.5, "y": 0.5, "radius": 0}]}, "balls[0].radius: must be positive"),
        ({"balls": [{"x": 0.5, "y": 0.5, "radius": -0.03}]}, "balls[0].radius: must be positive"),
        ({"balls": [{"x": 0.5, "y": 0.5, "mass": 0.0}]}, "balls[0].mass: must be positive"),
        (
            {"balls": [{"id": True, "x": 0.5, "y": 0.5}]},
            "balls[0].id: must be a string or a number",
        ),
        ({"balls": [{"id": " ", "x": 0.5, "y": 0.5}]}, "balls[0].id: must not be empty"),
        ({"balls": [{"id": [1], "x": 0.5, "y": 0.5}]}, "balls[0].id: must be a string or a number"),
        (
            {"balls": [{"id": 7, "x": 0.5, "y": 0.5}, {"id": "7", "x": 1.0, "y": 0.5}]},
            "balls[1] (id '7'): duplicate id (also balls[0])",
        ),
        ({"balls": [{"id": "cue", "x": 0.01, "y": 0.5}]}, "balls[0] (id 'cue'): off the table"),
        ({"balls": [{"id": "cue", "x": 0.5, "y": 1.26}]}, "balls[0] (id 'cue'): off the table"),
        ({"balls": [{"id": "cue", "x": 3.0, "y": 0.5}]}, "balls[0] (id 'cue'): off the table"),
        (
            {
                "balls": [
                    {"id": "cue", "x": 0.5, "y": 0.5},
                    {"id": "5", "x": 1.0, "y": 0.5},
                    {"id": "6", "x": 1.5, "y": 0.5},
                    {"id": "7", "x": 1.0 + 2 * R - 1e-3, "y": 0.5},
                ]
            },
            "balls[3] (id '7'): overlaps ball '5'",
        ),
        ({"table": {"length": 0.5, "width": 0.3, "pockets": "none"}}, "balls: rack '8ball' does"),
        # shot
        (two_balls(speed=1, ball="9"), "shot.ball: no ball with id '9' in the scene"),
        (two_balls(angle=10), "shot: missing key 'speed'"),
        (two_balls(speed=-1), "shot.speed: must not be negative"),
        (two_balls(speed=True), "shot.speed: must be a number"),
        (two_balls(speed=1, angle="north"), "shot.angle: must be a number"),
        (two_balls(speed=1, side=float("inf")), "shot.side: must be finite"),
        (two_balls(speed=1, top=0.45, side=0.3), "shot: tip offset 0.54 R is a miscue"),
        (two_balls(speed=1, power=3), "shot: unknown key 'power'"),
        ({"balls": "8ball", "shot": [8]}, "shot: must be an object"),
    ],
)
def test_validation_errors(scene: dict, expected: str) -> None:
    assert expected in error(scene)


def test_touching_balls_are_allowed_but_overlap_is_not() -> None:
    d = {"balls": [{"x": 1.0, "y": 0.5}, {"x": 1.0 + 2 * R - 0.5e-6, "y": 0.5}]}
    assert load_scene(d).ids == ["cue", "1"]
    d["balls"][1]["x"] = 1.0 + 2 * R - 2e-6
    assert error(d) == "balls[1] (id '1'): overlaps ball 'cue' (centres 0.057148 m apart)"


def test_invalid_json_names_line_and_column(tmp_path: Path) -> None:
    p = tmp_path / "bad.json"
    p.write_text('{\n "balls": "8ball",\n "shot": {"speed": 8,}\n}\n')
    msg = error(p)
    assert msg.startswith(f"{p}: invalid JSON at line 3 column")


def test_duplicate_json_key(tmp_path: Path) -> None:
    p = tmp_path / "dup.json"
    p.write_text('{"balls": "8ball", "balls": "9ball"}')
    assert "duplicate key 'balls'" in error(p)


def test_missing_file_and_non_object(tmp_path: Path) -> None:
    assert error(tmp_path / "nope.json").startswith("cannot read scene")
    p = tmp_path / "list.json"
    p.write_text("[1, 2]")
    assert error(p) == "scene: must be a JSON object"


def test_loads_scene_text() -> None:
    assert loads_scene('{"balls": "9ball"}').ids[-1] == "9"
    with pytest.raises(SceneError, match="invalid JSON at line 1 column"):
        loads_scene("{balls}")


# ---------------------------------------------------------------------------------- limits

ONE = {"id": "cue", "x": 0.6, "y": 0.6}


@pytest.mark.parametrize(
    "scene, expected",
    [
        ({"balls": [{**ONE, "radius": 1e-200}]}, "balls[0].radius: must be at least 0.001 m, "
                                                 "not 1e-200"),
        ({"balls": [{**ONE, "radius": 0.6}]}, "balls[0].radius: must be at most 0.5 m"),
        ({"balls": [{**ONE, "mass": 5e-324}]}, "balls[0].mass: must be at least 0.001 kg"),
        ({"balls": [{**ONE, "mass": 1e-20}]}, "balls[0].mass: must be at least 0.001 kg"),
        ({"balls": [{**ONE, "mass": 1e5}]}, "balls[0].mass: must be at most 100 kg"),
        ({"balls": [{**ONE, "vx": 20.0, "vy": 20.0}]},
         "balls[0] (id 'cue'): speed 28.2843 m/s is above the limit of 25 m/s"),
        ({"balls": [{**ONE, "w": [0, 0, 1e308]}]},
         "balls[0] (id 'cue'): spin w times the radius is 2.8575e+306 m/s, above the limit"),
        ({"balls": [{**ONE, "x": 10 ** 400}]}, "balls[0].x: must be finite"),
        (two_balls(speed=1e10), "shot.speed: must be at most 25 m/s, not 1e+10"),
        (two_balls(speed=1e308), "shot.speed: must be at most 25 m/s"),
        ({"physics": {"mu_slide": 5e-324}}, "physics.mu_slide: must be at least 0.1, "
                                            "not 4.94066e-324 (or 0, frictionless)"),
        # The old lower ends, at which the slip completion set a ball 2 mm into a rail.
        ({"physics": {"mu_slide": 1e-4}}, "physics.mu_slide: must be at least 0.1"),
        ({"physics": {"g": 0.1}}, "physics.g: must be at least 1 m/s^2"),
        ({"physics": {"mu_slide": 1e15}}, "physics.mu_slide: must be at most 1"),
        ({"physics": {"mu_slide": 1e308}}, "physics.mu_slide: must be at most 1"),
        ({"physics": {"mu_roll": 2}}, "physics.mu_roll: must be at most 1"),
        ({"physics": {"mu_spin": 1e-9}}, "physics.mu_spin: must be at least 0.001"),
        ({"physics": {"mu_roll": 1e-4}}, "physics.mu_roll: must be at least 0.001"),
        ({"physics": {"mu_cushion": 3}}, "physics.mu_cushion: must be at most 1"),
        ({"physics": {"g": 5e-324}}, "physics.g: must be at least 1 m/s^2"),
        ({"physics": {"g": 1e4}}, "physics.g: must be at most 100 m/s^2"),
        ({"physics": {"cushion_height": 1e308}}, "physics.cushion_height: must be at most 1 m"),
        ({"physics": {"v_inelastic": 50}}, "physics.v_inelastic: must be at most 1 m/s"),
        ({"table": {"length": 1e-300}}, "table.length: must be at least 0.1 m, not 1e-300"),
        ({"table": {"width": 1e300}}, "table.width: must be at most 100 m"),
        ({"table": {"corner_mouth": 1e308}}, "table.corner_mouth: must be at most 1 m"),
        ({"table": {"jaw_length": 1e-9}}, "table.jaw_length: must be at least 0.001 m"),
        ({"table": {"side_hole_radius": 2}}, "table.side_hole_radius: must be at most 1 m"),
        ({"table": {"hole_depth": 1e300}}, "table.hole_depth: must be at most 1 m"),
        ({"table": {"side_jaw_angle": 1e-3}}, "table.side_jaw_angle: must be at least 1 degrees"),
    ],
)
def test_values_without_physical_meaning_are_refused(scene: dict, expected: str) -> None:
    assert error(scene) == expected or error(scene).startswith(expected)


def test_every_number_of_the_physics_has_its_range() -> None:
    numbers = {f.name for f in fields(Physics) if "float" in str(f.type)}
    assert numbers == set(PHYSICS_RANGES)
    for key, (lo, hi) in PHYSICS_RANGES.items():  # and the defaults lie within them
        assert lo <= getattr(Physics(), key) <= hi, key


@pytest.mark.parametrize("ok", [
    {"balls": [{**ONE, "radius": 0.001, "mass": 0.001}]},
    {"balls": [{**ONE, "radius": 0.5, "mass": 100, "x": 1.0}]},
    {"balls": [{**ONE, "vx": 25.0}]},
    two_balls(speed=25.0, top=0.5),
    {"physics": {"mu_slide": 0, "mu_roll": 0, "mu_spin": 0}},
    {"physics": {"mu_slide": 0.1, "mu_roll": 1, "mu_spin": 1e-3, "g": 1, "e_cushion": 0}},
    {"physics": {"mu_slide": 1, "mu_roll": 1e-3, "e_ball": 0, "mu_cushion": 0}},
    {"physics": {"g": 100, "mu_cushion": 1, "v_inelastic": 1, "cushion_height": 1}},
    {"table": {"pockets": "none", "length": 0.1, "width": 0.1},
     "balls": [{"x": 0.05, "y": 0.05, "radius": 0.01}]},
    {"table": {"pockets": "none", "length": 10, "width": 10}, "balls": [ONE]},
])
def test_values_at_the_limits_load(ok: dict) -> None:
    load_scene(ok)


# The jaws end where the hole no longer lies under them: a ball that slips between them
# must fall in before it passes their ends (found rolling off a table at (-1.24, 0.06)).
LEAKY_POCKETS = [{"hole_depth": 0.1}, {"jaw_length": 0.017, "hole_depth": 0.03},
                 {"jaw_length": 0.01}, {"jaw_length": 0.3}, {"corner_hole_radius": 0.03},
                 {"side_jaw_angle": 170, "jaw_length": 0.2}]


@pytest.mark.parametrize("table", LEAKY_POCKETS)
def test_pockets_a_ball_could_pass_through_are_refused(table: dict) -> None:
    msg = error({"table": table, "balls": [ONE]})
    assert msg.startswith("table: the jaws of the ") and "outside its hole" in msg


@pytest.mark.parametrize("table", [{"hole_depth": 0.019}, {"jaw_length": 0.1},
                                   {"side_hole_radius": 0.09, "hole_depth": 0.015}])
def test_a_ball_through_an_accepted_pocket_falls_in(table: dict) -> None:
    from termpool.physics.engine import POCKETED, Engine

    # The shot that left the table with hole_depth 0.1: at 42 degrees into the side pocket.
    sc = load_scene({"table": table, "balls": [{"id": "cue", "x": 0.8984, "y": 0.9354}],
                     "shot": {"speed": 4.0, "angle": 42.0}})
    eng = Engine(sc.table, sc.physics, sc.pos, sc.vel, sc.w, sc.radius, sc.mass)
    eng.run(1 / 60)
    x, y = eng.pos[0, 0]
    assert eng.state[0, 0] == POCKETED or sc.table.on_bed(x, y, R / 2)


def test_every_preset_has_pockets_that_hold() -> None:
    for name in ("7ft", "8ft", "9ft"):
        load_scene({"table": name, "balls": "8ball"})
        load_scene({"table": {"preset": name}, "balls": "9ball"})


def test_more_balls_than_the_limit_is_one_line() -> None:
    from termpool.scene import MAX_BALLS

    balls = [{"x": 0.1, "y": 0.1}] * (MAX_BALLS + 1)
    assert error({"balls": balls}) == f"balls: {MAX_BALLS + 1} balls is more than the limit " \
                                      f"of {MAX_BALLS}"
    assert error({"balls": balls * 10}).startswith(f"balls: {10 * (MAX_BALLS + 1)} balls")


def grid(n: int, table: float = 10.0, gap: float = 0.1) -> list[dict]:
    cols = int(table / gap) - 1
    return [{"id": str(k), "x": gap * (1 + k % cols), "y": gap * (1 + k // cols)}
            for k in range(n)]


def test_the_limit_of_balls_loads() -> None:
    from termpool.scene import MAX_BALLS

    sc = load_scene({"table": {"pockets": "none", "length": 10, "width": 10},
                     "balls": grid(MAX_BALLS)})
    assert len(sc.ids) == MAX_BALLS


def test_overlaps_are_found_in_list_order_among_many_balls() -> None:
    from termpool.scene import MAX_BALLS

    table = {"pockets": "none", "length": 10, "width": 10}
    balls = grid(MAX_BALLS)
    balls[900] = {**balls[900], "x": balls[10]["x"] + 2 * R - 1e-3, "y": balls[10]["y"]}
    balls[700] = {**balls[700], "x": balls[650]["x"], "y": balls[650]["y"] + R}
    assert error({"table": table, "balls": balls}).startswith(
        "balls[700] (id '700'): overlaps ball '650' (centres 0.028575 m apart)")
    # A ball found off the table before the first overlap is reported first, as before.
    balls[600] = {**balls[600], "x": 20.0}
    assert error({"table": table, "balls": balls}).startswith("balls[600] (id '600'): off the")
    # Exactly touching (frozen) balls are not overlaps.
    row = [{"id": str(k), "x": 1.0 + 2 * R * k, "y": 0.5} for k in range(15)]
    assert len(load_scene({"balls": row}).ids) == 15


# ---------------------------------------------------------------------------------- racks


def touching_pairs(pos: np.ndarray, r: float) -> list[tuple[int, int]]:
    pairs = []
    for i, j in itertools.combinations(range(len(pos)), 2):
        d = math.dist(pos[i], pos[j])
        assert d > 2 * r - 1e-12, "racked balls overlap"
        if d < 2 * r + 1e-9:
            assert abs(d - 2 * r) < 1e-12
            pairs.append((i, j))
    return pairs


def test_eight_ball_rack_geometry() -> None:
    s = load_scene({"balls": "8ball"})
    t = s.table
    assert s.ids[0] == "cue" and sorted(s.ids[1:], key=int) == [str(k) for k in range(1, 16)]
    assert len(s.ids) == 16
    assert tuple(s.pos[0]) == t.head_spot == (t.length / 4, t.width / 2)
    fx, fy = t.foot_spot
    assert (fx, fy) == (3 * t.length / 4, t.width / 2)
    rack = s.pos[1:]
    apex = s.pos[s.index("1")]
    assert tuple(apex) == (fx, fy)
    # Rows extend towards the foot rail, sqrt(3) R apart, holding 1..5 balls.
    rows = np.rint((rack[:, 0] - fx) / (math.sqrt(3) * R)).astype(int)
    assert np.allclose(rack[:, 0], fx + rows * math.sqrt(3) * R, rtol=0, atol=1e-12)
    assert sorted(np.bincount(rows).tolist()) == [1, 2, 3, 4, 5]
    assert np.bincount(rows).tolist() == [1, 2, 3, 4, 5]
    # A triangle of 5 rows has 3 * 5 * 4 / 2 = 30 touching neighbour pairs.
    assert len(touching_pairs(rack, R)) == 30
    # The 8 is in the centre of the third row.
    eight = s.pos[s.index("8")]
    assert abs(eight[0] - (fx + 2 * math.sqrt(3) * R)) < 1e-12 and abs(eight[1] - fy) < 1e-12
    # Back corners: one solid and one stripe.
    back = [s.ids[1 + k] for k in np.nonzero(rows == 4)[0]]
    ys = {bid: s.pos[s.index(bid), 1] for bid in back}
    corners = [min(ys, key=ys.get), max(ys, key=ys.get)]
    assert abs(ys[corners[0]] - (fy - 4 * R)) < 1e-12 and abs(ys[corners[1]] - (fy + 4 * R)) < 1e-12
    kinds = sorted("solid" if int(b) < 8 else "stripe" for b in corners)
    assert kinds == ["solid", "stripe"]
    # Defaults on every ball, nothing moving.
    assert np.all(s.radius == BALL_RADIUS) and np.all(s.mass == BALL_MASS)
    assert not s.vel.any() and not s.w.any()


def test_nine_ball_rack_geometry() -> None:
    s = load_scene({"balls": "9ball", "table": "7ft"})
    t = s.table
    assert t.length == 1.981
    assert s.ids == ["cue"] + [str(k) for k in range(1, 10)]
    fx, fy = t.foot_spot
    assert tuple(s.pos[s.index("1")]) == (fx, fy)
    assert tuple(s.pos[0]) == t.head_spot
    nine = s.pos[s.index("9")]
    assert abs(nine[0] - (fx + 2 * math.sqrt(3) * R)) < 1e-12 and abs(nine[1] - fy) < 1e-12
    rack = s.pos[1:]
    rows = np.rint((rack[:, 0] - fx) / (math.sqrt(3) * R)).astype(int)
    assert np.bincount(rows).tolist() == [1, 2, 3, 2, 1]
    assert len(touching_pairs(rack, R)) == 16  # 4 within rows + 12 between rows


# ------------------------------------------------------------------------------- defaults


def test_empty_scene_defaults() -> None:
    s = load_scene({})
    assert (s.table.length, s.table.width, s.table.pockets) == (2.54, 1.27, "standard")
    assert s.physics == Physics()
    assert len(s.ids) == 16 and s.ids[0] == "cue"
    assert s.pos.shape == (16, 2) and s.vel.shape == (16, 2) and s.w.shape == (16, 3)
    assert s.radius.shape == (16,) and s.mass.shape == (16,)
    for a in (s.pos, s.vel, s.w, s.radius, s.mass):
        assert a.dtype == np.float64


def test_ball_defaults_and_ids() -> None:
    s = load_scene(
        {
            "balls": [
                {"x": 0.5, "y": 0.5},
                {"x": 1.0, "y": 0.5, "vx": 0.3, "w": [1, 2, 3]},
                {"id": 7, "x": 1.5, "y": 0.5, "radius": 0.03, "mass": 0.2},
                {"id": 8.0, "x": 2.0, "y": 0.5},
            ]
        }
    )
    assert s.ids == ["cue", "1", "7", "8"]
    assert s.vel.tolist() == [[0, 0], [0.3, 0], [0, 0], [0, 0]]
    assert s.w[1].tolist() == [1, 2, 3] and not s.w[0].any()
    assert s.radius.tolist() == [BALL_RADIUS, BALL_RADIUS, 0.03, BALL_RADIUS]
    assert s.mass.tolist() == [BALL_MASS, BALL_MASS, 0.2, BALL_MASS]
    assert s.index("7") == 2


def test_table_objects_and_physics_overrides() -> None:
    s = load_scene(
        {
            "table": {"length": 2.0, "width": 1.0, "pockets": "none"},
            "physics": {"mu_slide": 0.3, "ball_ball": "frictionless"},
            "balls": [{"x": 1.0, "y": 0.5}],
        }
    )
    assert (s.table.length, s.table.width, s.table.hole_names) == (2.0, 1.0, ())
    assert s.physics.mu_slide == 0.3 and s.physics.ball_ball == "frictionless"
    assert s.physics.mu_roll == Physics().mu_roll
    t = load_scene({"table": {"preset": "8ft", "corner_mouth": 0.12}, "balls": "9ball"}).table
    assert (t.length, t.width, t.corner_mouth) == (2.235, 1.118, 0.12)
    assert t.side_mouth == Table().side_mouth
    assert set(t.hole_names) == {
        "head_left",
        "head_right",
        "side_left",
        "side_right",
        "foot_left",
        "foot_right",
    }
    # An explicit length wins over the preset's.
    t = load_scene({"table": {"preset": "7ft", "length": 2.2}, "balls": "9ball"}).table
    assert (t.length, t.width) == (2.2, 0.991)


# ----------------------------------------------------------------------------------- shot


def test_shot_applies_strike() -> None:
    s = load_scene(two_balls(speed=2.0, angle=30, side=0.2, top=-0.3))
    (vx, vy), w = strike(2.0, 30, 0.2, -0.3, BALL_RADIUS)
    assert s.vel[0].tolist() == [vx, vy] and s.w[0].tolist() == list(w)
    assert math.hypot(*s.vel[0]) == pytest.approx(2.0, abs=1e-15)
    assert s.w[0, 2] > 0  # right side spins counter-clockwise seen from above
    assert not s.vel[1].any()


def test_shot_defaults_and_other_ball() -> None:
    s = load_scene(two_balls(speed=1.5))
    assert s.vel[0].tolist() == [1.5, 0.0] and not s.w[0].any()
    d = {
        "balls": [
            {"id": "cue", "x": 0.6, "y": 0.6, "vx": 9.0, "w": [5, 5, 5]},
            {"id": 3, "x": 1.5, "y": 0.6, "radius": 0.03, "vx": 4.0},
        ],
        "shot": {"ball": 3, "speed": 1.0, "angle": 90, "top": 0.4},
    }
    s = load_scene(d)
    (vx, vy), w = strike(1.0, 90, 0.0, 0.4, 0.03)
    assert s.vel[1].tolist() == [vx, vy] and s.w[1].tolist() == list(w)  # replaced, not added
    assert s.vel[0].tolist() == [9.0, 0.0]  # other balls untouched
    # Natural roll: v = R (wy, -wx)
    assert np.allclose(s.vel[1], 0.03 * np.array([s.w[1, 1], -s.w[1, 0]]))


def test_raw_is_a_copy() -> None:
    d = two_balls(speed=1.0)
    s = load_scene(d)
    assert s.raw == d and s.raw is not d
    s.raw["balls"][0]["x"] = 99
    assert d["balls"][0]["x"] == 0.6


# ----------------------------------------------------------------------------- round trip


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_round_trip(path: Path) -> None:
    s = load_scene(path)
    d = json.loads(json.dumps(scene_to_dict(s)))
    assert "shot" not in d and isinstance(d["balls"], list)
    s2 = load_scene(d)
    assert s2.ids == s.ids
    for name in ("pos", "vel", "w", "radius", "mass"):
        assert np.array_equal(getattr(s2, name), getattr(s, name)), name
    assert s2.physics == s.physics
    assert scene_to_dict(s2) == d
    for name in ("length", "width", "pockets", "corner_mouth", "side_mouth"):
        assert getattr(s2.table, name) == getattr(s.table, name)


# ------------------------------------------------------------------------------- examples


def test_examples_present_and_bundled() -> None:
    names = {p.name for p in EXAMPLES}
    assert {"break.json", "stun.json", "cut.json", "bank.json", "draw.json", "nineball.json"} <= (
        names
    )
    for p in EXAMPLES:
        bundled = ROOT / "termpool" / "examples" / p.name
        assert bundled.read_text() == p.read_text(), f"{bundled} differs from {p}"


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_examples_validate(path: Path) -> None:
    s = load_scene(path)
    assert isinstance(s.raw.get("description"), str)
    assert s.vel.any()  # every example has a shot


def test_example_specifics() -> None:
    brk = load_scene(ROOT / "examples" / "break.json")
    assert len(brk.ids) == 16 and brk.vel[0].tolist() == [8.0, 0.0]
    stun = load_scene(ROOT / "examples" / "stun.json")
    assert stun.physics.ball_ball == "frictionless" and stun.physics.e_ball == 1.0
    bank = load_scene(ROOT / "examples" / "bank.json")
    assert bank.table.pockets == "none" and bank.w[0, 2] != 0
    cut = load_scene(ROOT / "examples" / "cut.json")
    assert cut.raw["shot"]["top"] == 0.4
    # Half-ball: the cue ball's path passes one radius from the object ball's centre.
    d = cut.vel[0] / np.linalg.norm(cut.vel[0])
    rel = cut.pos[1] - cut.pos[0]
    assert abs(d[0] * rel[1] - d[1] * rel[0]) == pytest.approx(R, rel=1e-3)
    assert len(load_scene(ROOT / "examples" / "nineball.json").ids) == 10
    assert load_scene(ROOT / "examples" / "draw.json").w[0, 1] < 0


# ------------------------------------------------------------- where a ball may rest


def one_ball(x: float, y: float) -> dict:
    return {"balls": [{"id": "1", "x": x, "y": y}]}


def test_a_ball_touching_a_rail_nose_is_on_the_table() -> None:
    # The nose is above the equator, so a ball touching it has its centre nearer than R.
    t, h, r = Table.preset("9ft"), Physics().cushion_height, BALL_RADIUS
    sin_t = (h - r) / r
    reach = r * math.sqrt(1 - sin_t * sin_t)
    assert reach < r
    load_scene(one_ball(0.7, t.width - reach))
    load_scene(one_ball(t.length - reach, 0.6))
    with pytest.raises(SceneError, match="off the table"):
        load_scene(one_ball(0.7, t.width - reach + 1e-5))


def test_a_ball_in_a_pocket_mouth_is_on_the_table_but_not_over_the_hole() -> None:
    t = Table.preset("9ft")
    x = t.length / 2
    load_scene(one_ball(x, t.width - 0.5 * BALL_RADIUS))  # past the rail line, between the jaws
    k = t.hole_names.index("side_left")
    hx, hy = t.hole_c[k]
    with pytest.raises(SceneError, match="off the table"):
        load_scene(one_ball(hx, hy))
    with pytest.raises(SceneError, match="off the table"):
        load_scene(one_ball(0.7, t.width + 0.01))  # in the rail, far from any pocket


def test_every_layout_the_engine_leaves_loads_as_a_scene() -> None:
    # Balls come to rest against rails and in pocket mouths; the next shot's scene must load.
    from termpool.physics.engine import POCKETED, Engine

    base = load_scene({"balls": "8ball"})
    rng = np.random.default_rng(5)
    B = 24
    pos = np.repeat(base.pos[None], B, axis=0)
    vel = np.zeros_like(pos)
    w = np.zeros(pos.shape[:2] + (3,))
    for b in range(B):
        pos[b, 0, 1] += rng.uniform(-0.2, 0.2)
        aim = base.pos[1] + rng.uniform(-0.03, 0.03, 2) - pos[b, 0]
        angle = math.degrees(math.atan2(aim[1], aim[0]))
        v, spin = strike(rng.uniform(3, 9), angle, rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3))
        vel[b, 0], w[b, 0] = v, spin
    eng = Engine(base.table, base.physics, pos, vel, w, record=False)
    eng.run(1 / 60)
    for b in range(B):
        balls = [{"id": base.ids[k], "x": float(eng.pos[b, k, 0]), "y": float(eng.pos[b, k, 1])}
                 for k in range(len(base.ids)) if eng.state[b, k] != POCKETED]
        load_scene({"balls": balls})
