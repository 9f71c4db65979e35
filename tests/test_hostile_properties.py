"""Generators of hostile input (hypothesis, in bounded numbers): huge numbers, deep nesting,
tiny and huge physical values, hostile strings, truncated and mutated records, random key
scripts with spin and quit keys, and --record on bad paths. Whatever they make, the commands
answer with their result or one line and status 2: never a traceback, a numpy warning, a hang,
a control character on the terminal or a partial file."""

from __future__ import annotations

import json
import math
import os
import warnings
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from termpool import cli, files
from termpool.game import Match, Shot
from termpool.physics.cue import MISCUE_OFFSET, clamp_tip, strike
from termpool.physics.params import FRICTIONLESS_OK, PHYSICS_RANGES
from termpool.scene import (
    MASS_RANGE,
    MAX_SPEED,
    MAX_SURFACE_SPEED,
    RADIUS_RANGE,
    TABLE_RANGES,
    SceneError,
    load_scene,
)
from termpool.text import shown
from termpool.ui.app import App, Options
from termpool.ui.headless import play
from termpool.ui.keys import legacy_events, parse_script

SETTINGS = dict(deadline=None, report_multiple_bugs=False,
                suppress_health_check=[HealthCheck.too_slow,
                                       HealthCheck.function_scoped_fixture])
CONTROL = [chr(c) for c in [*range(32), *range(0x7F, 0xA0), 0x2028, 0x202E]]


def run(capsys, *argv: str) -> tuple[int, str, str]:
    """The command in-process, warnings as errors (none may reach stderr)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        rc = cli.main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def one_line_or_result(rc: int, out: str, err: str, ok: tuple[int, ...] = (0,)) -> None:
    assert "Traceback" not in err
    if rc == 2:
        assert out == "" and err.startswith("termpool: ") and err.count("\n") == 1, err
    else:
        assert rc in ok, err
    for c in CONTROL:
        assert c not in out.replace("\n", "") and c not in err.replace("\n", "")


# ----------------------------------------------------------------------------- JSON values

huge_digits = st.integers(min_value=1, max_value=6000).map(lambda n: "9" * n)  # JSON text
hostile_text = st.text(alphabet=st.sampled_from([*CONTROL, "a", "é", "\\", '"', "🎱", " "]),
                       max_size=30)
numbers = st.one_of(
    st.floats(allow_nan=False, allow_infinity=False),
    st.sampled_from([5e-324, 1e-300, 1e-200, 1e308, -1e308, -0.0, 0.0, 1e15]),
    st.integers(min_value=-10 ** 30, max_value=10 ** 30),
)


PLACE = "@@here@@"  # where a generated JSON text goes


def deep(levels: int, inner: str = "1") -> str:
    return "[" * levels + inner + "]" * levels


def json_number(n) -> str:
    """A number as JSON text: huge integers written out (json.dumps would refuse some)."""
    return str(n) if isinstance(n, int) else json.dumps(n)


# ------------------------------------------------------------------------ numbers in scenes

SCENE = {"table": {"pockets": "none", "length": 3.0, "width": 3.0},
         "balls": [{"id": "cue", "x": 1.5, "y": 1.5}]}
SLOTS = ["table.length", "table.width", "table.jaw_length", "table.hole_depth",
         "physics.mu_slide", "physics.g", "physics.e_cushion", "balls.radius", "balls.mass",
         "balls.vx", "balls.w"]


def scene_with(slot: str, text: str) -> str:
    """SCENE's JSON with the value at `slot` written as `text` (any JSON text)."""
    marker = '"@@"'
    d = json.loads(json.dumps(SCENE))
    group, key = slot.split(".")
    if group == "balls":
        d["balls"][0][key] = [0, 0, "@@"] if key == "w" else "@@"
    else:
        d.setdefault(group, {})[key] = "@@"
    return json.dumps(d).replace(marker, text)


@settings(max_examples=120, **SETTINGS)
@given(slot=st.sampled_from(SLOTS),
       value=st.one_of(numbers.map(json_number), huge_digits, st.integers(1, 3000).map(deep),
                       hostile_text.map(json.dumps)))
def test_any_value_in_any_field_loads_or_is_one_line(capsys, tmp_path, slot, value) -> None:
    p = tmp_path / "s.json"
    p.write_text(scene_with(slot, value))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            load_scene(p)
        except SceneError as e:
            assert "\n" not in str(e)


def limits_of(slot: str) -> tuple[float, float]:
    group, key = slot.split(".")
    if group == "table":
        lo, hi = TABLE_RANGES[key]
        return (lo if key == "hole_depth" else max(lo, 5e-324)), hi
    if group == "physics":
        return PHYSICS_RANGES[key]
    return {"radius": RADIUS_RANGE, "mass": MASS_RANGE}[key]


physical = st.one_of(
    st.floats(min_value=-1e3, max_value=1e3),
    st.floats(min_value=1e-320, max_value=1e308).map(lambda v: v),
    st.integers(-300, 308).map(lambda e: 10.0 ** e),
    st.sampled_from([0.0, 5e-324, 1e-4, 0.1, 0.5, 1.0, 10.0, 100.0, 25.0, 50.0]),
)


@settings(max_examples=200, **SETTINGS)
@given(slot=st.sampled_from(["table.length", "table.width", "physics.mu_slide",
                             "physics.mu_roll", "physics.mu_spin", "physics.mu_cushion",
                             "physics.e_ball", "physics.e_cushion", "physics.g",
                             "physics.cushion_height", "physics.v_inelastic", "balls.radius",
                             "balls.mass"]),
       value=physical)
def test_a_physical_value_loads_exactly_when_it_is_within_its_documented_limits(slot,
                                                                               value) -> None:
    lo, hi = limits_of(slot)
    key = slot.split(".")[1]
    inside = lo <= value <= hi or (value == 0 and key in FRICTIONLESS_OK)
    if slot.startswith("table") or key in ("length", "width"):
        inside = inside and value > 0
    if key in ("radius", "mass"):
        inside = inside and value > 0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        d = json.loads(scene_with(slot, json.dumps(value)))
        if slot.startswith("table"):  # a small ball in the corner fits the smallest table
            d["balls"][0].update(x=0.05, y=0.05, radius=0.01)
        try:
            load_scene(d)
            loaded = True
        except SceneError as e:
            loaded = False
            assert key in str(e)
    assert loaded == inside, (slot, value)


@settings(max_examples=100, **SETTINGS)
@given(speed=physical, wz=physical)
def test_speeds_and_spins_load_exactly_within_their_limits(speed, wz) -> None:
    d = json.loads(json.dumps(SCENE))
    d["balls"][0].update(vx=speed, w=[0.0, 0.0, wz])
    surface = 0.028575 * abs(wz)
    try:
        load_scene(d)
        loaded = True
    except SceneError:
        loaded = False
    assert loaded == (abs(speed) <= MAX_SPEED and surface <= MAX_SURFACE_SPEED)


@settings(max_examples=60, **SETTINGS)
@given(levels=st.integers(1, 5000), where=st.sampled_from(["description", "balls", "table",
                                                           "physics", "shot"]))
def test_any_nesting_anywhere_is_loaded_or_one_line(capsys, tmp_path, levels, where) -> None:
    p = tmp_path / "s.json"
    d = {"balls": "8ball", where: PLACE}
    p.write_text(json.dumps(d).replace(json.dumps(PLACE), deep(levels, "{}")))
    rc, out, err = run(capsys, "sim", str(p))
    one_line_or_result(rc, out, err)
    if levels + 1 > files.MAX_DEPTH:
        assert f"nested more than {files.MAX_DEPTH} levels" in err


# ------------------------------------------------------------------------- hostile strings


@settings(max_examples=80, **SETTINGS)
@given(text=hostile_text.filter(bool),
       where=st.sampled_from(["key", "id", "table", "preset", "game"]))
def test_hostile_strings_reach_the_terminal_escaped(capsys, tmp_path, text, where) -> None:
    scene = {
        "key": {text: 1},
        "id": {"balls": [{"id": text, "x": 0.5, "y": 0.5}, {"id": text, "x": 1.0, "y": 0.5}]},
        "table": {"table": text},
        "preset": {"table": {"preset": text}},
        "game": {"balls": "8ball", "game": {"mode": text}},
    }[where]
    p = tmp_path / "s.json"
    p.write_text(json.dumps(scene))
    rc, out, err = run(capsys, "sim", str(p))
    one_line_or_result(rc, out, err)
    # named as it is or as a Python literal, on one line (runs of spaces become one space)
    names = [" ".join(shown(t).split()) for t in (text, repr(text))]
    assert rc == 2 and (any(n in err for n in names) or "must not be empty" in err)


def test_shown_never_leaves_a_control_character() -> None:
    @settings(max_examples=300, **SETTINGS)
    @given(st.text())
    def check(text):
        out = shown(text)
        assert not any(c in out for c in CONTROL)
        assert all(c in out for c in text if c.isprintable() and c != "\\")

    check()


# ------------------------------------------------------------------- truncated and mutated


@pytest.fixture(scope="module")
def small_record() -> str:
    """A practice match of two soft shots: quick to replay."""
    m = Match("practice", seed=2, players=("Ann", "Bob"))
    m.place_cue(0.5, 0.6)
    m.begin(Shot(1.0, 10.0, top=0.2)).finish()
    m.begin(Shot(0.8, 200.0, side=-0.1)).finish()
    return json.dumps(m.to_json())


def leaves(d, path=()):
    if isinstance(d, dict):
        for k, v in d.items():
            yield from leaves(v, (*path, k))
    elif isinstance(d, list):
        for k, v in enumerate(d):
            yield from leaves(v, (*path, k))
    yield path


hostile_value = st.one_of(  # as JSON text
    huge_digits, st.integers(2, 3000).map(deep), hostile_text.map(json.dumps),
    st.sampled_from(["null", "true", "-1", "0", "5e-324", "1e308", "-1e308", "[]", "{}", '""',
                     "NaN", "Infinity"]))


@settings(max_examples=40, **SETTINGS)
@given(data=st.data())
def test_mutated_records_replay_or_are_one_line(capsys, tmp_path, small_record, data) -> None:
    rec = json.loads(small_record)
    path = data.draw(st.sampled_from(list(leaves(rec))[:-1]))  # any value but the root
    how = data.draw(st.sampled_from(["replace", "delete", "rename"]))
    parent = rec
    for k in path[:-1]:
        parent = parent[k]
    last = path[-1]
    if how == "replace" or isinstance(parent, list):
        parent[last] = PLACE
    elif how == "delete":
        del parent[last]
    else:
        parent[data.draw(hostile_text)] = parent.pop(last)
    p = tmp_path / "r.json"
    p.write_text(json.dumps(rec).replace(json.dumps(PLACE), data.draw(hostile_value)))
    rc, out, err = run(capsys, "replay", str(p))
    one_line_or_result(rc, out, err, ok=(0, 1))


@settings(max_examples=40, **SETTINGS)
@given(cut=st.floats(0.0, 1.0))
def test_truncated_records_are_one_line(capsys, tmp_path, small_record, cut) -> None:
    p = tmp_path / "r.json"
    p.write_text(small_record[:int(cut * (len(small_record) - 1))])
    rc, out, err = run(capsys, "replay", str(p))
    assert rc == 2
    one_line_or_result(rc, out, err)


# ------------------------------------------------------------------------ random key scripts

KEYS = ["w", "a", "s", "d", "x", "left", "right", "up", "down", "shift+left", "enter", "esc",
        "q", "y", "n", "h", "p", "g", "c", "o", "b", "u", "r", "f", "m", "1", "2", "5",
        "space", "space-hold 0.3", "space-hold 1.2", "w*7", "d*9", "wait 0.5", "wait 6",
        "click 30 10", "q y"]


@settings(max_examples=25, **SETTINGS)
@given(tokens=st.lists(st.sampled_from(KEYS), max_size=25),
       size=st.tuples(st.integers(20, 250), st.integers(8, 80)),
       mode=st.sampled_from(["practice", "8ball", "9ball", None]),
       legacy=st.booleans())
def test_random_key_scripts_with_spin_and_quit_keys(tokens, size, mode, legacy) -> None:
    app = App(Options(mode=mode, opponent="human", colors="mono"),
              input_mode="repeat" if legacy else "release")
    events = parse_script("enter " + " ".join(tokens))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        screen = play(app, legacy_events(events) if legacy else events, *size)
        match = app.record()  # the shot in progress, if any, played out
    assert len(screen.splitlines()) <= size[1]
    if match is not None:
        saved = json.loads(json.dumps(match.to_json()))
        for rec in saved["shots"]:
            assert math.hypot(rec["shot"]["side"], rec["shot"]["top"]) <= MISCUE_OFFSET


@settings(max_examples=200, **SETTINGS)
@given(side=st.floats(allow_nan=False, allow_infinity=False),
       top=st.floats(allow_nan=False, allow_infinity=False))
def test_every_clamped_tip_is_struck(side, top) -> None:
    s, t = clamp_tip(side, top)
    strike(1.0, 0.0, s, t)  # never a miscue
    if math.hypot(side, top) <= MISCUE_OFFSET:
        assert (s, t) == (side, top)
    else:  # moved in along its own direction, onto the limit
        assert math.hypot(s, t) == pytest.approx(MISCUE_OFFSET, rel=1e-12)
        assert math.copysign(1, s) == math.copysign(1, side) or s == 0
        assert math.copysign(1, t) == math.copysign(1, top) or t == 0


# ------------------------------------------------------------------ --record on bad paths

PATH_PARTS = ["x.json", "missing", "file", "dir", "..", ".", "", "/dev/null", "/proc",
              "n" * 300, "\x1b[2J", "sub"]


@settings(max_examples=30, **SETTINGS)
@given(parts=st.lists(st.sampled_from(PATH_PARTS), min_size=1, max_size=4),
       force=st.booleans())
def test_record_on_any_path_saves_or_is_one_line(capsys, tmp_path_factory, parts,
                                                 force) -> None:
    base = tmp_path_factory.mktemp("rec")
    (base / "file").write_text("an old file")
    (base / "dir").mkdir()
    (base / "dir" / "sub").mkdir()
    keys = base / "k.txt"
    keys.write_text("q y")
    path = parts[0] if parts[0].startswith("/") else str(base / parts[0])
    for part in parts[1:]:
        path = os.path.join(path, part)
    before = {p: p.read_bytes() for p in base.rglob("*") if p.is_file()}
    rc, out, err = run(capsys, "play", "--headless", "--mode", "practice", "--keys", str(keys),
                       "--record", path, *(["--force"] if force else []))
    one_line_or_result(rc, out.splitlines()[-1] if out else "", err)
    after = {p for p in base.rglob("*") if p.is_file()}
    assert not [p for p in after if p.name.endswith(".tmp")]  # no temporary file left
    if rc == 0:
        assert err.startswith("termpool: record saved to ")
        assert json.loads(Path(path).read_text())["shots"] == []
    else:
        assert "--record" in err
        assert {p: p.read_bytes() for p in before} == before  # nothing was touched
