"""The game state as JSON, read and written here only, in its two forms:

- the **state** form (a saved match's ``current.state``): every field of `State`;
- the **game block** of a scene (documented in docs/scenes.md): what the referee needs to
  judge one shot from the scene, where the balls of the game's set that are not in the scene
  count as pocketed. `read_game` validates a block (one line naming the key) and normalizes
  it; `state_from_game` and `game_block` go between a block and a `State`.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from typing import Any

from termpool.rules.common import EIGHT_BREAKS, GROUPS, MODE_BALLS, MODES, State, groups_to_json
from termpool.scene import SceneError, ball_id

GAME_KEYS = ("mode", "shooter", "groups", "break", "called", "fouls", "push_out", "three_foul",
             "eight_break")
KEY_BALL = {"8ball": "8", "9ball": "9"}  # the ball a game cannot be played without


# ------------------------------------------------------------------------------ the state


def state_to_json(s: State) -> dict:
    """The state form. `eight_break` is written only for the re-rack variant (saves from
    before it re-spot)."""
    out = {"mode": s.mode, "shooter": s.shooter, "groups": groups_to_json(s.groups),
           "fouls": list(s.fouls), "pocketed": list(s.pocketed), "is_break": s.is_break,
           "push_out": s.push_out, "called": None if s.called is None else list(s.called),
           "three_foul": s.three_foul}
    if s.eight_break != "respot":
        out["eight_break"] = s.eight_break
    return out


def state_from_json(d: Any, path: str = "state") -> State:
    """A state from its state form; ValueError naming `path` and the key."""
    if not isinstance(d, dict):
        raise ValueError(f"{path}: must be an object")
    try:
        groups = d.get("groups")
        called = d.get("called")
        return State(
            mode=d["mode"], shooter=d["shooter"],
            groups=None if groups is None else {int(p): g for p, g in groups.items()},
            fouls=tuple(int(n) for n in d["fouls"]), pocketed=tuple(d["pocketed"]),
            is_break=bool(d["is_break"]), push_out=d["push_out"],
            called=None if called is None else (str(called[0]), str(called[1])),
            three_foul=bool(d["three_foul"]), eight_break=d.get("eight_break", "respot"))
    except KeyError as e:
        raise ValueError(f"{path}: missing key '{e.args[0]}'") from None
    except (TypeError, ValueError, AttributeError, IndexError) as e:
        raise ValueError(f"{path}: {e}") from None


# ------------------------------------------------------------------------- the game block


def game_block(s: State) -> dict:
    """The game block for the referee of the shot about to be played from `s`."""
    g: dict[str, Any] = {"mode": s.mode, "shooter": s.shooter, "break": s.is_break,
                         "fouls": {"0": s.fouls[0], "1": s.fouls[1]}}
    if s.groups is not None:
        g["groups"] = groups_to_json(s.groups)
    if s.called is not None:
        g["called"] = {"ball": s.called[0], "pocket": s.called[1]}
    if s.mode == "9ball":
        g["push_out"] = s.push_out == "declared"
        g["three_foul"] = s.three_foul
    if s.eight_break != "respot":  # blocks from before the variant re-spot
        g["eight_break"] = s.eight_break
    return g


def state_from_game(game: dict, ids: Sequence[str]) -> State:
    """The state before the shot of a (validated) game block, for a scene of balls `ids`."""
    mode = game["mode"]
    groups = game.get("groups")
    called = game.get("called")
    fouls = game.get("fouls", {})
    present = set(ids)
    return State(
        mode=mode,
        shooter=int(game.get("shooter", 0)),
        groups=None if groups is None else {int(p): g for p, g in groups.items()},
        fouls=(int(fouls.get("0", 0)), int(fouls.get("1", 0))),
        pocketed=tuple(b for b in MODE_BALLS[mode] if b not in present),
        is_break=bool(game.get("break", False)),
        push_out="declared" if game.get("push_out") else "none",
        called=None if called is None else (str(called["ball"]), str(called["pocket"])),
        three_foul=bool(game.get("three_foul", False)),
        eight_break=game.get("eight_break", "respot"),
    )


def _fmt(v: Any) -> str:
    return repr(v) if isinstance(v, str) else json.dumps(v)


def _keys(d: Any, allowed: Sequence[str], path: str) -> dict:
    if not isinstance(d, dict):
        raise SceneError(f"{path}: must be an object")
    for key in d:
        if key not in allowed:
            raise SceneError(f"{path}: unknown key '{key}' (allowed: {', '.join(allowed)})")
    return d


def _flag(spec: dict, key: str) -> bool:
    val = spec.get(key, False)
    if not isinstance(val, bool):
        raise SceneError(f"game.{key}: must be true or false, not {_fmt(val)}")
    return val


def read_game(spec: Any, ids: Sequence[str], pockets: Sequence[str],
              shot_ball: str | None = None) -> dict:
    """A scene's game block, validated and normalized (see docs/scenes.md): `ids` are the
    scene's balls in order, `pockets` its table's pocket names, `shot_ball` the ball its shot
    strikes (None: no shot). SceneError, one line naming the key, when it is not valid."""
    _keys(spec, GAME_KEYS, "game")
    if "mode" not in spec:
        raise SceneError("game: missing key 'mode'")
    mode = spec["mode"]
    if not isinstance(mode, str) or mode not in MODES:
        raise SceneError(f"game.mode: must be {', '.join(repr(m) for m in MODES[:-1])} or "
                         f"{MODES[-1]!r}, not {_fmt(mode)}")
    shooter = spec.get("shooter", 0)
    if type(shooter) is not int or shooter not in (0, 1):
        raise SceneError(f"game.shooter: must be 0 or 1, not {_fmt(shooter)}")
    is_break = _flag(spec, "break")
    game: dict[str, Any] = {"mode": mode, "shooter": shooter, "break": is_break}

    allowed = MODE_BALLS[mode]
    for i, b in enumerate(ids):
        if b != "cue" and b not in allowed:
            raise SceneError(f"balls[{i}] (id '{b}'): not a ball of game mode '{mode}' "
                             f"(use 'cue' and '1'..'{allowed[-1]}')")
    if "cue" not in ids:
        raise SceneError("game: the scene needs the cue ball, id 'cue'")
    key_ball = KEY_BALL.get(mode)
    if key_ball and key_ball not in ids:
        raise SceneError(f"game: mode '{mode}' needs the {key_ball} on the table")
    if shot_ball is not None and shot_ball != "cue":
        raise SceneError("shot.ball: must be the cue ball 'cue' in a scene with a game block")

    if "groups" in spec:
        if mode != "8ball":
            raise SceneError("game.groups: only for mode '8ball'")
        if is_break:
            raise SceneError("game.groups: the table is open on a break; leave groups out")
        groups = _keys(spec["groups"], ("0", "1"), "game.groups")
        if not groups:
            raise SceneError("game.groups: must give the group of player 0 or 1")
        names = tuple(GROUPS)
        for p, g in groups.items():
            if not isinstance(g, str) or g not in GROUPS:
                raise SceneError(f"game.groups.{p}: must be {' or '.join(map(repr, names))}, "
                                 f"not {_fmt(g)}")
        if len(groups) == 2 and groups["0"] == groups["1"]:
            raise SceneError(f"game.groups: players 0 and 1 cannot both have the {groups['0']}")
        p, g = next(iter(groups.items()))  # the other player has the other group
        full = {p: g, str(1 - int(p)): names[1 - names.index(g)]}
        game["groups"] = {"0": full["0"], "1": full["1"]}

    if "called" in spec:
        called = _keys(spec["called"], ("ball", "pocket"), "game.called")
        for key in ("ball", "pocket"):
            if key not in called:
                raise SceneError(f"game.called: missing key '{key}'")
        ball = ball_id(called["ball"], "game.called.ball")
        if ball == "cue" or ball not in ids:
            raise SceneError(f"game.called.ball: no object ball with id '{ball}' on the table")
        pocket = called["pocket"]
        if not pockets:
            raise SceneError("game.called.pocket: the table has no pockets")
        if pocket not in pockets:
            raise SceneError(f"game.called.pocket: unknown pocket {_fmt(pocket)} "
                             f"(use {', '.join(pockets)})")
        game["called"] = {"ball": ball, "pocket": pocket}

    fouls = _keys(spec.get("fouls", {}), ("0", "1"), "game.fouls")
    for p, n in fouls.items():
        if type(n) is not int or n < 0:
            raise SceneError(f"game.fouls.{p}: must be a whole number >= 0, not {_fmt(n)}")
    game["fouls"] = {p: fouls.get(p, 0) for p in ("0", "1")}

    for key in ("push_out", "three_foul"):
        if key in spec and mode != "9ball":
            raise SceneError(f"game.{key}: only for mode '9ball'")
    if mode == "9ball":
        game["push_out"] = _flag(spec, "push_out")
        game["three_foul"] = _flag(spec, "three_foul")
        if game["push_out"] and is_break:
            raise SceneError("game.push_out: a break shot cannot be a push-out")
    if "eight_break" in spec:
        if mode != "8ball":
            raise SceneError("game.eight_break: only for mode '8ball'")
        if spec["eight_break"] not in EIGHT_BREAKS:
            raise SceneError(f"game.eight_break: must be one of {', '.join(EIGHT_BREAKS)}, "
                             f"not {_fmt(spec['eight_break'])}")
        if spec["eight_break"] != "respot":
            game["eight_break"] = spec["eight_break"]
    return game
