"""The scriptable referee: a scene's `game` block plus one shot's events -> an outcome.

`termpool sim` calls `referee` when a scene has a `game` block (validated by
``termpool.scene``); the block and its meaning are documented in docs/scenes.md.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from termpool.rules import eight, nine, practice
from termpool.rules.common import MODE_BALLS, Outcome, State
from termpool.rules.events import ShotSummary, summarize

JUDGES = {"8ball": eight.judge, "9ball": nine.judge, "practice": practice.judge}


def judge(state: State, summary: ShotSummary) -> tuple[Outcome, State]:
    """Judge one shot by the rules of `state.mode`."""
    return JUDGES[state.mode](state, summary)


def state_from_game(game: dict, ids: Sequence[str]) -> State:
    """The state before the shot described by a scene's (validated) `game` block.

    Balls of the game's set that are not in the scene count as already pocketed.
    """
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
    )


def referee(game: dict, ids: Sequence[str], events: Iterable[dict]) -> dict:
    """The JSON `outcome` of one shot: the scene's game block, its ball ids and its events."""
    state = state_from_game(game, ids)
    summary = summarize(events, ids, is_break=state.is_break)
    outcome, _ = judge(state, summary)
    return outcome.to_json()
