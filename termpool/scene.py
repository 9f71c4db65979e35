"""Scenes: a JSON description of a table, its physics and the balls on it, validated.

Every problem is reported as one `SceneError` line naming the key path or the ball, e.g.
``balls[3] (id '7'): overlaps ball '5'`` or ``physics.mu_slide: must not be negative``.
"""

from __future__ import annotations

import copy
import json
import math
import os
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np

from termpool.files import MAX_SCENE_BYTES, FileError, parse_json, read_text
from termpool.physics.cue import strike
from termpool.physics.params import BALL_MASS, BALL_RADIUS, Physics, nose_reach, within
from termpool.physics.table import PRESETS, Table


class SceneError(ValueError):
    """A scene that cannot be loaded; the message is a single line."""


TOP_KEYS = ("description", "table", "physics", "balls", "shot", "game")
BALL_KEYS = ("id", "x", "y", "vx", "vy", "w", "radius", "mass")
SHOT_KEYS = ("ball", "speed", "angle", "side", "top")
TABLE_FIELDS = tuple(f.name for f in fields(Table) if f.init)
TABLE_KEYS = ("preset", *TABLE_FIELDS)
RACKS = ("8ball", "9ball")
OVERLAP_TOL = 1e-6

# Limits on what a scene may hold (docs/scenes.md lists them): values beyond them mean nothing
# on a pool table, and the extreme ones (a radius of 1e-200, a speed of 1e308) only overflow or
# ask the engine for unbounded work. Lengths in m, angles in degrees.
MAX_BALLS = 1000  # the engine keeps N x N pair arrays: about 190 MB at 1000 balls
RADIUS_RANGE = (0.001, 0.5)  # m
MASS_RANGE = (0.001, 100.0)  # kg
MAX_SPEED = 25.0  # m/s, a ball's or a shot's (a hard break is about 11 m/s)
MAX_SURFACE_SPEED = 2 * MAX_SPEED  # m/s, a ball's radius times its spin; a tip offset of
# 0.5 R at MAX_SPEED gives 1.25 MAX_SPEED
TABLE_RANGES = {
    "length": (0.1, 100.0), "width": (0.1, 100.0),
    "corner_mouth": (0.001, 1.0), "side_mouth": (0.001, 1.0), "jaw_length": (0.001, 1.0),
    "corner_hole_radius": (0.001, 1.0), "side_hole_radius": (0.001, 1.0),
    "hole_depth": (0.0, 1.0), "corner_jaw_angle": (1.0, 180.0), "side_jaw_angle": (1.0, 180.0),
}
# Physics values: params.PHYSICS_RANGES, checked by Physics.from_dict.

# Rows from the apex (on the foot spot) towards the foot rail; within a row, ids by increasing y.
RACK_ROWS = {
    "8ball": [
        ["1"],
        ["9", "2"],
        ["10", "8", "3"],
        ["11", "7", "14", "4"],
        ["5", "13", "15", "6", "12"],
    ],
    "9ball": [["1"], ["2", "3"], ["4", "9", "5"], ["6", "7"], ["8"]],
}


@dataclass
class Scene:
    table: Table
    physics: Physics
    ids: list[str]
    pos: np.ndarray  # (N, 2) m
    vel: np.ndarray  # (N, 2) m/s
    w: np.ndarray  # (N, 3) rad/s
    radius: np.ndarray  # (N,) m
    mass: np.ndarray  # (N,) kg
    raw: dict = field(default_factory=dict, repr=False)
    game: dict | None = None  # the `game` block, if any: rules.referee.load_game_scene
    # validates and normalizes it (the rules' business; this module only carries it)

    def index(self, ball_id: str) -> int:
        return self.ids.index(ball_id)


# ---------------------------------------------------------------------------------- helpers


def _fmt(v: Any) -> str:
    return repr(v) if isinstance(v, str) else json.dumps(v)


def _check_keys(d: Any, allowed: tuple[str, ...], path: str) -> None:
    if not isinstance(d, dict):
        raise SceneError(f"{path}: must be an object")
    for key in d:
        if key not in allowed:
            raise SceneError(f"{path}: unknown key '{key}' (allowed: {', '.join(allowed)})")


def _number(val: Any, path: str, *, positive: bool = False, nonneg: bool = False,
            within: tuple[float, float] | None = None, unit: str = "") -> float:
    if isinstance(val, bool) or not isinstance(val, (int, float)):
        raise SceneError(f"{path}: must be a number, not {_fmt(val)}")
    try:
        val = float(val)
    except OverflowError:  # an integer beyond any float
        val = math.inf
    if not math.isfinite(val):
        raise SceneError(f"{path}: must be finite")
    if positive and val <= 0:
        raise SceneError(f"{path}: must be positive")
    if nonneg and val < 0:
        raise SceneError(f"{path}: must not be negative")
    if within is not None:
        _within(val, within, path, unit)
    return val


def _within(val: float, limits: tuple[float, float], path: str, unit: str = "") -> None:
    try:
        within(val, limits, path, unit)
    except ValueError as e:
        raise SceneError(str(e)) from None


def _reject_duplicates(pairs: list[tuple[str, Any]]) -> dict:
    out: dict = {}
    for key, val in pairs:
        if key in out:
            raise SceneError(f"duplicate key '{key}'")
        out[key] = val
    return out


def _parse_json(text: str, where: str) -> Any:
    try:
        return parse_json(text, where, _reject_duplicates)
    except FileError as e:
        raise SceneError(str(e)) from None


# ------------------------------------------------------------------------------------ table


def load_table(spec: Any) -> Table:
    """The table of a `table` value (a scene's or a saved match's): a preset name or an
    object, checked (SceneError naming the key)."""
    if isinstance(spec, str):
        if spec not in PRESETS:
            raise SceneError(f"table: unknown preset '{spec}' (use {', '.join(PRESETS)})")
        return Table.preset(spec)
    if not isinstance(spec, dict):
        raise SceneError("table: must be a preset name ('7ft', '8ft', '9ft') or an object")
    _check_keys(spec, TABLE_KEYS, "table")
    kw: dict[str, Any] = {}
    preset = spec.get("preset")
    if preset is not None:
        if not isinstance(preset, str) or preset not in PRESETS:
            raise SceneError(
                f"table.preset: unknown preset {_fmt(preset)} (use {', '.join(PRESETS)})"
            )
        kw["length"], kw["width"] = PRESETS[preset]
    for key, val in spec.items():
        if key == "preset":
            continue
        if key == "pockets":
            if val not in ("standard", "none"):
                raise SceneError("table.pockets: must be 'standard' or 'none'")
            kw[key] = val
        else:
            unit = "degrees" if key.endswith("_angle") else "m"
            kw[key] = _number(val, f"table.{key}", positive=key != "hole_depth",
                              nonneg=key == "hole_depth", within=TABLE_RANGES.get(key), unit=unit)
    try:
        t = Table(**kw)
    except ValueError as e:
        raise SceneError(str(e)) from None
    if t.pockets == "standard":
        a = t.corner_mouth / math.sqrt(2)  # corner jaw tip distance from the corner
        if 2 * a + t.side_mouth >= t.length:
            raise SceneError("table: pocket mouths do not fit along the length")
        if 2 * a >= t.width:
            raise SceneError("table: corner pocket mouths do not fit across the width")
        _check_pockets(t)
    return t


def _check_pockets(t: Table) -> None:
    """A ball between a pocket's jaws can leave only past their outer ends; when both ends lie
    over the hole, it falls in first. Beyond that it would roll off the table."""
    ends = t.seg_b[[k for k, kind in enumerate(t.seg_kind) if kind == "jaw"]]
    for k, name in enumerate(t.hole_names):
        far = np.hypot(*(ends[2 * k:2 * k + 2] - t.hole_c[k]).T).max() - t.hole_r[k]
        if far > 0:
            raise SceneError(
                f"table: the jaws of the {name.replace('_', ' ')} pocket end {far:.3g} m "
                "outside its hole, so a ball could pass between them and leave the table (the "
                "hole must reach both jaw ends: change jaw_length, hole_depth or the hole's "
                "radius)")


def table_to_dict(t: Table) -> dict:
    return {name: getattr(t, name) for name in TABLE_FIELDS}


# ------------------------------------------------------------------------------------ balls


def ball_id(val: Any, path: str) -> str:
    """A ball id as scenes write it ("cue", "3"; a whole number stands for its digits);
    SceneError naming `path` when it is not one."""
    return _ball_id(val, path)


def _ball_id(val: Any, path: str) -> str:
    if isinstance(val, bool):
        raise SceneError(f"{path}: must be a string or a number")
    if isinstance(val, int):
        return str(val)
    if isinstance(val, float):
        if not math.isfinite(val):
            raise SceneError(f"{path}: must be finite")
        return str(int(val)) if val.is_integer() else repr(val)
    if isinstance(val, str):
        if not val.strip():
            raise SceneError(f"{path}: must not be empty")
        return val
    raise SceneError(f"{path}: must be a string or a number")


def _ball(spec: Any, i: int) -> dict:
    path = f"balls[{i}]"
    _check_keys(spec, BALL_KEYS, path)
    bid = _ball_id(spec["id"], f"{path}.id") if "id" in spec else ("cue" if i == 0 else str(i))
    for key in ("x", "y"):
        if key not in spec:
            raise SceneError(f"{path} (id '{bid}'): missing key '{key}'")
    b = {"id": bid}
    for key in ("x", "y", "vx", "vy"):
        b[key] = _number(spec.get(key, 0.0), f"{path}.{key}")
    w = spec.get("w", [0.0, 0.0, 0.0])
    if not isinstance(w, list) or len(w) != 3:
        raise SceneError(f"{path}.w: must be a list of 3 numbers [wx, wy, wz]")
    b["w"] = [_number(v, f"{path}.w[{k}]") for k, v in enumerate(w)]
    b["radius"] = _number(spec.get("radius", BALL_RADIUS), f"{path}.radius", positive=True,
                          within=RADIUS_RANGE, unit="m")
    b["mass"] = _number(spec.get("mass", BALL_MASS), f"{path}.mass", positive=True,
                        within=MASS_RANGE, unit="kg")
    if math.hypot(b["vx"], b["vy"]) > MAX_SPEED:
        raise SceneError(f"{path} (id '{bid}'): speed {math.hypot(b['vx'], b['vy']):g} m/s "
                         f"is above the limit of {MAX_SPEED:g} m/s")
    surface = b["radius"] * math.hypot(*b["w"])
    if surface > MAX_SURFACE_SPEED:
        raise SceneError(f"{path} (id '{bid}'): spin w times the radius is {surface:g} m/s, "
                         f"above the limit of {MAX_SURFACE_SPEED:g} m/s")
    return b


def rack(kind: str, table: Table, radius: float = BALL_RADIUS) -> list[dict]:
    """Cue ball on the head spot plus touching racked balls, apex on the foot spot."""
    if kind not in RACK_ROWS:
        raise SceneError(f"balls: unknown rack '{kind}' (use {', '.join(RACKS)} or a list)")
    hx, hy = table.head_spot
    fx, fy = table.foot_spot
    dx = math.sqrt(3.0) * radius
    placed = {}
    for k, row in enumerate(RACK_ROWS[kind]):
        n = len(row)
        for j, bid in enumerate(row):
            placed[bid] = (fx + k * dx, fy + (2 * j - (n - 1)) * radius)
    out = [{"id": "cue", "x": hx, "y": hy}]
    for bid in sorted(placed, key=int):
        x, y = placed[bid]
        out.append({"id": bid, "x": x, "y": y})
    for b in out:
        b.update(vx=0.0, vy=0.0, w=[0.0, 0.0, 0.0], radius=radius, mass=BALL_MASS)
        if not table.inside(b["x"], b["y"], radius):
            raise SceneError(f"balls: rack '{kind}' does not fit on the table (ball '{b['id']}')")
    return out


def _balls(spec: Any, table: Table) -> list[dict]:
    if isinstance(spec, str):
        return rack(spec, table)
    if not isinstance(spec, list):
        raise SceneError("balls: must be a list of balls or a rack name ('8ball' or '9ball')")
    if not spec:
        raise SceneError("balls: must list at least one ball")
    if len(spec) > MAX_BALLS:
        raise SceneError(f"balls: {len(spec)} balls is more than the limit of {MAX_BALLS}")
    return [_ball(b, i) for i, b in enumerate(spec)]


def _first_overlaps(balls: list[dict]) -> dict[int, int]:
    """{i: j} for the first ball i (in list order) that overlaps an earlier ball j, if any:
    all pairs at once in numpy, a block of rows at a time (memory BLOCK x N)."""
    n = len(balls)
    pos = np.array([[b["x"], b["y"]] for b in balls], float)
    rad = np.array([b["radius"] for b in balls], float)
    block = 256
    for start in range(0, n, block):
        rows = np.arange(start, min(n, start + block))
        d = np.hypot(pos[rows, None, 0] - pos[None, :, 0], pos[rows, None, 1] - pos[None, :, 1])
        bad = (d < rad[rows, None] + rad[None, :] - OVERLAP_TOL) & (np.arange(n) < rows[:, None])
        if bad.any():
            r, j = np.argwhere(bad)[0]  # the first row, then its first earlier ball
            return {int(rows[r]): int(j)}
    return {}


def _check_layout(balls: list[dict], table: Table, physics: Physics) -> None:
    overlap = _first_overlaps(balls)
    seen: dict[str, int] = {}
    for i, b in enumerate(balls):
        tag = f"balls[{i}] (id '{b['id']}')"
        if b["id"] in seen:
            raise SceneError(f"{tag}: duplicate id (also balls[{seen[b['id']]}])")
        seen[b["id"]] = i
        # A ball touching a rail has its centre nose_reach (< radius) from the nose line.
        reach = float(nose_reach(b["radius"], physics.cushion_height))
        if not table.on_bed(b["x"], b["y"], reach):
            raise SceneError(
                f"{tag}: off the table at ({b['x']:g}, {b['y']:g}); the centre must lie within "
                f"[{reach:g}, {table.length - reach:g}] x [{reach:g}, {table.width - reach:g}] "
                "(or in a pocket's mouth, clear of the jaws)"
            )
        if i in overlap:
            o = balls[overlap[i]]
            d = math.hypot(b["x"] - o["x"], b["y"] - o["y"])
            raise SceneError(f"{tag}: overlaps ball '{o['id']}' (centres {d:.6g} m apart)")


# ------------------------------------------------------------------------------------- shot


def _apply_shot(spec: Any, balls: list[dict]) -> None:
    _check_keys(spec, SHOT_KEYS, "shot")
    bid = _ball_id(spec.get("ball", "cue"), "shot.ball")
    match = [b for b in balls if b["id"] == bid]
    if not match:
        raise SceneError(f"shot.ball: no ball with id '{bid}' in the scene")
    if "speed" not in spec:
        raise SceneError("shot: missing key 'speed'")
    speed = _number(spec["speed"], "shot.speed", nonneg=True, within=(0.0, MAX_SPEED),
                    unit="m/s")
    angle = _number(spec.get("angle", 0.0), "shot.angle")
    side = _number(spec.get("side", 0.0), "shot.side")
    top = _number(spec.get("top", 0.0), "shot.top")
    b = match[0]
    try:
        (vx, vy), w = strike(speed, angle, side, top, b["radius"])
    except ValueError as e:
        raise SceneError(str(e)) from None
    b["vx"], b["vy"], b["w"] = vx, vy, list(w)


# -------------------------------------------------------------------------------------- API


def _read(path: str | os.PathLike) -> dict:
    try:
        text = read_text(path, MAX_SCENE_BYTES, "scene")
    except FileError as e:
        raise SceneError(str(e)) from None
    return _parse_json(text, "stdin" if os.fspath(path) == "-" else os.fspath(path))


def load_scene(src: str | os.PathLike | dict) -> Scene:
    """Load and validate a scene from a JSON file path ("-": standard input) or an already
    parsed dict."""
    raw = src if isinstance(src, dict) else _read(src)
    if not isinstance(raw, dict):
        raise SceneError("scene: must be a JSON object")
    raw = copy.deepcopy(raw)
    _check_keys(raw, TOP_KEYS, "scene")
    if "description" in raw and not isinstance(raw["description"], str):
        raise SceneError("description: must be a string")
    table = load_table(raw.get("table", "9ft"))
    phys_spec = raw.get("physics", {})
    if not isinstance(phys_spec, dict):
        raise SceneError("physics: must be an object")
    try:
        physics = Physics.from_dict(phys_spec)
    except ValueError as e:
        raise SceneError(str(e)) from None
    balls = _balls(raw.get("balls", "8ball"), table)
    _check_layout(balls, table, physics)
    if "shot" in raw:
        _apply_shot(raw["shot"], balls)
    game = raw.get("game")
    if "game" in raw and not isinstance(game, dict):
        raise SceneError("game: must be an object")
    return Scene(
        table=table,
        physics=physics,
        ids=[b["id"] for b in balls],
        pos=np.array([[b["x"], b["y"]] for b in balls], dtype=float),
        vel=np.array([[b["vx"], b["vy"]] for b in balls], dtype=float),
        w=np.array([b["w"] for b in balls], dtype=float),
        radius=np.array([b["radius"] for b in balls], dtype=float),
        mass=np.array([b["mass"] for b in balls], dtype=float),
        raw=raw,
        game=game,
    )


def scene_to_dict(scene: Scene) -> dict:
    """A JSON-able dict with an explicit balls list (any shot already applied)."""
    out: dict[str, Any] = {}
    if isinstance(scene.raw.get("description"), str):
        out["description"] = scene.raw["description"]
    out["table"] = table_to_dict(scene.table)
    out["physics"] = scene.physics.to_dict()
    out["balls"] = [
        {
            "id": bid,
            "x": float(scene.pos[i, 0]),
            "y": float(scene.pos[i, 1]),
            "vx": float(scene.vel[i, 0]),
            "vy": float(scene.vel[i, 1]),
            "w": [float(v) for v in scene.w[i]],
            "radius": float(scene.radius[i]),
            "mass": float(scene.mass[i]),
        }
        for i, bid in enumerate(scene.ids)
    ]
    if scene.game is not None:
        out["game"] = copy.deepcopy(scene.game)
    return out


def loads_scene(text: str) -> Scene:
    """Load a scene from JSON text."""
    return load_scene(_parse_json(text, "scene"))
