"""A match as JSON (`Match.to_json`) and back (`Match.from_json`), with one-line errors
naming the key. The file is a replay file: its settings, the position between shots, the
options answered and every shot's record."""

from __future__ import annotations

import copy
from dataclasses import replace
from typing import Any, NamedTuple

import numpy as np

from termpool.physics.params import Physics, as_recorded
from termpool.rules.codec import state_from_json, state_to_json
from termpool.rules.codes import Option
from termpool.rules.common import AREAS, State
from termpool.scene import SceneError, load_table, table_to_dict

from .players import Person
from .record import ReplayError, recorded_verdict

FORMAT = "termpool-replay"
VERSION = 1


class Position(NamedTuple):
    """A match between shots, as a file keeps it ("current")."""

    pos: np.ndarray
    on_table: np.ndarray
    state: State
    frame: int
    breaker: int
    scores: list[int]
    winner: int | None
    frame_winner: int | None
    ball_in_hand: str | None
    option: Option | None
    rng: dict


def match_json(m) -> dict:
    """A `Match` as JSON (see `Match.to_json`)."""
    return copy.deepcopy({
        "format": FORMAT,
        "version": VERSION,
        "match": {"mode": m.mode, "table": table_to_dict(m.table),
                  "physics": m.physics.to_dict(), "frames": m.frames,
                  "players": list(m.players), "seed": m.seed,
                  "three_foul": m.three_foul, "theme": m.theme, "dt": m.dt,
                  "eight_break": m.eight_break, "levels": list(m.levels)},
        "current": {
            "frame": m.frame, "breaker": m.breaker, "scores": list(m.scores),
            "winner": m.winner, "frame_winner": m.frame_winner,
            "ball_in_hand": m.ball_in_hand,
            "option": None if m.option is None else str(m.option),
            "state": state_to_json(m.state),
            "balls": m.balls.to_json(),
            "last_outcome": None if m.last_outcome is None else m.last_outcome.to_json(),
            "rng": m.rng.bit_generator.state,
        },
        "choices": m.choices,
        "shots": m.history,
    })


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


class _Recorded(NamedTuple):
    """A computer player as a file records it: its name and level."""

    name: str
    level: str


def _players(m: dict) -> tuple:
    names = _get(m, "players", "match", list, "a list of two names")
    levels = m.get("levels", [None, None])  # files from before levels: unknown
    if not isinstance(levels, list) or len(levels) != 2:
        raise ValueError("match.levels: must be a list of two levels (null for a person)")
    if len(names) != 2:
        return tuple(names)  # the match names what is wrong
    # The players as the record keeps them: their names and levels (who or what played).
    return tuple(Person(n) if lv is None else _Recorded(n, lv)
                 for n, lv in zip(names, levels, strict=True))


def settings(data: Any) -> dict:
    """`Match`'s arguments from a saved match's "match" block."""
    if not isinstance(data, dict):
        raise ValueError("match file: must be a JSON object")
    if data.get("format") != FORMAT:
        raise ValueError(f"format: must be '{FORMAT}'")
    m = _get(data, "match", "match file", dict, "an object")
    try:
        table = load_table(_get(m, "table", "match", (dict, str), "an object"))
    except SceneError as e:
        raise ValueError(f"match.{e}") from None
    return {
        "mode": _get(m, "mode", "match", str, "a string"), "table": table,
        "frames": _get(m, "frames", "match", int, "a whole number"),
        "players": _players(m),
        "seed": _get(m, "seed", "match", int, "a whole number"),
        "physics": Physics.from_dict(as_recorded(_get(m, "physics", "match", dict,
                                                      "an object"))),
        "three_foul": _get(m, "three_foul", "match", bool, "true or false"),
        "theme": _get(m, "theme", "match", str, "a string"),
        "dt": float(_get(m, "dt", "match", (int, float), "a number")),
        "eight_break": m.get("eight_break", "respot"),  # files from before the variant re-spot
    }


def position(data: dict, ids: list[str], mode: str, eight_break: str) -> Position:
    """The "current" block of a saved match whose balls are `ids`, game `mode` and 8-ball
    variant `eight_break`."""
    cur = _get(data, "current", "match file", dict, "an object")
    balls = _get(cur, "balls", "current", list, "a list")
    if [b.get("id") if isinstance(b, dict) else None for b in balls] != ids:
        raise ValueError(f"current.balls: must list {', '.join(ids)} in that order")
    pos, on = np.zeros((len(ids), 2)), np.zeros(len(ids), dtype=bool)
    for k, b in enumerate(balls):
        pos[k] = (float(_get(b, "x", f"current.balls[{k}]", (int, float), "a number")),
                  float(_get(b, "y", f"current.balls[{k}]", (int, float), "a number")))
        on[k] = _get(b, "on_table", f"current.balls[{k}]", bool, "true or false")
    raw = _get(cur, "state", "current", dict, "an object")
    state = state_from_json(raw, "current.state")
    if state.mode != mode:
        raise ValueError("current.state.mode: must be the match's mode")
    if mode == "8ball" and "eight_break" not in raw:  # saved before the state said it
        state = replace(state, eight_break=eight_break)
    frame = _get(cur, "frame", "current", int, "a whole number")
    breaker = _player(_get(cur, "breaker", "current", int, "0 or 1"), "current.breaker")
    scores = _get(cur, "scores", "current", list, "a list of two whole numbers")
    if len(scores) != 2 or not all(type(s) is int and s >= 0 for s in scores):
        raise ValueError("current.scores: must be a list of two whole numbers")
    winner = _player(cur.get("winner"), "current.winner")
    frame_winner = _player(cur.get("frame_winner"), "current.frame_winner")
    area = cur.get("ball_in_hand")
    if area is not None and area not in AREAS:
        raise ValueError("current.ball_in_hand: must be null, 'anywhere' or 'kitchen'")
    option = cur.get("option")
    if option is not None and option not in tuple(Option):
        raise ValueError(f"current.option: must be null or one of {', '.join(Option)}")
    rng = _get(cur, "rng", "current", dict, "an object")
    try:
        np.random.default_rng().bit_generator.state = rng
    except (TypeError, ValueError, KeyError) as e:
        raise ValueError(f"current.rng: not a generator state ({e})") from None
    return Position(pos, on, state, frame, breaker, list(scores), winner, frame_winner, area,
                    None if option is None else Option(option), rng)


def load_match(cls: type, data: Any):
    """Build a `cls` (Match) from its JSON; see `Match.from_json`."""
    match = cls(**settings(data))
    where = position(data, match.ids, match.mode, match.eight_break)
    choices = list(_get(data, "choices", "match file", list, "a list"))
    history = list(_get(data, "shots", "match file", list, "a list"))
    try:
        last = recorded_verdict(history[-1], f"shots[{len(history) - 1}]") if history else None
    except ReplayError as e:
        raise ValueError(str(e)) from None
    return match.resume(where, choices, history, last)
