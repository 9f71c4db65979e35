"""Loading a saved match (`Match.to_json`) back, with one-line errors naming the key."""

from __future__ import annotations

from typing import Any

import numpy as np

from termpool.physics.params import Physics, as_recorded
from termpool.rules.common import Outcome
from termpool.scene import SceneError, load_table

from .match import FORMAT, OPTIONS
from .turn import state_from_json

AREAS = (None, "anywhere", "kitchen")


def _get(d: dict, key: str, path: str, kind: type | tuple, what: str) -> Any:
    if key not in d:
        raise ValueError(f"{path}: missing key '{key}'")
    val = d[key]
    if isinstance(val, bool) and bool not in (kind if isinstance(kind, tuple) else (kind,)):
        raise ValueError(f"{path}.{key}: must be {what}")
    if not isinstance(val, kind):
        raise ValueError(f"{path}.{key}: must be {what}")
    return val


def _player(val: Any, path: str) -> int | None:
    if val is None:
        return None
    if type(val) is not int or val not in (0, 1):
        raise ValueError(f"{path}: must be 0, 1 or null")
    return val


def outcome_from_json(d: Any, path: str) -> Outcome:
    if not isinstance(d, dict):
        raise ValueError(f"{path}: must be an object")
    try:
        groups = d["groups"]
        return Outcome(
            foul=d["foul"], next_shooter=int(d["next_shooter"]),
            ball_in_hand=bool(d["ball_in_hand"]),
            groups=None if groups is None else {int(p): g for p, g in groups.items()},
            winner=d["winner"], reason=str(d["reason"]), respot=tuple(d["respot"]),
            continue_turn=bool(d["continue_turn"]), ball_in_hand_area=d["ball_in_hand_area"],
            fouls=tuple(d["fouls"]), option=d["option"])
    except KeyError as e:
        raise ValueError(f"{path}: missing key '{e.args[0]}'") from None
    except (TypeError, ValueError, AttributeError) as e:
        raise ValueError(f"{path}: {e}") from None


def _levels(val: Any) -> tuple:
    if not isinstance(val, list) or len(val) != 2:
        raise ValueError("match.levels: must be a list of two levels (null for a person)")
    return tuple(val)


def load_match(cls: type, data: Any):
    """Build a `cls` (Match) from its JSON; see `Match.from_json`."""
    if not isinstance(data, dict):
        raise ValueError("match file: must be a JSON object")
    if data.get("format") != FORMAT:
        raise ValueError(f"format: must be '{FORMAT}'")
    m = _get(data, "match", "match file", dict, "an object")
    try:
        table = load_table(_get(m, "table", "match", (dict, str), "an object"))
    except SceneError as e:
        raise ValueError(f"match.{e}") from None
    physics = Physics.from_dict(as_recorded(_get(m, "physics", "match", dict, "an object")))
    match = cls(
        _get(m, "mode", "match", str, "a string"), table=table,
        frames=_get(m, "frames", "match", int, "a whole number"),
        players=tuple(_get(m, "players", "match", list, "a list of two names")),
        seed=_get(m, "seed", "match", int, "a whole number"), physics=physics,
        three_foul=_get(m, "three_foul", "match", bool, "true or false"),
        theme=_get(m, "theme", "match", str, "a string"),
        dt=float(_get(m, "dt", "match", (int, float), "a number")),
        eight_break=m.get("eight_break", "respot"),  # files from before the variant re-spot
        levels=_levels(m.get("levels", [None, None])))  # files from before levels: unknown
    cur = _get(data, "current", "match file", dict, "an object")
    balls = _get(cur, "balls", "current", list, "a list")
    ids = [b.get("id") if isinstance(b, dict) else None for b in balls]
    if ids != match.ids:
        raise ValueError(f"current.balls: must list {', '.join(match.ids)} in that order")
    for k, b in enumerate(balls):
        x = _get(b, "x", f"current.balls[{k}]", (int, float), "a number")
        y = _get(b, "y", f"current.balls[{k}]", (int, float), "a number")
        match.pos[k] = (float(x), float(y))
        match.on_table[k] = _get(b, "on_table", f"current.balls[{k}]", bool, "true or false")
    match.state = state_from_json(_get(cur, "state", "current", dict, "an object"),
                                  "current.state")
    if match.state.mode != match.mode:
        raise ValueError("current.state.mode: must be the match's mode")
    match.frame = _get(cur, "frame", "current", int, "a whole number")
    match.breaker = _player(_get(cur, "breaker", "current", int, "0 or 1"), "current.breaker")
    scores = _get(cur, "scores", "current", list, "a list of two whole numbers")
    if len(scores) != 2 or not all(type(s) is int and s >= 0 for s in scores):
        raise ValueError("current.scores: must be a list of two whole numbers")
    match.scores = list(scores)
    match.winner = _player(cur.get("winner"), "current.winner")
    match.frame_winner = _player(cur.get("frame_winner"), "current.frame_winner")
    area = cur.get("ball_in_hand")
    if area not in AREAS:
        raise ValueError("current.ball_in_hand: must be null, 'anywhere' or 'kitchen'")
    match.ball_in_hand = area
    option = cur.get("option")
    if option is not None and option not in OPTIONS:
        raise ValueError(f"current.option: must be null or one of {', '.join(OPTIONS)}")
    match.option = option
    last = cur.get("last_outcome")
    match.last_outcome = None if last is None else outcome_from_json(last, "current.last_outcome")
    rng = _get(cur, "rng", "current", dict, "an object")
    try:
        match.rng.bit_generator.state = rng
    except (TypeError, ValueError, KeyError) as e:
        raise ValueError(f"current.rng: not a generator state ({e})") from None
    match.choices = list(_get(data, "choices", "match file", list, "a list"))
    match.history = list(_get(data, "shots", "match file", list, "a list"))
    match.pos = np.asarray(match.pos, float)
    return match
