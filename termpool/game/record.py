"""Shot records and replays: one shot as JSON, and re-simulating it bit for bit.

A shot record (one item of a replay file's "shots") is::

    {"n": 1, "frame": 1, "player": 0,
     "scene": {...},        # the table before the shot: `scene_to_dict` form, balls at rest,
                            # plus the `game` block the referee needs (see docs/scenes.md)
     "shot": {"speed": .., "angle": .., "side": .., "top": .., "called": [ball, pocket] | null,
              "push_out": false},
     "dt": 0.016666666666666666,   # the fixed step the engine was driven with
     "time": .., "steps": ..,      # the engine's clock and step count when all was at rest
     "events": [...],              # as `termpool sim` prints them
     "final": [...],               # the balls at rest, as `termpool sim` prints them
     "outcome": {...}}             # the referee's outcome (`Outcome.to_json`)

Replaying loads the scene with the shot applied (`load_scene`), drives a fresh engine with the
same fixed steps until the table is at rest, and compares time, steps, events, final balls and
the referee's outcome with the record, floats bit for bit.
"""

from __future__ import annotations

import json
import math
import os
import struct
from typing import Any

from termpool.files import MAX_REPLAY_BYTES, FileError, parse_json, read_text
from termpool.physics.engine import Engine
from termpool.physics.params import as_recorded
from termpool.physics.results import DT_RANGE, sim_result
from termpool.rules import words
from termpool.rules.common import Outcome
from termpool.rules.referee import load_game_scene, verdict
from termpool.rules.words import RECORD, Voice
from termpool.scene import Scene, SceneError

MAX_SHOT_TIME = 600.0  # simulated seconds: a shot that runs longer is a broken record
NEVER_STOP = ("mu_slide", "mu_roll")  # with either at 0 a rolling ball never stops
RECORD_KEYS = ("n", "frame", "player", "scene", "shot", "dt", "time", "steps", "events",
               "final", "outcome")
SHOT_NUMBERS = ("speed", "angle", "side", "top")


class ReplayError(ValueError):
    """A replay file that cannot be read or checked; the message is one line."""


def cue_shot(shot: dict) -> dict:
    """The scene `shot` block for a record's shot parameters."""
    return {"ball": "cue", **{k: shot[k] for k in SHOT_NUMBERS}}


def shot_scene(scene_dict: dict, shot: dict) -> Scene:
    """The scene of a record with its shot applied, loaded and validated, its game block too
    (with the cushion it was played with, for records from before scenes chose one)."""
    physics = scene_dict.get("physics", {})
    if isinstance(physics, dict):
        scene_dict = {**scene_dict, "physics": as_recorded(physics)}
    return load_game_scene({**scene_dict, "shot": cue_shot(shot)})


def start_engine(scene: Scene) -> Engine:
    return Engine(scene.table, scene.physics, scene.pos, scene.vel, scene.w, scene.radius,
                  scene.mass, record=True)


def run_to_rest(engine: Engine, dt: float, max_steps: int | None = None) -> bool:
    """Drive `engine` in fixed steps of dt until every ball is at rest (the shot's one driver,
    live and in replays, so both take exactly the same steps). With `max_steps` (a replay's
    recorded count: its work budget) it stops there and returns False if the balls still
    move."""
    while not engine.at_rest().all():
        if max_steps is not None and engine.steps >= max_steps:
            return False
        if engine.time > MAX_SHOT_TIME:
            raise RuntimeError(f"shot: still moving after {MAX_SHOT_TIME:g} s")
        engine.step(dt)
    return True


def still_moving(steps: int) -> str:
    """The difference of a replayed shot whose balls still move after its recorded steps."""
    return f"steps: still moving after the recorded {steps} steps (a replay takes no more)"


def results(scene: Scene, engine: Engine, dt: float) -> dict:
    """time, steps, events and final balls of a finished shot, as `termpool sim` prints them."""
    res = sim_result(scene.ids, scene.table.hole_names, engine, None, "fixed", dt, 0.0)
    # Through JSON once: the record holds exactly what a saved file will hold.
    return json.loads(json.dumps({k: res[k] for k in ("time", "steps", "events")}
                                 | {"final": res["balls"]}))


def shot_record(run, outcome: Outcome, n: int, frame: int) -> dict:
    """The record of a shot run to rest (a `turn.ShotRun`) and judged `outcome`: shot `n`
    of the match, in frame `frame` (both from 1)."""
    return {"n": n, "frame": frame, "player": run.state.shooter, "scene": run.scene_dict,
            "shot": run.shot.to_json(), "dt": run.dt, **results(run.scene, run.engine, run.dt),
            "outcome": outcome.to_json()}


def recorded_verdict(rec: Any, path: str = "shot") -> Outcome | None:
    """The referee's verdict on a record's shot, from its scene and its recorded events (the
    verdict it was given, for a true record); None for a scene without a game block. Raises
    ReplayError for a malformed record."""
    scene, _ = _check_record(rec, path)
    if scene.game is None:
        return None
    try:
        return verdict(scene.game, scene.ids, rec["events"])
    except (KeyError, IndexError, TypeError, ValueError) as e:
        raise _fail(f"{path}.events", f"not the events of a shot ({e})") from None


# ------------------------------------------------------------------------------ comparing


def _bits(x: float) -> bytes:
    return struct.pack("<d", float(x))


def first_difference(a: Any, b: Any, path: str = "") -> str | None:
    """Where two JSON values first differ ("events[3].balls[0].x: ..."), or None.

    Numbers compare bit for bit (so 0.0 and -0.0 differ); an int and a float of the same value
    are the same number."""
    num = (int, float)
    if isinstance(a, num) and isinstance(b, num) and not isinstance(a, bool) \
            and not isinstance(b, bool):
        return None if _bits(a) == _bits(b) else f"{path}: recorded {a!r}, replayed {b!r}"
    if isinstance(a, dict) and isinstance(b, dict):
        for k in list(a) + [k for k in b if k not in a]:
            if k not in a or k not in b:
                where = "recorded" if k in a else "replayed"
                return f"{path}.{k}: only in the {where} shot".lstrip(".")
            d = first_difference(a[k], b[k], f"{path}.{k}".lstrip("."))
            if d:
                return d
        return None
    if isinstance(a, list) and isinstance(b, list):
        for k, (x, y) in enumerate(zip(a, b, strict=False)):
            d = first_difference(x, y, f"{path}[{k}]")
            if d:
                return d
        if len(a) != len(b):
            return f"{path}: {len(a)} recorded, {len(b)} replayed"
        return None
    if type(a) is not type(b) or a != b:
        return f"{path}: recorded {json.dumps(a)}, replayed {json.dumps(b)}"
    return None


# ------------------------------------------------------------------------------ validating


def _fail(path: str, msg: str) -> ReplayError:
    return ReplayError(f"{path}: {msg}")


def _is_number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def check_shot_params(shot: Any, path: str) -> None:
    """Validate a record's `shot` object (raises ReplayError naming the key)."""
    if not isinstance(shot, dict):
        raise _fail(path, "must be an object")
    for k in SHOT_NUMBERS:
        if k not in shot:
            raise _fail(path, f"missing key '{k}'")
        if not _is_number(shot[k]):
            raise _fail(f"{path}.{k}", "must be a finite number")
    called = shot.get("called")
    if called is not None and not (isinstance(called, list) and len(called) == 2
                                   and all(isinstance(c, str) for c in called)):
        raise _fail(f"{path}.called", "must be null or [ball, pocket]")
    if not isinstance(shot.get("push_out", False), bool):
        raise _fail(f"{path}.push_out", "must be true or false")


def _check_record(rec: Any, path: str) -> tuple[Scene, float]:
    if not isinstance(rec, dict):
        raise _fail(path, "must be an object")
    for k in RECORD_KEYS:
        if k not in rec:
            raise _fail(path, f"missing key '{k}'")
    for k in ("n", "frame", "player", "steps"):
        if type(rec[k]) is not int:
            raise _fail(f"{path}.{k}", "must be a whole number")
    dt = rec["dt"]
    if not _is_number(dt) or dt <= 0:
        raise _fail(f"{path}.dt", "must be a positive number of seconds")
    if not DT_RANGE[0] <= dt <= DT_RANGE[1]:
        raise _fail(f"{path}.dt", f"must be from {DT_RANGE[0]:g} to {DT_RANGE[1]:g} seconds, "
                                  f"not {dt:g}")
    if not _is_number(rec["time"]):
        raise _fail(f"{path}.time", "must be a finite number")
    for k in ("events", "final"):
        if not isinstance(rec[k], list):
            raise _fail(f"{path}.{k}", "must be a list")
    if rec["outcome"] is not None and not isinstance(rec["outcome"], dict):
        raise _fail(f"{path}.outcome", "must be an object or null")
    if not isinstance(rec["scene"], dict):
        raise _fail(f"{path}.scene", "must be an object")
    check_shot_params(rec["shot"], f"{path}.shot")
    if "shot" in rec["scene"]:
        raise _fail(f"{path}.scene", "must not hold a 'shot' (the record's 'shot' is applied)")
    try:
        scene = shot_scene(rec["scene"], rec["shot"])
    except SceneError as e:
        raise _fail(f"{path}.scene", str(e)) from None
    for k in NEVER_STOP:
        if getattr(scene.physics, k) <= 0:
            raise _fail(f"{path}.scene.physics.{k}", "must be positive (the balls never stop)")
    return scene, float(dt)


def replay_shot(rec: Any, path: str = "shot", v: Voice = RECORD) -> dict:
    """Re-simulate one record: {"ok", "differences", "events", "reason"} (the verdict in the
    voice `v`). Raises ReplayError when the record is malformed."""
    scene, dt = _check_record(rec, path)
    engine = start_engine(scene)
    try:
        rested = run_to_rest(engine, dt, max_steps=rec["steps"])
    except RuntimeError as e:  # the engine's work limit, or a shot that never ends
        raise _fail(path, str(e)) from None
    fresh = results(scene, engine, dt)
    if not rested:
        return {"ok": False, "events": len(fresh["events"]), "reason": "",
                "differences": [still_moving(rec["steps"])]}
    outcome = None if scene.game is None else verdict(scene.game, scene.ids, engine.log[0])
    fresh["outcome"] = None if outcome is None else json.loads(json.dumps(outcome.to_json()))
    diffs = []
    for k in ("time", "steps", "events", "final", "outcome"):
        d = first_difference(rec[k], fresh[k], k)
        if d:
            diffs.append(d)
    reason = "" if outcome is None else words.reason(outcome.said, v)
    return {"ok": not diffs, "differences": diffs, "events": len(fresh["events"]),
            "reason": reason}


def parse_replay(text: str, where: str = "replay") -> dict:
    """Parse a replay file's text and check its outline (raises ReplayError)."""
    try:
        data = parse_json(text, where)
    except FileError as e:
        raise ReplayError(str(e)) from None
    if not isinstance(data, dict):
        raise ReplayError(f"{where}: must be a JSON object")
    if "shots" not in data:
        raise ReplayError(f"{where}: missing key 'shots'")
    if not isinstance(data["shots"], list):
        raise ReplayError(f"{where}: shots: must be a list")
    match = data.get("match", {})
    if not isinstance(match, dict):
        raise ReplayError(f"{where}: match: must be an object")
    names = match.get("players", ["", ""])
    if not (isinstance(names, list) and len(names) == 2 and all(isinstance(n, str)
                                                                for n in names)):
        raise ReplayError(f"{where}: match.players: must be a list of two names (strings)")
    return data


def _where(path: str | os.PathLike) -> str:
    """A replay file's name as its errors say it ("-" is stdin)."""
    return "stdin" if os.fspath(path) == "-" else os.fspath(path)


def read_replays(path: str | os.PathLike) -> list[dict]:
    """Read and parse a replay file ("-": standard input): one match, or several as JSON
    Lines (a match a line, as `play --record -` writes them). Raises ReplayError with one
    line (naming the line of a JSON Lines file)."""
    try:
        text = read_text(path, MAX_REPLAY_BYTES, "replay")
    except FileError as e:
        raise ReplayError(str(e)) from None
    where = _where(path)
    try:
        return [parse_replay(text, where)]
    except ReplayError:
        lines = [(k, line) for k, line in enumerate(text.splitlines(), 1) if line.strip()]
        first = lines[0][1].strip() if lines else ""
        if not (len(lines) > 1 and first.startswith("{") and first.endswith("}")):
            raise
    return [parse_replay(line, f"{where} line {k}") for k, line in lines]


def read_replay(path: str | os.PathLike) -> dict:
    """`read_replays` for a file that must hold one match."""
    matches = read_replays(path)
    if len(matches) > 1:
        raise ReplayError(f"{_where(path)}: holds {len(matches)} matches (JSON Lines); give one, "
                          "e.g. the second with `sed -n 2p`")
    return matches[0]


def check_records(data: dict) -> list[tuple[Scene, float]]:
    """Check every shot record of a parsed replay (raises ReplayError for the first malformed
    one, naming it as the screens count shots and by its place in the file: "shot 2:
    shots[1].dt: ..."): each shot's scene with its shot applied, and its fixed step."""
    out = []
    for k, rec in enumerate(data["shots"]):
        try:
            out.append(_check_record(rec, f"shots[{k}]"))
        except ReplayError as e:
            raise ReplayError(f"shot {k + 1}: {e}") from None
    return out


def replay(data: dict, v: Voice = RECORD) -> list[dict]:
    """Check every shot of a parsed replay; one result per shot (see `replay_shot`: its
    verdict in the voice `v`), with the record's n, frame and player. Raises ReplayError for
    the first malformed record, before any shot is simulated."""
    shots = data["shots"]
    check_records(data)
    out = []
    for k, rec in enumerate(shots):
        res = replay_shot(rec, f"shots[{k}]", v)
        out.append({"n": rec["n"], "frame": rec["frame"], "player": rec["player"], **res})
    return out
