"""The scriptable referee: a scene's `game` block plus one shot's events -> an outcome.

`termpool sim` loads its scene and, when it has a game block, checks the block (`check_game`,
as `load_game_scene` does: see `rules.codec`) and calls `referee`; the block and its
meaning are documented in docs/scenes.md.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Sequence

from termpool.physics.events import Event
from termpool.rules import eight, nine, practice
from termpool.rules.codec import read_game, state_from_game
from termpool.rules.common import Outcome, State
from termpool.rules.events import ShotSummary, summarize
from termpool.scene import Scene, ball_id, load_scene

JUDGES = {"8ball": eight.judge, "9ball": nine.judge, "practice": practice.judge}


def judge(state: State, summary: ShotSummary) -> tuple[Outcome, State]:
    """Judge one shot by the rules of `state.mode`."""
    return JUDGES[state.mode](state, summary)


def load_game_scene(src: str | os.PathLike | dict) -> Scene:
    """`scene.load_scene`, and the scene's game block (if any) validated and normalized;
    SceneError, one line naming the key, for a bad one."""
    return check_game(load_scene(src))


def check_game(scene: Scene) -> Scene:
    """Validate and normalize a loaded scene's game block, if it has one, in place (as
    `load_game_scene` does); SceneError, one line naming the key, for a bad one."""
    if scene.game is not None:
        shot = scene.raw.get("shot")
        struck = None if shot is None else ball_id(shot.get("ball", "cue"), "shot.ball")
        scene.game = read_game(scene.game, scene.ids, scene.table.hole_names, struck)
    return scene


def verdict(game: dict, ids: Sequence[str], events: Iterable[Event | dict]) -> Outcome:
    """The outcome of one shot: the scene's (validated) game block, its ball ids and the
    shot's events (the engine's typed log, or as `termpool sim` prints them)."""
    state = state_from_game(game, ids)
    summary = summarize(events, ids, is_break=state.is_break)
    outcome, _ = judge(state, summary)
    return outcome


def referee(game: dict, ids: Sequence[str], events: Iterable[Event | dict]) -> dict:
    """The JSON `outcome` of one shot (see `verdict`)."""
    return verdict(game, ids, events).to_json()
